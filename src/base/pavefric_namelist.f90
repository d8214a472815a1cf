!> A Fortran namelist reader that returns what it read: groups, assignments
!> and their value tokens with line numbers, so that every parameter can be
!> looked up in the one table of declarations (pavefric_model) instead of
!> being declared again in a NAMELIST statement. No physics, no file I/O:
!> it parses text.
!>
!> The syntax is the standard's: a group starts with `&name` (or `$name`)
!> anywhere outside a group, holds `name = value, value ...` and
!> `name(i) = value ...` assignments separated by commas or blanks, and ends
!> with `/` (or `&end`, `$end`). Values: numbers, logicals (`.true.`,
!> `.false.`, `t`, `f`), quoted text ('...' or "...", a doubled quote stands
!> for one), repeat counts `r*value`. `!` starts a comment. Blank characters
!> are blanks, tabs, line and form feeds, vertical tabs, the UTF-8 byte-order
!> mark and no-break spaces, so a group is found wherever the standard
!> allows it (after a BOM, on the same line as the end of the previous
!> group). Stricter than compilers where leniency hides mistakes: anything
!> outside a group that is not a comment, an unterminated group or text, and
!> null values (`,,`) are errors naming the file and line.
module pavefric_namelist
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str, to_lower
   implicit none
   private

   public :: nml_group_type, nml_item_type, nml_token_type, parse_namelist, at

   !> One value as written (quotes removed from text values).
   type :: nml_token_type
      character(len=:), allocatable :: text
      !> Whether it was quoted (text values must be).
      logical :: quoted = .false.
      !> Repeat count r of `r*value` (1 when none).
      integer :: repeat = 1
   end type nml_token_type

   !> One assignment `name = values` or `name(subscript) = values`.
   type :: nml_item_type
      !> The variable's name in lower case.
      character(len=:), allocatable :: name
      !> The subscript of `name(i) = ...`; 0 when there is none.
      integer :: subscript = 0
      type(nml_token_type), allocatable :: values(:)
      integer :: n_values = 0
      !> Line of the name, and the values as written (for messages).
      integer :: line = 0
      character(len=:), allocatable :: written
   end type nml_item_type

   !> One group `&name ... /`.
   type :: nml_group_type
      !> The group's name in lower case.
      character(len=:), allocatable :: name
      integer :: line = 0
      type(nml_item_type), allocatable :: items(:)
      integer :: n_items = 0
   end type nml_group_type

   character(len=*), parameter :: letters = &
      & "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
   character(len=*), parameter :: name_chars = letters // "0123456789_"
   !> The longest value a namelist item may hold (characters): far beyond
   !> any path, title or number, and small enough that the text handled for
   !> it never strains the stack (a 10 MB value used to end the process).
   integer, parameter, public :: max_value_length = 65536
   !> The longest name a Fortran namelist item can have.
   integer, parameter :: max_name_length = 63

   !> The parser's position in the text.
   type :: cursor_type
      integer :: pos = 1
      integer :: line = 1
   end type cursor_type

contains

   !> Parse namelist `text` (read from `path`, named in messages) into groups.
   pure subroutine parse_namelist(text, path, groups, n_groups, error)
      character(len=*), intent(in) :: text, path
      type(nml_group_type), allocatable, intent(out) :: groups(:)
      integer, intent(out) :: n_groups
      type(error_type), allocatable, intent(out) :: error
      type(cursor_type) :: c
      integer :: start, line
      character(len=:), allocatable :: name

      allocate(groups(8))
      n_groups = 0
      do
         call skip_blanks_and_comments(text, c)
         if (c%pos > len(text)) exit
         if (text(c%pos:c%pos) == "&" .or. text(c%pos:c%pos) == "$") then
            line = c%line
            start = c%pos
            c%pos = c%pos + 1
            call read_name(text, c, name)
            if (len(name) == 0) then
               call fatal_error(error, at(path, line) // "'" // &
                  & text(start:min(len(text), start + 1)) // &
                  & "' is not the start of a namelist group (expected &name)")
               return
            end if
            if (to_lower(name) == "end") then
               call fatal_error(error, at(path, line) // &
                  & "'&end' outside a namelist group")
               return
            end if
            if (n_groups == size(groups)) call grow_groups(groups)
            n_groups = n_groups + 1
            groups(n_groups)%name = to_lower(name)
            groups(n_groups)%line = line
            call read_group(text, path, c, groups(n_groups), error)
            if (allocated(error)) return
         else
            call fatal_error(error, at(path, c%line) // "'" // &
               & visible(text, c%pos) // "' outside a namelist group (only comments " // &
               & "starting with '!' may stand between groups)")
            return
         end if
      end do
   end subroutine parse_namelist

   !> The assignments of one group, up to its terminator.
   pure subroutine read_group(text, path, c, group, error)
      character(len=*), intent(in) :: text, path
      type(cursor_type), intent(inout) :: c
      type(nml_group_type), intent(inout) :: group
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: name
      type(cursor_type) :: save
      integer :: line, sub
      logical :: is_item, ended

      allocate(group%items(8))
      group%n_items = 0
      do
         call skip_separators(text, c)
         if (c%pos > len(text)) then
            call fatal_error(error, at(path, group%line) // "&" // group%name // &
               & " is not terminated (a '/' must end the group)")
            return
         end if
         call terminator(text, c, ended)
         if (ended) return
         if (text(c%pos:c%pos) == "&" .or. text(c%pos:c%pos) == "$") then
            call fatal_error(error, at(path, c%line) // "&" // group%name // &
               & " (line " // to_str(group%line) // ") is not terminated by '/' before '" // &
               & visible(text, c%pos) // "'")
            return
         end if
         save = c
         call item_start(text, c, name, sub, is_item)
         if (.not. is_item) then
            c = save
            call fatal_error(error, at(path, c%line) // "&" // group%name // &
               & ": '" // visible(text, c%pos) // "' where 'name = value' was expected")
            return
         end if
         if (sub < 0) then
            call fatal_error(error, at(path, save%line) // "&" // group%name // &
               & " " // name // ": a subscript must be one whole number >= 1, as in " // &
               & name // "(2) = ...")
            return
         end if
         line = save%line
         if (group%n_items == size(group%items)) call grow_items(group%items)
         group%n_items = group%n_items + 1
         associate(item => group%items(group%n_items))
            item%name = to_lower(name)
            item%subscript = sub
            item%line = line
            call read_values(text, path, c, group%name, item, error)
         end associate
         if (allocated(error)) return
      end do
   end subroutine read_group

   !> The values of one assignment, up to the next `name =`, or the group's end.
   pure subroutine read_values(text, path, c, group, item, error)
      character(len=*), intent(in) :: text, path, group
      type(cursor_type), intent(inout) :: c
      type(nml_item_type), intent(inout) :: item
      type(error_type), allocatable, intent(out) :: error
      type(cursor_type) :: save
      character(len=:), allocatable :: name, tok
      integer :: sub, first, last, r, stat
      logical :: is_item, need_value, quoted, ended

      allocate(item%values(4))
      item%n_values = 0
      first = c%pos
      last = c%pos - 1
      need_value = .true.        ! after '=' or a comma
      do
         call skip_blanks_and_comments(text, c)
         if (c%pos > len(text)) exit
         if (text(c%pos:c%pos) == ",") then
            if (need_value) then
               call fatal_error(error, at(path, c%line) // "&" // group // " " // &
                  & item%name // ": an empty value (null values are not supported)")
               return
            end if
            need_value = .true.
            c%pos = c%pos + 1
            cycle
         end if
         save = c
         call terminator(text, c, ended)
         c = save                                 ! read_group consumes it
         if (ended) exit
         if (text(c%pos:c%pos) == "&" .or. text(c%pos:c%pos) == "$") exit
         save = c
         call item_start(text, c, name, sub, is_item)
         c = save
         if (is_item) exit                        ! the next assignment
         ! a value, possibly with a repeat count
         r = 1
         call repeat_count(text, c, r, stat)
         if (stat == 2) then
            call fatal_error(error, at(path, c%line) // "&" // group // " " // &
               & item%name // ": '" // visible(text, c%pos) // "': a repeat count of more " // &
               & "than 9 digits, more values than any list holds")
            return
         else if (stat /= 0) then
            call fatal_error(error, at(path, c%line) // "&" // group // " " // &
               & item%name // ": '" // visible(text, c%pos) // "': a repeat count r*value " // &
               & "needs a whole number r >= 1 and a value")
            return
         end if
         call read_token(text, path, c, tok, quoted, error)
         if (allocated(error)) then
            error%message = error%message // " (&" // group // " " // item%name // ")"
            return
         end if
         if (len(tok) > max_value_length) then
            call fatal_error(error, at(path, save%line) // "&" // group // " " // &
               & item%name // ": a value of " // to_str(len(tok)) // " characters, more " // &
               & "than the " // to_str(max_value_length) // " allowed; check that its " // &
               & "quotes are closed where they should be")
            return
         end if
         if (item%n_values == size(item%values)) call grow_tokens(item%values)
         item%n_values = item%n_values + 1
         item%values(item%n_values)%text = tok
         item%values(item%n_values)%quoted = quoted
         item%values(item%n_values)%repeat = r
         last = c%pos - 1
         need_value = .false.
      end do
      if (item%n_values == 0) then
         call fatal_error(error, at(path, item%line) // "&" // group // " " // &
            & item%name // " = : no value given; give one, or remove the assignment to " // &
            & "keep the default")
         return
      end if
      item%written = squeeze_blanks(text(first:last))
   end subroutine read_values

   !> `name [ ( int ) ] =` at the cursor? On success the cursor is after '='.
   !> `sub` is 0 without a subscript, -1 for a malformed one.
   pure subroutine item_start(text, c, name, sub, is_item)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      character(len=:), allocatable, intent(out) :: name
      integer, intent(out) :: sub
      logical, intent(out) :: is_item
      integer :: close, k, v
      logical :: ok
      is_item = .false.
      sub = 0
      call read_name(text, c, name)
      if (len(name) == 0 .or. len(name) > max_name_length) return
      call skip_blanks(text, c)
      if (c%pos <= len(text)) then
         if (text(c%pos:c%pos) == "(") then
            close = index(text(c%pos:), ")")
            if (close == 0) return
            close = c%pos + close - 1
            ok = close > c%pos + 1
            v = 0
            do k = c%pos + 1, close - 1
               if (text(k:k) == " ") cycle
               if (text(k:k) < "0" .or. text(k:k) > "9" .or. v > 100000000) then
                  ok = .false.
                  exit
               end if
               v = 10 * v + (iachar(text(k:k)) - iachar("0"))
            end do
            sub = merge(v, -1, ok .and. v >= 1)
            c%pos = close + 1
            call skip_blanks(text, c)
         end if
      end if
      if (c%pos > len(text)) return
      if (text(c%pos:c%pos) /= "=") return
      c%pos = c%pos + 1
      is_item = .true.
   end subroutine item_start

   !> `r*` before a value: r (>= 1) and stat 0; no repeat: r = 1, stat 0;
   !> a malformed one (`0*1`, `3*` with no value): stat 1; one of more than 9
   !> digits: stat 2.
   pure subroutine repeat_count(text, c, r, stat)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      integer, intent(out) :: r, stat
      integer :: k
      r = 1
      stat = 0
      k = c%pos
      do while (k <= len(text))
         if (text(k:k) < "0" .or. text(k:k) > "9") exit
         k = k + 1
      end do
      if (k == c%pos .or. k > len(text)) return
      if (text(k:k) /= "*") return
      if (k - c%pos > 9) then
         stat = 2                        ! a whole number, but too large to hold
         return
      end if
      read(text(c%pos:k-1), *) r
      if (r < 1 .or. k == len(text)) then
         stat = 1
         return
      end if
      if (is_blank_at(text, k + 1) .or. index(",/!", text(k+1:k+1)) > 0) then
         stat = 1
         return
      end if
      c%pos = k + 1
   end subroutine repeat_count

   !> One value token: quoted text (doubled quotes inside stand for one), or
   !> a run of characters up to a blank, comma, slash or '!'.
   pure subroutine read_token(text, path, c, tok, quoted, error)
      character(len=*), intent(in) :: text, path
      type(cursor_type), intent(inout) :: c
      character(len=:), allocatable, intent(out) :: tok
      logical, intent(out) :: quoted
      type(error_type), allocatable, intent(out) :: error
      character :: q
      integer :: k, start, n
      character(len=:), allocatable :: buf
      quoted = text(c%pos:c%pos) == "'" .or. text(c%pos:c%pos) == '"'
      if (quoted) then
         q = text(c%pos:c%pos)
         allocate(character(len=len(text)) :: buf)
         n = 0
         k = c%pos + 1
         do
            if (k > len(text)) then
               call fatal_error(error, at(path, c%line) // &
                  & "quoted text is not closed")
               return
            end if
            if (text(k:k) == achar(10)) then
               call fatal_error(error, at(path, c%line) // &
                  & "quoted text is not closed on its line")
               return
            end if
            if (text(k:k) == q) then
               if (k < len(text)) then
                  if (text(k+1:k+1) == q) then
                     n = n + 1
                     buf(n:n) = q
                     k = k + 2
                     cycle
                  end if
               end if
               exit
            end if
            n = n + 1
            buf(n:n) = text(k:k)
            k = k + 1
         end do
         tok = buf(1:n)
         c%pos = k + 1
         return
      end if
      start = c%pos
      k = c%pos
      do while (k <= len(text))
         if (is_blank_at(text, k)) exit
         if (index(",/!", text(k:k)) > 0) exit
         k = k + 1
      end do
      tok = text(start:k-1)
      c%pos = k
   end subroutine read_token

   !> A Fortran name at the cursor (empty if there is none); the cursor moves past it.
   pure subroutine read_name(text, c, name)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      character(len=:), allocatable, intent(out) :: name
      integer :: k
      name = ""
      if (c%pos > len(text)) return
      if (index(letters, text(c%pos:c%pos)) == 0) return
      k = c%pos
      do while (k <= len(text))
         if (index(name_chars, text(k:k)) == 0) exit
         k = k + 1
      end do
      name = text(c%pos:k-1)
      c%pos = k
   end subroutine read_name

   !> A group's end at the cursor ('/', '&end', '$end', '$' alone); consumed.
   pure subroutine terminator(text, c, at_terminator)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      logical, intent(out) :: at_terminator
      character :: ch
      integer :: k
      at_terminator = .false.
      ch = text(c%pos:c%pos)
      if (ch == "/") then
         at_terminator = .true.
         c%pos = c%pos + 1
         return
      end if
      if (ch /= "&" .and. ch /= "$") return
      k = c%pos + 1
      if (k + 2 <= len(text)) then
         if (to_lower(text(k:k+2)) == "end") then
            if (k + 3 > len(text)) then
               at_terminator = .true.
            else
               at_terminator = index(name_chars, text(k+3:k+3)) == 0
            end if
            if (at_terminator) c%pos = k + 3
            return
         end if
      end if
      if (ch == "$") then
         if (k > len(text)) then
            at_terminator = .true.
         else
            at_terminator = index(letters, text(k:k)) == 0
         end if
         if (at_terminator) c%pos = k
      end if
   end subroutine terminator

   !> Blanks (see the module's notes) and '!' comments.
   pure subroutine skip_blanks_and_comments(text, c)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      do
         call skip_blanks(text, c)
         if (c%pos > len(text)) return
         if (text(c%pos:c%pos) /= "!") return
         do while (c%pos <= len(text))
            if (text(c%pos:c%pos) == achar(10)) exit
            c%pos = c%pos + 1
         end do
      end do
   end subroutine skip_blanks_and_comments

   !> Blanks, comments and commas between assignments.
   pure subroutine skip_separators(text, c)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      do
         call skip_blanks_and_comments(text, c)
         if (c%pos > len(text)) return
         if (text(c%pos:c%pos) /= ",") return
         c%pos = c%pos + 1
      end do
   end subroutine skip_separators

   pure subroutine skip_blanks(text, c)
      character(len=*), intent(in) :: text
      type(cursor_type), intent(inout) :: c
      integer :: width
      do while (c%pos <= len(text))
         width = blank_width(text, c%pos)
         if (width == 0) return
         if (text(c%pos:c%pos) == achar(10)) c%line = c%line + 1
         c%pos = c%pos + width
      end do
   end subroutine skip_blanks

   pure logical function is_blank_at(text, k)
      character(len=*), intent(in) :: text
      integer, intent(in) :: k
      is_blank_at = blank_width(text, k) > 0
   end function is_blank_at

   !> Bytes of the blank character at k (0: not a blank): ASCII blank, tab,
   !> LF, VT, FF, CR; UTF-8 BOM (EF BB BF) and no-break space (C2 A0); a
   !> Latin-1 no-break space (A0).
   pure integer function blank_width(text, k)
      character(len=*), intent(in) :: text
      integer, intent(in) :: k
      integer :: b
      blank_width = 0
      b = iachar(text(k:k))
      select case (b)
      case (32, 9, 10, 11, 12, 13, 160)
         blank_width = 1
      case (194)
         if (k < len(text)) then
            if (iachar(text(k+1:k+1)) == 160) blank_width = 2
         end if
      case (239)
         if (k + 2 <= len(text)) then
            if (iachar(text(k+1:k+1)) == 187 .and. iachar(text(k+2:k+2)) == 191) blank_width = 3
         end if
      end select
   end function blank_width

   !> The text at k up to the end of its line (at most 40 characters), for messages.
   pure function visible(text, k) result(s)
      character(len=*), intent(in) :: text
      integer, intent(in) :: k
      character(len=visible_len(text, k)) :: s
      character(len=:), allocatable :: deferred_text
      call visible_text(text, k, deferred_text)
      s = deferred_text
   end function visible

   !> The length of visible's text.
   pure integer function visible_len(text, k)
      character(len=*), intent(in) :: text
      integer, intent(in) :: k
      character(len=:), allocatable :: deferred_text
      call visible_text(text, k, deferred_text)
      visible_len = len(deferred_text)
   end function visible_len

   !> The text of visible, into a deferred-length argument.
   pure subroutine visible_text(text, k, s)
      character(len=*), intent(in) :: text
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: s
      integer :: e
      e = index(text(k:), achar(10))
      if (e == 0) then
         e = len(text)
      else
         e = k + e - 2
      end if
      e = min(e, k + 39)
      s = trim(text(k:e))
      if (len(s) > 0) then
         if (s(len(s):len(s)) == achar(13)) s = s(1:len(s)-1)
      end if
   end subroutine visible_text

   !> Line breaks and runs of blanks as one blank; ends trimmed.
   pure function squeeze_blanks(s) result(t)
      character(len=*), intent(in) :: s
      character(len=squeeze_blanks_len(s)) :: t
      character(len=:), allocatable :: deferred_text
      call squeeze_blanks_text(s, deferred_text)
      t = deferred_text
   end function squeeze_blanks

   !> The length of squeeze_blanks's text.
   pure integer function squeeze_blanks_len(s)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: deferred_text
      call squeeze_blanks_text(s, deferred_text)
      squeeze_blanks_len = len(deferred_text)
   end function squeeze_blanks_len

   !> The text of squeeze_blanks, into a deferred-length argument.
   pure subroutine squeeze_blanks_text(s, t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable, intent(out) :: t
      character(len=:), allocatable :: buf    ! on the heap: s may be long
      integer :: k, n
      logical :: prev_blank
      allocate(character(len=len(s)) :: buf)
      n = 0
      prev_blank = .true.
      do k = 1, len(s)
         if (index(" " // achar(9) // achar(10) // achar(13), s(k:k)) > 0) then
            if (.not. prev_blank) then
               n = n + 1
               buf(n:n) = " "
            end if
            prev_blank = .true.
         else
            n = n + 1
            buf(n:n) = s(k:k)
            prev_blank = .false.
         end if
      end do
      if (n > 0) then
         if (buf(n:n) == " ") n = n - 1
      end if
      t = buf(1:n)
   end subroutine squeeze_blanks_text

   !> "path:line: " for messages; nothing when the text has no file (keywords).
   pure function at(path, line) result(t)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=at_len(path, line)) :: t
      character(len=:), allocatable :: deferred_text
      call at_text(path, line, deferred_text)
      t = deferred_text
   end function at

   !> The length of at's text.
   pure integer function at_len(path, line)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=:), allocatable :: deferred_text
      call at_text(path, line, deferred_text)
      at_len = len(deferred_text)
   end function at_len

   !> The text of at, into a deferred-length argument.
   pure subroutine at_text(path, line, t)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=:), allocatable, intent(out) :: t
      if (len(path) == 0) then
         t = ""
      else
         t = path // ":" // to_str(line) // ": "
      end if
   end subroutine at_text

   pure subroutine grow_groups(a)
      type(nml_group_type), allocatable, intent(inout) :: a(:)
      type(nml_group_type), allocatable :: t(:)
      allocate(t(2 * size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine grow_groups

   pure subroutine grow_items(a)
      type(nml_item_type), allocatable, intent(inout) :: a(:)
      type(nml_item_type), allocatable :: t(:)
      allocate(t(2 * size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine grow_items

   pure subroutine grow_tokens(a)
      type(nml_token_type), allocatable, intent(inout) :: a(:)
      type(nml_token_type), allocatable :: t(:)
      allocate(t(2 * size(a)))
      t(1:size(a)) = a
      call move_alloc(t, a)
   end subroutine grow_tokens

end module pavefric_namelist
