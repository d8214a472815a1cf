!> File-system helpers from the C library: atomic rename, remove, mkdir,
!> process id, file identity (stat, realpath), the guard that keeps an
!> output off the inputs and off devices, and the list of temporary files a
!> fatal signal removes (src/io/pavefric_posix.c). Fortran has none of these
!> portably.
module pavefric_fsys
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_long_long
   use pavefric_error, only: error_type, fatal_error, stat_input
   use pavefric_format, only: to_str
   implicit none
   private

   public :: rename_file, remove_file, make_directory, process_id, dir_name, base_name, &
      & join_path, is_absolute
   public :: output_guard_type, check_output_path, canonical_path, os_message
   public :: register_temporary, release_temporary, install_signal_cleanup, test_pause
   public :: remove_stale_temporaries, setting, is_symlink, temporary_path, &
      & is_temporary_name, file_identity

   !> Kinds of file (pavefric_file_id in pavefric_posix.c).
   integer, parameter :: kind_missing = 0, kind_regular = 1

   !> An output path that passed `check_output_path`: it is missing or a
   !> regular file. `check_input` refuses an input that is the same file.
   type :: output_guard_type
      !> The output path as given, and the name of the setting that gave it
      !> ("-o", "&output file", ...), for messages.
      character(len=:), allocatable :: path, what
      !> Whether a file is there now, and its identity (device, inode).
      logical :: exists = .false.
      integer(c_long_long) :: dev = 0, ino = 0
   contains
      procedure :: check_input => guard_check_input
   end type output_guard_type

   interface
      function c_rename(old, new) bind(C, name="rename") result(stat)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: old(*), new(*)
         integer(c_int) :: stat
      end function c_rename
      function c_remove(path) bind(C, name="remove") result(stat)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: stat
      end function c_remove
      function c_mkdir(path, mode) bind(C, name="mkdir") result(stat)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: stat
      end function c_mkdir
      function c_getpid() bind(C, name="getpid") result(pid)
         import :: c_int
         integer(c_int) :: pid
      end function c_getpid
      function c_may_replace(path) bind(C, name="pavefric_may_replace") result(yes)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: yes
      end function c_may_replace
      function c_keep_mode(path, tmp) bind(C, name="pavefric_keep_mode") result(stat)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*), tmp(*)
         integer(c_int) :: stat
      end function c_keep_mode
      function c_is_symlink(path) bind(C, name="pavefric_is_symlink") result(yes)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: yes
      end function c_is_symlink
      function c_file_id(path, dev, ino, kind) bind(C, name="pavefric_file_id") result(stat)
         import :: c_int, c_char, c_long_long
         character(kind=c_char), intent(in) :: path(*)
         integer(c_long_long), intent(out) :: dev, ino
         integer(c_int), intent(out) :: kind
         integer(c_int) :: stat
      end function c_file_id
      !> strerror into `buf` (src/io/pavefric_ncmem.c); the length written.
      pure subroutine c_strerror(err, buf, n, written) bind(C, name="pavefric_strerror_into")
         import :: c_int, c_char
         integer(c_int), value :: err, n
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_int), intent(out) :: written
      end subroutine c_strerror
      function c_realpath(path, out, outlen) bind(C, name="pavefric_realpath") result(need)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int), value :: outlen
         integer(c_int) :: need
      end function c_realpath
      function c_temp_register(path) bind(C, name="pavefric_temp_register") result(slot)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: slot
      end function c_temp_register
      subroutine c_temp_release(path) bind(C, name="pavefric_temp_release")
         import :: c_char
         character(kind=c_char), intent(in) :: path(*)
      end subroutine c_temp_release
      function c_install_cleanup() bind(C, name="pavefric_install_cleanup") result(stat)
         import :: c_int
         integer(c_int) :: stat
      end function c_install_cleanup
      function c_remove_stale(path) bind(C, name="pavefric_remove_stale_temporaries") &
            & result(removed)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: removed
      end function c_remove_stale
      function c_temporary_name(path, out, outlen) bind(C, name="pavefric_temporary_name") &
            & result(need)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int), value :: outlen
         integer(c_int) :: need
      end function c_temporary_name
      function c_temporary_pid(base, name) bind(C, name="pavefric_temporary_pid") result(pid)
         import :: c_char, c_long_long
         character(kind=c_char), intent(in) :: base(*), name(*)
         integer(c_long_long) :: pid
      end function c_temporary_pid
      subroutine c_test_pause(point) bind(C, name="pavefric_test_pause")
         import :: c_char
         character(kind=c_char), intent(in) :: point(*)
      end subroutine c_test_pause
   end interface

contains

   !> Rename `old` to `new` atomically (same file system); true on success.
   !> Whether `path` is itself a symbolic link (lstat; not followed).
   function is_symlink(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      yes = c_is_symlink(path // c_null_char) /= 0
   end function is_symlink

   !> Rename `old` onto `new`, `old` first given the permission bits of the
   !> file it replaces (a private 0600 result stays private).
   function rename_file(old, new) result(ok)
      character(len=*), intent(in) :: old, new
      logical :: ok
      integer(c_int) :: stat
      stat = c_keep_mode(new // c_null_char, old // c_null_char)
      ok = c_rename(old // c_null_char, new // c_null_char) == 0
   end function rename_file

   !> Remove a file if it exists; true on success.
   function remove_file(path) result(ok)
      character(len=*), intent(in) :: path
      logical :: ok
      ok = c_remove(path // c_null_char) == 0
   end function remove_file

   !> Create one directory level (mode 0777 less umask); true if it exists after.
   function make_directory(path) result(ok)
      character(len=*), intent(in) :: path
      logical :: ok
      integer(c_int) :: stat
      stat = c_mkdir(path // c_null_char, int(o'777', c_int))
      inquire(file=path // "/.", exist=ok)
   end function make_directory

   !> This process's id, to make temporary names unique.
   function process_id() result(pid)
      integer :: pid
      pid = int(c_getpid())
   end function process_id

   !> Directory part of a path ("." when there is none).
   pure function dir_name(path) result(dir)
      character(len=*), intent(in) :: path
      character(len=dir_name_len(path)) :: dir
      character(len=:), allocatable :: deferred_text
      call dir_name_text(path, deferred_text)
      dir = deferred_text
   end function dir_name

   !> The length of dir_name's text.
   pure integer function dir_name_len(path)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: deferred_text
      call dir_name_text(path, deferred_text)
      dir_name_len = len(deferred_text)
   end function dir_name_len

   !> The text of dir_name, into a deferred-length argument.
   pure subroutine dir_name_text(path, dir)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: dir
      integer :: pos
      pos = index(path, "/", back=.true.)
      if (pos == 0) then
         dir = "."
      else if (pos == 1) then
         dir = "/"
      else
         dir = path(1:pos-1)
      end if
   end subroutine dir_name_text

   !> File name without directory and without its last extension.
   pure function base_name(path) result(base)
      character(len=*), intent(in) :: path
      character(len=base_name_len(path)) :: base
      character(len=:), allocatable :: deferred_text
      call base_name_text(path, deferred_text)
      base = deferred_text
   end function base_name

   !> The length of base_name's text.
   pure integer function base_name_len(path)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: deferred_text
      call base_name_text(path, deferred_text)
      base_name_len = len(deferred_text)
   end function base_name_len

   !> The text of base_name, into a deferred-length argument.
   pure subroutine base_name_text(path, base)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: base
      integer :: pos
      base = path(index(path, "/", back=.true.)+1:)
      pos = index(base, ".", back=.true.)
      if (pos > 1) base = base(1:pos-1)
   end subroutine base_name_text

   !> Whether a path is absolute.
   pure function is_absolute(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      yes = .false.
      if (len(path) > 0) yes = path(1:1) == "/"
   end function is_absolute

   !> `path` relative to `dir`, unless it is absolute.
   pure function join_path(dir, path) result(full)
      character(len=*), intent(in) :: dir, path
      character(len=join_path_len(dir, path)) :: full
      character(len=:), allocatable :: deferred_text
      call join_path_text(dir, path, deferred_text)
      full = deferred_text
   end function join_path

   !> The length of join_path's text.
   pure integer function join_path_len(dir, path)
      character(len=*), intent(in) :: dir, path
      character(len=:), allocatable :: deferred_text
      call join_path_text(dir, path, deferred_text)
      join_path_len = len(deferred_text)
   end function join_path_len

   !> The text of join_path, into a deferred-length argument.
   pure subroutine join_path_text(dir, path, full)
      character(len=*), intent(in) :: dir, path
      character(len=:), allocatable, intent(out) :: full
      if (is_absolute(path) .or. dir == ".") then
         full = path
      else
         full = dir // "/" // path
      end if
   end subroutine join_path_text

   !> The C library's text for an errno value.
   pure function os_message(err) result(text)
      integer(c_int), intent(in) :: err
      character(len=os_message_len(err)) :: text
      character(len=:), allocatable :: deferred_text
      call os_message_text(err, deferred_text)
      text = deferred_text
   end function os_message

   !> The length of os_message's text.
   pure integer function os_message_len(err)
      integer(c_int), intent(in) :: err
      character(len=:), allocatable :: deferred_text
      call os_message_text(err, deferred_text)
      os_message_len = len(deferred_text)
   end function os_message_len

   !> The text of os_message, into a deferred-length argument.
   pure subroutine os_message_text(err, text)
      integer(c_int), intent(in) :: err
      character(len=:), allocatable, intent(out) :: text
      character(len=256) :: buf
      integer(c_int) :: n
      buf = ""
      call c_strerror(err, buf, int(len(buf), c_int), n)
      text = buf(1:max(0, min(int(n), len(buf))))
   end subroutine os_message_text

   !> Refuse an output `path` that exists and is not a regular file (a
   !> directory, device, FIFO or socket: the temp-file-and-rename write would
   !> replace it); on success `guard` remembers the file's identity so that
   !> `guard%check_input` can refuse inputs that are the same file. `what`
   !> names the setting that gave the path ("-o", "&output file").
   subroutine check_output_path(path, what, guard, error)
      character(len=*), intent(in) :: path, what
      type(output_guard_type), intent(out) :: guard
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: kind, stat
      guard%path = path
      guard%what = what
      stat = c_file_id(path // c_null_char, guard%dev, guard%ino, kind)
      if (stat /= 0) then
         call fatal_error(error, setting(what, path) // ": cannot inspect it (" // &
            & os_message(stat) // ")", stat_input)
         return
      end if
      guard%exists = kind /= kind_missing
      if (guard%exists .and. kind /= kind_regular) then
         call fatal_error(error, &
            & setting(what, path) // ": exists and is " // kind_name(int(kind)) // &
            & ", not a regular file; the output must be a regular file (it would replace " // &
            & "this one)", stat_input)
         return
      end if
      ! a file made read-only is not replaced (a rename would, whatever its mode)
      if (guard%exists) then
         if (c_may_replace(path // c_null_char) == 0) call fatal_error(error, &
            & setting(what, path) // ": exists and is read-only; pavefric does not replace " // &
            & "a file you made read-only: make it writable, or choose another path", stat_input)
      end if
   end subroutine check_output_path

   !> Refuse the output if it is the same file as `input` (same device and
   !> inode: symbolic links, '..' and hard links are seen through). `role`
   !> says what the input is ("the scene file", "&surface profile_file").
   !> An input that does not exist cannot clash (its reader reports it).
   subroutine guard_check_input(guard, input, role, error)
      class(output_guard_type), intent(in) :: guard
      character(len=*), intent(in) :: input, role
      type(error_type), allocatable, intent(out) :: error
      integer(c_long_long) :: dev, ino
      integer(c_int) :: kind, stat
      character(len=:), allocatable :: where
      if (.not. guard%exists .or. len(input) == 0) return
      stat = c_file_id(input // c_null_char, dev, ino, kind)
      if (stat /= 0 .or. kind == kind_missing) return
      if (dev /= guard%dev .or. ino /= guard%ino) return
      call canonical_path(input, where)
      if (len(where) > 0 .and. where /= input) then
         where = " (resolves to '" // where // "')"
      else
         where = ""
      end if
      call fatal_error(error, setting(guard%what, guard%path) // ": is " // role // " '" // &
         & input // "'" // where // "; writing the output there would destroy an input", &
         & stat_input)
   end subroutine guard_check_input

   !> A regular file's identity as text, '<device>:<inode>' (one file by any
   !> name: symbolic and hard links, '..'); empty where nothing is there or it
   !> cannot be inspected (its reader says why).
   subroutine file_identity(path, id)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: id
      integer(c_long_long) :: dev, ino
      integer(c_int) :: kind, stat
      id = ""
      if (len(path) == 0) return
      stat = c_file_id(path // c_null_char, dev, ino, kind)
      if (stat /= 0 .or. kind /= kind_regular) return
      id = to_str(dev) // ":" // to_str(ino)
   end subroutine file_identity

   !> The canonical absolute path of an existing file (symbolic links, '.'
   !> and '..' resolved); empty if it cannot be resolved.
   subroutine canonical_path(path, full)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: full
      integer(c_int) :: need
      integer :: stat
      allocate(character(len=4096) :: full, stat=stat)
      if (stat /= 0) then
         full = ""
         return
      end if
      need = c_realpath(path // c_null_char, full, len(full, c_int))
      if (need > len(full)) then
         deallocate(full)
         allocate(character(len=need) :: full, stat=stat)
         if (stat /= 0) then
            full = ""
            return
         end if
         need = c_realpath(path // c_null_char, full, len(full, c_int))
      end if
      if (need < 0 .or. need > len(full)) then
         full = ""
      else
         full = full(1:need)
      end if
   end subroutine canonical_path

   !> Record `path` as a temporary file that a fatal signal (SIGTERM, SIGINT,
   !> SIGHUP) removes before the program dies; see `install_signal_cleanup`.
   subroutine register_temporary(path)
      character(len=*), intent(in) :: path
      integer(c_int) :: slot
      slot = c_temp_register(path // c_null_char)
   end subroutine register_temporary

   !> Remove the temporaries (`path`.tmpPID.pavefric) that writers killed outright
   !> left beside `path` (their process is gone); how many were removed.
   function remove_stale_temporaries(path) result(removed)
      character(len=*), intent(in) :: path
      integer :: removed
      removed = int(c_remove_stale(path // c_null_char))
   end function remove_stale_temporaries

   !> The name `path` is first written under, `<path>.tmp<PID>.pavefric`
   !> (made in pavefric_posix.c, which alone knows the form; empty if it
   !> cannot be formed).
   subroutine temporary_path(path, tmp)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: tmp
      integer(c_int) :: need
      allocate(character(len=len(path) + 40) :: tmp)
      need = c_temporary_name(path // c_null_char, tmp, len(tmp, c_int))
      if (need > len(tmp)) then
         deallocate(tmp)
         allocate(character(len=need) :: tmp)
         need = c_temporary_name(path // c_null_char, tmp, len(tmp, c_int))
      end if
      if (need < 0) then
         tmp = ""
      else
         tmp = tmp(1:need)
      end if
   end subroutine temporary_path

   !> Whether the file name `name` is a pavefric temporary of a file named
   !> `base` (`<base>.tmp<PID>.pavefric`; both last path components).
   logical function is_temporary_name(base, name)
      character(len=*), intent(in) :: base, name
      is_temporary_name = c_temporary_pid(base // c_null_char, name // c_null_char) > 0
   end function is_temporary_name

   !> Forget the temporary file `path` once it is renamed into place or removed.
   subroutine release_temporary(path)
      character(len=*), intent(in) :: path
      call c_temp_release(path // c_null_char)
   end subroutine release_temporary

   !> Install the handlers that remove registered temporary files on SIGTERM,
   !> SIGINT and SIGHUP, then let the signal kill the program as usual, and
   !> ignore SIGXFSZ (a file-size limit becomes a write error). For the
   !> program only: never from the Python extension (SIGINT is Python's).
   subroutine install_signal_cleanup()
      integer(c_int) :: stat
      stat = c_install_cleanup()
   end subroutine install_signal_cleanup

   !> Test hook: stop the process at `point` ("create", "commit") when the
   !> environment variable PAVEFRIC_TEST_PAUSE says so; nothing otherwise.
   subroutine test_pause(point)
      character(len=*), intent(in) :: point
      call c_test_pause(point // c_null_char)
   end subroutine test_pause

   !> "-o 'x'" or "&output file = 'x'", the way messages name a setting.
   pure function setting(what, path) result(text)
      character(len=*), intent(in) :: what, path
      character(len=setting_len(what, path)) :: text
      character(len=:), allocatable :: deferred_text
      call setting_text(what, path, deferred_text)
      text = deferred_text
   end function setting

   !> The length of setting's text.
   pure integer function setting_len(what, path)
      character(len=*), intent(in) :: what, path
      character(len=:), allocatable :: deferred_text
      call setting_text(what, path, deferred_text)
      setting_len = len(deferred_text)
   end function setting_len

   !> The text of setting, into a deferred-length argument.
   pure subroutine setting_text(what, path, text)
      character(len=*), intent(in) :: what, path
      character(len=:), allocatable, intent(out) :: text
      if (len(what) > 0) then
         if (what(1:1) == "&") then
            text = what // " = '" // path // "'"
            return
         end if
      end if
      text = what // " '" // path // "'"
   end subroutine setting_text

   pure function kind_name(kind) result(name)
      integer, intent(in) :: kind
      character(len=kind_name_len(kind)) :: name
      character(len=:), allocatable :: deferred_text
      call kind_name_text(kind, deferred_text)
      name = deferred_text
   end function kind_name

   !> The length of kind_name's text.
   pure integer function kind_name_len(kind)
      integer, intent(in) :: kind
      character(len=:), allocatable :: deferred_text
      call kind_name_text(kind, deferred_text)
      kind_name_len = len(deferred_text)
   end function kind_name_len

   !> The text of kind_name, into a deferred-length argument.
   pure subroutine kind_name_text(kind, name)
      integer, intent(in) :: kind
      character(len=:), allocatable, intent(out) :: name
      select case (kind)
      case (2)
         name = "a directory"
      case (3)
         name = "a character device"
      case (4)
         name = "a block device"
      case (5)
         name = "a FIFO (named pipe)"
      case (6)
         name = "a socket"
      case default
         name = "a special file"
      end select
   end subroutine kind_name_text

end module pavefric_fsys
