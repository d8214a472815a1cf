!> Error handling: fallible routines return an allocatable error_type.
!>
!> Library code never stops; a caller tests `if (allocated(error)) return`.
!> The status says what kind of failure it was, so the program can choose
!> its exit code and Python its exception (MemoryError for stat_memory).
module pavefric_error
   implicit none
   private

   public :: error_type, fatal_error, add_warning, add_warnings
   public :: stat_input, stat_internal, stat_memory, stat_io

   !> Bad input: a namelist value, a profile file, a scene that cannot run.
   integer, parameter :: stat_input = 1
   !> An inconsistency inside pavefric (a bug): please report it.
   integer, parameter :: stat_internal = 2
   !> Not enough memory for the work asked for (estimated or failed allocation).
   integer, parameter :: stat_memory = 3
   !> A file could not be written or read back (disk full, permissions).
   integer, parameter :: stat_io = 4

   !> An error with a status code and a one-line message.
   type :: error_type
      !> Non-zero status code (stat_input, stat_internal, stat_memory, stat_io).
      integer :: stat = stat_input
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
      call printable(message, error%message)
      if (present(stat)) error%stat = stat
   end subroutine fatal_error

   !> Append one line to a list of warnings (lines separated by newlines):
   !> plausible-but-suspicious input or results, printed by the program,
   !> raised as warnings in Python and recorded in the output.
   pure subroutine add_warning(warnings, line)
      character(len=:), allocatable, intent(inout) :: warnings
      character(len=*), intent(in) :: line
      character(len=:), allocatable :: clean
      if (.not. allocated(warnings)) warnings = ""
      if (len(warnings) > 0) warnings = warnings // achar(10)
      call printable(line, clean)
      warnings = warnings // clean
   end subroutine add_warning

   !> Append a list of warnings (lines separated by newlines, as add_warning
   !> builds them) line by line: each stays its own line, its newline not
   !> escaped as one line's control character would be.
   pure subroutine add_warnings(warnings, lines)
      character(len=:), allocatable, intent(inout) :: warnings
      character(len=*), intent(in) :: lines
      integer :: start, stop
      start = 1
      do while (start <= len(lines))
         stop = index(lines(start:), achar(10))
         if (stop == 0) then
            stop = len(lines) + 1
         else
            stop = start + stop - 1
         end if
         if (stop > start) call add_warning(warnings, lines(start:stop - 1))
         start = stop + 1
      end do
   end subroutine add_warnings

   !> `text` with every control character (a form feed, a tab, a line break
   !> quoted from the input) written as \xHH: a message is one line on a
   !> terminal and in Python, whatever bytes of the input it quotes.
   pure subroutine printable(text, clean)
      character(len=*), intent(in) :: text
      character(len=:), allocatable, intent(out) :: clean
      character(len=*), parameter :: hex = "0123456789abcdef"
      integer :: k, n, c
      n = 0
      do k = 1, len(text)
         c = iachar(text(k:k))
         n = n + merge(4, 1, c < 32 .or. c == 127)
      end do
      allocate(character(len=n) :: clean)
      n = 0
      do k = 1, len(text)
         c = iachar(text(k:k))
         if (c < 32 .or. c == 127) then
            clean(n+1:n+4) = "\x" // hex(c/16+1:c/16+1) // hex(mod(c, 16)+1:mod(c, 16)+1)
            n = n + 4
         else
            n = n + 1
            clean(n:n) = text(k:k)
         end if
      end do
   end subroutine printable

end module pavefric_error
