!> The paper's Kelvin-Voigt pad on a dry road, integrated exactly in time
!> (&numerics time_scheme = 'exact').
!>
!> Between the nodes of the pad's grid the road under each element rises
!> linearly, z_i(t) = z0_i + s_i t (the profile is interpolated linearly
!> between its samples). An element in contact has the compression of the
!> road, g_i = delta + z_i - h_i, and pushes with f_i = k (g_i + tau g_i')
!> (k = l dx K its spring, tau = C / K); a free element relaxes,
!> u_i = u0_i exp(-t / tau). The load balance sum f_i = W over the contact
!> set is then a linear ODE for the penetration,
!>     tau delta' + delta = (W / k - sum_c (z_i - h_i + tau s_i)) / n_c,
!> whose solution is delta = A + B t + (delta0 - A) exp(-t / tau), and every
!> contact force is linear in t (the exponentials cancel, as every element
!> has the same tau). The contact set changes at events: a contact's force
!> reaching 0 (a linear root) or a free element's gap
!>     r_i = (u0_i - delta0 + A) exp(-t/tau) - (A + z0_i - h_i) - (B + s_i) t
!> reaching 0 (convex or concave: bracketed, then safeguarded Newton). The
!> scheme steps from event to event, so the only errors left are the
!> roots' (to rounding) and the road's interpolation, which is the model's;
!> it is what backward Euler converges to as substeps grows
!> (tests/test_exact.py; docs/accuracy.md).
!>
!> The friction is the work of the facet forces on the elements, sum f_i s_i
!> integrated exactly (f and s linear in each segment), per unit load and
!> distance (the rubber's part, as in the energy scheme), plus the local
!> friction's part, sum f_i a_i with the facets' tangents a_i interpolated
!> linearly between nodes, integrated exactly.
!>
!> Under the paper's pseudo-bearing (wet_model = 'kane2017') the film's load
!> Wh (Eq. 15 of the mean gap h_m under the pad) joins the balance:
!> sum_c f_i + Wh = W. Between events the free elements' gaps, hence h_m,
!> are linear in the penetration and known in t, and Wh is linearised in
!> h_m about the part's start, Wh0 + Wh' (h_m - h_m0). The balance is then
!> a linear ODE with the film's stiffness kappa = -Wh' n_free / N beside
!> the contacts' springs, whose solution is
!>     delta = A + B t + D exp(-t/tau) + G exp(-lambda t),
!>     lambda = (n_c k + kappa) / (n_c k tau),  D = (sum of the free
!> compressions) / n_free; every contact force is linear in t plus the
!> one term -(kappa G / n_c) exp(-lambda t), every gap a sum of the two
!> exponentials and a line, and the film's own switch (its linear load
!> reaching 0, or h_m falling to H_in where it was off) a root of the same
!> form: the events come from the one solution. The error left is the
!> linearisation's, of the order of the change of h_m over a part squared:
!> second order in the step. With no element in contact the pad floats:
!> the film alone carries W, so h_m is the h* of Wh(h*) = W and the
!> penetration follows the free elements exactly until one touches. The
!> film's work on the pad, the integral of (W - sum f) d(delta), is
!> counted out of the rubber's part as the driver does (Eq. 15's lift is
!> not a dissipation).
module pavefric_kv_exact
   use pavefric_kinds, only: wp, i8
   use pavefric_balance, only: dry_root
   use pavefric_bearing, only: hydro_load
   implicit none
   private

   public :: kv_exact_lane, kv_exact_type, two_exp_root

   !> What one speed's exact slide gives.
   type :: kv_exact_type
      real(wp) :: mu_hysteresis = 0.0_wp, mu_adhesion = 0.0_wp
      real(wp) :: max_balance_residual = 0.0_wp, max_compression = 0.0_wp
      integer(i8) :: n_clamped = 0, events = 0
      !> Averaged positions with no element in contact (the pad is carried
      !> by the elements at every instant: 0 in practice).
      integer :: n_nocontact = 0
      !> The share of the elements in contact, summed over averaged positions.
      real(wp) :: contact_share_sum = 0.0_wp
      !> Under a film: the film's load summed over averaged positions, the
      !> positions where it carried load, and the evaluations of Eq. 15.
      real(wp) :: hydro_sum = 0.0_wp
      integer :: n_wet = 0
      integer(i8) :: film_evaluations = 0
      !> 0, or 1 when a step had more events than max_events (its position
      !> in bad_position), 2 when the work arrays could not be allocated, 3
      !> when a film is beyond the integrator (min_float_share).
      integer :: status = 0, bad_position = 0
   end type kv_exact_type

   !> Events allowed in one step per element (and 100 more): far above the
   !> few per step a real profile gives (about 0.5 per element).
   integer, parameter :: events_per_element = 40
   !> Changes of side of one element in one step after which it keeps its
   !> side to the step's end.
   integer, parameter :: max_flips = 8
   !> The same for the film's own switches (on and off) in one step.
   integer, parameter :: max_film_flips = 64
   !> The floating gap h* (Wh(h*) = W) below which, as a share of the water
   !> depth, the integrator declines a film (status 3): the film then
   !> carries the pad only at a gap far below the texture's (on
   !> inputs/ctm_wet.nml h* is 0.2 to 0.5 of the depth at 5 to 80 km/h, 1e-60
   !> at 1 km/h; a flat-topped texture under a 100 N pad: 2e-6 at 20 km/h,
   !> where the linearised film went 2 orders of magnitude off).
   real(wp), parameter :: min_float_share = 1.0e-3_wp

contains

   !> One speed over the positions -n_spin .. n_avg - 1 of the pad's grid.
   !> z, adhesion and clamped_at are the refined profile as the driver lays
   !> it out (closed profiles extended by the pad's length); element i at
   !> position t stands on index k1(t) + (i - 1) spacing.
   subroutine kv_exact_lane(z, h, adhesion, clamped_at, n, spacing, npf, closed, n_avg, &
         & n_spin, k, tau, dt, advance, load, k_land, res, mu_inst, penetration, contact_count, &
         & bearing, depth, hydro)
      real(wp), intent(in) :: z(:), h(:), adhesion(:), clamped_at(:)
      integer, intent(in) :: n, spacing, npf, n_avg, n_spin
      logical, intent(in) :: closed
      !> Element spring l dx K (N m-1), retardation time C / K (s), time
      !> step advance / V (s), step (m) and load (N).
      real(wp), intent(in) :: k, tau, dt, advance, load
      !> The landing's element spring (N m-1): l dx (K + C / dt_land), the
      !> backward-Euler step over the time the road takes to move one element
      !> length, as the driver's landing (docs/model.md, "The landing").
      real(wp), intent(in) :: k_land
      type(kv_exact_type), intent(out) :: res
      real(wp), intent(out), optional :: mu_inst(:), penetration(:)
      integer, intent(out), optional :: contact_count(:)
      !> The pseudo-bearing's prefactor P (Eq. 15, N m**2... as
      !> bearing_prefactor) and the water depth H_in (m): a film where both
      !> are given and > 0; hydro its load at each averaged position (N).
      real(wp), intent(in), optional :: bearing, depth
      real(wp), intent(out), optional :: hydro(:)

      real(wp), allocatable :: zc(:), s(:), u(:), f(:), a0(:), a1(:), f0(:), sl(:)
      logical, allocatable :: touch(:)
      ! each element's changes of side in the step
      integer, allocatable :: flips(:)
      real(wp) :: delta, a_coef, b_coef, theta, rem, hstep, e, t_ev, t_min, w_step, adh_int
      real(wp) :: ad_a, ad_b, f1, tolf, wk, hyst_sum, adh_sum
      ! an open profile's stretch: the elements' stored energy and the
      ! penetration at its start
      real(wp) :: stored_start, delta_start
      integer :: t, i, i_ev, nc, kp, kn, n_ev, stat, segments, last_el, graze
      logical :: series
      ! the film: on, its prefactor and depth, the floating mean gap h*, the
      ! segment's load Wh0 + w1 t, the load at the node, the step's work of
      ! the film on the pad, the free elements' sums (compressions, h - z,
      ! slopes, count) at the segment's start
      logical :: wet
      real(wp) :: pfac, hin, hstar, wh0, wh_node, film_w, eu, qf, sf, nf
      ! a part's penetration A + B t + D exp(-t/tau) + G exp(-lam t), the
      ! contacts' common exponential term ce exp(-lam t), the film's
      ! linearisation (on, its slope whp and the mean gap hm0 at the start,
      ! the mean gap hoff where its load reaches 0), floating; the film's
      ! state, which only its own switches change (its linear load reaching
      ! 0 turns it off, the mean gap falling to h_eng turns it on: the
      ! state holds across the parts, so that a load the linearisation left
      ! a rounding above 0 does not turn it on again at once), the mean gap
      ! at which it engages (H_in, or below it where it last went off); the
      ! film's switches in the step
      real(wp) :: d_coef, g_coef, lam, ce, whp, hm0, hoff, h_eng
      logical :: film_on, floating, film_state
      integer :: film_flips

      series = present(mu_inst)
      allocate(zc(n), s(n), u(n), f(n), a0(n), a1(n), f0(n), sl(n), touch(n), flips(n), &
         & stat=stat)
      if (stat /= 0) then
         res%status = 2
         return
      end if
      tolf = 1.0e-12_wp * load
      wk = load / k
      wet = .false.
      pfac = 0.0_wp
      hin = 0.0_wp
      if (present(bearing) .and. present(depth)) then
         pfac = bearing
         hin = depth
         wet = pfac > 0.0_wp .and. hin > 0.0_wp
      end if
      wh0 = 0.0_wp
      wh_node = 0.0_wp
      d_coef = 0.0_wp
      g_coef = 0.0_wp
      lam = 1.0_wp / tau
      ce = 0.0_wp
      whp = 0.0_wp
      hm0 = 0.0_wp
      hoff = 0.0_wp
      film_on = .false.
      floating = .false.
      film_state = .false.
      h_eng = hin
      film_flips = 0
      hstar = 0.0_wp
      if (wet) then
         hstar = floating_gap()
         if (hstar < min_float_share * hin) then
            ! a film that lifts the pad only when all but closed: its load
            ! changes by its own size across one element's travel, beyond
            ! what a linearisation over a part of a step follows
            res%status = 3
            return
         end if
      end if

      ! the first position: the pad lands on relaxed elements in one
      ! backward-Euler step of the time the road takes to move one element
      ! length (the driver's landing, the same whatever the substeps): its
      ! balance with the landing's spring, the elements it presses then
      ! compressed to the road
      kp = node(-n_spin)
      do i = 1, n
         zc(i) = z(kp + (i - 1) * spacing)
      end do
      f = 0.0_wp
      do i = 1, n
         a0(i) = h(i) - zc(i)
      end do
      theta = minval(a0)
      do i = 1, n
         a1(i) = a0(i) - theta
      end do
      call dry_root(a1, load / k_land, 0.0_wp, delta, sl)
      if (wet) call wet_landing()
      do i = 1, n
         u(i) = max(0.0_wp, delta - a1(i))
      end do
      touch = u > 0.0_wp
      delta = theta + delta

      hyst_sum = 0.0_wp
      adh_sum = 0.0_wp
      segments = 0
      if (.not. closed .and. n_avg >= 1) then
         ! an open profile starts at its first averaged position: its forces
         ! are those the landing pad starts the first segment with (the
         ! right limit), and the adhesion there is the node's
         s = 0.0_wp
         if (n_avg >= 2) then
            do i = 1, n
               s(i) = (z(node(1) + (i - 1) * spacing) - zc(i)) / dt
            end do
         end if
         theta = 0.0_wp
         t = 0
         call contact_set()
         if (res%status /= 0) return
         f = f0
         if (ce /= 0.0_wp) then
            where (touch) f = f0 + ce
         end if
         wh_node = wh0
         call record_node(0, 0.0_wp, 0.0_wp, .true.)
         stored_start = 0.5_wp * k * sum(u**2)
         delta_start = delta
      end if
      do t = -n_spin + 1, n_avg - 1
         kp = node(t - 1)
         kn = node(t)
         do i = 1, n
            zc(i) = z(kp + (i - 1) * spacing)
            s(i) = (z(kn + (i - 1) * spacing) - zc(i)) / dt
            a0(i) = adhesion(kp + (i - 1) * spacing)
            a1(i) = adhesion(kn + (i - 1) * spacing)
         end do
         theta = 0.0_wp
         w_step = 0.0_wp
         adh_int = 0.0_wp
         film_w = 0.0_wp
         n_ev = 0
         last_el = 0
         flips = 0
         film_flips = 0
         do
            call contact_set()
            if (res%status /= 0) return
            rem = dt - theta
            ! the earliest event
            t_min = huge(1.0_wp)
            i_ev = 0
            graze = 0
            do i = 1, n
               ! an element that has changed side max_flips times in the
               ! step keeps its side to the step's end (under a film a
               ! grazing element can chatter between two sets whose
               ! motions each bring it back: Zeno; never seen dry)
               if (flips(i) >= max_flips) cycle
               if (touch(i)) then
                  if (ce /= 0.0_wp) then
                     ! f = ce exp(-lam t) + f0 + sl t
                     t_ev = free_root(ce, -f0(i), -sl(i), rem, 1.0_wp / lam)
                  else if (sl(i) < 0.0_wp) then
                     t_ev = max(f0(i), 0.0_wp) / (-sl(i))
                  else
                     cycle
                  end if
               else if (.not. wet) then
                  t_ev = free_root(u(i) - delta + a_coef, a_coef + zc(i) - h(i), &
                     & b_coef + s(i), rem, tau)
               else
                  ! the gap (u - D) exp(-t/tau) - G exp(-lam t) - (A + z - h) - (B + s) t
                  t_ev = two_exp_root(u(i) - d_coef, -g_coef, a_coef + zc(i) - h(i), &
                     & b_coef + s(i), rem, tau, lam)
               end if
               ! the element that changed side at this instant does not
               ! change back within a rounding of it (no zero-length
               ! round trips at a grazing contact)
               if (i == last_el .and. t_ev <= 1.0e-9_wp * dt) then
                  ! an element that has just touched with no force and would
                  ! leave at once only grazed the road: it stays free
                  if (touch(i) .and. nc > 1) graze = i
                  cycle
               end if
               if (t_ev < t_min) then
                  t_min = t_ev
                  i_ev = i
               end if
            end do
            if (wet .and. .not. floating .and. film_flips < max_film_flips) then
               t_ev = film_root(rem)
               if (t_ev < t_min) then
                  t_min = t_ev
                  i_ev = -1
               end if
            end if
            if (graze /= 0) then
               n_ev = n_ev + 1               ! (counted: no loop without end)
               if (n_ev > events_per_element * n + 100) then
                  res%status = 1
                  res%bad_position = t
                  return
               end if
               touch(graze) = .false.
               u(graze) = delta + zc(graze) - h(graze)
               f(graze) = 0.0_wp
               cycle
            end if
            hstep = min(t_min, rem)
            ! the segment's work and local friction, exactly
            do i = 1, n
               if (.not. touch(i)) cycle
               f1 = f0(i) + sl(i) * hstep
               w_step = w_step + s(i) * 0.5_wp * (f0(i) + f1) * hstep
               ad_a = a0(i) + (a1(i) - a0(i)) * (theta / dt)
               ad_b = a0(i) + (a1(i) - a0(i)) * ((theta + hstep) / dt)
               adh_int = adh_int + hstep / 6.0_wp * (2.0_wp * f0(i) * ad_a + f0(i) * ad_b + &
                  & f1 * ad_a + 2.0_wp * f1 * ad_b)
               f(i) = f1
               if (ce /= 0.0_wp) then
                  ! the common term ce exp(-lam t)
                  w_step = w_step + s(i) * ce * hstep * phi1(lam * hstep)
                  adh_int = adh_int + ce * hstep * (ad_a * phi1(lam * hstep) + &
                     & (ad_b - ad_a) * phi2(lam * hstep))
                  f(i) = f1 + ce * exp(-lam * hstep)
               end if
            end do
            e = exp(-hstep / tau)
            if (wet) then
               f1 = a_coef + b_coef * hstep + d_coef * e + g_coef * exp(-lam * hstep)
               if (floating) then
                  film_w = film_w + load * (f1 - delta)
               else if (film_on) then
                  film_w = film_w + film_work(hstep)
               end if
               delta = f1
            else
               delta = a_coef + b_coef * hstep + (delta - a_coef) * e
            end if
            theta = theta + hstep
            do i = 1, n
               zc(i) = zc(i) + s(i) * hstep
               if (touch(i)) then
                  u(i) = delta + zc(i) - h(i)
               else
                  u(i) = u(i) * e
               end if
            end do
            if (hstep > 0.0_wp) then
               last_el = 0
                     end if
            if (wet) call node_load()
            if (t_min > rem) exit
            ! the event: its element changes side, or the film switches
            n_ev = n_ev + 1
            res%events = res%events + 1
            if (n_ev > events_per_element * n + 100) then
               res%status = 1
               res%bad_position = t
               return
            end if
            if (i_ev == -1) then
               film_flips = film_flips + 1
               if (film_on) then
                  ! off: it engages again once the gap has fallen a
                  ! little (1e-9 H_in) below where it went off, so that a
                  ! film at its edge does not switch back and forth
                  film_state = .false.
                  h_eng = min(hin, mean_gap()) - 1.0e-9_wp * hin
               else
                  film_state = .true.
               end if
               if (t_min >= rem) exit
               cycle
            end if
            touch(i_ev) = .not. touch(i_ev)
            flips(i_ev) = flips(i_ev) + 1
            u(i_ev) = delta + zc(i_ev) - h(i_ev)
            f(i_ev) = 0.0_wp
            last_el = i_ev
            if (t_min >= rem) exit
         end do
         ! the node: the road exactly at its samples again
         do i = 1, n
            zc(i) = z(kn + (i - 1) * spacing)
            if (touch(i)) u(i) = delta + zc(i) - h(i)
         end do
         if (t < 0) cycle                                    ! spin-up
         segments = segments + 1
         hyst_sum = hyst_sum + (w_step - film_w) / (load * advance)
         adh_sum = adh_sum + adh_int / (load * dt)
         call record_node(t, w_step / (load * advance), adh_int / (load * dt), .false.)
      end do
      if (segments > 0 .and. .not. closed) then
         ! the facets' work over an open stretch is the elements' stored
         ! energy's change plus their dissipation less the load's work
         ! W (delta_end - delta_start) (every contact force adds up to W at
         ! every instant): the dissipation, as the driver's mean (a closed
         ! lap returns both terms)
         hyst_sum = hyst_sum - ((0.5_wp * k * sum(u**2) - stored_start) - &
            & load * (delta - delta_start)) / (load * advance)
      end if
      if (segments > 0) then
         res%mu_hysteresis = hyst_sum / real(segments, wp)
         res%mu_adhesion = adh_sum / real(segments, wp)
      end if
   contains
      !> The grid index of element 1 at position tt (as the driver's).
      pure integer function node(tt)
         integer, intent(in) :: tt
         if (closed) then
            node = modulo(tt + 1, npf) + 1
         else
            node = tt + 1
         end if
      end function node

      !> A consistent contact set at theta (every contact force >= 0, from
      !> the most negative out), the coefficients A, B of the penetration,
      !> and each contact's force f0 and its slope sl. An empty set drops
      !> the pad until the nearest free element touches.
      subroutine contact_set()
         real(wp) :: s0, s1, worst, reach, best, dfloat
         integer :: iter, iw, ib
         do iter = 1, 4 * n + 10
            nc = count(touch)
            if (nc == 0) then
               best = huge(1.0_wp)
               ib = 1
               do i = 1, n
                  reach = u(i) - zc(i) + h(i)
                  if (reach < best) then
                     best = reach
                     ib = i
                  end if
               end do
               if (wet) then
                  ! the film alone carries W if the pad, floating at the
                  ! mean gap h*, clears every element
                  call free_sums()
                  dfloat = (eu + qf) / real(n, wp) - hstar
                  if (dfloat <= best) then
                     ! (a jump where the last contact left with the
                     ! linearised film off h* by its error: the film's work)
                     film_w = film_w + load * (dfloat - delta)
                     delta = dfloat
                     floating = .true.
                     film_on = .false.
                     film_state = .true.
                     a_coef = qf / real(n, wp) - hstar
                     b_coef = -sf / real(n, wp)
                     d_coef = eu / real(n, wp)
                     g_coef = 0.0_wp
                     lam = 1.0_wp / tau
                     ce = 0.0_wp
                     wh0 = load
                     f0 = 0.0_wp
                     sl = 0.0_wp
                     return
                  end if
               end if
               delta = best
               touch(ib) = .true.
               nc = 1
            end if
            s0 = 0.0_wp
            s1 = 0.0_wp
            do i = 1, n
               if (.not. touch(i)) cycle
               s0 = s0 + (zc(i) - h(i) + tau * s(i))
               s1 = s1 + s(i)
            end do
            if (wet) then
               floating = .false.
               call film_part(s0, s1)
               if (wh0 > 1.0e6_wp * load) then
                  ! a film squeezed to nothing: the pad floats off every
                  ! element (its contacts leave)
                  do i = 1, n
                     if (.not. touch(i)) cycle
                     touch(i) = .false.
                     flips(i) = flips(i) + 1
                     u(i) = delta + zc(i) - h(i)
                     f(i) = 0.0_wp
                  end do
                  cycle
               end if
            else
               b_coef = -s1 / real(nc, wp)
               a_coef = (wk - s0) / real(nc, wp) - tau * b_coef
            end if
            worst = -tolf
            iw = 0
            do i = 1, n
               if (.not. touch(i)) then
                  f0(i) = 0.0_wp
                  sl(i) = 0.0_wp
                  cycle
               end if
               f0(i) = k * ((a_coef + zc(i) - h(i)) + tau * (b_coef + s(i)))
               sl(i) = k * (b_coef + s(i))
               if (f0(i) + ce < worst) then
                  worst = f0(i) + ce
                  iw = i
               end if
            end do
            if (iw == 0) return
            touch(iw) = .false.
            flips(iw) = flips(iw) + 1
            u(iw) = delta + zc(iw) - h(iw)
            f(iw) = 0.0_wp
            last_el = iw
         end do
         res%status = 1
         res%bad_position = t
      end subroutine contact_set

      !> The free elements' sums at the segment's start: compressions eu,
      !> h - z qf, road slopes sf and their count nf (the mean gap is
      !> (eu e(t) + qf - sf t - nf delta(t)) / n, e(t) = exp(-t/tau)).
      subroutine free_sums()
         eu = 0.0_wp
         qf = 0.0_wp
         sf = 0.0_wp
         nf = 0.0_wp
         do i = 1, n
            if (touch(i)) cycle
            eu = eu + u(i)
            qf = qf + (h(i) - zc(i))
            sf = sf + s(i)
            nf = nf + 1.0_wp
         end do
      end subroutine free_sums

      !> A part with contacts under a film: the mean gap at its start, the
      !> film's load Wh0 and slope Wh' there, and the penetration's
      !> coefficients: the film linearised in the mean gap where it carries
      !> load (or engages: the slope from below at H_in, -P / (12 H_in**3));
      !> the dry form where it is off. s0, s1: the contacts' sums of
      !> z - h + tau s and of s.
      subroutine film_part(s0, s1)
         real(wp), intent(in) :: s0, s1
         real(wp) :: kap, m_all, r0, r1, knc
         call free_sums()
         hm0 = (eu + qf - nf * delta) / real(n, wp)
         call hydro_load(pfac, hin, hm0, wh0, whp)
         res%film_evaluations = res%film_evaluations + 1
         ! off, it engages where the gap has fallen below its level (as an
         ! event would have had it)
         if (.not. film_state .and. hm0 < h_eng) film_state = .true.
         film_on = film_state
         if (film_on .and. .not. (wh0 > 0.0_wp)) then
            ! engaging at H_in: the slope from below
            wh0 = 0.0_wp
            whp = -pfac / (12.0_wp * hin**3)
         end if
         if (.not. film_on) wh0 = 0.0_wp
         knc = k * real(nc, wp)
         if (.not. film_on .or. nf <= 0.0_wp .or. wh0 > 1.0e6_wp * load) then
            film_on = .false.
            b_coef = -s1 / real(nc, wp)
            a_coef = ((load - wh0) / k - s0) / real(nc, wp) - tau * b_coef
            d_coef = 0.0_wp
            g_coef = delta - a_coef
            lam = 1.0_wp / tau
            ce = 0.0_wp
            return
         end if
         kap = -whp * nf / real(n, wp)
         m_all = knc + kap
         r0 = load - wh0 - k * s0 + (whp / real(n, wp)) * (eu - nf * delta)
         r1 = -k * s1 + (whp / real(n, wp)) * sf
         b_coef = r1 / m_all
         a_coef = (r0 - knc * tau * b_coef) / m_all
         d_coef = eu / nf
         g_coef = delta - a_coef - d_coef
         lam = m_all / (knc * tau)
         ce = -g_coef * kap / real(nc, wp)
         ! (whp < 0: the linear load falls to 0 at a larger mean gap)
         hoff = hm0 - wh0 / whp
      end subroutine film_part

      !> The mean gap under the pad now.
      real(wp) function mean_gap() result(hm)
         hm = 0.0_wp
         do i = 1, n
            if (touch(i)) cycle
            hm = hm + (u(i) - delta - zc(i) + h(i))
         end do
         hm = hm / real(n, wp)
      end function mean_gap

      !> The film's work on the pad over a part of length x, the integral of
      !> (W - sum f) delta': W - sum f = p0 + p1 t + p2 exp(-lam t) and
      !> delta' = B - (D / tau) exp(-t/tau) - lam G exp(-lam t).
      real(wp) function film_work(x) result(wf)
         real(wp), intent(in) :: x
         real(wp) :: p0, p1, p2, sumf0, sumsl
         sumf0 = 0.0_wp
         sumsl = 0.0_wp
         do i = 1, n
            if (.not. touch(i)) cycle
            sumf0 = sumf0 + f0(i)
            sumsl = sumsl + sl(i)
         end do
         p0 = load - sumf0
         p1 = -sumsl
         p2 = -real(nc, wp) * ce
         wf = b_coef * (p0 * x + 0.5_wp * p1 * x * x + p2 * x * phi1(lam * x)) &
            & - (d_coef / tau) * (p0 * x * phi1(x / tau) + p1 * x * x * phi2(x / tau) + &
            &    p2 * x * phi1((lam + 1.0_wp / tau) * x)) &
            & - lam * g_coef * (p0 * x * phi1(lam * x) + p1 * x * x * phi2(lam * x) + &
            &    p2 * x * phi1(2.0_wp * lam * x))
      end function film_work

      !> The film's load at the end of the part just made (the node's, if it
      !> is the step's last): its linearised load where it is on, W
      !> floating, 0 off (the forces then add up to W less it, to rounding).
      subroutine node_load()
         if (floating) then
            wh_node = load
         else if (film_on) then
            wh_node = max(0.0_wp, wh0 + whp * (mean_gap() - hm0))
         else
            wh_node = 0.0_wp
         end if
      end subroutine node_load

      !> The first time in (0, tmax] the film switches: on, where its
      !> linear load reaches 0 (the mean gap reaches hoff); off (and no
      !> contact left floating), where the mean gap falls to H_in. The mean
      !> gap is ((eu - nf D) exp(-t/tau) - nf G exp(-lam t) + qf - nf A
      !> - (sf + nf B) t) / n.
      real(wp) function film_root(tmax) result(root)
         real(wp), intent(in) :: tmax
         real(wp) :: rn
         rn = real(n, wp)
         if (film_on) then
            root = two_exp_root(-(eu - nf * d_coef) / rn, nf * g_coef / rn, &
               & (qf - nf * a_coef) / rn - hoff, -(sf + nf * b_coef) / rn, tmax, tau, lam)
         else
            ! (the dry form: D = 0, lam = 1 / tau)
            root = free_root((eu - nf * g_coef) / rn, h_eng - (qf - nf * a_coef) / rn, &
               & (sf + nf * b_coef) / rn, tmax, tau)
         end if
      end function film_root


      !> The mean gap h* at which the film alone carries the load,
      !> Wh(h*) = W (Wh falls from huge at 0 to 0 at H_in): bisection.
      real(wp) function floating_gap() result(hs)
         real(wp) :: lo, hi, mid, whm, dwh
         integer :: it
         lo = 0.0_wp
         hi = hin
         do it = 1, 200
            mid = 0.5_wp * (lo + hi)
            if (mid <= lo .or. mid >= hi) exit
            call hydro_load(pfac, hin, mid, whm, dwh)
            if (whm > load) then
               lo = mid
            else
               hi = mid
            end if
         end do
         hs = hi
      end function floating_gap

      !> The landing under a film: the penetration of the landing's balance
      !> sum k_land max(0, delta - a1_i) + Wh(mean max(0, a1_i - delta)) = W,
      !> increasing in delta, between the dry root (>= 0) and a level where
      !> nothing touches and the mean gap is H_in (= -W): bisection.
      subroutine wet_landing()
         real(wp) :: lo, hi, mid, fm, gsum, psum, whm, dwh
         integer :: it, q
         hi = delta
         lo = min(0.0_wp, sum(a1) / real(n, wp) - hin)
         do it = 1, 200
            mid = 0.5_wp * (lo + hi)
            if (mid <= lo .or. mid >= hi) exit
            gsum = 0.0_wp
            psum = 0.0_wp
            do q = 1, n
               gsum = gsum + max(0.0_wp, a1(q) - mid)
               psum = psum + max(0.0_wp, mid - a1(q))
            end do
            call hydro_load(pfac, hin, gsum / real(n, wp), whm, dwh)
            fm = k_land * psum + whm - load
            if (fm > 0.0_wp) then
               hi = mid
            else
               lo = mid
            end if
         end do
         delta = hi
      end subroutine wet_landing


      !> One averaged position's outputs.
      subroutine record_node(tt, hyst_step, adh_step, first)
         integer, intent(in) :: tt
         real(wp), intent(in) :: hyst_step, adh_step
         logical, intent(in) :: first
         real(wp) :: total, ad
         integer :: ncount, q
         total = 0.0_wp
         ncount = 0
         ad = 0.0_wp
         do q = 1, n
            if (touch(q)) then
               ncount = ncount + 1
               total = total + f(q)
               res%n_clamped = res%n_clamped + int(clamped_at(node(tt) + (q - 1) * spacing), i8)
               ad = ad + f(q) * adhesion(node(tt) + (q - 1) * spacing)
            end if
            res%max_compression = max(res%max_compression, u(q))
         end do
         if (wet) then
            res%max_balance_residual = max(res%max_balance_residual, &
               & abs(total + wh_node - load) / load)
            res%hydro_sum = res%hydro_sum + wh_node
            if (wh_node > 0.0_wp) res%n_wet = res%n_wet + 1
         else
            res%max_balance_residual = max(res%max_balance_residual, abs(total - load) / load)
         end if
         if (ncount == 0) res%n_nocontact = res%n_nocontact + 1
         res%contact_share_sum = res%contact_share_sum + real(ncount, wp) / real(n, wp)
         if (first) then
            ! (the open profile's first position: no segment before it)
            if (series) mu_inst(1) = ad / load
            if (present(hydro)) hydro(1) = wh_node
            if (present(penetration)) penetration(1) = delta
            if (present(contact_count)) contact_count(1) = ncount
            return
         end if
         if (series) mu_inst(tt + 1) = hyst_step + adh_step
         if (present(hydro)) hydro(tt + 1) = wh_node
         if (present(penetration)) penetration(tt + 1) = delta
         if (present(contact_count)) contact_count(tt + 1) = ncount
      end subroutine record_node
   end subroutine kv_exact_lane

   !> The first root in (0, tmax] of r(x) = al exp(-x/tc) - be - ga x,
   !> r(0) taken as >= 0 (a free element); huge when there is none (or
   !> when r dips below 0 by no more than rounding).
   pure real(wp) function free_root(al, be, ga, tmax, tc) result(root)
      real(wp), intent(in) :: al, be, ga, tmax, tc
      real(wp) :: tm, q, tol, x_lo, x_hi, x, fx, dfx
      integer :: it
      root = huge(1.0_wp)
      tol = 1.0e-13_wp * (abs(al) + abs(be) + abs(ga) * tmax)
      ! where r is smallest on [0, tmax]: its end, or a convex r's minimum
      tm = tmax
      if (al > 0.0_wp .and. ga < 0.0_wp) then
         q = -ga * tc / al
         if (q < 1.0_wp) then
            tm = min(tmax, -tc * log(q))
         else
            return                       ! r' >= 0 from 0 on: r only grows
         end if
      end if
      if (.not. (tm > 0.0_wp)) return
      if (.not. (al * exp(-tm / tc) - be - ga * tm < -tol)) return
      ! r(x_lo) >= 0 > r(x_hi), r monotone or single-crossing between
      x_lo = 0.0_wp
      x_hi = tm
      ! start from the root of the linear part (where a stiff rubber's
      ! exponential has died away), else from the bracket's end
      x = tm
      if (ga /= 0.0_wp) then
         q = -be / ga
         if (q > 0.0_wp .and. q < tm) x = q
      end if
      do it = 1, 200
         fx = al * exp(-x / tc) - be - ga * x
         if (fx > 0.0_wp) then
            x_lo = x
         else
            x_hi = x
         end if
         if (x_hi - x_lo <= 4.0_wp * epsilon(1.0_wp) * x_hi) exit
         dfx = -al / tc * exp(-x / tc) - ga
         x = x - fx / dfx
         ! Newton inside the bracket, else bisection
         if (.not. (x > x_lo .and. x < x_hi)) x = 0.5_wp * (x_lo + x_hi)
         if (x <= x_lo .or. x >= x_hi) exit
      end do
      root = x_hi
   end function free_root

   !> The first root in (0, tmax] of
   !>     r(x) = p exp(-x/tau) + q exp(-lam x) - be - ga x,
   !> r(0) taken as >= 0; huge when there is none (or r dips below 0 by
   !> no more than rounding). r'' changes sign at most once, so r' has
   !> at most two roots and r at most three monotone pieces: each piece's
   !> end is checked in order, and the first that falls below 0 holds the
   !> root (bisection). A lower bound of r on [0, tmax] rejects most
   !> elements at once.
   pure real(wp) function two_exp_root(p, q, be, ga, tmax, tau, lam) result(root)
      real(wp), intent(in) :: p, q, be, ga, tmax, tau, lam
      real(wp) :: tol, e1, e2, bound, cuts(4), x2, w, lo, hi, mid
      integer :: nc_, j
      root = huge(1.0_wp)
      if (q == 0.0_wp .or. lam == 1.0_wp / tau) then
         root = free_root(p + q, be, ga, tmax, tau)
         return
      end if
      if (.not. (tmax > 0.0_wp)) return
      tol = 1.0e-13_wp * (abs(p) + abs(q) + abs(be) + abs(ga) * tmax)
      e1 = exp(-tmax / tau)
      e2 = exp(-lam * tmax)
      bound = min(p, p * e1) + min(q, q * e2) - be - max(0.0_wp, ga * tmax)
      if (bound >= -tol) return
      ! the pieces: [0, x2], [x2, tmax] split at r'' = 0, each split again
      ! at r' = 0 (r' monotone on each)
      nc_ = 1
      cuts(1) = 0.0_wp
      if (p * q < 0.0_wp) then
         w = -q * lam * lam * tau * tau / p
         if (w > 0.0_wp) then
            x2 = log(w) / (lam - 1.0_wp / tau)
            if (x2 > 0.0_wp .and. x2 < tmax) then
               nc_ = nc_ + 1
               cuts(nc_) = x2
            end if
         end if
      end if
      nc_ = nc_ + 1
      cuts(nc_) = tmax
      ! each interval: where r' changes sign, its root splits it
      lo = 0.0_wp
      do j = 2, nc_
         hi = cuts(j)
         if (dr(cuts(j - 1)) * dr(hi) < 0.0_wp) then
            mid = slope_root(cuts(j - 1), hi)
            if (r(mid) < -tol) then
               root = crossing(lo, mid)
               return
            end if
            lo = mid
         end if
         if (r(hi) < -tol) then
            root = crossing(lo, hi)
            return
         end if
         lo = hi
      end do
   contains
      pure real(wp) function r(x)
         real(wp), intent(in) :: x
         r = p * exp(-x / tau) + q * exp(-lam * x) - be - ga * x
      end function r
      pure real(wp) function dr(x)
         real(wp), intent(in) :: x
         dr = -p / tau * exp(-x / tau) - q * lam * exp(-lam * x) - ga
      end function dr
      !> The root of r' between a and b (a sign change; r' monotone).
      pure real(wp) function slope_root(a, b) result(x)
         real(wp), intent(in) :: a, b
         x = illinois(a, b, .true.)
      end function slope_root
      !> r's first crossing below 0 in [a, b], r(a) >= -tol > r(b), r
      !> monotone there: the end of a bracket of width 4 eps at the root
      !> where r < 0.
      pure real(wp) function crossing(a, b) result(x)
         real(wp), intent(in) :: a, b
         x = illinois(a, b, .false.)
      end function crossing
      !> The Illinois variant of regula falsi on [a, b] for r (or r'),
      !> whose values at a and b differ in sign: superlinear, the bracket
      !> shrinking from both sides; returns the bracket's end on b's side.
      pure real(wp) function illinois(a, b, slope) result(x)
         real(wp), intent(in) :: a, b
         logical, intent(in) :: slope
         real(wp) :: xa, xb, fa, fb, fx
         integer :: it, side
         xa = a
         xb = b
         fa = g(a, slope)
         fb = g(b, slope)
         side = 0
         do it = 1, 200
            if (xb - xa <= 4.0_wp * epsilon(1.0_wp) * max(abs(xa), abs(xb))) exit
            x = xb - fb * (xb - xa) / (fb - fa)
            if (.not. (x > xa .and. x < xb)) x = 0.5_wp * (xa + xb)
            if (x <= xa .or. x >= xb) exit
            fx = g(x, slope)
            if (fx == 0.0_wp) then
               xb = x
               exit
            end if
            if ((fx > 0.0_wp) .eqv. (fa > 0.0_wp)) then
               xa = x
               fa = fx
               if (side == -1) fb = 0.5_wp * fb
               side = -1
            else
               xb = x
               fb = fx
               if (side == 1) fa = 0.5_wp * fa
               side = 1
            end if
         end do
         x = xb
      end function illinois
      !> r, or r' where slope.
      pure real(wp) function g(y, slope)
         real(wp), intent(in) :: y
         logical, intent(in) :: slope
         if (slope) then
            g = dr(y)
         else
            g = r(y)
         end if
      end function g
   end function two_exp_root

   !> (1 - exp(-x)) / x for x >= 0 (1 at 0; its series below 1e-4).
   pure real(wp) function phi1(x)
      real(wp), intent(in) :: x
      if (x < 1.0e-4_wp) then
         phi1 = 1.0_wp - x / 2.0_wp + x * x / 6.0_wp
      else
         phi1 = -expm1_neg(x) / x
      end if
   end function phi1

   !> (1 - exp(-x) (1 + x)) / x**2 for x >= 0 (1/2 at 0; its series below
   !> 1e-3).
   pure real(wp) function phi2(x)
      real(wp), intent(in) :: x
      if (x < 1.0e-3_wp) then
         phi2 = 0.5_wp - x / 3.0_wp + x * x / 8.0_wp
      else
         phi2 = (1.0_wp - exp(-x) * (1.0_wp + x)) / (x * x)
      end if
   end function phi2

   !> exp(-x) - 1, accurate for small x (x >= 1e-4 here: the direct form
   !> loses at most 4 digits there, so a series to 1e-1 keeps it).
   pure real(wp) function expm1_neg(x)
      real(wp), intent(in) :: x
      real(wp) :: term, total
      integer :: j
      if (x > 0.1_wp) then
         expm1_neg = exp(-x) - 1.0_wp
         return
      end if
      term = -x
      total = term
      do j = 2, 20
         term = -term * x / real(j, wp)
         total = total + term
      end do
      expm1_neg = total
   end function expm1_neg

end module pavefric_kv_exact
