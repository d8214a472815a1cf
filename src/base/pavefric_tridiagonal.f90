!> A tridiagonal system factored once and solved for several right sides, by
!> Gaussian elimination without pivoting. The matrices it is for are
!> column diagonally dominant (|a_jj| >= the sum of |a_ij|, i /= j, in every
!> column), which elimination preserves: every pivot is at least as large
!> in magnitude as the entry below it, so partial pivoting would swap no
!> rows (LAPACK's dgttrf keeps the row where |d| >= |dl|, ties included)
!> and the growth of the factors is at most 2 (Golub & Van Loan, "Matrix
!> Computations", 4th ed., sections 3.4.10 and 4.3; Wilkinson 1961). The
!> Reynolds film's systems are (pavefric_reynolds, assemble_and_solve). Written
!> in line with its caller: a pad's few tens of rows, solved many times a
!> position, where a library call and its argument checks cost as much as
!> the arithmetic.
module pavefric_tridiagonal
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: tridiagonal_factor, tridiagonal_solve

contains

   !> Factor the n x n tridiagonal matrix of sub-diagonal dl(1:n-1),
   !> diagonal d(1:n) and super-diagonal du(1:n-1) in place, without pivoting
   !> (the matrix column diagonally dominant): on return dl holds the
   !> multipliers and d the reciprocals of U's diagonal (the solve
   !> multiplies: a division is several times a product's latency, and the
   !> back substitution is a chain of them); du, U's super-diagonal, is
   !> unchanged. info = 0, or the first i with U(i, i) = 0 (the matrix is
   !> singular; the factors are not to be used).
   pure subroutine tridiagonal_factor(n, dl, d, du, info)
      integer, intent(in) :: n
      real(wp), intent(inout) :: dl(:), d(:)
      real(wp), intent(in) :: du(:)
      integer, intent(out) :: info
      integer :: i
      info = 0
      if (n < 1) return
      do i = 1, n - 1
         if (d(i) == 0.0_wp) then
            info = i
            return
         end if
         d(i) = 1.0_wp / d(i)
         dl(i) = dl(i) * d(i)
         d(i + 1) = d(i + 1) - dl(i) * du(i)
      end do
      if (d(n) == 0.0_wp) then
         info = n
         return
      end if
      d(n) = 1.0_wp / d(n)
   end subroutine tridiagonal_factor

   !> Solve the factored system (tridiagonal_factor's output, info = 0) for
   !> the right side b(1:n), overwritten by the solution.
   pure subroutine tridiagonal_solve(n, dl, d, du, b)
      integer, intent(in) :: n
      real(wp), intent(in) :: dl(:), d(:), du(:)
      real(wp), intent(inout) :: b(:)
      integer :: i
      if (n < 1) return
      do i = 1, n - 1
         b(i + 1) = b(i + 1) - dl(i) * b(i)
      end do
      b(n) = b(n) * d(n)
      do i = n - 1, 1, -1
         b(i) = (b(i) - du(i) * b(i + 1)) * d(i)
      end do
   end subroutine tridiagonal_solve

end module pavefric_tridiagonal
