!> Operations on arrays of profile heights that both the readers and the
!> model need: checking them and refining them onto a finer grid. No I/O,
!> no physics (the model's driver uses this, not the file readers).
module pavefric_heights
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   implicit none
   private

   public :: check_heights, refine_profile, resample_to_length, resampled_points
   public :: max_profile_height

   !> Heights beyond +- this (m) are no road texture: refused (the file's
   !> reader names the line, the run the index).
   real(wp), parameter :: max_profile_height = 1.0e6_wp

contains

   !> Error unless every height is finite.
   pure subroutine check_heights(z, error)
      real(wp), intent(in) :: z(:)
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      do k = 1, size(z)
         if (.not. (abs(z(k)) <= huge(1.0_wp))) then
            call fatal_error(error, "profile height " // to_str(k) // " = " // to_str(z(k)) // &
               & ": heights must be finite; fill or remove the dropouts first (a profile " // &
               & "file: &preprocess dropouts = 'interpolate')")
            return
         end if
      end do
   end subroutine check_heights

   !> Linear interpolation onto a spacing `factor` times finer. A closed
   !> profile of n points gives n*factor points (the last interval wraps); an
   !> open one gives (n-1)*factor + 1. The original samples are kept exactly.
   !> `stat` (nonzero: zf could not be allocated, left unallocated).
   pure subroutine refine_profile(z, closed, factor, zf, stat)
      real(wp), intent(in) :: z(:)
      logical, intent(in) :: closed
      integer, intent(in) :: factor
      real(wp), allocatable, intent(out) :: zf(:)
      integer, intent(out) :: stat
      integer :: n, k, q, nxt
      real(wp) :: w
      n = size(z)
      if (closed) then
         allocate(zf(n * factor), stat=stat)
      else
         allocate(zf((n - 1) * factor + 1), stat=stat)
      end if
      if (stat /= 0) return
      if (.not. closed) zf(size(zf)) = z(n)
      do k = 1, n
         if (.not. closed .and. k == n) exit
         nxt = k + 1
         if (nxt > n) nxt = 1
         zf((k-1)*factor + 1) = z(k)
         do q = 1, factor - 1
            w = real(q, wp) / real(factor, wp)
            zf((k-1)*factor + 1 + q) = (1.0_wp - w) * z(k) + w * z(nxt)
         end do
      end do
   end subroutine refine_profile

   !> Points of a profile of n samples at spacing dx resampled to `length`
   !> from `phase` (a fraction of the new spacing, in [0, 1)): the size
   !> resample_to_length gives; 0 when it would exceed 2e9 (or, open, when
   !> the profile is shorter than the phase).
   pure integer function resampled_points(n, dx, closed, length, phase) result(m)
      integer, intent(in) :: n
      real(wp), intent(in) :: dx, length, phase
      logical, intent(in) :: closed
      real(wp) :: r
      m = 0
      if (closed) then
         r = real(n, wp) * dx / length
         if (r < 2.0e9_wp) m = max(1, nint(r))
      else
         r = real(n - 1, wp) * dx / length - phase
         if (r >= -1.0e-12_wp .and. r < 2.0e9_wp) m = int(max(0.0_wp, r) * &
            & (1.0_wp + 1.0e-12_wp) + 1.0e-12_wp) + 1
      end if
   end function resampled_points

   !> The profile seen by pad elements of length `length`: the mean height of
   !> its linear interpolant over a window (a box filter: the element's
   !> footprint, which removes what the element cannot resolve before the
   !> resampling can alias it), taken every `length` from `phase` x the new
   !> spacing. The window is narrower than the element by what the linear
   !> interpolant already averages: its width w has w^2 = length^2 - 2 dx^2
   !> (the variances of interpolating between point samples, dx^2/6, and of
   !> the window add up to one element's, length^2/12), so that a profile
   !> given at any spacing finer than the element is smoothed alike; no
   !> window at dx >= length / sqrt(2). A closed
   !> profile of circumference n dx gets a whole number m = nint(n dx /
   !> length) of samples at spacing n dx / m; an open one m samples at exactly
   !> `length` from its first point, its windows clipped at the ends. The
   !> integrals are exact for the linear interpolant; heights are taken
   !> relative to the first so that a vertical shift passes through.
   !> `stat` /= 0: the result could not be allocated.
   pure subroutine resample_to_length(z, dx, closed, length, phase, zr, dxr, stat)
      real(wp), intent(in) :: z(:), dx, length, phase
      logical, intent(in) :: closed
      real(wp), allocatable, intent(out) :: zr(:)
      real(wp), intent(out) :: dxr
      integer, intent(out) :: stat
      integer :: n, m, k, q, q0, q1
      real(wp) :: a, b, lo, hi, za, zb, w, integral, covered, z0, step, half
      n = size(z)
      m = resampled_points(n, dx, closed, length, phase)
      allocate(zr(max(m, 1)), stat=stat)
      if (stat /= 0) return
      if (closed) then
         dxr = real(n, wp) * dx / real(m, wp)
      else
         dxr = length
      end if
      z0 = z(1)
      step = dxr / dx                     ! the new spacing in old samples
      ! half a window in old samples: the window's variance w^2 / 12 and the
      ! linear interpolant's, 2 dx^2 / 12, make up one element's box,
      ! length^2 / 12
      half = 0.5_wp * sqrt(max(0.0_wp, (length / dx)**2 - 2.0_wp))
      do k = 1, m
         ! the window in units of the old spacing, sample 1 at 0
         a = (real(k - 1, wp) + phase) * step - half
         b = (real(k - 1, wp) + phase) * step + half
         if (.not. b - a > 1.0e-9_wp) then
            ! no window left: the interpolant at the point
            q0 = floor(a + half)
            zr(k) = z0 + value_at(q0, a + half - real(q0, wp))
            if (.not. closed .and. q0 > n - 2) zr(k) = z(n)
            if (.not. closed .and. q0 < 0) zr(k) = z(1)
            cycle
         end if
         q0 = floor(a)
         q1 = floor(b)
         integral = 0.0_wp
         covered = 0.0_wp
         do q = q0, q1
            ! interval q runs from sample q+1 to q+2 (1-based)
            if (.not. closed .and. (q < 0 .or. q > n - 2)) cycle
            lo = max(a, real(q, wp))
            hi = min(b, real(q + 1, wp))
            if (.not. hi > lo) cycle
            za = value_at(q, lo - real(q, wp))
            zb = value_at(q, hi - real(q, wp))
            w = hi - lo
            integral = integral + 0.5_wp * (za + zb) * w
            covered = covered + w
         end do
         if (covered > 0.0_wp) then
            zr(k) = z0 + integral / covered
         else
            zr(k) = z(min(n, nint((real(k - 1, wp) + phase) * step) + 1))
         end if
      end do
   contains
      !> The interpolant on interval q (wrapping round a closed profile) at
      !> fraction f of it, relative to z0.
      pure real(wp) function value_at(qq, f)
         integer, intent(in) :: qq
         real(wp), intent(in) :: f
         integer :: i1, i2
         i1 = modulo(qq, n) + 1
         i2 = modulo(qq + 1, n) + 1
         if (n == 1) i2 = i1
         value_at = (1.0_wp - f) * (z(i1) - z0) + f * (z(i2) - z0)
      end function value_at
   end subroutine resample_to_length

end module pavefric_heights
