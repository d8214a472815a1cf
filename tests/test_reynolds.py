"""The Reynolds film (&water wet_model = 'reynolds', docs/model.md "The
Reynolds film"): the invariants issue 21 asks of it and the inertial
hydroplaning of a smooth surface, on synthetic closed profiles."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest

import pavefric
from pavefric.surfaces import spectral_profile
from pavefric.texture import texture

DX = 0.87e-3
SPEEDS = [20.0, 40.0, 60.0, 80.0, 100.0]


def profile(name):
    rms, seed = {"rough": (0.5e-3, 31), "fine": (0.2e-3, 7), "smooth": (0.01e-3, 3)}[name]
    return spectral_profile(512, DX, rms=rms, skew=0.0, seed=seed)


def run(z, speeds, **kw):
    kw.setdefault("mu_loc", 0.6)
    return pavefric.simulate(z, DX, speeds, closed=True, error_estimate=False, **kw)


def wet(z, speeds, depth, **kw):
    return run(z, speeds, wet_model="reynolds", depth=depth, **kw)


@pytest.fixture(scope="module", params=["rough", "fine"])
def textured(request):
    return profile(request.param)


def test_zero_and_a_nanometre_of_water_give_the_dry_result(textured):
    dry = run(textured, SPEEDS)["mu"].values
    np.testing.assert_array_equal(wet(textured, SPEEDS, 0.0)["mu"].values, dry)
    # 1e-9 m of water fills no gap (every c >= 0.4 sigma): the film carries nothing
    nano = wet(textured, SPEEDS, 1e-9)
    assert np.max(np.abs(nano["mu"].values - dry)) < 1e-3
    assert np.all(nano["mean_hydro_load"].values == 0.0)


def test_the_film_sets_in_continuously(textured):
    """The film is full first at the contacts, where c = sigma / sqrt(2 pi)
    (2 H_in = c: H_in = 8 um at sigma = 40 um). Below, mu is the dry one;
    across the onset it falls steeply (the stopped share 1 - c / (2 H_in)
    of the inlet's rho V^2 / 2 grows from 0) but continuously: a ten times
    finer step in depth gives steps in mu at least five times smaller."""
    dry = run(textured, [60.0])["mu"].values[0]

    def mu_at(depths):
        return np.array([wet(textured, [60.0], h)["mu"].values[0] for h in depths])

    coarse = np.linspace(7.0e-6, 1.0e-5, 13)
    mu = mu_at(coarse)
    assert abs(mu[0] - dry) < 1e-12
    steep = int(np.argmax(np.abs(np.diff(mu))))
    fine = np.linspace(coarse[steep], coarse[steep + 1], 11)
    assert np.max(np.abs(np.diff(mu_at(fine)))) < 0.2 * np.max(np.abs(np.diff(mu)))


def test_mu_never_rises_with_depth_or_with_speed(textured):
    depths = [1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3]
    mu = np.array([wet(textured, SPEEDS, h)["mu"].values for h in depths])
    lift = np.array([wet(textured, SPEEDS, h)["mean_hydro_load"].values for h in depths])
    # deeper: never more grip, but for the wet balance's choice of root
    # (docs/model.md: the film's load is not monotone in the penetration, and
    # its lower bracket -2 H_in moves with the depth; seen: +0.0016 at 60 km/h)
    assert np.all(np.diff(mu, axis=0) <= 5e-3), mu
    assert np.all(np.diff(mu, axis=1) <= 1e-9), mu               # faster: never more grip
    # more of the load on the film never raises mu
    order = np.argsort(lift, axis=0)
    for j in range(len(SPEEDS)):
        assert np.all(np.diff(mu[order[:, j], j]) <= 1e-9)


def test_a_textured_road_keeps_its_grip_at_speed():
    """MPD >= 1 mm at 1 mm of water: mu at 80 km/h above 0.3 times 20 km/h's."""
    z = profile("rough")
    assert texture(z, DX)["mpd"] >= 1e-3
    mu = wet(z, [20.0, 80.0], 1e-3)["mu"].values
    assert mu[1] > 0.3 * mu[0]


def test_the_viscous_film_alone_carries_little_on_a_texture(textured):
    """Without the inlet's inertia (density = 0) the film carries under 10 %
    of the load on a textured road (MODEL.md section 8: a classical film on
    this geometry carries little)."""
    share = wet(textured, [20.0, 60.0, 100.0], 1e-3, density=0.0)["mean_hydro_load"].values / 11.8
    assert np.all(share > 0.0) and np.all(share < 0.1)


def collapse_speed(z, load):
    """The first speed (1 km/h steps) at which mu falls below 10 % of dry."""
    speeds = np.arange(20.0, 301.0, 1.0)
    dry = run(z, [20.0], load=load)["mu"].values[0]
    mu = wet(z, speeds, 2e-3, load=load)["mu"].values
    below = np.nonzero(mu < 0.1 * dry)[0]
    assert below.size, "no hydroplaning up to 300 km/h"
    assert np.all(mu[below[0]:] < 0.1 * dry)             # it stays collapsed
    return speeds[below[0]]


def test_a_smooth_road_in_deep_water_hydroplanes_with_the_square_root_of_the_load():
    """Inertia: the stopped water's rho V^2 / 2 lifts the pad where it matches
    the nominal pressure, so the collapse speed scales with sqrt(load)."""
    z = profile("smooth")
    v1 = collapse_speed(z, 11.8)
    v2 = collapse_speed(z, 23.6)
    assert 30.0 < v1 < 200.0
    assert abs(v2 / v1 / np.sqrt(2.0) - 1.0) < 0.2, (v1, v2)


@pytest.mark.parametrize("kw", [
    dict(depth=10.0), dict(depth=1e-12), dict(viscosity=1e-6), dict(viscosity=10.0),
    dict(microtexture_rms=0.0), dict(microtexture_rms=0.5e-3), dict(density=0.0),
    dict(load=1e-3), dict(load=1e4)])
def test_hard_cases_stay_finite(kw):
    kw.setdefault("depth", 1e-3)
    depth = kw.pop("depth")
    r = wet(profile("fine"), [1e-6, 20.0, 300.0], depth, **kw)
    mu = r["mu"].values
    assert np.all(np.isfinite(mu)) and np.all(mu >= 0.0)
    assert np.all(r["max_balance_residual"].values < 1e-6)
    for name in ("contact_fraction", "film_load_share", "mean_water_thickness"):
        v = r[name].values
        assert np.all(np.isfinite(v)) and np.all(v >= 0.0), name
    assert np.all(r["contact_fraction"].values <= 1.0)
    assert np.all(r["film_load_share"].values <= 1.0 + 1e-6)
    assert np.all(r["film_unsettled"].values == 0)


def test_the_outputs_mean_what_they_say():
    """Issue 21's outputs per speed: the film's share of the load is its mean
    load over the pad's load; the contact fraction is the mean share of
    elements touching (the series' contact_elements over the pad's
    elements); a smooth road in deep water at speed has the film carry the
    pad (share near 1, no contact, hydroplaning) over water thicker than
    the microtexture; a textured road's contact shrinks and the film's share
    grows with speed; a nanometre of water holds at most twice itself."""
    z = profile("rough")
    r = wet(z, SPEEDS, 1e-3, series=True)
    share = r["film_load_share"].values
    np.testing.assert_allclose(share, r["mean_hydro_load"].values / 11.8, rtol=1e-14)
    n_el = r.attrs["pad_elements"]
    ce = r["contact_elements"]
    per_speed = ce.mean(dim=[d for d in ce.dims if d not in r["mu"].dims]).values
    np.testing.assert_allclose(r["contact_fraction"].values, per_speed / n_el, rtol=1e-12)
    assert np.all(np.diff(r["contact_fraction"].values) <= 1e-12)
    assert np.all(np.diff(share) >= -1e-12) and share[-1] > share[0]
    assert np.all(r["film_unsettled"].values == 0)
    water = r["mean_water_thickness"].values
    assert np.all(water > 0.0) and np.all(water < 2e-3)

    smooth = wet(profile("smooth"), [20.0, 300.0], 2e-3)
    assert smooth["film_load_share"].values[1] > 0.99
    assert smooth["contact_fraction"].values[1] < 0.01
    assert smooth["hydroplaning_fraction"].values[1] > 0.99
    assert smooth["contact_fraction"].values[0] > smooth["contact_fraction"].values[1]
    assert smooth["mean_water_thickness"].values[1] > 40e-6     # > the microtexture

    nano = wet(z, SPEEDS, 1e-9)
    assert np.all(nano["mean_water_thickness"].values <= 2e-9)


def test_the_series_hold_the_films_pressure_and_water_per_position():
    """Issue 21: with series, the Reynolds film's largest pressure and its
    water per unit area at every position; the film's load never exceeds
    its largest pressure over the pad's area, the water's mean over the
    positions is mean_water_thickness, a speed without motion has neither,
    and where the inlet is flooded its dynamic pressure
    (1 - c_1 / (2 H_in)) rho V^2 / 2 is among the nodes': the largest pressure
    reaches a good share of rho V^2 / 2 somewhere. Only the Reynolds film
    writes them."""
    z = profile("rough")
    speeds = [0.0, 20.0, 80.0]
    r = wet(z, speeds, 1e-3, series=True)
    pmax = r["film_pressure_max"].transpose("speed_kmh", ...).values
    water = r["water_thickness"].transpose("speed_kmh", ...).values
    load = r["hydro_load"].transpose("speed_kmh", ...).values
    assert np.all(np.isfinite(pmax)) and np.all(pmax >= 0.0)
    assert np.all(pmax[0] == 0.0) and np.all(water[0] == 0.0)
    area = 0.016 * 0.020
    assert np.all(load <= pmax * area * (1 + 1e-12))
    np.testing.assert_allclose(water.mean(axis=1), r["mean_water_thickness"].values,
                               rtol=1e-12)
    for j, v in enumerate(speeds[1:], start=1):
        dynamic = 0.5 * 998.2 * (v / 3.6) ** 2
        # (the wedges at the contact lands' edges can build far more, locally)
        assert pmax[j].max() > 0.5 * dynamic, (v, pmax[j].max(), dynamic)
    for model in ("kane2017", "squeeze"):
        other = run(z, [20.0], wet_model=model, depth=1e-3, series=True)
        assert "film_pressure_max" not in other and "water_thickness" not in other
    assert "film_pressure_max" not in run(z, [20.0], series=True)


@pytest.mark.parametrize("model", ["kane2017", "squeeze"])
def test_other_wet_models_resolve_no_water_and_always_settle(model):
    r = run(profile("fine"), [20.0, 80.0], wet_model=model, depth=1e-3)
    assert np.all(r["mean_water_thickness"].values == 0.0)
    assert np.all(r["film_unsettled"].values == 0)
    np.testing.assert_allclose(r["film_load_share"].values,
                               r["mean_hydro_load"].values / 11.8, rtol=1e-14)


SOLVER_CHECK = """
program check
   use pavefric_kinds, only: wp
   use pavefric_reynolds, only: reynolds_solve
   implicit none
   integer, parameter :: n = 23
   real(wp) :: gap(n), p(n), theta(n), load, u(n), r, depth, speed, sigma, a, expect, worst
   logical :: full(n), conv
   integer :: it, trial, m, max_it, bad, kind
   ! 1. random gap fields: the active set settles, p >= 0, 0 <= theta <= 1
   call random_seed(put=[(17 * m + 3, m = 1, 64)])
   max_it = 0
   bad = 0
   do trial = 1, 20000
      call random_number(u)
      call random_number(r)
      kind = int(4 * r)
      select case (kind)
      case (0); gap = 2e-3_wp * u**2
      case (1); gap = merge(0.0_wp, 1e-3_wp * u, u < 0.5_wp)
      case (2); gap = 1e-5_wp * u
      case default; gap = 0.0_wp
      end select
      call random_number(r); depth = 10.0_wp**(-9 + 7 * r)
      call random_number(r); speed = 0.1_wp + 40 * r
      call random_number(r); sigma = 10.0_wp**(-6 + 3 * r)
      call reynolds_solve(depth, 1e-3_wp, sigma, 0.016_wp, 0.02_wp, 998.2_wp, speed, gap, p, &
         & theta, full, load, it, conv)
      max_it = max(max_it, it)
      if (.not. conv .or. any(p < 0) .or. any(theta < 0) .or. any(theta > 1) .or. &
         & .not. (load >= 0 .and. load < huge(1.0_wp))) bad = bad + 1
   end do
   print *, max_it, bad
   ! 2. a uniform open gap, flooded: no wedge, the inlet's pressure decays as
   !    the discrete closed form p_m = p_in sinh((n - m) a) / sinh(n a),
   !    cosh a = 1 + 6 (ds / b)**2 with the drainage length b = L (< l)
   gap = 3e-4_wp
   call reynolds_solve(1e-2_wp, 1e-3_wp, 40e-6_wp, 0.05_wp, 0.02_wp, 1000.0_wp, 20.0_wp, gap, &
      & p, theta, full, load, it, conv)
   a = acosh(1.0_wp + 6.0_wp / real(n, wp)**2)
   worst = 0
   do m = 1, n - 1
      expect = sinh((n - m) * a) / sinh(n * a)
      worst = max(worst, abs(p(m) / p(1) * sinh((n - 1) * a) / sinh(n * a) - expect) / expect)
   end do
   print *, worst, p(1) / (sinh((n - 1) * a) / sinh(n * a)), all(full(1:n-1))
end program check
"""


WARM_CHECK = """
program warm
   use pavefric_kinds, only: wp
   use pavefric_film, only: film_step_type
   use pavefric_reynolds, only: reynolds_film
   implicit none
   integer, parameter :: n = 23
   type(reynolds_film) :: film
   type(film_step_type) :: step(1)
   real(wp) :: gap(1, n), row(n), u(n), r, wh(1), dwh(1), wh_c, dwh_c, water, pmax
   real(wp) :: water_c, pmax_c, x
   real(wp), allocatable :: work(:, :), cold(:, :)
   logical :: settled, settled_c
   integer :: trial, m, differ, kind, kinks
   film = reynolds_film(depth=1e-3_wp, eta=1e-3_wp, sigma=5e-6_wp, width=0.016_wp, &
      & length=0.02_wp, density=998.2_wp)
   call film%prepare(16.0_wp, 0.87e-3_wp, step(1))
   allocate(work(film%work_size(n), 1), cold(film%work_size(n), 1))
   work = 0
   call random_seed(put=[(11 * m + 5, m = 1, 64)])
   differ = 0
   kinks = 0
   do trial = 1, 6000
      ! a sliding pad (the penetration and the texture move a little), then
      ! now and again an unrelated field: the warm start comes from either
      call random_number(r)
      kind = merge(1, 0, r < 0.1_wp)
      if (kind == 1 .or. trial == 1) then
         call random_number(u)
      else
         call random_number(row)
         u = cshift(u, 1) + 0.02_wp * (row - 0.5_wp)
      end if
      call random_number(x)
      gap(1, :) = max(0.0_wp, 1.5e-4_wp * (u + 0.3_wp * x - 0.5_wp))
      call film%loads(1, n, step, gap, [.true.], wh, dwh, work)
      row = gap(1, :)
      call film%load(step(1), row, wh_c, dwh_c)
      if (wh(1) /= wh_c) differ = differ + 1
      if (.not. (dwh(1) >= 0 .and. dwh(1) < huge(1.0_wp))) differ = differ + 1
      if (dwh(1) /= dwh_c) kinks = kinks + 1
      call film%report(step(1), row, settled, water, pmax, work(:, 1))
      cold = 0
      call film%report(step(1), row, settled_c, water_c, pmax_c, cold(:, 1))
      if (water /= water_c .or. pmax /= pmax_c .or. (settled .neqv. settled_c)) &
         & differ = differ + 1
      ! a report on a field the last load was not on (it keeps that load's
      ! solution for the report at the same field: this one solves)
      if (mod(trial, 3) == 0) then
         call film%loads(1, n, step, gap, [.true.], wh, dwh, work)
         row = gap(1, :) * 1.01_wp
         call film%report(step(1), row, settled, water, pmax, work(:, 1))
         cold = 0
         call film%report(step(1), row, settled_c, water_c, pmax_c, cold(:, 1))
         if (water /= water_c .or. pmax /= pmax_c .or. (settled .neqv. settled_c)) &
            & differ = differ + 1
      end if
   end do
   print *, differ, kinks, work(1, 1)
end program warm
"""


SLOPE_CHECK = """
program slope
   use pavefric_kinds, only: wp
   use pavefric_film, only: film_step_type
   use pavefric_reynolds, only: reynolds_film
   implicit none
   integer, parameter :: n = 23
   type(reynolds_film) :: film
   type(film_step_type) :: step
   real(wp) :: d(n), u(n), r, x, h, sigma, wh, dwh, w_up, w_down, dum, ahead, behind
   integer :: trial, m, smooth, bad, negative
   call random_seed(put=[(7 * m + 1, m = 1, 64)])
   smooth = 0
   bad = 0
   negative = 0
   do trial = 1, 20000
      call random_number(u)
      d = 1.0e-3_wp * u**2
      d = d - minval(d)
      call random_number(r)
      sigma = 10.0_wp**(-6 + 2 * r)
      film = reynolds_film(depth=1e-3_wp, eta=1e-3_wp, sigma=sigma, width=0.016_wp, &
         & length=0.02_wp, density=998.2_wp)
      call random_number(r)
      call film%prepare(1.0_wp + 25 * r, 1e-3_wp, step)
      call random_number(r)
      x = 4e-4_wp * r
      call film%load(step, max(0.0_wp, d - x), wh, dwh)
      if (.not. (dwh >= 0 .and. dwh < huge(1.0_wp))) bad = bad + 1
      ! a difference of the load itself, x -/+ h, away from the touching
      ! points (the load jumps there)
      h = 1e-3_wp * sigma
      if (any(abs(d - x) < 3 * h)) cycle
      call film%load(step, max(0.0_wp, d - x - h), w_up, dum)
      call film%load(step, max(0.0_wp, d - x + h), w_down, dum)
      ahead = (w_up - wh) / h
      behind = (wh - w_down) / h
      ! smooth here: both sides' slopes agree (no node changed its state)
      if (abs(ahead - behind) > 1e-4_wp * max(abs(ahead), abs(behind))) cycle
      if (ahead < 0 .and. behind < 0) then
         ! the film's load falls as the pad sinks: the slope is clipped at 0
         negative = negative + 1
         if (dwh > 1e-6_wp * wh / sigma) bad = bad + 1
         cycle
      end if
      smooth = smooth + 1
      if (abs(dwh - 0.5_wp * (ahead + behind)) > 1e-4_wp * abs(ahead) + 1e-6_wp * wh / sigma) &
         & bad = bad + 1
   end do
   print *, smooth, bad, negative
end program slope
"""


def _compile_and_run(tmp_path, source):
    from test_api import _run, pkg_config

    bin_dir = Path(sys.executable).parent
    pcdir = _run([bin_dir / "pavefric-config", "--pkgconfigdir"]).stdout.strip()
    env = dict(os.environ, PKG_CONFIG_PATH=pcdir, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    src = tmp_path / "check.f90"
    src.write_text(source)
    exe = tmp_path / "check"
    flags = pkg_config(env, "--cflags") + pkg_config(env, "--libs")
    _run(["gfortran", "-o", exe, src, *flags], env=env, cwd=tmp_path)
    return _run([exe], env=dict(env, LD_LIBRARY_PATH=""), cwd=tmp_path).stdout.split()


def test_the_warm_start_changes_no_number(tmp_path):
    """The film's active set starts from the lane's last solve (its
    workspace, film%loads and film%report): on 6,000 gap fields of a sliding
    pad, with unrelated fields among them, the load and the report are the
    cold solve's to the bit (the complementarity solution does not depend on
    where the iteration starts). The report on the field of the last load
    reads that load's solution, kept in the workspace; on any other field
    (every third trial, the field scaled by 1.01) it solves, and both are
    the cold solve's. The derivative (the balance's Newton step)
    is taken at the settled set, which is not unique at a node on the
    boundary (p = 0 and theta = 1 at once, a kink of the load): there the
    warm and the cold solve may take the two sides' slopes (a few fields in
    a thousand; the balance is bracketed and converges either way)."""
    out = _compile_and_run(tmp_path, WARM_CHECK)
    differ, kinks, warm = int(out[0]), int(out[1]), float(out[2])
    assert differ == 0
    assert kinks <= 12, kinks
    assert warm == 1.0          # the last solve settled: warm


def test_the_load_slope_is_the_loads_derivative(tmp_path):
    """The film's d(load)/d(penetration) is the settled system
    differentiated (analytic cell-term slopes, one more tridiagonal solve;
    before 2026-11-28 a difference at a narrowed gap with the cell terms
    evaluated again). Independent check, compiled against the installed
    modules: on 20,000 random gap fields (sigma 1-100 um, 1-26 m/s), wherever
    the load is smooth (the slopes ahead and behind, 1e-3 sigma away, agree
    to 1e-4), the slope equals their mean to 1e-4 (plus 1e-6 of the load's
    scale, load / sigma, for slopes near 0); where the load falls as the pad
    sinks (the film's defect, docs/model.md) it is clipped at 0 (to that
    scale); it is always finite and >= 0."""
    smooth, bad, negative = (int(v) for v in _compile_and_run(tmp_path, SLOPE_CHECK))
    assert bad == 0
    assert smooth > 5000 and negative > 100, (smooth, negative)


def test_a_root_at_the_films_jump_takes_few_evaluations():
    """Where an element touches, the film's drainage lengths change and its
    load jumps; a balance whose root lies at such a jump used to halve its
    bracket to adjacent doubles (about 50 evaluations; 19 % of the
    positions at 80 km/h on this profile, 13.8 evaluations per position on
    average). The bracket is now split at the touching points first
    (pavefric_balance: breakpoint_split): at most 7 per position at every
    speed here, and every position still balanced (the jump's
    intermediate load) within wet_tolerance."""
    z = np.tile(spectral_profile(1024, DX, rms=0.5e-3, skew=-0.3, seed=22), 2)
    speeds = [10.0, 20.0, 40.0, 80.0]
    ds = pavefric.simulate(z, DX, speeds, error_estimate=False, time_scheme="euler",
                           min_contacts=0, depth=1e-3, wet_model="reynolds")
    positions = ds.attrs["averaged_positions"] + ds.attrs["spinup_positions"]
    per_position = ds["bearing_evaluations"].values / positions
    assert np.all(per_position < 7.0), per_position
    assert np.all(ds["max_balance_residual"].values <= 1e-14)
    assert np.all(ds["film_unsettled"].values == 0)


def test_the_solver_settles_and_meets_its_closed_form(tmp_path):
    """The film's solver, compiled against the installed modules: on 20,000
    random gap fields (depths 1 nm to 1 cm, 0.1 to 40 m/s, sigma 1 um to
    1 mm) the active set settles, p >= 0 and 0 <= theta <= 1; on a uniform
    open gap the inlet's dynamic pressure decays into the film as the
    discrete closed form, from p_in = (1 - c / (2 H_in)) rho V^2 / 2."""
    from scipy.special import erfc

    out = _compile_and_run(tmp_path, SOLVER_CHECK)
    max_it, bad = int(out[0]), int(out[1])
    assert bad == 0 and max_it <= 40
    worst, p_in, all_full = float(out[2]), float(out[3]), out[4]
    assert worst < 1e-9 and all_full == "T"
    g, sigma = 3e-4, 40e-6
    hs = g / sigma
    h_t = g * 0.5 * erfc(-hs / np.sqrt(2)) + sigma * np.exp(-0.5 * hs * hs) / np.sqrt(2 * np.pi)
    c = h_t + sigma * 1.126 * np.exp(-0.25 * hs)
    assert p_in == pytest.approx((1 - c / (2 * 1e-2)) * 0.5 * 1000.0 * 20.0**2, rel=1e-9)


def test_the_film_load_share_is_a_share_on_a_hydroplaning_pad():
    """Where the film carries the whole pad, the share of the load is 1, not
    1 + 4e-15 (the mean of loads that each balance to W rounds past it; an
    attack found 1 + 3.6e-15 on a 100 m wide pad and 1 + 3.1e-15 on a flat
    road at 1e4 km/h)."""
    from pavefric.surfaces import spectral_profile

    z = spectral_profile(256, DX, rms=0.5e-3, seed=3)
    wide = pavefric.simulate(z, DX, [20.0, 60.0], wet_model="reynolds", depth=1e-3,
                             width=100.0, mu_loc=0.6)["film_load_share"].values
    flat = pavefric.simulate(np.zeros(256), DX, [0.0, 1e4], wet_model="reynolds",
                             depth=1e-3, mu_loc=0.6)["film_load_share"].values
    for share in (wide, flat):
        assert np.all((share >= 0.0) & (share <= 1.0)), share - 1
    assert np.all(wide == 1.0) and flat[1] == 1.0 and flat[0] == 0.0


def test_the_roots_study_is_the_paragraph_it_regenerates():
    """docs/model.md's "more than one root" paragraph cites `python -m
    pavefric.studies.reynolds_roots`: its first rows are the paragraph's
    figures (mu and film_load_share at substeps 1 and 16), and the jump it
    names (0.5 mm at 16 substeps) is the Reynolds film's alone: the dry pad
    and the other wet models move under 2e-5 m in a step. When the film's
    defect is mended, this test fails and the paragraph is rewritten."""
    import re

    from pavefric.studies import reynolds_roots as study

    z = spectral_profile(**study.PROFILE)
    text = (Path(__file__).resolve().parents[1] / "docs" / "model.md").read_text()
    flat = " ".join(text.split())
    said = re.search(r"shrinks: mu ([0-9.]+), ([0-9.]+), .*? and `film_load_share` "
                     r"([0-9.]+), ([0-9.]+),", flat)
    assert said, "the paragraph's figures are not where this test reads them"
    rows = study.substep_table(z, (1, 16))
    # to the paragraph's three decimals, with room for the last bits: at 16
    # substeps a change of 1e-15 in the heights moves the share by 3e-4 (the
    # root the balance takes is that sensitive: the defect itself)
    for (s, mu, share, *_), doc_mu, doc_share in zip(rows, said.group(1, 2),
                                                     said.group(3, 4)):
        assert abs(mu - float(doc_mu)) < 2e-3, (s, mu, doc_mu)
        assert abs(share - float(doc_share)) < 2e-3, (s, share, doc_share)
    jumps = {name: jump for s, name, mu, jump in study.model_jumps(z, (16,))}
    assert 4e-4 < jumps["reynolds"] < 6e-4
    assert max(jumps["dry"], jumps["kane2017"], jumps["squeeze"]) < 2e-5


def test_a_hydroplaning_film_holds_about_twice_the_water_on_the_road():
    """mean_water_thickness on a pad the film carries (400 km/h): the water
    brought, V H_in per unit width, moves under the pad at V/2 (the road at
    V, the pad at rest), so it is about twice as thick as on the road; an
    attack took 2.2 times the depth for a defect (docs/outputs.md)."""
    for name, depth in (("smooth", 1e-3), ("rough", 1e-4), ("rough", 1e-3)):
        ds = wet(profile(name), [400.0], depth)
        assert float(ds["film_load_share"][0]) > 0.5
        ratio = float(ds["mean_water_thickness"][0]) / depth
        assert 1.5 < ratio < 2.3, (name, depth, ratio)
    # at walking pace the same water barely fills the texture under the pad
    slow = wet(profile("rough"), [20.0], 1e-3)
    assert float(slow["mean_water_thickness"][0]) < 0.2e-3


def test_one_positions_water_may_exceed_twice_the_depth_where_the_mean_does_not():
    """docs/outputs.md, water_thickness: the film is solved quasi-steady at
    each position (no storage term, docs/model.md), so nothing holds the
    water in the valleys under the pad to what entered at its leading edge:
    on a closed white-noise profile (RMS 2 mm) at 300 km/h one position's
    water reaches several times the depth (an attack saw 6.5 times), while
    its mean over the positions stays within about twice the depth, as the
    flow through the pad says (the figures the description quotes)."""
    z = np.random.default_rng(1).normal(0.0, 2e-3, 1024)
    ds = wet(z, [300.0], 1e-3, series=True)
    water = ds["water_thickness"].values.ravel() / 1e-3
    mean = float(ds["mean_water_thickness"][0]) / 1e-3
    assert np.all(np.isfinite(water)) and water.min() >= 0.0
    assert 5.0 < water.max() < 9.0, water.max()          # 6.2
    assert mean < 2.3, mean


TRIDIAGONAL_CHECK = """
program check
   use pavefric_kinds, only: wp
   use pavefric_tridiagonal, only: tridiagonal_factor, tridiagonal_solve
   implicit none
   integer, parameter :: nmax = 40
   real(wp), dimension(nmax) :: dl, d, du, l0, d0, u0, b, x, r, kd, runf, c, full
   real(wp) :: worst, scale, u(6 * nmax), piv, growth
   integer :: trial, n, i, info, kind, rhs, singular, would_swap
   call random_seed(put=[(31 * i + 7, i = 1, 64)])
   worst = 0.0_wp
   growth = 0.0_wp
   would_swap = 0
   do trial = 1, 3000
      call random_number(u)
      n = 1 + mod(trial, nmax)
      kind = mod(trial, 3)
      select case (kind)
      case (0, 1)
         ! column diagonally dominant, entries of both signs (kind 1: over
         ! 12 decades, column by column)
         l0(1:n) = u(1:n) - 0.5_wp
         u0(1:n) = u(nmax + 1:nmax + n) - 0.5_wp
         if (kind == 1) then
            do i = 1, n
               l0(i) = l0(i) * 10.0_wp**(12 * u(2 * nmax + i) - 6)
               if (i < n) u0(i) = u0(i) * 10.0_wp**(12 * u(2 * nmax + i + 1) - 6)
            end do
         end if
         do i = 1, n
            d0(i) = 0.0_wp
            if (i < n) d0(i) = d0(i) + abs(l0(i))
            if (i > 1) d0(i) = d0(i) + abs(u0(i - 1))
            d0(i) = sign(d0(i) * (1.0_wp + u(3 * nmax + i)) + 1e-300_wp, u(4 * nmax + i) - 0.5_wp)
         end do
      case default
         ! the Reynolds film's pattern (pavefric_reynolds, assemble_and_solve):
         ! full nodes -kd beside kd + kd' + leak; partial nodes -c/2 on the
         ! diagonal and c/2 below (weakly dominant); coefficients over 12 decades
         do i = 1, n + 1
            kd(i) = 10.0_wp**(12 * u(i) - 6)
            runf(i) = 10.0_wp**(-6 * u(nmax + i))
            c(i) = 10.0_wp**(6 * u(2 * nmax + i) - 3)
         end do
         full(1:n) = merge(1.0_wp, 0.0_wp, u(3 * nmax + 1:3 * nmax + n) > 0.4_wp)
         do i = 1, n
            if (full(i) > 0.5_wp) then
               d0(i) = kd(i) + kd(i + 1) + kd(i) * runf(i) + kd(i + 1) * runf(i + 1)
            else
               d0(i) = -0.5_wp * c(i + 1)
            end if
            if (i > 1) l0(i - 1) = merge(-kd(i), 0.5_wp * c(i), full(i - 1) > 0.5_wp)
            if (i < n) u0(i) = merge(-kd(i + 1), 0.0_wp, full(i + 1) > 0.5_wp)
         end do
      end select
      ! where partial pivoting would swap rows (the entry below a pivot the
      ! larger), and the growth of the pivots, in an elimination of this test
      dl = l0; d = d0; du = u0
      do i = 1, n - 1
         piv = d(i)
         if (abs(dl(i)) > abs(piv)) would_swap = would_swap + 1
         d(i + 1) = d(i + 1) - dl(i) / piv * du(i)
      end do
      growth = max(growth, maxval(abs(d(1:n))) / (maxval(abs(d0(1:n))) + maxval(abs(l0(1:n))) &
         & + maxval(abs(u0(1:n)))))
      dl = l0; d = d0; du = u0
      call tridiagonal_factor(n, dl, d, du, info)
      if (info /= 0) stop 3
      ! two right sides with the same factors
      do rhs = 1, 2
         call random_number(b(1:n))
         x(1:n) = b(1:n)
         call tridiagonal_solve(n, dl, d, du, x)
         ! the residual of the original system, scaled (backward stability)
         do i = 1, n
            r(i) = d0(i) * x(i) - b(i)
            if (i > 1) r(i) = r(i) + l0(i - 1) * x(i - 1)
            if (i < n) r(i) = r(i) + u0(i) * x(i + 1)
         end do
         scale = maxval(abs(d0(1:n))) + maxval(abs(l0(1:n))) + maxval(abs(u0(1:n)))
         worst = max(worst, maxval(abs(r(1:n))) / (scale * maxval(abs(x(1:n))) + maxval(abs(b(1:n)))))
      end do
   end do
   ! a singular matrix: its third column zero
   n = 5
   dl(1:4) = [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
   d(1:5) = [4.0_wp, 4.0_wp, 0.0_wp, 4.0_wp, 4.0_wp]
   du(1:4) = [1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp]
   call tridiagonal_factor(n, dl, d, du, singular)
   ! a 1 x 1 system
   d(1) = 4.0_wp
   call tridiagonal_factor(1, dl, d, du, info)
   x(1) = 2.0_wp
   call tridiagonal_solve(1, dl, d, du, x)
   print '(es12.4, i8, es12.4, i8, es25.17)', worst, would_swap, growth, singular, x(1)
end program check
"""


def test_the_tridiagonal_solver_solves_and_reuses_its_factors(tmp_path):
    """The film's tridiagonal solver (src/base/pavefric_tridiagonal.f90,
    elimination without pivoting, for column diagonally dominant matrices,
    its factors kept for a second right side): on 3,000 random such systems
    of 1-40 rows (entries of both signs, over 12 decades, and the Reynolds
    film's pattern of full and partial nodes, whose partial columns are
    only weakly dominant) both right sides solved with one factorisation
    leave a residual of rounding size (backward stability: |A x - b| <=
    1e-13 (|A| |x| + |b|)); partial pivoting would have swapped no row and
    the pivots stay within twice the matrix's entries (the reason no
    pivoting is needed); a matrix with a zero column (after elimination, a
    zero pivot) is reported singular at that row; a 1 x 1 system divides."""
    out = _compile_and_run(tmp_path, TRIDIAGONAL_CHECK)
    worst, would_swap, growth = float(out[0]), int(out[1]), float(out[2])
    singular, one = int(out[3]), float(out[4])
    assert worst <= 1e-13, worst
    assert would_swap == 0
    assert growth <= 2.0, growth
    assert singular == 3
    assert one == 0.5


def jump_warnings(ds):
    return [w for w in str(ds.attrs.get("warnings", "")).splitlines()
            if w.startswith("the wet balance's root left the range")]


def test_a_root_that_leaves_the_clearances_range_is_counted_and_said():
    """film_root_jumps (docs/model.md, "The film's balance has more than one
    root"): under a load monotone in the penetration and in each gap, the
    balance's root moves from one position to the next within the range of
    the clearances' moves; the Reynolds film's root leaves it where its load
    is not monotone, and on the paragraph's profile it keeps leaving it as
    the step shrinks (the jumps do not vanish: mu has no converged value).
    The run says so in a warning recorded in the output. Each speed's count
    is its own, whichever speeds share the call."""
    import warnings

    from pavefric.studies import reynolds_roots as study

    z = spectral_profile(**study.PROFILE)
    counts = []
    for s in (16, 256):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            ds = wet(z, [20.0, 60.0], study.DEPTH, substeps=s, min_contacts=0)
        counts.append(ds["film_root_jumps"].values)
        said = jump_warnings(ds)
        assert len(said) == 1, said
        assert "(film_root_jumps)" in said[0] and "no converged value" in said[0]
        assert any("(film_root_jumps)" in str(w.message) for w in caught)
    assert np.all(counts[0] > 0), counts
    assert np.all(counts[1] >= counts[0]), counts
    alone = wet(z, [60.0], study.DEPTH, substeps=16, min_contacts=0)
    assert int(alone["film_root_jumps"].values[0]) == int(counts[0][1])
    # the monotone models are not counted, and say nothing
    for model in ("kane2017", "squeeze"):
        other = run(z, [20.0, 60.0], wet_model=model, depth=study.DEPTH, substeps=16,
                    min_contacts=0)
        assert np.all(other["film_root_jumps"].values == 0)
        assert jump_warnings(other) == []


def test_a_root_that_left_its_range_in_the_estimates_pass_is_said():
    """The default run (one step per sample) can have no such position where
    its error estimate's pass at half the step has some: its estimate then
    rests on a balance that jumps (on the paper's GSS surface the estimate
    was a quarter of the actual error, docs/accuracy.md), and the one
    warning says that the pass that had them was not the reported one. On
    this profile at 60 km/h the pass at substeps = 2 has 16 (this machine)
    where the run has none; the test holds the warning to whichever
    happens."""
    z = spectral_profile(256, DX, rms=0.5e-3, seed=1)
    one = wet(z, [60.0], 1e-3, min_contacts=0, time_scheme="euler")
    two = wet(z, [60.0], 1e-3, min_contacts=0, time_scheme="euler", substeps=2)
    n1, n2 = int(one["film_root_jumps"].values[0]), int(two["film_root_jumps"].values[0])
    assert n2 > 0
    default = pavefric.simulate(z, DX, [60.0], closed=True, mu_loc=0.6, wet_model="reynolds",
                                depth=1e-3, min_contacts=0)
    assert int(default["film_root_jumps"].values[0]) == n1     # the run's own pass
    said = jump_warnings(default)
    assert len(said) == 1, said
    if n1 > 0:
        assert f"{n1} averaged position" in said[0] and "(film_root_jumps)" in said[0]
    else:
        assert f"{n2} averaged position" in said[0]
        assert "in a pass the run made to refine or estimate" in said[0]
    # the estimate's own warning then does not advise a tolerance
    estimate = [w for w in str(default.attrs["warnings"]).splitlines()
                if w.startswith("mu is estimated to be off")]
    assert len(estimate) == 1 and "tolerance (e.g. 1e-3)" not in estimate[0], estimate
    assert "neither the estimate nor &numerics tolerance bounds" in estimate[0]
