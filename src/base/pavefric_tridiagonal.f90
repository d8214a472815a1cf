!> A tridiagonal system factored once and solved for several right sides:
!> Gaussian elimination with partial pivoting (rows i and i+1 swapped where
!> the sub-diagonal's entry is the larger in magnitude), the factors kept
!> (Golub & Van Loan, "Matrix Computations", 4th ed., section 4.3; the
!> algorithm of LAPACK's dgttrf and dgttrs, written here for one right side
!> and in line with its caller: the Reynolds film solves systems of a pad's
!> size, a few tens of rows, many times a position, where the library call
!> and its argument checks cost as much as the arithmetic).
module pavefric_tridiagonal
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: tridiagonal_factor, tridiagonal_solve

contains

   !> Factor the n x n tridiagonal matrix of sub-diagonal dl(1:n-1),
   !> diagonal d(1:n) and super-diagonal du(1:n-1) in place: on return dl
   !> holds the multipliers, d the reciprocals of U's diagonal (the solve
   !> multiplies: a division is several times a product's latency, and the
   !> back substitution is a chain of them), du U's first super-diagonal,
   !> du2(1:n-2) its second (the fill-in of a swap), and swapped(i) is 1
   !> where rows i and i+1 were swapped, else 0. info = 0, or the first i
   !> with U(i, i) = 0 (the matrix is singular; the factors are not to be
   !> used).
   pure subroutine tridiagonal_factor(n, dl, d, du, du2, swapped, info)
      integer, intent(in) :: n
      real(wp), intent(inout) :: dl(:), d(:), du(:)
      real(wp), intent(out) :: du2(:), swapped(:)
      integer, intent(out) :: info
      real(wp) :: factor, upper
      integer :: i
      info = 0
      do i = 1, n - 1
         if (abs(d(i)) >= abs(dl(i))) then
            ! no swap (a zero column stays zero: the singularity is found below)
            swapped(i) = 0.0_wp
            if (d(i) /= 0.0_wp) then
               factor = dl(i) / d(i)
               dl(i) = factor
               d(i + 1) = d(i + 1) - factor * du(i)
            end if
            if (i < n - 1) du2(i) = 0.0_wp
         else
            ! row i + 1 is the pivot's
            swapped(i) = 1.0_wp
            factor = d(i) / dl(i)
            d(i) = dl(i)
            dl(i) = factor
            upper = du(i)
            du(i) = d(i + 1)
            d(i + 1) = upper - factor * d(i + 1)
            if (i < n - 1) then
               du2(i) = du(i + 1)
               du(i + 1) = -factor * du(i + 1)
            end if
         end if
      end do
      do i = 1, n
         if (d(i) == 0.0_wp) then
            info = i
            return
         end if
      end do
      d(1:n) = 1.0_wp / d(1:n)
   end subroutine tridiagonal_factor

   !> Solve the factored system (tridiagonal_factor's output, info = 0) for
   !> the right side b(1:n), overwritten by the solution.
   pure subroutine tridiagonal_solve(n, dl, d, du, du2, swapped, b)
      integer, intent(in) :: n
      real(wp), intent(in) :: dl(:), d(:), du(:), du2(:), swapped(:)
      real(wp), intent(inout) :: b(:)
      real(wp) :: held
      integer :: i
      if (n < 1) return
      ! L, with the rows swapped as the factorisation did
      do i = 1, n - 1
         if (swapped(i) > 0.5_wp) then
            held = b(i)
            b(i) = b(i + 1)
            b(i + 1) = held - dl(i) * b(i)
         else
            b(i + 1) = b(i + 1) - dl(i) * b(i)
         end if
      end do
      ! U, from the bottom
      b(n) = b(n) * d(n)
      if (n > 1) b(n - 1) = (b(n - 1) - du(n - 1) * b(n)) * d(n - 1)
      do i = n - 2, 1, -1
         b(i) = (b(i) - du(i) * b(i + 1) - du2(i) * b(i + 2)) * d(i)
      end do
   end subroutine tridiagonal_solve

end module pavefric_tridiagonal
