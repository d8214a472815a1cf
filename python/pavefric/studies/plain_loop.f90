!> The plain loop: MODEL.md's pad written the obvious way in Fortran, one
!> speed at a time, one position at a time, the dry balance by sorting the
!> elements' gaps (insertion sort for a short pad, LAPACK dlasrt for a long
!> one) and scanning them, the wet balance by
!> bisection (as tests/reference.py). It is what "a plain Fortran loop"
!> means in the benchmark (python -m pavefric bench): the yardstick for the
!> core's kernel and for the whole program, compiled with the core's
!> optimisation (-O3 -funroll-loops). Default numerics only (one element a
!> sample, one step a sample, every position averaged); tests/test_reference.py
!> checks that it computes the core's friction.
!>
!> Usage: plain_loop HEIGHTS.bin DX CLOSED(0/1) DEPTH_M SPEED_KMH [SPEED_KMH...]
!> HEIGHTS.bin: the heights in metres as raw float64. Prints one JSON line:
!> the compute time (the reading excluded), the element-steps done and mu
!> per speed. Paper parameters: mu_loc 0.5, 20 mm x 16 mm pad, W 11.8 N,
!> K 1.4e8, C 1e2, water viscosity 1e-3, alpha 12.0, beta 1.75, theta_max 85.
program plain_loop
   use, intrinsic :: iso_fortran_env, only: int64, real64
   implicit none
   integer, parameter :: wp = real64
   real(wp), parameter :: mu_loc = 0.5_wp, length = 0.020_wp, width = 0.016_wp, &
      & load = 11.8_wp, stiffness = 1.4e8_wp, viscosity = 1.0e2_wp, eta = 1.0e-3_wp, &
      & alpha = 12.0_wp, beta = 1.75_wp, theta_max_deg = 85.0_wp
   real(wp), allocatable :: z(:), tan_t(:), u(:), c(:), cs(:), speeds(:), mu(:)
   real(wp), allocatable :: ze(:), te(:)
   real(wp) :: dx, depth, v, k_eff, kel, decay, pref, delta, s, level, total, mu_sum, wh
   real(wp) :: lo, hi, mid, f, hm, tmax, theta, slope
   integer :: n_p, n, nspeeds, a, j, i, k, js, j_first, j_last, m, unit, it, n_avg
   integer(int64) :: t0, t1, rate, steps, bytes
   logical :: closed
   character(len=4096) :: arg

   if (command_argument_count() < 5) then
      write (*, '(a)') "usage: plain_loop HEIGHTS.bin DX CLOSED DEPTH_M SPEED_KMH [...]"
      stop 1
   end if
   call get_command_argument(1, arg)
   open (newunit=unit, file=trim(arg), access="stream", form="unformatted", status="old", &
      & action="read")
   inquire (unit=unit, size=bytes)
   n_p = int(bytes / 8)
   allocate (z(n_p))
   read (unit) z
   close (unit)
   call get_command_argument(2, arg); read (arg, *) dx
   call get_command_argument(3, arg); closed = trim(arg) == "1"
   call get_command_argument(4, arg); read (arg, *) depth
   nspeeds = command_argument_count() - 4
   allocate (speeds(nspeeds), mu(nspeeds))
   do a = 1, nspeeds
      call get_command_argument(4 + a, arg)
      read (arg, *) speeds(a)
   end do

   call system_clock(t0, rate)
   n = int(floor(length / dx + 0.5_wp))
   allocate (tan_t(n_p), u(n), c(n), cs(n))
   tmax = theta_max_deg * acos(-1.0_wp) / 180.0_wp
   do k = 1, n_p                                          ! facets (Eq. 9)
      if (closed) then
         slope = (z(modulo(k, n_p) + 1) - z(modulo(k - 2, n_p) + 1)) / (2 * dx)
      else if (k == 1) then
         slope = (z(2) - z(1)) / dx
      else if (k == n_p) then
         slope = (z(n_p) - z(n_p - 1)) / dx
      else
         slope = (z(k + 1) - z(k - 1)) / (2 * dx)
      end if
      theta = atan(slope) + atan(mu_loc)
      tan_t(k) = tan(max(-tmax, min(tmax, theta)))
   end do
   ! the profile as the pad meets it, wrapped once round a closed profile
   if (closed) then
      j_first = 1 - n; j_last = n_p
      ze = [z(n_p - n + 1:n_p), z, z(1:n)]
      te = [tan_t(n_p - n + 1:n_p), tan_t, tan_t(1:n)]
   else
      j_first = 0; j_last = n_p - n
      ze = [z(1:n), z]
      te = [tan_t(1:n), tan_t]
   end if
   steps = 0
   do js = 1, nspeeds
      v = speeds(js) / 3.6_wp
      k_eff = stiffness + viscosity * v / dx
      kel = width * dx * k_eff
      decay = 0
      if (v > 0) decay = 1 / (1 + stiffness * (dx / v) / viscosity)
      pref = alpha * 6 * eta * v**beta * width * length**2
      u = 0
      mu_sum = 0
      n_avg = 0
      do j = j_first, j_last
         do i = 1, n
            k = j + i + n                                 ! z(j + i) wrapped
            u(i) = decay * u(i)                           ! free recovery
            c(i) = -ze(k) + u(i)
         end do
         ! dry balance: sum max(0, delta - c_i) = W / kel, by sorting and scanning
         cs = c
         if (n <= 32) then
            do i = 2, n
               level = cs(i)
               m = i - 1
               do while (m >= 1)
                  if (cs(m) <= level) exit
                  cs(m + 1) = cs(m)
                  m = m - 1
               end do
               cs(m + 1) = level
            end do
         else
            call dlasrt("I", n, cs, it)
         end if
         s = load / kel
         total = 0
         do m = 1, n
            total = total + cs(m)
            level = (s + total) / m
            if (m == n) then
               delta = level
            else if (level <= cs(m + 1)) then
               delta = level
               exit
            end if
         end do
         wh = 0
         if (depth > 0 .and. v > 0) then
            hm = sum(max(0.0_wp, c - delta)) / n
            if (hm < depth) then                           ! wet balance, by bisection
               lo = min(minval(c), sum(c) / n - depth)
               hi = delta
               do it = 1, 200
                  mid = 0.5_wp * (lo + hi)
                  if (mid <= lo .or. mid >= hi) exit
                  hm = sum(max(0.0_wp, c - mid)) / n
                  f = kel * sum(max(0.0_wp, mid - c)) + bearing(depth, hm, pref) - load
                  if (f > 0) then
                     hi = mid
                  else
                     lo = mid
                  end if
               end do
               delta = 0.5_wp * (lo + hi)
            end if
         end if
         f = 0
         do i = 1, n
            k = j + i + n
            f = f + kel * max(0.0_wp, delta - c(i)) * te(k)
            u(i) = max(delta + ze(k), u(i))               ! compressed to the pad's level
         end do
         steps = steps + n
         if (closed .and. j < 1) cycle                    ! spin-up
         mu_sum = mu_sum + f / load
         n_avg = n_avg + 1
      end do
      mu(js) = mu_sum / n_avg
   end do
   call system_clock(t1)
   write (*, '(a, es24.16, a, i0, a)', advance="no") '{"seconds": ', &
      & real(t1 - t0, wp) / real(rate, wp), ', "element_steps": ', steps, ', "mu": ['
   do js = 1, nspeeds
      write (*, '(es24.16, a)', advance="no") mu(js), merge(", ", "]}", js < nspeeds)
   end do
   write (*, *)

contains

   !> Eq. 15 (and MODEL.md's series near a = 1).
   pure real(wp) function bearing(h_in, h_out, prefactor)
      real(wp), intent(in) :: h_in, h_out, prefactor
      real(wp) :: a, e, bracket
      if (h_out >= h_in) then
         bearing = 0
      else if (h_out <= 0) then
         bearing = huge(1.0_wp)
      else
         a = h_in / h_out
         e = (h_in - h_out) / h_out
         if (e < 1e-3_wp) then
            bracket = e / 12 - e**2 / 8 + 11 * e**3 / 80 - 13 * e**4 / 96
         else
            bracket = (log(a) - 2 * (a - 1) / (a + 1)) / (a - 1)**2
         end if
         bearing = prefactor / h_out**2 * bracket
      end if
   end function bearing

end program plain_loop
