!> Error handling: fallible routines return an allocatable error_type.
!>
!> Library code never stops; a caller tests `if (allocated(error)) return`.
module pavefric_error
   implicit none
   private

   public :: error_type, fatal_error

   !> An error with a status code and a one-line message.
   type :: error_type
      !> Non-zero status code.
      integer :: stat = 1
      !> Human-readable message naming what was wrong.
      character(len=:), allocatable :: message
   end type error_type

contains

   !> Allocate `error` with `message` (and an optional status code).
   pure subroutine fatal_error(error, message, stat)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: message
      integer, intent(in), optional :: stat
      allocate(error)
      error%message = message
      if (present(stat)) error%stat = stat
   end subroutine fatal_error

end module pavefric_error
