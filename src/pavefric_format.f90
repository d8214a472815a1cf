!> Small helpers that turn numbers into text for messages and attributes.
module pavefric_format
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use pavefric_kinds, only: wp, i8
   implicit none
   private

   public :: to_str

   !> Shortest faithful text of a number.
   interface to_str
      module procedure :: real_to_str
      module procedure :: int_to_str
      module procedure :: int8_to_str
      module procedure :: logical_to_str
   end interface to_str

contains

   !> A real as text with enough digits to identify it (G0 editing).
   pure function real_to_str(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=40) :: buf
      if (ieee_is_nan(x)) then
         s = "NaN"
      else if (abs(x) > huge(x)) then
         if (x > 0) then
            s = "Infinity"
         else
            s = "-Infinity"
         end if
      else
         write(buf, '(es23.16e3)') x
         s = trim(adjustl(buf))
         call strip_mantissa_zeros(s)
      end if
   end function real_to_str

   !> Remove trailing zeros of the mantissa: 1.5000E+002 -> 1.5E+002.
   pure subroutine strip_mantissa_zeros(s)
      character(len=:), allocatable, intent(inout) :: s
      integer :: epos, last
      epos = scan(s, "Ee")
      if (epos <= 1) return
      last = epos - 1
      do while (last > 1)
         if (s(last:last) /= "0") exit
         last = last - 1
      end do
      if (s(last:last) == ".") last = last - 1
      s = s(1:last) // "e" // exponent_text(s(epos+1:))
   end subroutine strip_mantissa_zeros

   !> "+002" -> "2", "-003" -> "-3".
   pure function exponent_text(e) result(t)
      character(len=*), intent(in) :: e
      character(len=:), allocatable :: t
      integer :: ev, ios
      read(e, *, iostat=ios) ev
      if (ios /= 0) then
         t = e
      else
         t = int_to_str(ev)
      end if
   end function exponent_text

   !> A default integer as text.
   pure function int_to_str(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function int_to_str

   !> A 64-bit integer as text.
   pure function int8_to_str(i) result(s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function int8_to_str

   !> A logical as Fortran namelist text.
   pure function logical_to_str(b) result(s)
      logical, intent(in) :: b
      character(len=:), allocatable :: s
      if (b) then
         s = ".true."
      else
         s = ".false."
      end if
   end function logical_to_str

end module pavefric_format
