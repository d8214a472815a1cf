!> Interfaces of the LAPACK routines the core uses (reference LAPACK,
!> side-effect free, hence declared pure).
module pavefric_lapack
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: dlasrt, dgels

   interface
      !> Sort d(1:n): increasing with id = 'I', decreasing with 'D'.
      pure subroutine dlasrt(id, n, d, info)
         import :: wp
         character, intent(in) :: id
         integer, intent(in) :: n
         real(wp), intent(inout) :: d(*)
         integer, intent(out) :: info
      end subroutine dlasrt

      !> Least squares by QR: min |A x - B| for a full-rank m x n A.
      pure subroutine dgels(trans, m, n, nrhs, a, lda, b, ldb, work, lwork, info)
         import :: wp
         character, intent(in) :: trans
         integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
         real(wp), intent(inout) :: a(lda, *), b(ldb, *)
         real(wp), intent(out) :: work(*)
         integer, intent(out) :: info
      end subroutine dgels
   end interface

end module pavefric_lapack
