!> Interfaces of the LAPACK routines the core uses (reference LAPACK,
!> side-effect free, hence declared pure).
module pavefric_lapack
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: dlasrt, dgels, dgtsv

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

      !> Solve a tridiagonal system (sub-diagonal dl, diagonal d, super-
      !> diagonal du; overwritten) by Gaussian elimination with partial
      !> pivoting; b holds the right-hand sides, then the solutions.
      pure subroutine dgtsv(n, nrhs, dl, d, du, b, ldb, info)
         import :: wp
         integer, intent(in) :: n, nrhs, ldb
         real(wp), intent(inout) :: dl(*), d(*), du(*), b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgtsv
   end interface

end module pavefric_lapack
