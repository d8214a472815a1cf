"""An independent, slow NumPy implementation of MODEL.md, for tests and the
benchmark only. Written from the specification, not from the Fortran: the dry
balance sorts the c_i, the wet balance bisects in absolute penetration, the
bearing uses the closed form with the MODEL.md series near a = 1.

Default numerics only (one element per sample, one step per sample, every
position averaged), on the profile's own spacing (&pad element_length = 0).

Two friction schemes (MODEL.md §3 and §10): 'paper', Eq. 10 on
central-difference slopes; 'energy', the facets' work: the rubber's part from
the elements' work over each step (each element's force K u + C du/dt
averaged along the step's path, u linear in time from the step's start to its
end, times the rise of the road under it; none for an element off the road at
both ends) less the pad's descent, the local friction's part mu (1 + s^2) / (1 - mu s) per unit force;
per position (series) the facets' work, on average the dissipation (the
facets' work less the load the elements did not carry times the pad's
descent: on a closed profile whose state repeats at every step, elsewhere
where the film carries load).
"""
from __future__ import annotations

import numpy as np


def bearing(h_in, h_out, prefactor):
    """Eq. 15: Wh = P / Hout^2 * [ln a - 2(a-1)/(a+1)] / (a-1)^2."""
    if h_out >= h_in:
        return 0.0
    if h_out <= 0.0:
        return np.inf
    a = h_in / h_out
    e = (h_in - h_out) / h_out
    if e < 1e-3:
        bracket = e / 12 - e**2 / 8 + 11 * e**3 / 80 - 13 * e**4 / 96
    else:
        bracket = (np.log(a) - 2 * (a - 1) / (a + 1)) / (a - 1) ** 2
    return prefactor / h_out**2 * bracket


def facet_tangent(z, dx, closed, mu_loc, theta_max_deg):
    if closed:
        slope = (np.roll(z, -1) - np.roll(z, 1)) / (2 * dx)
    else:
        slope = np.empty_like(z)
        slope[1:-1] = (z[2:] - z[:-2]) / (2 * dx)
        slope[0] = (z[1] - z[0]) / dx
        slope[-1] = (z[-1] - z[-2]) / dx
    theta = np.arctan(slope) + np.arctan(mu_loc)
    tmax = np.radians(theta_max_deg)
    clamped = np.abs(theta) > tmax
    return np.tan(np.clip(theta, -tmax, tmax)), clamped, slope


def local_friction_tangent(slope, tan_t, clamped, mu_loc, theta_max_deg):
    """tan(theta) - tan(alpha): the friction force per unit normal element
    force that mu_loc adds on a facet of slope s (unclamped: mu (1 + s^2) /
    (1 - mu s), from N = F / (cos a - mu sin a) sliding 1 / cos a per unit
    distance)."""
    if mu_loc == 0:
        return np.zeros_like(slope)
    tmax = np.tan(np.radians(theta_max_deg))
    free = mu_loc * (1 + slope**2) / (1 - mu_loc * slope)
    walls = np.maximum(0.0, tan_t - np.clip(slope, -tmax, tmax))
    return np.where(clamped, walls, free)


def spin_up(n, n_p, dx, decay, push_total, tol=1e-6, max_laps=4):
    """Spin-up steps of a closed profile (docs/model.md, "Spin-up"): at least
    the pad's n; with a memory decaying by `decay` a step, until what is
    left of the relaxed start, decay^S, changes the state over a lap of n_p
    steps by so little that, as friction (half the load times the mean push
    over W and the lap), it is below tol; at most max_laps laps."""
    left = (1.0 - decay**n_p) * (push_total / n) / (2.0 * n_p * dx)
    if left <= tol:
        return n
    need = np.log(tol / left) / np.log(decay)
    if need > max_laps * n_p:
        return max(n, max_laps * n_p)
    return max(n, int(np.ceil(need)))


def dry_delta(c, s):
    """Root of sum max(0, delta - c_i) = s by sorting ("water-filling")."""
    cs = np.sort(c)
    m = np.arange(1, cs.size + 1)
    levels = (s + np.cumsum(cs)) / m
    upper = np.append(cs[1:], np.inf)
    ok = levels <= upper
    return levels[np.argmax(ok)]


def simulate(z, dx, speeds_kmh, *, closed=True, mu_loc=0.5, length=0.020, width=0.016,
             load=11.8, stiffness=1.4e8, viscosity=1e2, depth=0.0, water_viscosity=1e-3,
             alpha=1.0, beta=1.75, theta_max_deg=85.0, h=None, series=False,
             friction_scheme="energy"):
    """Mean friction per speed (and, with series, per-position mu and delta)."""
    z = np.asarray(z, dtype=float)
    n_p = z.size
    n = int(np.floor(length / dx + 0.5))
    h = np.zeros(n) if h is None else np.asarray(h, dtype=float)
    tan_t, clamped, slope = facet_tangent(z, dx, closed, mu_loc, theta_max_deg)
    adh = local_friction_tangent(slope, tan_t, clamped, mu_loc, theta_max_deg)
    i = np.arange(1, n + 1)
    if closed:
        steps = range(1 - n, n_p + 1)
    else:
        steps = range(0, n_p - n + 1)
    out_mu, out_series = [], []
    for kmh in np.atleast_1d(speeds_kmh):
        v = kmh / 3.6
        k_eff = stiffness + viscosity * v / dx
        kel = width * dx * k_eff
        decay = 0.0
        if viscosity > 0 and v > 0:
            dt = dx / v
            decay = 1.0 / (1.0 + stiffness * dt / viscosity)
        pref = alpha * 6 * water_viscosity * v**beta * width * length**2
        speed_steps = steps
        repeats = False
        if closed and 0.0 < decay < 1.0 and friction_scheme == "energy":
            spin = spin_up(n, n_p, dx, decay, load / kel)
            # the state repeats round the lap where what is left of the
            # start, as friction, is below 1e-9 (docs/model.md, "Which the
            # mean takes"); the mean is then the dissipation. The pad's
            # creep under its load decays as the element does and is
            # k_eff / K - 1 times its instant compression (at least 1);
            # where reaching 1e-9 takes at most a quarter lap more, the
            # spin-up runs that far
            weight = max(1.0, viscosity * v / dx / stiffness) if stiffness > 0 else np.inf
            left = weight * (1.0 - decay**n_p) * (load / kel / n) / (2.0 * n_p * dx)
            short = np.log(1e-6 / (left / weight)) / np.log(decay) > 4 * n_p
            if left > 1e-9 and not short:
                need = np.log(1e-9 / left) / np.log(decay)
                if need <= spin + 0.25 * n_p:
                    spin = max(spin, int(np.ceil(need)))
            speed_steps = range(1 - spin, n_p + 1)
            repeats = np.log(left) + spin * np.log(decay) <= np.log(1e-9)
        u = np.zeros(n)
        mus, deltas, whs, means, works, adhesions = [], [], [], [], [], []
        prev = None
        # an open profile: the elements' work over each step (the descent
        # not taken out) and their stored energy at the stretch's ends
        elem_works, stored = [], []
        for j in speed_steps:
            k = (j + i - 1) % n_p if closed else j + i - 1
            u_free = decay * u
            c = h - z[k] + u_free
            delta = dry_delta(c, load / kel)
            wh = 0.0
            if depth > 0 and v > 0:
                hm = np.mean(np.maximum(0.0, c - delta))
                if hm < depth:
                    def f(d):
                        return (kel * np.maximum(0.0, d - c).sum()
                                + bearing(depth, np.mean(np.maximum(0.0, c - d)), pref) - load)
                    lo = min(c.min(), c.mean() - depth)
                    hi = delta
                    for _ in range(200):
                        mid = 0.5 * (lo + hi)
                        if mid <= lo or mid >= hi:
                            break
                        if f(mid) > 0:
                            hi = mid
                        else:
                            lo = mid
                    delta = 0.5 * (lo + hi)
                    wh = bearing(depth, np.mean(np.maximum(0.0, c - delta)), pref)
            force = kel * np.maximum(0.0, delta - c)
            u_old = u
            u = np.maximum(delta - h + z[k], u_free)
            if friction_scheme == "paper":
                mu_j = (force * tan_t[k]).sum() / load
                mean_j = mu_j
            else:
                work = film = 0.0
                if prev is not None:
                    f_old, d_old, wh_old = prev
                    # K u + C du/dt along u linear over the step (dt = dx/V);
                    # an element off the road at both ends touches nothing
                    rate = viscosity * v / dx * (u - u_old)
                    f_mean = width * dx * (stiffness * 0.5 * (u_old + u) + rate)
                    # less the contact ramp: the free path's own mean (from
                    # u_old to decay u_old, K (1 - decay) u_old / 2) where
                    # the pushes are nil, falling linearly to 0 as they reach
                    # the free path's change (docs/model.md, "The step's
                    # force where a contact starts or ends")
                    pushes = (f_old + force) / kel
                    f_mean = f_mean - width * dx * stiffness * 0.5 * np.maximum(
                        0.0, (u_old - decay * u_old) - pushes)
                    f_mean = np.where((f_old > 0) | (force > 0), f_mean, 0.0)
                    work = (f_mean * ((u - u_old) - (delta - d_old))).sum()
                    elem_works.append((f_mean * (u - u_old)).sum())
                    # the load the elements did not carry, times the descent:
                    # on a closed profile whose state repeats at every step
                    # (the load's own work returns round the lap, so the
                    # mean is the dissipation); elsewhere only where the film
                    # carries load at either end of the step (else the
                    # facets' work)
                    if repeats or (depth > 0 and v > 0 and (wh > 0 or wh_old > 0)):
                        film = (load - f_mean.sum()) * (delta - d_old)
                adhesion = (force * adh[k]).sum() / load
                mu_j = work / (load * dx) + adhesion             # the facets' work (series)
                mean_j = (work - film) / (load * dx) + adhesion  # the dissipation (mean)
                stepped = prev is not None
            prev = (force, delta, wh)
            if closed and j < 1:
                continue
            stored.append(0.5 * width * dx * stiffness * (u ** 2).sum())
            mus.append(mu_j)
            means.append(mean_j)
            deltas.append(delta)
            whs.append(wh)
            if friction_scheme != "paper":
                adhesions.append(adhesion)
                if stepped:
                    works.append(mean_j - adhesion)
        if friction_scheme != "paper" and not closed and elem_works:
            # an open profile: the rubber's dissipation over its steps (the
            # first position has none before it), the elements' work less
            # their stored energy's change between the stretch's ends; an
            # elastic rubber's is nil (docs/model.md)
            dissipation = sum(elem_works) - (stored[-1] - stored[0])
            if viscosity == 0 or v == 0:
                dissipation = 0.0
            out_mu.append(dissipation / (load * dx * len(elem_works)) + np.mean(adhesions))
        else:
            out_mu.append(np.mean(means))
        out_series.append((np.array(mus), np.array(deltas), np.array(whs)))
    if series:
        return np.array(out_mu), out_series
    return np.array(out_mu)
