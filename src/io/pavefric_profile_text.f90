!> Text profiles (plain columns, CSV, CAPTIF laser export) parsed in one pass
!> over the file's bytes, held in memory (pavefric_profile_file). No
!> per-line formatted or list-directed read: each token is checked against
!> pavefric_numbers' grammar and converted in the same pass, so reading is
!> linear in the file's size and every token is a number or an error naming
!> file and line.
!>
!> Rules (docs/profiles.md states them for users):
!> - Lines end at LF; a CR before it is dropped. A UTF-8 byte-order mark at
!>   the start of the file is skipped. A NUL byte anywhere is an error
!>   (binary content, not a text profile).
!> - Comments, plain: a '#' that starts a line or follows a separator (blank,
!>   tab, ',' or ';') starts a comment running to the end of the line. A '#'
!>   glued to a token is part of it, so '1.#INF' and '12#' are not numbers.
!>   CSV and laser export: only a line whose first non-blank character is
!>   '#' is a comment (a '#' inside a field is text).
!> - Header, plain: the first non-comment line is a header when none of its
!>   tokens looks like a number (`looks_numeric`); otherwise it is data and
!>   must parse. CSV: the first non-comment line is the header. Laser
!>   export: the first non-blank line after '*****DATA*****'.
!> - NaN (any case, optionally signed) in the height column is a dropout;
!>   Inf, Infinity or a number beyond the double range is an error.
module pavefric_profile_text
   use pavefric_kinds, only: wp, i8
   use pavefric_error, only: error_type, fatal_error, stat_memory
   use pavefric_format, only: to_str, to_lower
   use pavefric_numbers, only: convert_real, is_nan_word, is_inf_word
   use pavefric_profile_types, only: raw_profile_type
   implicit none
   private

   public :: detect_text_format, parse_plain, parse_table, name_unit, looks_numeric

   character, parameter :: lf = achar(10), cr = achar(13), tab = achar(9), nul = achar(0)
   character(len=*), parameter :: bom = char(239) // char(187) // char(191)
   character(len=*), parameter :: data_mark = "*****DATA*****"

   !> Longest token quoted in a message.
   integer, parameter :: quote_len = 60

contains

   !> The format of a text profile from its content: 'captif' when a line
   !> starting with '*****DATA*****' comes before any line that starts with
   !> a number (a laser export's header block is text), 'csv' when the first
   !> non-comment line holds a comma and a letter, 'plain' otherwise. Only
   !> the leading lines are examined.
   pure function detect_text_format(buf) result(format)
      character(len=*), intent(in) :: buf
      character(len=detect_text_format_len(buf)) :: format
      character(len=:), allocatable :: deferred_text
      call detect_text_format_text(buf, deferred_text)
      format = deferred_text
   end function detect_text_format

   !> The length of detect_text_format's text.
   pure integer function detect_text_format_len(buf)
      character(len=*), intent(in) :: buf
      character(len=:), allocatable :: deferred_text
      call detect_text_format_text(buf, deferred_text)
      detect_text_format_len = len(deferred_text)
   end function detect_text_format_len

   !> The text of detect_text_format, into a deferred-length argument.
   pure subroutine detect_text_format_text(buf, format)
      character(len=*), intent(in) :: buf
      character(len=:), allocatable, intent(out) :: format
      integer(i8) :: pos, ls, le, k, nb
      logical :: letter, first
      nb = len(buf, kind=i8)
      format = "plain"
      first = .true.
      pos = first_byte(buf)
      do while (pos <= nb)
         call next_line(buf, pos, ls, le)
         if (le - ls + 1 >= len(data_mark)) then
            if (buf(ls:ls+len(data_mark)-1) == data_mark) then
               format = "captif"
               return
            end if
         end if
         k = ls
         do while (k <= le)
            if (buf(k:k) /= " " .and. buf(k:k) /= tab) exit
            k = k + 1
         end do
         if (k > le) cycle                            ! blank
         if (buf(k:k) == "#") cycle                   ! a comment
         if (looks_numeric(buf(k:k))) return          ! data: not a laser export
         if (first) then
            first = .false.
            le = plain_content_end(buf, ls, le)
            if (index(buf(ls:le), ",") > 0) then
               letter = .false.
               do k = ls, le
                  if (is_letter(buf(k:k))) then
                     letter = .true.
                     exit
                  end if
               end do
               if (letter) then
                  format = "csv"
                  return
               end if
            end if
         end if
      end do
   end subroutine detect_text_format_text

   !> A plain profile: one column of heights, or two (distance, height),
   !> separated by blanks, tabs, ',' or ';'; values times `factor` metres.
   !> NaN heights are dropouts when `keep_nan`, else errors.
   subroutine parse_plain(buf, path, factor, keep_nan, raw, error)
      character(len=*), intent(in) :: buf, path
      real(wp), intent(in) :: factor
      logical, intent(in) :: keep_nan
      type(raw_profile_type), intent(inout) :: raw
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: xs(:), zs(:)
      logical, allocatable :: ok(:)
      integer, allocatable :: lines(:)
      integer(i8) :: nb, pos, i, le, cs, ts(2), te(2)
      integer :: cap, n, ncol, ntok, lineno, k, st
      real(wp) :: v(2)
      integer :: kind
      logical :: drop

      call count_lines(buf, path, cap, error)
      if (allocated(error)) return
      nb = len(buf, kind=i8)
      ! leading blank and comment lines and a header line: skipped here, so
      ! the arrays fit the data lines exactly in the usual case
      pos = first_byte(buf)
      lineno = 0
      do while (pos <= nb)
         le = pos
         do while (le <= nb)
            if (buf(le:le) == lf) exit
            le = le + 1
         end do
         kind = plain_line_kind(buf, pos, le - 1)
         if (kind == 2) exit                          ! the first data line
         lineno = lineno + 1
         pos = le + 1
         if (kind == 1) exit                          ! the header: the first content line
      end do
      cap = max(cap - lineno, 1)
      allocate(zs(cap), ok(cap), lines(cap), stat=st)
      if (st /= 0) then
         call memory_error(path, cap, 16, error)
         return
      end if
      n = 0
      ncol = 0
      do while (pos <= nb)
         lineno = lineno + 1
         le = pos
         do while (le <= nb)
            if (buf(le:le) == lf) exit
            le = le + 1
         end do
         ! tokens of buf(pos:le-1); the first two kept, the rest counted
         ntok = 0
         i = pos
         do
            do while (i < le)
               if (.not. is_plain_sep(buf(i:i))) exit
               i = i + 1
            end do
            if (i >= le) exit
            if (buf(i:i) == "#") exit                 ! a comment to the end of the line
            ntok = ntok + 1
            cs = i
            do while (i < le)
               if (is_plain_sep(buf(i:i))) exit
               i = i + 1
            end do
            if (ntok <= 2) then
               ts(ntok) = cs
               te(ntok) = i - 1
            end if
         end do
         pos = le + 1
         if (ntok == 0) cycle
         if (ntok > 2) then
            call fatal_error(error, path // ":" // to_str(lineno) // &
               & ": more than two columns (expected heights, or distance and height)")
            return
         end if
         drop = .false.
         do k = 1, ntok
            call convert_real(buf(ts(k):te(k)), v(k), st)
            if (st /= 0) then
               if (k == ntok .and. keep_nan .and. is_signed_nan(buf(ts(k):te(k)))) then
                  drop = .true.                       ! a dropout
                  cycle
               end if
               call token_error(path, lineno, "", buf(ts(k):te(k)), error)
               return
            end if
            if (.not. (abs(v(k)) <= huge(1.0_wp))) then
               call token_error(path, lineno, "", buf(ts(k):te(k)), error)
               return
            end if
         end do
         if (ncol == 0) then
            ncol = ntok
            if (ncol == 2) then
               allocate(xs(cap), stat=st)
               if (st /= 0) then
                  call memory_error(path, cap, 24, error)
                  return
               end if
            end if
         end if
         if (ntok /= ncol) then
            call fatal_error(error, path // ":" // to_str(lineno) // ": " // to_str(ntok) // &
               & " columns where earlier lines have " // to_str(ncol) // ": every line " // &
               & "holds a height, or a distance and a height (a decimal comma? write 0.5)")
            return
         end if
         n = n + 1
         lines(n) = lineno
         ok(n) = .not. drop
         if (ncol == 2) then
            xs(n) = v(1) * factor
            zs(n) = 0.0_wp
            if (.not. drop) zs(n) = v(2) * factor
         else
            zs(n) = 0.0_wp
            if (.not. drop) zs(n) = v(1) * factor
         end if
      end do
      call finish(path, n, ncol == 2, xs, zs, ok, lines, raw, error)
   end subroutine parse_plain

   !> A CSV file (format 'csv': comma-separated, a header of column names)
   !> or a laser profiler export (format 'captif': a header block, a line
   !> '*****DATA*****', a tab-separated column header, then rows of point
   !> number, distance and depth). Units stated in the used columns' names
   !> override `factor` (metres per unit).
   subroutine parse_table(buf, path, fmt, factor, x_column, z_column, raw, error)
      character(len=*), intent(in) :: buf, path, fmt, x_column, z_column
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(inout) :: raw
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: xs(:), zs(:)
      logical, allocatable :: ok(:)
      integer, allocatable :: lines(:)
      integer(i8) :: nb, pos, ls, le, fs, fe, a, b, xa, xb, za, zb
      integer :: cap, n, lineno, st, ix, iz, nf
      real(wp) :: v, xf, zf
      logical :: captif, in_data, header_done, x_found, z_found
      character :: sep

      call count_lines(buf, path, cap, error)
      if (allocated(error)) return
      captif = fmt == "captif"
      sep = ","
      if (captif) sep = tab
      nb = len(buf, kind=i8)
      ix = 0
      iz = 0
      xf = factor
      zf = factor
      ! the laser export's header block, blank and comment lines, the column
      ! header: before the arrays are sized to the lines that follow
      lineno = 0
      in_data = .not. captif
      header_done = .false.
      pos = first_byte(buf)
      do while (pos <= nb .and. .not. header_done)
         lineno = lineno + 1
         call next_line(buf, pos, ls, le)
         if (.not. in_data) then
            if (le - ls + 1 >= len(data_mark)) in_data = buf(ls:ls+len(data_mark)-1) == data_mark
            cycle
         end if
         if (blank_or_comment(buf, ls, le)) cycle
         header_done = .true.
         call header_columns(buf(ls:le), sep, captif, x_column, z_column, factor, ix, iz, &
            & xf, zf, error)
         if (allocated(error)) then
            error%message = path // ":" // to_str(lineno) // ": " // error%message
            return
         end if
      end do
      if (.not. in_data) then
         call fatal_error(error, path // ": no '*****DATA*****' line, so not a laser " // &
            & "profiler export; set &surface format = 'auto' (or 'plain', 'csv')")
         return
      end if
      cap = max(cap - lineno, 1)
      allocate(zs(cap), ok(cap), lines(cap), stat=st)
      if (st == 0 .and. ix > 0) allocate(xs(cap), stat=st)
      if (st /= 0) then
         call memory_error(path, cap, 24, error)
         return
      end if
      n = 0
      do while (pos <= nb)
         lineno = lineno + 1
         call next_line(buf, pos, ls, le)
         if (blank_or_comment(buf, ls, le)) cycle
         ! the fields of this line: the distance and the height; in a laser
         ! export every field is checked
         nf = 0
         x_found = .false.
         z_found = .false.
         fs = ls
         do
            fe = fs
            do while (fe <= le)
               if (buf(fe:fe) == sep) exit
               fe = fe + 1
            end do
            nf = nf + 1
            call trim_field(buf, fs, fe - 1, a, b)
            if (nf == ix) then
               x_found = .true.
               xa = a
               xb = b
            end if
            if (nf == iz) then
               z_found = .true.
               za = a
               zb = b
            end if
            if (captif .and. nf /= ix .and. nf /= iz) then
               if (nf == 1) then
                  call convert_real(buf(a:b), v, st)
                  if (st /= 0 .or. .not. (abs(v) <= huge(v))) then
                     call token_error(path, lineno, "point number ", buf(a:b), error)
                     return
                  end if
               else if (b >= a) then
                  call fatal_error(error, path // ":" // to_str(lineno) // ": '" // &
                     & quoted(buf(a:b)) // "' beyond the three columns of a laser " // &
                     & "profiler export")
                  return
               end if
            end if
            if (fe > le) exit
            fs = fe + 1
         end do
         n = n + 1
         lines(n) = lineno
         ! distance: a number, always
         if (ix > 0) then
            if (.not. x_found) then
               call fatal_error(error, path // ":" // to_str(lineno) // &
                  & ": no distance (column " // to_str(ix) // "; the line has " // &
                  & to_str(nf) // ")")
               return
            end if
            call convert_real(buf(xa:xb), v, st)
            if (st /= 0 .or. .not. (abs(v) <= huge(v))) then
               call token_error(path, lineno, "distance ", buf(xa:xb), error)
               return
            end if
            xs(n) = v * xf
         end if
         ! height: empty, NaN or missing is a dropout
         ok(n) = .false.
         zs(n) = 0.0_wp
         if (z_found .and. zb >= za) then
            call convert_real(buf(za:zb), v, st)
            if (st /= 0) then
               if (.not. is_signed_nan(buf(za:zb))) then
                  call token_error(path, lineno, "height ", buf(za:zb), error)
                  return
               end if
            else if (abs(v) <= huge(v)) then
               ok(n) = .true.
               zs(n) = v * zf
            else
               call token_error(path, lineno, "height ", buf(za:zb), error)
               return
            end if
         end if
      end do
      call finish(path, n, ix > 0, xs, zs, ok, lines, raw, error)
   end subroutine parse_table

   !> Bounds of field k (trimmed of blanks and tabs) of line buf(ls:le); an
   !> empty field gives fe < fs.
   pure subroutine field_bounds(buf, ls, le, sep, k, fs, fe)
      character(len=*), intent(in) :: buf
      integer(i8), intent(in) :: ls, le
      character, intent(in) :: sep
      integer, intent(in) :: k
      integer(i8), intent(out) :: fs, fe
      integer(i8) :: i, start
      integer :: nf
      nf = 1
      start = ls
      i = ls
      do while (i <= le)
         if (buf(i:i) == sep) then
            if (nf == k) exit
            nf = nf + 1
            start = i + 1
         end if
         i = i + 1
      end do
      if (nf /= k) then
         fs = 1
         fe = 0
         return
      end if
      call trim_field(buf, start, i - 1, fs, fe)
   end subroutine field_bounds

   !> buf(a:b) without surrounding blanks and tabs, as (fs, fe); fe < fs if empty.
   pure subroutine trim_field(buf, a, b, fs, fe)
      character(len=*), intent(in) :: buf
      integer(i8), intent(in) :: a, b
      integer(i8), intent(out) :: fs, fe
      fs = a
      fe = b
      do while (fs <= fe)
         if (buf(fs:fs) /= " " .and. buf(fs:fs) /= tab) exit
         fs = fs + 1
      end do
      do while (fe >= fs)
         if (buf(fe:fe) /= " " .and. buf(fe:fe) /= tab) exit
         fe = fe - 1
      end do
   end subroutine trim_field

   !> Columns of a CSV or laser-export header, and the units their names state.
   subroutine header_columns(line, sep, captif, x_column, z_column, factor, ix, iz, xf, zf, error)
      character(len=*), intent(in) :: line, x_column, z_column
      character, intent(in) :: sep
      logical, intent(in) :: captif
      real(wp), intent(in) :: factor
      integer, intent(out) :: ix, iz
      real(wp), intent(out) :: xf, zf
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: name, xname, zname
      integer :: k, nf
      ix = 0
      iz = 0
      xf = factor
      zf = factor
      nf = 1
      do k = 1, len(line)
         if (line(k:k) == sep) nf = nf + 1
      end do
      if (captif) then
         ! Data Point No, Distance (mm), Depth (mm)
         if (nf < 3) then
            call fatal_error(error, "expected the header 'Data Point No, Distance (mm), Depth (mm)'")
            return
         end if
         ix = 2
         iz = 3
      else
         do k = 1, nf
            name = to_lower(column_name(line, sep, k))
            if (len_trim(x_column) > 0) then
               if (name == to_lower(trim(x_column))) ix = k
            else if (ix == 0 .and. (index(name, "dist") > 0 .or. name == "x" .or. &
                  & index(name, "x ") == 1 .or. index(name, "x(") == 1 .or. &
                  & index(name, "x[") == 1 .or. index(name, "x_") == 1 .or. &
                  & index(name, "chainage") > 0)) then
               ix = k
            end if
            if (len_trim(z_column) > 0) then
               if (name == to_lower(trim(z_column))) iz = k
            else if (iz == 0 .and. (index(name, "height") > 0 .or. index(name, "depth") > 0 .or. &
                  & index(name, "elev") > 0 .or. name == "z" .or. index(name, "z ") == 1 .or. &
                  & index(name, "z(") == 1 .or. index(name, "z[") == 1 .or. &
                  & index(name, "z_") == 1)) then
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
         xname = column_name(line, sep, ix)
         call column_unit(xname, factor, xf, error)
         if (allocated(error)) return
      end if
      zname = column_name(line, sep, iz)
      call column_unit(zname, factor, zf, error)
   end subroutine header_columns

   !> Metres per unit of a column (the unit its name states, else `factor`).
   subroutine column_unit(name, factor, f, error)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: factor
      real(wp), intent(out) :: f
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: bad
      logical :: stated
      call name_unit(name, f, stated, bad)
      if (len(bad) > 0) then
         call fatal_error(error, "column '" // name // "': unknown unit '" // bad // &
            & "' (expected m, mm, um or " // char(194) // char(181) // "m)")
         return
      end if
      if (.not. stated) f = factor
   end subroutine column_unit

   !> Field k of a header line: trimmed, without surrounding double quotes.
   pure function column_name(line, sep, k) result(name)
      character(len=*), intent(in) :: line
      character, intent(in) :: sep
      integer, intent(in) :: k
      character(len=column_name_len(line, sep, k)) :: name
      character(len=:), allocatable :: deferred_text
      call column_name_text(line, sep, k, deferred_text)
      name = deferred_text
   end function column_name

   !> The length of column_name's text.
   pure integer function column_name_len(line, sep, k)
      character(len=*), intent(in) :: line
      character, intent(in) :: sep
      integer, intent(in) :: k
      character(len=:), allocatable :: deferred_text
      call column_name_text(line, sep, k, deferred_text)
      column_name_len = len(deferred_text)
   end function column_name_len

   !> The text of column_name, into a deferred-length argument.
   pure subroutine column_name_text(line, sep, k, name)
      character(len=*), intent(in) :: line
      character, intent(in) :: sep
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: name
      integer(i8) :: fs, fe
      call field_bounds(line, 1_i8, len(line, kind=i8), sep, k, fs, fe)
      name = line(fs:fe)
      if (len(name) >= 2) then
         if (name(1:1) == '"' .and. name(len(name):len(name)) == '"') &
            & name = trim(adjustl(name(2:len(name)-1)))
      end if
   end subroutine column_name_text

   !> The unit a column name states: in parentheses or brackets ('Height
   !> (mm)', 'z [um]', 'Height (µm)') or as a suffix after the last '_'
   !> ('height_mm'). Units: m, mm, um, µm (U+00B5 or U+03BC, UTF-8, or the
   !> Latin-1 byte), and their spelled-out names. `f` is metres per unit
   !> when `stated`; `bad` holds the text of a bracket that is not a unit.
   pure subroutine name_unit(name, f, stated, bad)
      character(len=*), intent(in) :: name
      real(wp), intent(out) :: f
      logical, intent(out) :: stated
      character(len=:), allocatable, intent(out) :: bad
      character(len=:), allocatable :: inner
      integer :: open_pos, close_pos, k
      character :: closing
      f = 1.0_wp
      stated = .false.
      bad = ""
      ! a bracketed unit
      do k = 1, len(name)
         if (name(k:k) == "(" .or. name(k:k) == "[") exit
      end do
      open_pos = k
      if (open_pos <= len(name)) then
         closing = ")"
         if (name(open_pos:open_pos) == "[") closing = "]"
         close_pos = index(name(open_pos+1:), closing)
         if (close_pos == 0) then
            bad = name(open_pos:)
            return
         end if
         close_pos = open_pos + close_pos
         inner = trim(adjustl(name(open_pos+1:close_pos-1)))
         f = unit_metres(inner)
         if (f > 0.0_wp) then
            stated = .true.
         else
            bad = inner
         end if
         return
      end if
      ! a suffix after the last '_', only when it is a unit
      k = index(name, "_", back=.true.)
      if (k > 0 .and. k < len(name)) then
         f = unit_metres(name(k+1:))
         stated = f > 0.0_wp
      end if
      if (.not. stated) f = 1.0_wp
   end subroutine name_unit

   !> Metres per unit of a unit's text; 0 when it is not one.
   pure function unit_metres(text) result(f)
      character(len=*), intent(in) :: text
      real(wp) :: f
      character(len=:), allocatable :: t
      character(len=*), parameter :: micro_sign = char(194) // char(181), &
         & greek_mu = char(206) // char(188), latin1_micro = char(181)
      t = to_lower(trim(adjustl(text)))
      select case (t)
      case ("m", "metre", "metres", "meter", "meters")
         f = 1.0_wp
      case ("mm", "millimetre", "millimetres", "millimeter", "millimeters")
         f = 1.0e-3_wp
      case ("um", micro_sign // "m", greek_mu // "m", latin1_micro // "m", "micron", "microns", &
            & "micrometre", "micrometres", "micrometer", "micrometers")
         f = 1.0e-6_wp
      case default
         f = 0.0_wp
      end select
   end function unit_metres

   !> Whether a token looks like a number or nearly one: after an optional
   !> sign it starts with a digit or '.', or it is a NaN or Inf word. A
   !> header line holds no such token.
   pure logical function looks_numeric(tok)
      character(len=*), intent(in) :: tok
      integer :: i
      looks_numeric = .true.
      i = 1
      if (len(tok) == 0) return
      if (tok(1:1) == "+" .or. tok(1:1) == "-") i = 2
      if (i > len(tok)) return                       ! a sign alone
      if ((tok(i:i) >= "0" .and. tok(i:i) <= "9") .or. tok(i:i) == ".") return
      if (is_nan_word(tok(i:)) .or. is_inf_word(tok(i:))) return
      looks_numeric = .false.
   end function looks_numeric

   !> 'nan' in any case with an optional sign (C's printf writes '-nan').
   pure logical function is_signed_nan(tok)
      character(len=*), intent(in) :: tok
      is_signed_nan = .false.
      if (len(tok) == 0) return
      if (tok(1:1) == "+" .or. tok(1:1) == "-") then
         is_signed_nan = is_nan_word(tok(2:))
      else
         is_signed_nan = is_nan_word(tok)
      end if
   end function is_signed_nan

   !> The error for a token that is not a (finite) number.
   subroutine token_error(path, lineno, what, tok, error)
      character(len=*), intent(in) :: path, what, tok
      integer, intent(in) :: lineno
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v
      integer :: st
      call convert_real(tok, v, st)
      if (len(tok) == 0) then
         call fatal_error(error, path // ":" // to_str(lineno) // ": " // what // &
            & "missing (an empty field)")
      else if ((st == 0 .and. .not. (abs(v) <= huge(v))) .or. is_inf_word(tok) .or. &
            & is_signed_nan(tok)) then
         call fatal_error(error, path // ":" // to_str(lineno) // ": " // what // "'" // &
            & quoted(tok) // "' is not finite")
      else
         call fatal_error(error, path // ":" // to_str(lineno) // ": " // what // "'" // &
            & quoted(tok) // "' is not a number: write heights as numbers (0.25, -3e-1); " // &
            & "mark a dropout as NaN (or an empty CSV field) and set &preprocess " // &
            & "dropouts = 'interpolate'")
      end if
   end subroutine token_error

   !> A token for a message: at most quote_len characters.
   pure function quoted(tok) result(q)
      character(len=*), intent(in) :: tok
      character(len=quoted_len(tok)) :: q
      character(len=:), allocatable :: deferred_text
      call quoted_text(tok, deferred_text)
      q = deferred_text
   end function quoted

   !> The length of quoted's text.
   pure integer function quoted_len(tok)
      character(len=*), intent(in) :: tok
      character(len=:), allocatable :: deferred_text
      call quoted_text(tok, deferred_text)
      quoted_len = len(deferred_text)
   end function quoted_len

   !> The text of quoted, into a deferred-length argument.
   pure subroutine quoted_text(tok, q)
      character(len=*), intent(in) :: tok
      character(len=:), allocatable, intent(out) :: q
      if (len(tok) <= quote_len) then
         q = tok
      else
         q = tok(1:quote_len) // "..."
      end if
   end subroutine quoted_text

   !> Copy the first n points into `raw` (exactly sized), or fail.
   subroutine finish(path, n, has_x, xs, zs, ok, lines, raw, error)
      character(len=*), intent(in) :: path
      integer, intent(in) :: n
      logical, intent(in) :: has_x
      real(wp), allocatable, intent(inout) :: xs(:), zs(:)
      logical, allocatable, intent(inout) :: ok(:)
      integer, allocatable, intent(inout) :: lines(:)
      type(raw_profile_type), intent(inout) :: raw
      type(error_type), allocatable, intent(out) :: error
      integer :: st, k
      character(len=:), allocatable :: hint
      if (n == 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': holds no " // &
            & "heights (only comments or blank lines); give one height a line, or a " // &
            & "distance and a height (docs/profiles.md)")
         return
      end if
      raw%has_x = has_x
      call shrink_real(zs, n, st)
      if (st == 0) call shrink_logical(ok, n, st)
      if (st == 0) call shrink_int(lines, n, st)
      if (st == 0 .and. has_x) call shrink_real(xs, n, st)
      if (st /= 0) then
         call memory_error(path, n, 24, error)
         return
      end if
      call move_alloc(zs, raw%z)
      call move_alloc(ok, raw%valid)
      call move_alloc(lines, raw%line)
      if (has_x) then
         call move_alloc(xs, raw%x)
         do k = 2, n
            if (.not. raw%x(k) > raw%x(k-1)) then
               hint = ""
               ! 0,0993 / 0,1947 / ...: a decimal comma makes every line two
               ! numbers, the distances the whole parts
               if (all(raw%x(1:k) == aint(raw%x(1:k)))) hint = " (every distance up to " // &
                  & "there is a whole number: if the file writes decimals with a comma, as " // &
                  & "0,0993, each line reads as two numbers; write decimal points)"
               call fatal_error(error, path // ":" // to_str(raw%line(k)) // &
                  & ": distances do not increase" // hint)
               return
            end if
         end do
      end if
   end subroutine finish

   subroutine shrink_real(a, n, st)
      real(wp), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer, intent(out) :: st
      real(wp), allocatable :: t(:)
      st = 0
      if (size(a) == n) return
      allocate(t(n), stat=st)
      if (st /= 0) return
      t(1:n) = a(1:n)
      call move_alloc(t, a)
   end subroutine shrink_real

   subroutine shrink_logical(a, n, st)
      logical, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer, intent(out) :: st
      logical, allocatable :: t(:)
      st = 0
      if (size(a) == n) return
      allocate(t(n), stat=st)
      if (st /= 0) return
      t(1:n) = a(1:n)
      call move_alloc(t, a)
   end subroutine shrink_logical

   subroutine shrink_int(a, n, st)
      integer, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer, intent(out) :: st
      integer, allocatable :: t(:)
      st = 0
      if (size(a) == n) return
      allocate(t(n), stat=st)
      if (st /= 0) return
      t(1:n) = a(1:n)
      call move_alloc(t, a)
   end subroutine shrink_int

   subroutine memory_error(path, n, bytes_per_point, error)
      character(len=*), intent(in) :: path
      integer, intent(in) :: n, bytes_per_point
      type(error_type), allocatable, intent(out) :: error
      call fatal_error(error, "&surface profile_file = '" // path // &
         & "': not enough memory to read " // to_str(n) // " lines (about " // &
         & to_str(int(n, i8) * bytes_per_point / 1000000_i8) // " MB)", stat_memory)
   end subroutine memory_error

   !> Number of lines (an upper bound on the points); a NUL byte is an error.
   subroutine count_lines(buf, path, nlines, error)
      character(len=*), intent(in) :: buf, path
      integer, intent(out) :: nlines
      type(error_type), allocatable, intent(out) :: error
      integer(i8) :: k, nb, count
      nb = len(buf, kind=i8)
      count = 0
      do k = 1, nb
         if (buf(k:k) == lf) then
            count = count + 1
         else if (buf(k:k) == nul) then
            call fatal_error(error, path // ":" // to_str(count + 1) // &
               & ": binary content (a NUL byte): not a text profile")
            nlines = 0
            return
         end if
      end do
      if (nb > 0) then
         if (buf(nb:nb) /= lf) count = count + 1
      end if
      if (count > huge(1)) then
         call fatal_error(error, "&surface profile_file = '" // path // "': more than " // &
            & to_str(huge(1)) // " lines")
         nlines = 0
         return
      end if
      nlines = int(max(count, 1_i8))
   end subroutine count_lines

   !> The first byte after a UTF-8 byte-order mark, if there is one.
   pure function first_byte(buf) result(pos)
      character(len=*), intent(in) :: buf
      integer(i8) :: pos
      pos = 1
      if (len(buf) >= 3) then
         if (buf(1:3) == bom) pos = 4
      end if
   end function first_byte

   !> The line starting at `pos` as buf(ls:le), without LF and a final CR;
   !> `pos` moves to the next line.
   pure subroutine next_line(buf, pos, ls, le)
      character(len=*), intent(in) :: buf
      integer(i8), intent(inout) :: pos
      integer(i8), intent(out) :: ls, le
      integer(i8) :: nb
      nb = len(buf, kind=i8)
      ls = pos
      le = pos
      do while (le <= nb)
         if (buf(le:le) == lf) exit
         le = le + 1
      end do
      pos = le + 1
      le = le - 1
      if (le >= ls) then
         if (buf(le:le) == cr) le = le - 1
      end if
   end subroutine next_line

   !> End of a plain line's content before a comment ('#' at the start of
   !> the line or after a separator).
   pure function plain_content_end(buf, ls, le) result(ce)
      character(len=*), intent(in) :: buf
      integer(i8), intent(in) :: ls, le
      integer(i8) :: ce, k
      ce = le
      do k = ls, le
         if (buf(k:k) == "#") then
            if (k == ls) then
               ce = k - 1
               return
            else if (is_plain_sep(buf(k-1:k-1))) then
               ce = k - 1
               return
            end if
         end if
      end do
   end function plain_content_end

   !> Whether a CSV or laser-export line is blank or a comment (its first
   !> non-blank character is '#').
   pure logical function blank_or_comment(buf, ls, le)
      character(len=*), intent(in) :: buf
      integer(i8), intent(in) :: ls, le
      integer(i8) :: i
      blank_or_comment = .true.
      i = ls
      do while (i <= le)
         if (buf(i:i) /= " " .and. buf(i:i) /= tab) exit
         i = i + 1
      end do
      if (i > le) return
      blank_or_comment = buf(i:i) == "#"
   end function blank_or_comment

   !> What a plain line buf(ls:le) is before the data: 0 blank or comment,
   !> 1 a header (tokens, none looking like a number), 2 data.
   pure integer function plain_line_kind(buf, ls, le) result(kind)
      character(len=*), intent(in) :: buf
      integer(i8), intent(in) :: ls, le
      integer(i8) :: i, cs
      kind = 0
      i = ls
      do
         do while (i <= le)
            if (.not. is_plain_sep(buf(i:i))) exit
            i = i + 1
         end do
         if (i > le) return
         if (buf(i:i) == "#") return
         cs = i
         do while (i <= le)
            if (is_plain_sep(buf(i:i))) exit
            i = i + 1
         end do
         if (looks_numeric(buf(cs:i-1))) then
            kind = 2
            return
         end if
         kind = 1
      end do
   end function plain_line_kind

   pure logical function is_plain_sep(c)
      character, intent(in) :: c
      select case (c)
      case (" ", tab, ",", ";", cr)
         is_plain_sep = .true.
      case default
         is_plain_sep = .false.
      end select
   end function is_plain_sep

   pure logical function is_letter(c)
      character, intent(in) :: c
      is_letter = (c >= "a" .and. c <= "z") .or. (c >= "A" .and. c <= "Z")
   end function is_letter

end module pavefric_profile_text
