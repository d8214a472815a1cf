!> Operations on arrays of profile heights that both the readers and the
!> model need: checking them and refining them onto a finer grid. No I/O,
!> no physics (the model's driver uses this, not the file readers).
module pavefric_heights
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   implicit none
   private

   public :: check_heights, refine_profile

contains

   !> Error unless every height is finite.
   pure subroutine check_heights(z, error)
      real(wp), intent(in) :: z(:)
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      do k = 1, size(z)
         if (.not. (abs(z(k)) <= huge(1.0_wp))) then
            call fatal_error(error, "profile height " // to_str(k) // " = " // to_str(z(k)) // &
               & ": heights must be finite")
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

end module pavefric_heights
