!> Texture profiles: reading plain text files, checking and refining them.
!> No physics here.
module pavefric_profile
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str, to_lower
   implicit none
   private

   public :: profile_type, read_profile_text, unit_factor, refine_profile, check_heights
   public :: raw_profile_type, read_raw_profile, detect_format

   !> A profile of heights z at a uniform spacing.
   type :: profile_type
      !> Heights (m), positive up.
      real(wp), allocatable :: z(:)
      !> Spacing (m); 0 when the file gave no distances.
      real(wp) :: dx = 0.0_wp
      !> Whether the file held a distance column.
      logical :: has_x = .false.
      !> The distances (m), when the file held them.
      real(wp), allocatable :: x(:)
   end type profile_type

   !> A profile as an instrument file delivers it: distances (if any),
   !> heights, which points are dropouts, and the file line of each point.
   type :: raw_profile_type
      !> Distances (m), when the file had them.
      real(wp), allocatable :: x(:)
      !> Heights (m); undefined where `valid` is false.
      real(wp), allocatable :: z(:)
      !> False for a dropout (empty, NaN or missing height).
      logical, allocatable :: valid(:)
      !> Line of the file each point came from.
      integer, allocatable :: line(:)
      !> Whether distances were read.
      logical :: has_x = .false.
      !> The format that was read: 'plain', 'captif' or 'csv'.
      character(len=:), allocatable :: format
      !> The file.
      character(len=:), allocatable :: path
   end type raw_profile_type

   !> Grow a work array to twice its size.
   interface double_size
      module procedure :: double_real, double_int, double_logical
   end interface double_size

contains

   !> The format of a profile file from its content: 'captif' when a line
   !> starts with '*****DATA*****' (laser profiler export), 'csv' when the
   !> first non-comment line holds commas and a name, 'plain' otherwise.
   subroutine detect_format(path, format, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: format
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: line
      character(len=512) :: msg
      integer :: unit, ios, pos
      logical :: first
      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': cannot open (" // &
            & trim(msg) // ")")
         return
      end if
      format = "plain"
      first = .true.
      do
         call read_line(unit, line, ios)
         if (ios /= 0) exit
         if (index(line, "*****DATA*****") == 1) then
            format = "captif"
            exit
         end if
         pos = index(line, "#")
         if (pos > 0) line = line(1:pos-1)
         if (len_trim(line) == 0) cycle
         if (first) then
            first = .false.
            if (index(line, ",") > 0 .and. scan(line, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ") > 0) &
               & format = "csv"
            if (format == "csv") exit
         end if
      end do
      close(unit)
   end subroutine detect_format

   !> Read an instrument or text profile with its dropouts. `format`: 'auto',
   !> 'plain', 'captif' or 'csv'. Heights (and distances) are converted with
   !> `factor` metres per unit unless the file states its unit ('(mm)' in a
   !> CAPTIF or CSV header). For CSV, `x_column` and `z_column` name the
   !> columns (empty: the first whose name holds 'dist' or 'x', and the first
   !> holding 'height', 'depth', 'elev' or 'z').
   subroutine read_raw_profile(path, format, factor, x_column, z_column, raw, error)
      character(len=*), intent(in) :: path, format, x_column, z_column
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(out) :: raw
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: fmt, line, tok
      character(len=512) :: msg
      real(wp), allocatable :: xs(:), zs(:)
      logical, allocatable :: ok(:)
      integer, allocatable :: lines(:)
      real(wp) :: v, xf, zf
      integer :: unit, ios, lineno, n, pos, ix, iz, nf, k
      logical :: in_data, header_done
      character :: sep

      fmt = trim(adjustl(format))
      if (fmt == "auto") then
         call detect_format(path, fmt, error)
         if (allocated(error)) return
      end if
      if (fmt /= "plain" .and. fmt /= "captif" .and. fmt /= "csv") then
         call fatal_error(error, "&surface format = '" // fmt // &
            & "': unknown (expected 'auto', 'plain', 'captif' or 'csv')")
         return
      end if
      raw%format = fmt
      raw%path = path
      if (fmt == "plain") then
         call read_plain(path, factor, raw, error)
         return
      end if

      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': cannot open (" // &
            & trim(msg) // ")")
         return
      end if
      allocate(xs(4096), zs(4096), ok(4096), lines(4096))
      n = 0
      lineno = 0
      in_data = fmt == "csv"
      header_done = .false.
      xf = factor
      zf = factor
      ix = 0
      iz = 0
      sep = ","
      if (fmt == "captif") sep = achar(9)
      do
         call read_line(unit, line, ios)
         if (ios /= 0) exit
         lineno = lineno + 1
         if (len(line) > 0) then
            if (line(len(line):len(line)) == achar(13)) line = line(1:len(line)-1)
         end if
         if (.not. in_data) then
            in_data = index(line, "*****DATA*****") == 1
            cycle
         end if
         if (fmt == "csv") then
            pos = index(line, "#")
            if (pos > 0) line = line(1:pos-1)
         end if
         if (len_trim(line) == 0) cycle
         if (.not. header_done) then
            ! the column header: names and units
            header_done = .true.
            call header_columns(line, sep, fmt, x_column, z_column, ix, iz, xf, zf, factor, &
               & error)
            if (allocated(error)) then
               error%message = path // ":" // to_str(lineno) // ": " // error%message
               close(unit)
               return
            end if
            cycle
         end if
         n = n + 1
         if (n > size(zs)) call grow_raw(xs, zs, ok, lines)
         lines(n) = lineno
         nf = count_fields(line, sep)
         ! distance: must be a number
         if (ix > 0) then
            call field(line, sep, ix, tok)
            call parse_number(tok, v, ios)
            if (ios /= 0 .or. .not. (abs(v) <= huge(v))) then
               call fatal_error(error, path // ":" // to_str(lineno) // ": distance '" // tok // &
                  & "' is not a number")
               close(unit)
               return
            end if
            xs(n) = v * xf
         end if
         ! height: empty, NaN or missing is a dropout
         ok(n) = .false.
         zs(n) = 0.0_wp
         if (iz <= nf) then
            call field(line, sep, iz, tok)
            if (len_trim(tok) > 0) then
               call parse_number(tok, v, ios)
               if (ios /= 0) then
                  if (.not. is_nan_text(tok)) then
                     call fatal_error(error, path // ":" // to_str(lineno) // ": height '" // &
                        & trim(tok) // "' is not a number")
                     close(unit)
                     return
                  end if
               else if (abs(v) <= huge(v)) then
                  ok(n) = .true.
                  zs(n) = v * zf
               end if
            end if
         end if
      end do
      close(unit)
      if (.not. in_data) then
         call fatal_error(error, path // ": no '*****DATA*****' line (not a laser profiler file)")
         return
      end if
      if (n == 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': holds no heights")
         return
      end if
      raw%z = zs(1:n)
      raw%valid = ok(1:n)
      raw%line = lines(1:n)
      raw%has_x = ix > 0
      if (raw%has_x) raw%x = xs(1:n)
      do k = 2, n
         if (raw%has_x) then
            if (.not. raw%x(k) > raw%x(k-1)) then
               call fatal_error(error, path // ":" // to_str(raw%line(k)) // &
                  & ": distances do not increase")
               return
            end if
         end if
      end do
   end subroutine read_raw_profile

   !> A plain text profile read through read_profile_text's rules, with NaN
   !> heights kept as dropouts (the strict check comes with preprocessing).
   subroutine read_plain(path, factor, raw, error)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(inout) :: raw
      type(error_type), allocatable, intent(out) :: error
      type(profile_type) :: prof
      call read_profile_text(path, factor, prof, error, keep_nan=.true., lines=raw%line)
      if (allocated(error)) return
      raw%has_x = prof%has_x
      if (prof%has_x) raw%x = prof%x
      raw%valid = .not. ieee_is_nan(prof%z)
      raw%z = merge(prof%z, 0.0_wp, raw%valid)
   end subroutine read_plain

   !> Columns of a CAPTIF or CSV header, and their units.
   subroutine header_columns(line, sep, fmt, x_column, z_column, ix, iz, xf, zf, factor, error)
      character(len=*), intent(in) :: line, fmt, x_column, z_column
      character, intent(in) :: sep
      integer, intent(out) :: ix, iz
      real(wp), intent(inout) :: xf, zf
      real(wp), intent(in) :: factor
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: name
      integer :: k, nf
      nf = count_fields(line, sep)
      ix = 0
      iz = 0
      if (fmt == "captif") then
         ! Data Point No, Distance (mm), Depth (mm)
         if (nf < 3) then
            call fatal_error(error, "expected the header 'Data Point No, Distance (mm), Depth (mm)'")
            return
         end if
         ix = 2
         iz = 3
      else
         do k = 1, nf
            call field(line, sep, k, name)
            name = to_lower(trim(adjustl(name)))
            if (len_trim(x_column) > 0) then
               if (name == to_lower(trim(x_column))) ix = k
            else if (ix == 0 .and. (index(name, "dist") > 0 .or. name == "x" .or. &
                  & index(name, "x ") == 1 .or. index(name, "x(") == 1 .or. &
                  & index(name, "x_") == 1 .or. index(name, "chainage") > 0)) then
               ix = k
            end if
            if (len_trim(z_column) > 0) then
               if (name == to_lower(trim(z_column))) iz = k
            else if (iz == 0 .and. (index(name, "height") > 0 .or. index(name, "depth") > 0 .or. &
                  & index(name, "elev") > 0 .or. name == "z" .or. index(name, "z ") == 1 .or. &
                  & index(name, "z(") == 1 .or. index(name, "z_") == 1)) then
               iz = k
            end if
         end do
         if (iz == 0) then
            if (len_trim(z_column) > 0) then
               call fatal_error(error, "&surface z_column = '" // trim(z_column) // &
                  & "': no such column in the header '" // trim(line) // "'")
            else
               call fatal_error(error, "no height column in the header '" // trim(line) // &
                  & "' (name one with &surface z_column)")
            end if
            return
         end if
         if (len_trim(x_column) > 0 .and. ix == 0) then
            call fatal_error(error, "&surface x_column = '" // trim(x_column) // &
               & "': no such column in the header '" // trim(line) // "'")
            return
         end if
      end if
      if (ix > 0) then
         call field(line, sep, ix, name)
         xf = unit_in_name(name, factor)
      end if
      call field(line, sep, iz, name)
      zf = unit_in_name(name, factor)
   end subroutine header_columns

   !> Metres per unit stated in a column name ('(mm)', '[um]', '_m'), else `default`.
   pure function unit_in_name(name, default) result(f)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: default
      real(wp) :: f
      character(len=:), allocatable :: n
      n = to_lower(name)
      f = default
      if (index(n, "(mm)") > 0 .or. index(n, "[mm]") > 0 .or. index(n, "_mm") > 0) then
         f = 1.0e-3_wp
      else if (index(n, "(um)") > 0 .or. index(n, "[um]") > 0 .or. index(n, "_um") > 0) then
         f = 1.0e-6_wp
      else if (index(n, "(m)") > 0 .or. index(n, "[m]") > 0 .or. index(n, "_m") == len(n) - 1) then
         f = 1.0_wp
      end if
   end function unit_in_name


   pure logical function is_nan_text(tok)
      character(len=*), intent(in) :: tok
      is_nan_text = to_lower(trim(adjustl(tok))) == "nan"
   end function is_nan_text

   !> A number from a token ('/' and '*' have list-directed meanings: refused).
   subroutine parse_number(tok, v, ios)
      character(len=*), intent(in) :: tok
      real(wp), intent(out) :: v
      integer, intent(out) :: ios
      ios = 1
      v = 0.0_wp
      if (len_trim(tok) == 0) return
      if (scan(tok, "/*,;") > 0) return
      read(tok, *, iostat=ios) v
   end subroutine parse_number

   !> Number of `sep`-separated fields of a line (empty fields count).
   pure integer function count_fields(line, sep)
      character(len=*), intent(in) :: line
      character, intent(in) :: sep
      integer :: i
      count_fields = 1
      do i = 1, len(line)
         if (line(i:i) == sep) count_fields = count_fields + 1
      end do
   end function count_fields

   !> Field k of a `sep`-separated line (empty if there are fewer fields).
   pure subroutine field(line, sep, k, tok)
      character(len=*), intent(in) :: line
      character, intent(in) :: sep
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: tok
      integer :: i, start, nf
      nf = 1
      start = 1
      tok = ""
      do i = 1, len(line) + 1
         if (i > len(line)) then
            if (nf == k) tok = line(start:len(line))
            return
         end if
         if (line(i:i) == sep) then
            if (nf == k) then
               tok = line(start:i-1)
               return
            end if
            nf = nf + 1
            start = i + 1
         end if
      end do
   end subroutine field

   pure subroutine grow_raw(x, z, ok, lines)
      real(wp), allocatable, intent(inout) :: x(:), z(:)
      logical, allocatable, intent(inout) :: ok(:)
      integer, allocatable, intent(inout) :: lines(:)
      call double_size(x)
      call double_size(z)
      call double_size(ok)
      call double_size(lines)
   end subroutine grow_raw

   !> Double an array's size, keeping its values.
   pure subroutine double_real(a)
      real(wp), allocatable, intent(inout) :: a(:)
      real(wp), allocatable :: t(:)
      allocate(t(2*size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine double_real

   pure subroutine double_int(a)
      integer, allocatable, intent(inout) :: a(:)
      integer, allocatable :: t(:)
      allocate(t(2*size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine double_int

   pure subroutine double_logical(a)
      logical, allocatable, intent(inout) :: a(:)
      logical, allocatable :: t(:)
      allocate(t(2*size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine double_logical

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
   subroutine read_profile_text(path, factor, prof, error, keep_nan, lines)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: factor
      type(profile_type), intent(out) :: prof
      type(error_type), allocatable, intent(out) :: error
      !> Keep NaN heights (dropouts) instead of refusing them.
      logical, intent(in), optional :: keep_nan
      !> The file line of each point.
      integer, allocatable, intent(out), optional :: lines(:)
      character(len=:), allocatable :: line, tok
      character(len=512) :: msg
      real(wp), allocatable :: xs(:), zs(:)
      integer, allocatable :: ls(:)
      real(wp) :: vals(2), step
      integer :: unit, ios, lineno, n, ncol, ntok, pos, i
      logical :: header_seen, nan_ok

      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': cannot open (" // &
            & trim(msg) // ")")
         return
      end if
      nan_ok = .false.
      if (present(keep_nan)) nan_ok = keep_nan
      allocate(xs(1024), zs(1024), ls(1024))
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
            if (nan_ok .and. i == ntok .and. vals(i) /= vals(i)) cycle   ! a dropout
            if (.not. (abs(vals(i)) <= huge(1.0_wp))) then
               call fatal_error(error, path // ":" // to_str(lineno) // ": value " // &
                  & to_str(vals(i)) // " is not finite")
               close(unit)
               return
            end if
         end do
         n = n + 1
         if (n > size(zs)) then
            call double_size(xs)
            call double_size(zs)
            call double_size(ls)
         end if
         ls(n) = lineno
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
      if (present(lines)) lines = ls(1:n)
      prof%has_x = ncol == 2
      if (prof%has_x) then
         prof%x = xs(1:n)
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
      ! a short buffer: a non-advancing read pads all of it on every line;
      ! longer lines are read in pieces
      character(len=256) :: buf
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
