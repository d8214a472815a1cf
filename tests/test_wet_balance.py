"""The paper's wet balance (src/physics/pavefric_balance.f90, wet_roots on
the pseudo-bearing: Newton on each piece's formula, a pass over the elements
to check it; docs/performance.md, "How the core gets there"), against an
independent slow reference: bisection of the balance written out element by
element, on random pads of six lanes, including films that close, gaps that
span eight decades and guesses outside the bracket."""
from test_reynolds import _compile_and_run

CHECK = """
module plain_bearing_mod
   use pavefric_film, only: pseudo_bearing_film
   implicit none
   !> The same film, saying its sums do not suffice: the balance then takes
   !> a pass over the elements at every Newton step (the general path).
   type, extends(pseudo_bearing_film) :: plain_bearing
   contains
      procedure :: sums_suffice => no
   end type plain_bearing
contains
   pure logical function no(self)
      class(plain_bearing), intent(in) :: self
      no = .false.
   end function no
end module plain_bearing_mod

program check
   use pavefric_kinds, only: wp, i8
   use pavefric_film, only: pseudo_bearing_film, film_step_type
   use pavefric_balance, only: dry_roots, wet_roots
   use plain_bearing_mod, only: plain_bearing
   implicit none
   type(plain_bearing) :: plain
   integer, parameter :: nl = 6, n = 23
   type(pseudo_bearing_film) :: film
   type(film_step_type) :: steps(nl)
   real(wp) :: d(nl, n), kel(nl), s(nl), x(nl), x0(nl), xd(nl), wh(nl), gaps(nl, n)
   real(wp) :: fwork(1, nl), work(n), dl(n), u(n), r(nl), load, tol, lo, hi, mid, f, x_ref
   real(wp) :: spread, worst_f, worst_x, worst_fb
   integer(i8) :: evaluations(nl), passes(nl), passes_total, lanes_total, plain_passes(nl), &
      & plain_total
   real(wp) :: x_plain(nl), wh_plain(nl)  ! (the general path's root, not checked here)
   logical :: wet(nl)
   integer :: trial, j, k, bad, nan, fallback, m
   call random_seed(put=[(11 * m + 3, m = 1, 64)])
   load = 1000.0_wp
   tol = 1.0e-14_wp
   bad = 0
   nan = 0
   fallback = 0
   worst_f = 0.0_wp
   worst_x = 0.0_wp
   worst_fb = 0.0_wp
   passes_total = 0
   plain_total = 0
   lanes_total = 0
   do trial = 1, 3000
      call random_number(r)
      film = pseudo_bearing_film(depth=10.0_wp**(-6 + 3 * r(1)), eta=1e-3_wp, &
         & alpha=10.0_wp**(-1 + 4 * r(2)), beta=1.75_wp, width=0.016_wp, length=0.02_wp)
      do j = 1, nl
         call random_number(u)
         call random_number(spread)
         d(j, :) = 10.0_wp**(-7 + 4 * spread) * u**(1 + 3 * spread)
         d(j, :) = d(j, :) - minval(d(j, :))
         call random_number(spread)
         call film%prepare(0.5_wp + 40 * spread, 1e-3_wp, steps(j))
         call random_number(spread)
         kel(j) = load / (10.0_wp**(-7 + 4 * spread))
      end do
      s = load / kel
      call dry_roots(nl, n, d, s, [(-1.0_wp, j = 1, nl)], xd, work, dl)
      call random_number(r)
      do j = 1, nl
         wet(j) = r(j) > 0.1_wp
         ! guesses: inside the bracket, at its ends, beyond it, none
         select case (mod(trial + j, 4))
         case (0)
            x0(j) = xd(j) * r(j)
         case (1)
            x0(j) = xd(j) * (1.0_wp + r(j))
         case (2)
            x0(j) = -huge(1.0_wp)
         case default
            x0(j) = xd(j) * (1.0_wp - 1e-9_wp * r(j))
         end select
      end do
      x = xd
      ! the general path: Newton with a pass per step
      plain%pseudo_bearing_film = film
      x_plain = xd
      plain_passes = 0
      call wet_roots(nl, n, d, kel, load, plain, steps, wet, tol, x0, x_plain, wh_plain, &
         & plain_passes, gaps, fwork)
      ! the sums' path: Newton on each piece's formula, a pass to check it
      evaluations = 0
      call wet_roots(nl, n, d, kel, load, film, steps, wet, tol, x0, x, wh, evaluations, gaps, &
         & fwork)
      passes = evaluations
      do j = 1, nl
         if (.not. wet(j)) then
            if (x(j) /= xd(j) .or. evaluations(j) /= 0) bad = bad + 1
            cycle
         end if
         if (x(j) /= x(j) .or. wh(j) /= wh(j) .or. wh(j) < 0.0_wp) nan = nan + 1
         if (passes(j) < 1 .or. passes(j) > evaluations(j)) bad = bad + 1
         ! the reference: bisection of the balance on [lower bound, dry root]
         lo = min(0.0_wp, film%lower_bound(steps(j), d(j, :)))
         hi = xd(j)
         do k = 1, 400
            mid = 0.5_wp * (lo + hi)
            if (mid <= lo .or. mid >= hi) exit
            if (balance(j, mid) > 0.0_wp) then
               hi = mid
            else
               lo = mid
            end if
         end do
         x_ref = hi
         f = balance(j, x(j))
         if (abs(f) <= tol * load) then
            worst_f = max(worst_f, abs(f) / load)
            passes_total = passes_total + passes(j)
            plain_total = plain_total + plain_passes(j)
            lanes_total = lanes_total + 1
         else
            ! where no double balances to tol (a film closing, or carrying
            ! the lifted pad alone: f of x then moves in steps of its
            ! rounding, through the mean gap, larger than the tolerance),
            ! the bisected root to that rounding
            fallback = fallback + 1
            worst_fb = max(worst_fb, abs(x(j) - x_ref) / max(xd(j), maxval(d(j, :))))
         end if
         ! the root is unique (both terms rise with x): the reference's,
         ! to the x the tolerance allows
         worst_x = max(worst_x, abs(x(j) - x_ref) / max(xd(j), tiny(1.0_wp)))
      end do
   end do
   print *, bad, nan, fallback, worst_f, worst_x, worst_fb, &
      & real(passes_total, wp) / real(lanes_total, wp), &
      & real(plain_total, wp) / real(lanes_total, wp)
contains
   !> f(x) written out: the pad's push element by element and Eq. 15 of
   !> the gap field (film%load, not the sums the balance uses).
   real(wp) function balance(j, xx)
      integer, intent(in) :: j
      real(wp), intent(in) :: xx
      real(wp) :: push, w, dw
      integer :: i
      push = 0.0_wp
      do i = 1, n
         push = push + max(0.0_wp, xx - d(j, i))
      end do
      call film%load(steps(j), max(0.0_wp, d(j, :) - xx), w, dw)
      balance = kel(j) * push + w - load
   end function balance
end program check
"""


def test_the_wet_root_is_the_bisected_balances(tmp_path):
    """On 3,000 random six-lane pads (gaps from 0.1 um to 1 mm, water from
    1 um to 1 mm, alpha 0.1 to 1000, speeds 0.5-40 m/s, pads from a feather
    to a rock, guesses anywhere): every wet root balances the load to the
    tolerance 1e-14 W written out element by element, or, where no double
    does (a film closing, or carrying the lifted pad alone), lies within
    1e-10 of the largest clearance of the bisected root (measured: 7.4e-12;
    the Newton with a pass per step gave 8.2e-12); no NaN; the lanes without
    a film keep their dry root and count no evaluation. Every root is the
    bisected one to 1e-9 of the dry penetration (measured 1.4e-10). The
    second group was 2,937 of the about 16,200 wet lanes when every root was
    checked by a pass, and is 3,712 since a root of a piece's formula with
    no breakpoint between is taken as it is: the formula and the element by
    element sum round f differently, by about 1e-15 W, which at a tolerance
    of 1e-14 W moves some roots from one group to the other. Newton on each
    piece's formula takes 2.0 passes over the elements (with the film's
    load) per root on these pads (3.0 when every root was checked), where
    the general path (a pass per Newton step, the same film saying its sums
    do not suffice) takes 8.2: the test asks at most half."""
    out = _compile_and_run(tmp_path, CHECK)
    bad, nan, fallback = (int(v) for v in out[:3])
    worst_f, worst_x, worst_fb, passes, plain_passes = (float(v) for v in out[3:8])
    assert bad == 0
    assert nan == 0
    assert worst_f <= 1e-14
    assert worst_x <= 1e-9, worst_x
    assert worst_fb <= 1e-10, worst_fb
    assert 0 < fallback < 4000, fallback
    assert passes <= 0.5 * plain_passes, (passes, plain_passes)


LOADS_CHECK = """
program check
   use pavefric_kinds, only: wp, lanes
   use pavefric_film, only: pseudo_bearing_film, film_step_type
   use pavefric_bearing, only: hydro_load
   implicit none
   type(pseudo_bearing_film) :: film
   integer, parameter :: nmax = 12, n = 23
   type(film_step_type) :: steps(nmax)
   real(wp) :: total(nmax), n_open(nmax), wh(nmax), dwh(nmax), w, dw, r(nmax)
   logical :: active(nmax)
   integer :: trial, j, nl, differ, touched
   call random_seed(put=[(7 * j + 1, j = 1, 64)])
   differ = 0
   touched = 0
   do trial = 1, 2000
      nl = 1 + mod(trial, nmax)                  ! 1 to 12 films: beyond the 8 lanes too
      call random_number(r)
      film = pseudo_bearing_film(depth=10.0_wp**(-6 + 3 * r(1)), eta=1e-3_wp, &
         & alpha=10.0_wp**(-1 + 4 * r(2)), beta=1.75_wp, width=0.016_wp, length=0.02_wp)
      call random_number(r)
      do j = 1, nl
         call film%prepare(0.5_wp + 40 * r(j), 1e-3_wp, steps(j))
      end do
      call random_number(r)
      ! mean gaps from a film closing to none (e = a - 1 from 1e-3 to 1e12, and
      ! above H_in), each branch of Eq. 15's evaluation
      total = n * film%depth * 10.0_wp**(-12 + 13 * r)
      call random_number(r)
      n_open = real(floor(r * n) + 1, wp)
      call random_number(r)
      active = r > 0.2_wp
      wh = -1.0_wp
      dwh = -1.0_wp
      call film%loads_of_sums(nl, n, steps(1:nl), total(1:nl), n_open(1:nl), active(1:nl), &
         & wh(1:nl), dwh(1:nl))
      do j = 1, nl
         if (.not. active(j)) then
            if (wh(j) /= -1.0_wp .or. dwh(j) /= -1.0_wp) touched = touched + 1
            cycle
         end if
         call hydro_load(steps(j)%coef(1), film%depth, total(j) / real(n, wp), w, dw)
         if (wh(j) /= w .or. dwh(j) /= -(dw * n_open(j) / real(n, wp))) differ = differ + 1
      end do
   end do
   print *, differ, touched, lanes
end program check
"""


def test_the_lanes_film_loads_are_hydro_loads(tmp_path):
    """The paper's bearing evaluates Eq. 15 for all of a step's lanes in one
    call, in line, from the scales P / H_in**2 and P / H_in**3 its step
    keeps (film%loads_of_sums, hydro_loads): on 2,000 random calls of 1 to 12
    films (beyond the balance's 8 lanes, which take the one-at-a-time path),
    mean gaps from a closing film to none, every active film's load and
    derivative are hydro_load's to the bit and the inactive ones are left
    as they were."""
    out = _compile_and_run(tmp_path, LOADS_CHECK)
    differ, touched, lanes = (int(v) for v in out[:3])
    assert lanes == 8
    assert differ == 0
    assert touched == 0


# the first program's module (the bearing saying its sums do not suffice)
ENGAGE_CHECK = CHECK[:CHECK.index("program check")] + """
program check
   use pavefric_kinds, only: wp, lanes
   use pavefric_film, only: pseudo_bearing_film, film_step_type
   use pavefric_balance, only: engaged_lanes, gap_field
   use plain_bearing_mod, only: plain_bearing
   implicit none
   type(pseudo_bearing_film) :: film
   type(plain_bearing) :: plain
   integer, parameter :: n = 23
   type(film_step_type) :: steps(lanes)
   real(wp) :: d(lanes, n), x(lanes), sum_d(lanes), sum_p(lanes), r(lanes), dl(n), gap(n)
   real(wp) :: row(n)
   logical :: mask(lanes), wet(lanes), wet_p(lanes)
   integer :: trial, j, nl, differ, bound_differ, engaged, total
   call random_seed(put=[(5 * j + 3, j = 1, 64)])
   differ = 0
   bound_differ = 0
   engaged = 0
   total = 0
   do trial = 1, 3000
      nl = 1 + mod(trial, lanes)
      call random_number(r)
      film = pseudo_bearing_film(depth=10.0_wp**(-5 + 2 * r(1)), eta=1e-3_wp, alpha=12.0_wp, &
         & beta=1.75_wp, width=0.016_wp, length=0.02_wp)
      plain = plain_bearing(depth=film%depth, eta=1e-3_wp, alpha=12.0_wp, beta=1.75_wp, &
         & width=0.016_wp, length=0.02_wp)
      do j = 1, nl
         call film%prepare(20.0_wp, 1e-3_wp, steps(j))
      end do
      ! clearances spanning a film that fills the valleys and one that does not
      call random_number(d)
      d = d * film%depth * 10.0_wp**(-1 + 2 * mod(trial, 3))
      d(:, 1 + mod(trial, n)) = 0.0_wp
      call random_number(x)
      x = x * maxval(d)
      call random_number(r)
      mask = r > 0.2_wp
      call engaged_lanes(nl, n, d(1:nl, :), x(1:nl), film, steps(1:nl), mask(1:nl), &
         & wet(1:nl), dl, gap, sum_d(1:nl))
      call engaged_lanes(nl, n, d(1:nl, :), x(1:nl), plain, steps(1:nl), mask(1:nl), &
         & wet_p(1:nl), dl, gap, sum_p(1:nl))
      do j = 1, nl
         total = total + 1
         ! the field's answer, written out
         row = d(j, :)
         call gap_field(row, x(j), gap)
         if (wet(j) .neqv. (mask(j) .and. film%engages(steps(j), gap))) differ = differ + 1
         if (wet(j) .neqv. wet_p(j)) differ = differ + 1
         if (wet(j)) engaged = engaged + 1
         if (mask(j) .and. film%lower_bound_of_sum(steps(j), n, sum_d(j)) /= &
            & film%lower_bound(steps(j), row)) bound_differ = bound_differ + 1
      end do
   end do
   print *, differ, bound_differ, engaged, total
end program check
"""


def test_the_lanes_engage_as_each_field_does(tmp_path):
    """Whether the paper's bearing engages at the dry root is decided for
    all lanes at once from their gaps' sums (engaged_lanes, the film's
    engages_of_sums), and its lower bound from each lane's sum of the
    clearances (lower_bound_of_sum): on 3,000 random pads of 1 to 8 lanes,
    films that fill the valleys and films that do not, the answers are
    those of each lane's gap field (engages, lower_bound) and of the path
    for films whose sums do not suffice, to the bit."""
    out = _compile_and_run(tmp_path, ENGAGE_CHECK)
    differ, bound_differ, engaged, total = (int(v) for v in out[:4])
    assert differ == 0
    assert bound_differ == 0
    assert 0.2 * total < engaged < 0.8 * total, (engaged, total)


LEVEL_CHECK = """
program check
   use pavefric_kinds, only: wp, lanes
   use pavefric_film, only: pseudo_bearing_film, film_step_type
   use pavefric_balance, only: engaged_lanes, engaged_by_level, dry_roots
   implicit none
   type(pseudo_bearing_film) :: film
   integer, parameter :: n = 23
   type(film_step_type) :: steps(lanes)
   real(wp) :: d(lanes, n), x(lanes), s(lanes), x0(lanes), sum_d(lanes), sum_l(lanes)
   real(wp) :: upper(lanes), r(lanes), dl(n), gap(n), work(n)
   logical :: mask(lanes), wet(lanes), wet_l(lanes)
   integer :: trial, j, nl, differ, engaged, total, bad_upper, tight
   call random_seed(put=[(11 * j + 2, j = 1, 64)])
   differ = 0
   engaged = 0
   total = 0
   bad_upper = 0
   tight = 0
   do trial = 1, 3000
      nl = 1 + mod(trial, lanes)
      call random_number(r)
      film = pseudo_bearing_film(depth=10.0_wp**(-5 + 2 * r(1)), eta=1e-3_wp, alpha=12.0_wp, &
         & beta=1.75_wp, width=0.016_wp, length=0.02_wp)
      do j = 1, nl
         call film%prepare(20.0_wp, 1e-3_wp, steps(j))
      end do
      call random_number(d)
      ! (cubed on every other pad: many elements near the lowest, so that
      ! several touch at the film's level)
      if (mod(trial, 2) == 0) d = d**3
      d = d * film%depth * 10.0_wp**(-1 + 2 * mod(trial, 3))
      do j = 1, nl
         d(j, 1 + mod(trial + j, n)) = 0.0_wp            ! min d = 0 in every lane
      end do
      call random_number(s)
      s = s * film%depth * 10.0_wp**(-2 + mod(trial, 4))
      if (mod(trial, 5) == 0) then
         ! a flat stretch of the pad at the lowest clearance and a heavy
         ! load: several elements touch at the film's level, where the
         ! bound is below W / kel
         d(1:nl, 1:8) = 0.0_wp
         s = s * 100.0_wp
      end if
      call random_number(r)
      mask = r > 0.2_wp
      x0 = -1.0_wp
      call dry_roots(nl, n, d(1:nl, :), s(1:nl), x0(1:nl), x(1:nl), work, dl)
      call engaged_lanes(nl, n, d(1:nl, :), x(1:nl), film, steps(1:nl), mask(1:nl), &
         & wet(1:nl), dl, gap, sum_d(1:nl))
      call engaged_by_level(nl, n, d(1:nl, :), s(1:nl), film, steps(1:nl), mask(1:nl), &
         & wet_l(1:nl), sum_l(1:nl), upper(1:nl))
      do j = 1, nl
         total = total + 1
         if (wet(j) .neqv. wet_l(j)) differ = differ + 1
         if (wet_l(j)) then
            engaged = engaged + 1
            ! an upper bound of the dry root, and no larger than s
            if (upper(j) < x(j) .or. upper(j) > s(j)) bad_upper = bad_upper + 1
            if (upper(j) < s(j)) tight = tight + 1
         end if
      end do
   end do
   print *, differ, engaged, total, bad_upper, tight
end program check
"""


def test_the_film_engages_without_the_dry_roots(tmp_path):
    """Where every lane's film carried load at the previous position, the
    driver decides whether the paper's bearing engages without the dry
    roots (engaged_by_level: the dry root lies above the film's engage_level
    iff the pad's push there is below the load) and brackets the wet root
    by an upper bound of the dry one. On 3,000 random pads of 1 to 8 lanes,
    films that fill the valleys and films that do not, the answers are
    those of the mean gap at the dry root (engaged_lanes), and the bound
    lies between the dry root and W / kel (below W / kel on pads where
    several elements touch at the film's level)."""
    out = _compile_and_run(tmp_path, LEVEL_CHECK)
    differ, engaged, total, bad_upper, tight = (int(v) for v in out[:5])
    assert differ == 0
    assert 0.2 * total < engaged < 0.8 * total, (engaged, total)
    assert bad_upper == 0
    assert tight > 0.05 * engaged, (tight, engaged)


# An attack's reproducer (2026-12-06): 24 points, a long-memory rubber, a
# shallow film that engages and lets go (docs/numerics.md, "bit for bit")
LANES_Z = [-1.364388905843542e-05, -4.734159526227956e-06, 8.831765400001868e-06,
           1.1159555687932859e-05, -8.45446696157989e-06, -3.200168589822475e-07,
           -2.5857844206934897e-06, 1.1815585755823626e-05, 2.5046333741809186e-05,
           -1.8298868255199325e-05, 9.16422909984269e-06, -2.858175376906725e-05,
           1.406637216464734e-07, -1.1087845239491877e-05, 1.991818790110053e-05,
           1.663685283010593e-06, -7.367717479557876e-06, -4.993128547088203e-06,
           -5.752957520422239e-06, 1.883116085626878e-06, -1.5814847037970742e-06,
           6.5588557398152206e-06, 1.540261081924691e-05, 7.0141204690748395e-06]


def test_a_speeds_numbers_are_its_own_whichever_speeds_share_the_call():
    """Each speed's numbers do not depend on which other speeds run with
    it, to the bit (so neither on the chunking nor on the threads): a wet
    speed alone, beside a hydroplaning one, and among five; a speed of 0
    (no motion: no film) alone and in a wet call. Before: the film's
    engagement by the level and the dry roots' warm start were decided for
    a whole chunk of speeds (mu moved by 1e-16, the balance's evaluations
    by a few), and a speed of 0 took another dry balance beside moving
    speeds than alone."""
    import warnings

    import numpy as np

    import pavefric

    z = np.array(LANES_Z)
    kw = dict(closed=True, length=0.02, depth=1.8449213736658224e-05, wet_model="kane2017",
              load=11.8, stiffness=1.4e8, viscosity=1e10, mu_loc=0.5, time_scheme="euler",
              error_estimate=False, min_contacts=0, series=True)
    names = ["mu", "mu_hysteresis", "max_balance_residual", "bearing_evaluations",
             "wet_fraction", "mean_hydro_load", "mu_inst", "penetration", "hydro_load"]

    def take(speeds, speed):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = pavefric.simulate(z, 0.87e-3, speeds, **kw)
        return {k: ds[k].sel(speed_kmh=speed).values for k in names}

    for speed, companies in ((0.001, ([0.001, 300.0], [0.001, 10.0, 40.0, 60.0, 300.0])),
                             (0.0, ([0.0, 20.0], [20.0, 0.0, 80.0]))):
        alone = take([speed], speed)
        for company in companies:
            together = take(company, speed)
            for k in names:
                np.testing.assert_array_equal(together[k], alone[k], err_msg=f"{k} {company}")
