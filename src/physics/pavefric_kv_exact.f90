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
module pavefric_kv_exact
   use pavefric_kinds, only: wp, i8
   use pavefric_balance, only: dry_root
   implicit none
   private

   public :: kv_exact_lane, kv_exact_type

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
      !> 0, or 1 when a step had more events than max_events (its position
      !> in bad_position), 2 when the work arrays could not be allocated.
      integer :: status = 0, bad_position = 0
   end type kv_exact_type

   !> Events allowed in one step per element (and 100 more): far above the
   !> few per step a real profile gives (about 0.5 per element).
   integer, parameter :: events_per_element = 40

contains

   !> One speed over the positions -n_spin .. n_avg - 1 of the pad's grid.
   !> z, adhesion and clamped_at are the refined profile as the driver lays
   !> it out (closed profiles extended by the pad's length); element i at
   !> position t stands on index k1(t) + (i - 1) spacing.
   subroutine kv_exact_lane(z, h, adhesion, clamped_at, n, spacing, npf, closed, n_avg, &
         & n_spin, k, tau, dt, advance, load, k_land, res, mu_inst, penetration, contact_count)
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

      real(wp), allocatable :: zc(:), s(:), u(:), f(:), a0(:), a1(:), f0(:), sl(:)
      logical, allocatable :: touch(:)
      real(wp) :: delta, a_coef, b_coef, theta, rem, hstep, e, t_ev, t_min, w_step, adh_int
      real(wp) :: ad_a, ad_b, f1, tolf, wk, hyst_sum, adh_sum
      ! an open profile's stretch: the elements' stored energy and the
      ! penetration at its start
      real(wp) :: stored_start, delta_start
      integer :: t, i, i_ev, nc, kp, kn, n_ev, stat, segments, last_el, graze
      logical :: series

      series = present(mu_inst)
      allocate(zc(n), s(n), u(n), f(n), a0(n), a1(n), f0(n), sl(n), touch(n), stat=stat)
      if (stat /= 0) then
         res%status = 2
         return
      end if
      tolf = 1.0e-12_wp * load
      wk = load / k

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
         n_ev = 0
         last_el = 0
         do
            call contact_set()
            if (res%status /= 0) return
            rem = dt - theta
            ! the earliest event
            t_min = huge(1.0_wp)
            i_ev = 0
            graze = 0
            do i = 1, n
               if (touch(i)) then
                  if (sl(i) < 0.0_wp) then
                     t_ev = max(f0(i), 0.0_wp) / (-sl(i))
                  else
                     cycle
                  end if
               else
                  t_ev = free_root(u(i) - delta + a_coef, a_coef + zc(i) - h(i), &
                     & b_coef + s(i), rem)
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
            end do
            e = exp(-hstep / tau)
            delta = a_coef + b_coef * hstep + (delta - a_coef) * e
            theta = theta + hstep
            do i = 1, n
               zc(i) = zc(i) + s(i) * hstep
               if (touch(i)) then
                  u(i) = delta + zc(i) - h(i)
               else
                  u(i) = u(i) * e
               end if
            end do
            if (hstep > 0.0_wp) last_el = 0
            if (t_min > rem) exit
            ! the event: its element changes side
            n_ev = n_ev + 1
            res%events = res%events + 1
            if (n_ev > events_per_element * n + 100) then
               res%status = 1
               res%bad_position = t
               return
            end if
            touch(i_ev) = .not. touch(i_ev)
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
         hyst_sum = hyst_sum + w_step / (load * advance)
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
         real(wp) :: s0, s1, worst, reach, best
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
            b_coef = -s1 / real(nc, wp)
            a_coef = (wk - s0) / real(nc, wp) - tau * b_coef
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
               if (f0(i) < worst) then
                  worst = f0(i)
                  iw = i
               end if
            end do
            if (iw == 0) return
            touch(iw) = .false.
            u(iw) = delta + zc(iw) - h(iw)
            f(iw) = 0.0_wp
            last_el = iw
         end do
         res%status = 1
         res%bad_position = t
      end subroutine contact_set

      !> The first root in (0, tmax] of r(x) = al exp(-x/tau) - be - ga x,
      !> r(0) taken as >= 0 (a free element); huge when there is none (or
      !> when r dips below 0 by no more than rounding).
      pure real(wp) function free_root(al, be, ga, tmax) result(root)
         real(wp), intent(in) :: al, be, ga, tmax
         real(wp) :: tm, q, tol, x_lo, x_hi, x, fx, dfx
         integer :: it
         root = huge(1.0_wp)
         tol = 1.0e-13_wp * (abs(al) + abs(be) + abs(ga) * tmax)
         ! where r is smallest on [0, tmax]: its end, or a convex r's minimum
         tm = tmax
         if (al > 0.0_wp .and. ga < 0.0_wp) then
            q = -ga * tau / al
            if (q < 1.0_wp) then
               tm = min(tmax, -tau * log(q))
            else
               return                       ! r' >= 0 from 0 on: r only grows
            end if
         end if
         if (.not. (tm > 0.0_wp)) return
         if (.not. (al * exp(-tm / tau) - be - ga * tm < -tol)) return
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
            fx = al * exp(-x / tau) - be - ga * x
            if (fx > 0.0_wp) then
               x_lo = x
            else
               x_hi = x
            end if
            if (x_hi - x_lo <= 4.0_wp * epsilon(1.0_wp) * x_hi) exit
            dfx = -al / tau * exp(-x / tau) - ga
            x = x - fx / dfx
            ! Newton inside the bracket, else bisection
            if (.not. (x > x_lo .and. x < x_hi)) x = 0.5_wp * (x_lo + x_hi)
            if (x <= x_lo .or. x >= x_hi) exit
         end do
         root = x_hi
      end function free_root

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
         res%max_balance_residual = max(res%max_balance_residual, abs(total - load) / load)
         if (ncount == 0) res%n_nocontact = res%n_nocontact + 1
         res%contact_share_sum = res%contact_share_sum + real(ncount, wp) / real(n, wp)
         if (first) then
            ! (the open profile's first position: no segment before it)
            if (series) mu_inst(1) = ad / load
            if (present(penetration)) penetration(1) = delta
            if (present(contact_count)) contact_count(1) = ncount
            return
         end if
         if (series) mu_inst(tt + 1) = hyst_step + adh_step
         if (present(penetration)) penetration(tt + 1) = delta
         if (present(contact_count)) contact_count(tt + 1) = ncount
      end subroutine record_node
   end subroutine kv_exact_lane

end module pavefric_kv_exact
