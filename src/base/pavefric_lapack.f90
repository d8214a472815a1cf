!> Interfaces of the LAPACK routines the core uses (reference LAPACK,
!> side-effect free, hence declared pure).
module pavefric_lapack
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: dlasrt

   interface
      !> Sort d(1:n): increasing with id = 'I', decreasing with 'D'.
      pure subroutine dlasrt(id, n, d, info)
         import :: wp
         character, intent(in) :: id
         integer, intent(in) :: n
         real(wp), intent(inout) :: d(*)
         integer, intent(out) :: info
      end subroutine dlasrt
   end interface

end module pavefric_lapack
