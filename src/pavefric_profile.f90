!> Texture profiles: reading plain text files, checking and refining them.
!> No physics here.
module pavefric_profile
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   implicit none
   private

   public :: profile_type, read_profile_text, unit_factor, refine_profile, check_heights

   !> A profile of heights z at a uniform spacing.
   type :: profile_type
      !> Heights (m), positive up.
      real(wp), allocatable :: z(:)
      !> Spacing (m); 0 when the file gave no distances.
      real(wp) :: dx = 0.0_wp
      !> Whether the file held a distance column.
      logical :: has_x = .false.
   end type profile_type

contains

   !> Metres per unit for a height unit name; 0 when unknown.
   pure function unit_factor(name) result(f)
      character(len=*), intent(in) :: name
      real(wp) :: f
      select case (trim(adjustl(name)))
      case ("m")
         f = 1.0_wp
      case ("mm")
         f = 1.0e-3_wp
      case ("um")
         f = 1.0e-6_wp
      case default
         f = 0.0_wp
      end select
   end function unit_factor

   !> Read a profile from a text file: one column of heights, or two columns
   !> (distance, height), both in `factor` metres per unit. Blank lines and
   !> text after '#' are ignored; the first non-comment line may be a header.
   !> Separators: blanks, tabs, commas or semicolons. A two-column file must
   !> have a uniform spacing (within 1 %).
   subroutine read_profile_text(path, factor, prof, error)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: factor
      type(profile_type), intent(out) :: prof
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: line, tok
      character(len=512) :: msg
      real(wp), allocatable :: xs(:), zs(:)
      real(wp) :: vals(2), step
      integer :: unit, ios, lineno, n, ncol, ntok, pos, i
      logical :: header_seen

      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': cannot open (" // &
            & trim(msg) // ")")
         return
      end if
      allocate(xs(1024), zs(1024))
      n = 0
      ncol = 0
      lineno = 0
      header_seen = .false.
      do
         call read_line(unit, line, ios)
         if (ios /= 0) exit
         lineno = lineno + 1
         pos = index(line, "#")
         if (pos > 0) line = line(1:pos-1)
         if (len_trim(line) == 0) cycle
         ! tokenise and parse
         ntok = 0
         pos = 1
         do
            call next_token(line, pos, tok)
            if (len(tok) == 0) exit
            ntok = ntok + 1
            if (ntok > 2) exit
            ! list-directed input gives '/' and '*' a meaning of their own
            ios = 1
            if (scan(tok, "/*") == 0) read(tok, *, iostat=ios) vals(ntok)
            if (ios /= 0) exit
         end do
         if (ios /= 0 .or. ntok > 2) then
            if (n == 0 .and. .not. header_seen .and. ios /= 0) then
               header_seen = .true.          ! one header line is allowed
               cycle
            end if
            if (ntok > 2) then
               call fatal_error(error, path // ":" // to_str(lineno) // &
                  & ": more than two columns (expected heights, or distance and height)")
            else
               call fatal_error(error, path // ":" // to_str(lineno) // ": '" // tok // &
                  & "' is not a number")
            end if
            close(unit)
            return
         end if
         if (ncol == 0) ncol = ntok
         if (ntok /= ncol) then
            call fatal_error(error, path // ":" // to_str(lineno) // ": " // to_str(ntok) // &
               & " columns where earlier lines have " // to_str(ncol))
            close(unit)
            return
         end if
         do i = 1, ntok
            if (.not. (abs(vals(i)) <= huge(1.0_wp))) then
               call fatal_error(error, path // ":" // to_str(lineno) // ": value " // &
                  & to_str(vals(i)) // " is not finite")
               close(unit)
               return
            end if
         end do
         n = n + 1
         if (n > size(zs)) call grow(xs, zs)
         if (ncol == 2) then
            xs(n) = vals(1) * factor
            zs(n) = vals(2) * factor
         else
            zs(n) = vals(1) * factor
         end if
      end do
      close(unit)
      if (n == 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': holds no heights")
         return
      end if
      prof%z = zs(1:n)
      prof%has_x = ncol == 2
      if (prof%has_x) then
         if (n < 2) then
            call fatal_error(error, path // ": a distance column needs at least two points")
            return
         end if
         prof%dx = (xs(n) - xs(1)) / real(n - 1, wp)
         if (.not. (prof%dx > 0.0_wp)) then
            call fatal_error(error, path // ": distances do not increase")
            return
         end if
         do i = 2, n
            step = xs(i) - xs(i-1)
            if (abs(step - prof%dx) > 0.01_wp * prof%dx) then
               call fatal_error(error, path // ": non-uniform spacing near data point " // &
                  & to_str(i) // " (step " // to_str(step) // " m against mean " // &
                  & to_str(prof%dx) // " m)")
               return
            end if
         end do
      end if
   end subroutine read_profile_text

   !> Error unless every height is finite.
   pure subroutine check_heights(z, error)
      real(wp), intent(in) :: z(:)
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      do k = 1, size(z)
         if (.not. (abs(z(k)) <= huge(1.0_wp))) then
            call fatal_error(error, "profile height " // to_str(k) // " = " // to_str(z(k)) // &
               & ": heights must be finite")
            return
         end if
      end do
   end subroutine check_heights

   !> Linear interpolation onto a spacing `factor` times finer. A closed
   !> profile of n points gives n*factor points (the last interval wraps); an
   !> open one gives (n-1)*factor + 1. The original samples are kept exactly.
   pure subroutine refine_profile(z, closed, factor, zf)
      real(wp), intent(in) :: z(:)
      logical, intent(in) :: closed
      integer, intent(in) :: factor
      real(wp), allocatable, intent(out) :: zf(:)
      integer :: n, k, q, nxt
      real(wp) :: w
      n = size(z)
      if (closed) then
         allocate(zf(n * factor))
      else
         allocate(zf((n - 1) * factor + 1))
         zf(size(zf)) = z(n)
      end if
      do k = 1, n
         if (.not. closed .and. k == n) exit
         nxt = k + 1
         if (nxt > n) nxt = 1
         zf((k-1)*factor + 1) = z(k)
         do q = 1, factor - 1
            w = real(q, wp) / real(factor, wp)
            zf((k-1)*factor + 1 + q) = (1.0_wp - w) * z(k) + w * z(nxt)
         end do
      end do
   end subroutine refine_profile

   !> Grow two work arrays to twice their size.
   pure subroutine grow(a, b)
      real(wp), allocatable, intent(inout) :: a(:), b(:)
      real(wp), allocatable :: t(:)
      allocate(t(2*size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
      allocate(t(2*size(b)))
      t(1:size(b)) = b
      call move_alloc(t, b)
   end subroutine grow

   !> Next token of `line` from `pos`; separators are blanks, tabs, ',' and ';'.
   pure subroutine next_token(line, pos, tok)
      character(len=*), intent(in) :: line
      integer, intent(inout) :: pos
      character(len=:), allocatable, intent(out) :: tok
      integer :: start
      do while (pos <= len(line))
         if (index(" " // achar(9) // ",;" // achar(13), line(pos:pos)) == 0) exit
         pos = pos + 1
      end do
      start = pos
      do while (pos <= len(line))
         if (index(" " // achar(9) // ",;" // achar(13), line(pos:pos)) > 0) exit
         pos = pos + 1
      end do
      tok = line(start:pos-1)
   end subroutine next_token

   !> Read one whole line of any length.
   subroutine read_line(unit, line, ios)
      integer, intent(in) :: unit
      character(len=:), allocatable, intent(out) :: line
      integer, intent(out) :: ios
      character(len=4096) :: buf
      integer :: nread
      line = ""
      do
         read(unit, '(a)', advance="no", iostat=ios, size=nread) buf
         line = line // buf(1:nread)
         if (is_iostat_eor(ios)) then
            ios = 0
            return
         end if
         if (ios /= 0) then
            if (is_iostat_end(ios) .and. len(line) > 0) ios = 0
            return
         end if
      end do
   end subroutine read_line

end module pavefric_profile
