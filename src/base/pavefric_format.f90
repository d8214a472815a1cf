!> Small helpers that turn numbers into text for messages and attributes.
module pavefric_format
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use pavefric_kinds, only: wp, i8
   implicit none
   private

   public :: to_str, to_lower, round_sig, real_to_str_text, friction_table_text

   !> Shortest faithful text of a number.
   interface to_str
      module procedure :: real_to_str
      module procedure :: int_to_str
      module procedure :: int8_to_str
      module procedure :: logical_to_str
   end interface to_str

contains

   !> A real as its shortest text that reads back to the same value, in the
   !> style of C's %g: fixed notation for exponents -5..5 (0.02, 120,
   !> -0.00087), scientific otherwise (1.4e8, 1e-9).
   pure function real_to_str(x) result(s)
      real(wp), intent(in) :: x
      character(len=real_to_str_len(x)) :: s
      character(len=:), allocatable :: deferred_text
      call real_to_str_text(x, deferred_text)
      s = deferred_text
   end function real_to_str

   !> The length of real_to_str's text.
   pure integer function real_to_str_len(x)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: deferred_text
      call real_to_str_text(x, deferred_text)
      real_to_str_len = len(deferred_text)
   end function real_to_str_len

   !> The text of real_to_str, into a deferred-length argument.
   pure subroutine real_to_str_text(x, s)
      real(wp), intent(in) :: x
      character(len=:), allocatable, intent(out) :: s
      character(len=40) :: buf
      character(len=12) :: fmt
      character(len=:), allocatable :: digits
      real(wp) :: back
      integer :: p, ios, epos, expo, ndig, lo, hi
      if (ieee_is_nan(x)) then
         s = "NaN"
         return
      else if (abs(x) > huge(x)) then
         s = "Infinity"
         if (x < 0.0_wp) s = "-Infinity"
         return
      else if (x == 0.0_wp) then
         s = "0"
         return
      end if
      ! the fewest significant digits (1..17; 17 always read back) by
      ! bisection: a text of more digits, correctly rounded, is no farther
      ! from x (a handful of internal writes and reads, not up to 17 of each)
      lo = 1
      hi = 17
      do while (lo < hi)
         p = (lo + hi) / 2
         write(fmt, '(a, i0, a)') "(es30.", p - 1, "e3)"
         write(buf, fmt) x
         read(buf, *, iostat=ios) back
         if (ios == 0 .and. back == x) then
            hi = p
         else
            lo = p + 1
         end if
      end do
      write(fmt, '(a, i0, a)') "(es30.", lo - 1, "e3)"
      write(buf, fmt) x
      buf = adjustl(buf)
      epos = scan(buf, "Ee")
      read(buf(epos+1:), *) expo
      ! mantissa digits without sign and point, trailing zeros removed
      digits = ""
      do p = 1, epos - 1
         if (verify(buf(p:p), "0123456789") == 0) digits = digits // buf(p:p)
      end do
      ndig = len(digits)
      do while (ndig > 1)
         if (digits(ndig:ndig) /= "0") exit
         ndig = ndig - 1
      end do
      digits = digits(1:ndig)
      if (expo >= -5 .and. expo <= 5) then
         if (expo >= 0) then
            if (ndig <= expo + 1) then
               s = digits // repeat("0", expo + 1 - ndig)
            else
               s = digits(1:expo+1) // "." // digits(expo+2:)
            end if
         else
            s = "0." // repeat("0", -expo - 1) // digits
         end if
      else
         if (ndig == 1) then
            s = digits
         else
            s = digits(1:1) // "." // digits(2:)
         end if
         s = s // "e" // int_to_str(expo)
      end if
      if (x < 0.0_wp) s = "-" // s
   end subroutine real_to_str_text

   !> x rounded to n significant digits (for messages: to_str(round_sig(x, 3))
   !> prints 0.0015 where x is 0.0014999999999999944). Not finite: x.
   pure real(wp) function round_sig(x, n)
      real(wp), intent(in) :: x
      integer, intent(in) :: n
      character(len=40) :: buf
      character(len=16) :: fmt
      integer :: ios
      round_sig = x
      if (ieee_is_nan(x) .or. abs(x) > huge(x) .or. x == 0.0_wp) return
      write(fmt, '(a, i0, a)') "(es30.", max(n, 1) - 1, "e3)"
      write(buf, fmt) x
      read(buf, *, iostat=ios) round_sig
      if (ios /= 0) round_sig = x
   end function round_sig

   !> ASCII letters in lower case.
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i
      t = s
      do i = 1, len(s)
         if (s(i:i) >= "A" .and. s(i:i) <= "Z") t(i:i) = achar(iachar(s(i:i)) + 32)
      end do
   end function to_lower

   !> A default integer as text.
   pure function int_to_str(i) result(s)
      integer, intent(in) :: i
      character(len=int_to_str_len(i)) :: s
      character(len=:), allocatable :: deferred_text
      call int_to_str_text(i, deferred_text)
      s = deferred_text
   end function int_to_str

   !> The length of int_to_str's text.
   pure integer function int_to_str_len(i)
      integer, intent(in) :: i
      character(len=:), allocatable :: deferred_text
      call int_to_str_text(i, deferred_text)
      int_to_str_len = len(deferred_text)
   end function int_to_str_len

   !> The text of int_to_str, into a deferred-length argument.
   pure subroutine int_to_str_text(i, s)
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end subroutine int_to_str_text

   !> A 64-bit integer as text.
   pure function int8_to_str(i) result(s)
      integer(i8), intent(in) :: i
      character(len=int8_to_str_len(i)) :: s
      character(len=:), allocatable :: deferred_text
      call int8_to_str_text(i, deferred_text)
      s = deferred_text
   end function int8_to_str

   !> The length of int8_to_str's text.
   pure integer function int8_to_str_len(i)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: deferred_text
      call int8_to_str_text(i, deferred_text)
      int8_to_str_len = len(deferred_text)
   end function int8_to_str_len

   !> The text of int8_to_str, into a deferred-length argument.
   pure subroutine int8_to_str_text(i, s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable, intent(out) :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end subroutine int8_to_str_text

   !> A logical as Fortran namelist text.
   pure function logical_to_str(b) result(s)
      logical, intent(in) :: b
      character(len=logical_to_str_len(b)) :: s
      character(len=:), allocatable :: deferred_text
      call logical_to_str_text(b, deferred_text)
      s = deferred_text
   end function logical_to_str

   !> The length of logical_to_str's text.
   pure integer function logical_to_str_len(b)
      logical, intent(in) :: b
      character(len=:), allocatable :: deferred_text
      call logical_to_str_text(b, deferred_text)
      logical_to_str_len = len(deferred_text)
   end function logical_to_str_len

   !> The text of logical_to_str, into a deferred-length argument.
   pure subroutine logical_to_str_text(b, s)
      logical, intent(in) :: b
      character(len=:), allocatable, intent(out) :: s
      if (b) then
         s = ".true."
      else
         s = ".false."
      end if
   end subroutine logical_to_str_text

   !> A scene's run and its friction against speed as the program prints
   !> them (and `python -m pavefric run`): the pad's elements, the averaged
   !> positions and the effects that ran, a header and one line a speed,
   !> each line ending in a newline; the last column where `err` is given
   !> (mu's estimated error). mu in 12 columns: fixed point, or exponent form
   !> from 1e4 on (a wider number ran into the speed's column).
   pure subroutine friction_table_text(elements, positions, effects, speed_kmh, mu, wet, &
         & hydroplaning, text, err)
      integer, intent(in) :: elements, positions
      character(len=*), intent(in) :: effects
      real(wp), intent(in) :: speed_kmh(:), mu(:), wet(:), hydroplaning(:)
      real(wp), intent(in), optional :: err(:)
      character(len=:), allocatable, intent(out) :: text
      character(len=12) :: mu_text
      character(len=80) :: line
      integer :: j
      text = "  pad elements: " // to_str(elements) // ", averaged positions: " // &
         & to_str(positions) // ", effects: " // effects // achar(10)
      text = text // "  speed_kmh          mu   wet_fraction  hydroplaning"
      if (present(err)) text = text // "  mu_error_estimate"
      text = text // achar(10)
      do j = 1, size(mu)
         if (abs(mu(j)) < 1.0e4_wp) then
            write(mu_text, '(f12.5)') mu(j)
         else
            write(mu_text, '(es12.4e3)') mu(j)
         end if
         if (present(err)) then
            write(line, '(f11.3, a12, f15.4, f14.4, es19.2)') speed_kmh(j), mu_text, wet(j), &
               & hydroplaning(j), err(j)
         else
            write(line, '(f11.3, a12, f15.4, f14.4)') speed_kmh(j), mu_text, wet(j), &
               & hydroplaning(j)
         end if
         text = text // trim(line) // achar(10)
      end do
   end subroutine friction_table_text

end module pavefric_format
