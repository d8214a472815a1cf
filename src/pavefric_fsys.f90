!> File-system helpers from the C library: atomic rename, remove, mkdir,
!> process id. Fortran has none of these portably.
module pavefric_fsys
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   implicit none
   private

   public :: rename_file, remove_file, make_directory, process_id, dir_name, base_name, &
      & join_path, is_absolute

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
   end interface

contains

   !> Rename `old` to `new` atomically (same file system); true on success.
   function rename_file(old, new) result(ok)
      character(len=*), intent(in) :: old, new
      logical :: ok
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
      character(len=:), allocatable :: dir
      integer :: pos
      pos = index(path, "/", back=.true.)
      if (pos == 0) then
         dir = "."
      else if (pos == 1) then
         dir = "/"
      else
         dir = path(1:pos-1)
      end if
   end function dir_name

   !> File name without directory and without its last extension.
   pure function base_name(path) result(base)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: base
      integer :: pos
      base = path(index(path, "/", back=.true.)+1:)
      pos = index(base, ".", back=.true.)
      if (pos > 1) base = base(1:pos-1)
   end function base_name

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
      character(len=:), allocatable :: full
      if (is_absolute(path) .or. dir == ".") then
         full = path
      else
         full = dir // "/" // path
      end if
   end function join_path

end module pavefric_fsys
