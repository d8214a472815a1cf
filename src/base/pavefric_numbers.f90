!> Strict number parsing, shared by every reader (namelist values, profile
!> files): a token is a number by the grammar below or it is an error; no
!> list-directed leniency ('1-3' is not 0.001, '1+2' is not 100).
!>
!>   real    := sign? ( digits ( '.' digits? )? | '.' digits ) exponent?
!>   exponent:= ( 'e' | 'E' | 'd' | 'D' ) sign? digits
!>   integer := sign? digits
!>
!> A valid real is converted exactly: when its significand has at most 18
!> digits and fits 2**53, and its decimal exponent is at most 22 in size,
!> the value is one IEEE multiplication or division of two exact doubles,
!> hence correctly rounded (Clinger's fast path); any other token goes to
!> the C library's strtod (correctly rounded). Both give the bits of
!> gfortran's own formatted read, which also rounds correctly.
module pavefric_numbers
   use, intrinsic :: iso_c_binding, only: c_char, c_double, c_ptr, c_null_char, c_null_ptr
   use pavefric_kinds, only: wp, i8
   implicit none
   private

   public :: parse_real, parse_integer, is_real_syntax, is_nan_word, is_inf_word
   public :: convert_real

   ! strtod reads its argument and sets only errno: declared pure so that
   ! pure readers can use it.
   interface
      pure function c_strtod(str, endptr) bind(C, name="strtod") result(v)
         import :: c_char, c_double, c_ptr
         character(kind=c_char), intent(in) :: str(*)
         type(c_ptr), value :: endptr
         real(c_double) :: v
      end function c_strtod
   end interface

   !> Longest token converted through the stack buffer; longer ones (a
   !> thousand digits is still a number) go through an allocated copy.
   integer, parameter :: short_len = 64

   !> Exact powers of ten (10**22 < 2**53 * 2**22 is the largest exact one).
   real(wp), parameter :: pow10(0:22) = [1.0e0_wp, 1.0e1_wp, 1.0e2_wp, 1.0e3_wp, 1.0e4_wp, &
      & 1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp, 1.0e9_wp, 1.0e10_wp, 1.0e11_wp, 1.0e12_wp, &
      & 1.0e13_wp, 1.0e14_wp, 1.0e15_wp, 1.0e16_wp, 1.0e17_wp, 1.0e18_wp, 1.0e19_wp, &
      & 1.0e20_wp, 1.0e21_wp, 1.0e22_wp]
   !> Largest significand converted exactly to a double.
   integer(i8), parameter :: max_exact = 2_i8**53

contains

   !> Whether `tok` (no surrounding blanks) is a real number by the grammar.
   pure logical function is_real_syntax(tok)
      character(len=*), intent(in) :: tok
      integer :: i, n, nd
      is_real_syntax = .false.
      n = len(tok)
      i = 1
      if (n == 0) return
      if (tok(1:1) == "+" .or. tok(1:1) == "-") i = 2
      nd = 0
      do while (i <= n)
         if (.not. is_digit(tok(i:i))) exit
         nd = nd + 1
         i = i + 1
      end do
      if (i <= n) then
         if (tok(i:i) == ".") then
            i = i + 1
            do while (i <= n)
               if (.not. is_digit(tok(i:i))) exit
               nd = nd + 1
               i = i + 1
            end do
         end if
      end if
      if (nd == 0) return                 ! no mantissa digit: '.', '+', 'e5'
      if (i <= n) then
         if (index("eEdD", tok(i:i)) == 0) return
         i = i + 1
         if (i <= n) then
            if (tok(i:i) == "+" .or. tok(i:i) == "-") i = i + 1
         end if
         nd = 0
         do while (i <= n)
            if (.not. is_digit(tok(i:i))) exit
            nd = nd + 1
            i = i + 1
         end do
         if (nd == 0) return              ! '1e', '1e+'
      end if
      is_real_syntax = i > n
   end function is_real_syntax

   !> A real from `tok` (surrounding blanks allowed). stat = 0 on success, 1
   !> when the token is not a number by the grammar. Overflow gives
   !> +-Infinity with stat = 0: callers that need finite values check.
   pure subroutine parse_real(tok, value, stat)
      character(len=*), intent(in) :: tok
      real(wp), intent(out) :: value
      integer, intent(out) :: stat
      integer :: first, last
      value = 0.0_wp
      stat = 1
      first = verify(tok, " " // achar(9))
      if (first == 0) return
      last = verify(tok, " " // achar(9), back=.true.)
      call convert_real(tok(first:last), value, stat)
   end subroutine parse_real

   !> A real from `tok` exactly as it stands (no blanks), checked against the
   !> grammar and converted in the same pass. stat = 0 on success (overflow
   !> gives +-Infinity), 1 when `tok` is not a number. The readers' hot path.
   pure subroutine convert_real(tok, value, stat)
      character(len=*), intent(in) :: tok
      real(wp), intent(out) :: value
      integer, intent(out) :: stat
      integer(i8) :: m
      integer :: i, n, d, nsig, nd, dexp, expo, e10
      logical :: negative, exp_negative, slow
      value = 0.0_wp
      stat = 1
      n = len(tok)
      if (n == 0) return
      i = 1
      negative = .false.
      if (tok(1:1) == "-") then
         negative = .true.
         i = 2
      else if (tok(1:1) == "+") then
         i = 2
      end if
      m = 0
      nsig = 0          ! significant digits in m
      nd = 0            ! mantissa digits seen
      dexp = 0          ! decimal exponent of m's last digit
      slow = .false.    ! a digit did not fit m: strtod decides
      do while (i <= n)
         d = iachar(tok(i:i)) - 48
         if (d < 0 .or. d > 9) exit
         nd = nd + 1
         if (m > 0 .or. d > 0) then
            if (nsig < 18) then
               m = 10 * m + d
               nsig = nsig + 1
            else
               slow = .true.
            end if
         end if
         i = i + 1
      end do
      if (i <= n) then
         if (tok(i:i) == ".") then
            i = i + 1
            do while (i <= n)
               d = iachar(tok(i:i)) - 48
               if (d < 0 .or. d > 9) exit
               nd = nd + 1
               if (m > 0 .or. d > 0) then
                  if (nsig < 18) then
                     m = 10 * m + d
                     nsig = nsig + 1
                     dexp = dexp - 1
                  else
                     slow = .true.
                  end if
               else
                  dexp = dexp - 1            ! a leading zero after the point
               end if
               i = i + 1
            end do
         end if
      end if
      if (nd == 0) return                    ! no mantissa digit: '.', '+', 'e5'
      expo = 0
      if (i <= n) then
         select case (tok(i:i))
         case ("e", "E", "d", "D")
         case default
            return
         end select
         i = i + 1
         exp_negative = .false.
         if (i <= n) then
            if (tok(i:i) == "-") then
               exp_negative = .true.
               i = i + 1
            else if (tok(i:i) == "+") then
               i = i + 1
            end if
         end if
         nd = 0
         do while (i <= n)
            d = iachar(tok(i:i)) - 48
            if (d < 0 .or. d > 9) exit
            nd = nd + 1
            if (expo < 100000) expo = 10 * expo + d
            i = i + 1
         end do
         if (nd == 0) return                 ! '1e', '1e+'
         if (exp_negative) expo = -expo
      end if
      if (i <= n) return                     ! trailing characters: '1-3', '2.203-1'
      stat = 0
      e10 = dexp + expo
      if (m == 0) then
         value = 0.0_wp
      else if (.not. slow .and. m <= max_exact .and. abs(e10) <= 22) then
         ! both operands exact: one correctly rounded operation
         if (e10 >= 0) then
            value = real(m, wp) * pow10(e10)
         else
            value = real(m, wp) / pow10(-e10)
         end if
      else
         value = strtod_token(tok)
         return                              ! strtod applied the sign
      end if
      if (negative) value = -value
   end subroutine convert_real

   !> strtod of a token already checked against the grammar ('d' exponents as 'e').
   pure function strtod_token(tok) result(value)
      character(len=*), intent(in) :: tok
      real(wp) :: value
      character(kind=c_char, len=short_len+1) :: buf
      character(kind=c_char, len=:), allocatable :: long
      integer :: k, n
      n = len(tok)
      if (n <= short_len) then
         buf(1:n) = tok
         do k = 1, n
            if (buf(k:k) == "d" .or. buf(k:k) == "D") buf(k:k) = "e"
         end do
         buf(n+1:n+1) = c_null_char
         value = c_strtod(buf, c_null_ptr)
      else
         long = tok // c_null_char
         do k = 1, n
            if (long(k:k) == "d" .or. long(k:k) == "D") long(k:k) = "e"
         end do
         value = c_strtod(long, c_null_ptr)
      end if
   end function strtod_token

   !> An integer from `tok` (surrounding blanks allowed). stat = 0 on
   !> success, 1 when it is not an integer, 2 when it does not fit.
   pure subroutine parse_integer(tok, value, stat)
      character(len=*), intent(in) :: tok
      integer, intent(out) :: value
      integer, intent(out) :: stat
      integer :: first, last, i
      integer, parameter :: big = huge(1)
      integer :: digit
      logical :: negative
      value = 0
      stat = 1
      first = verify(tok, " " // achar(9))
      if (first == 0) return
      last = verify(tok, " " // achar(9), back=.true.)
      i = first
      negative = tok(i:i) == "-"
      if (tok(i:i) == "+" .or. tok(i:i) == "-") i = i + 1
      if (i > last) return
      do while (i <= last)
         if (.not. is_digit(tok(i:i))) then
            value = 0
            return
         end if
         digit = iachar(tok(i:i)) - iachar("0")
         if (value > (big - digit) / 10) then
            value = 0
            stat = 2
            return
         end if
         value = 10 * value + digit
         i = i + 1
      end do
      if (negative) value = -value
      stat = 0
   end subroutine parse_integer

   !> 'nan' in any case (what instruments write for a missing height).
   pure logical function is_nan_word(tok)
      character(len=*), intent(in) :: tok
      integer :: first, last
      is_nan_word = .false.
      first = verify(tok, " " // achar(9))
      if (first == 0) return
      last = verify(tok, " " // achar(9), back=.true.)
      if (last - first /= 2) return
      is_nan_word = index("nN", tok(first:first)) > 0 .and. index("aA", tok(first+1:first+1)) > 0 &
         & .and. index("nN", tok(last:last)) > 0
   end function is_nan_word

   !> 'inf', 'infinity' with an optional sign, in any case.
   pure logical function is_inf_word(tok)
      character(len=*), intent(in) :: tok
      character(len=:), allocatable :: t
      integer :: first, last, k
      is_inf_word = .false.
      first = verify(tok, " " // achar(9))
      if (first == 0) return
      last = verify(tok, " " // achar(9), back=.true.)
      t = tok(first:last)
      if (t(1:1) == "+" .or. t(1:1) == "-") t = t(2:)
      do k = 1, len(t)
         if (t(k:k) >= "A" .and. t(k:k) <= "Z") t(k:k) = achar(iachar(t(k:k)) + 32)
      end do
      is_inf_word = t == "inf" .or. t == "infinity"
   end function is_inf_word

   pure logical function is_digit(c)
      character, intent(in) :: c
      is_digit = c >= "0" .and. c <= "9"
   end function is_digit

end module pavefric_numbers
