!> Getting a profile file's bytes: only regular files (a device or FIFO
!> would never end or would block), the first bytes for format detection,
!> or the whole file in one stream read (readers then scan it in memory, so
!> reading is linear in the file's size).
module pavefric_profile_file
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
   use pavefric_kinds, only: i8
   use pavefric_error, only: error_type, fatal_error, stat_memory, stat_io
   use pavefric_format, only: to_str
   implicit none
   private

   public :: check_profile_file, read_file_head, read_whole_file, not_regular

   interface
      function c_file_kind(path) bind(C, name="pavefric_file_kind") result(kind)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: kind
      end function c_file_kind
   end interface

contains

   !> Error unless `path` is a regular file (or cannot be examined: then
   !> opening it reports why). Messages name &surface profile_file.
   subroutine check_profile_file(path, error)
      character(len=*), intent(in) :: path
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: what
      call not_regular(path, what)
      if (len(what) == 0) return
      call fatal_error(error, "&surface profile_file = '" // path // "': " // what // &
         & ", not a regular file (profiles are read from regular files only)")
   end subroutine check_profile_file

   !> What `path` is when it is not a regular file ("a FIFO (named pipe)",
   !> ...); empty for a regular file or one that cannot be examined (opening
   !> it then says why). Readers of whole files take regular files only: a
   !> pipe's reported size is 0 (read as empty), and a FIFO without a writer
   !> blocks the open forever.
   subroutine not_regular(path, what)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: what
      select case (c_file_kind(path // c_null_char))
      case (-1, 0)
         what = ""
      case (1)
         what = "a directory"
      case (2)
         what = "a character device"
      case (3)
         what = "a block device"
      case (4)
         what = "a FIFO (named pipe)"
      case (5)
         what = "a socket"
      case default
         what = "not a regular file"
      end select
   end subroutine not_regular

   !> Open a checked regular file for stream reading.
   subroutine open_stream(path, unit, nbytes, error)
      character(len=*), intent(in) :: path
      integer, intent(out) :: unit
      integer(i8), intent(out) :: nbytes
      type(error_type), allocatable, intent(out) :: error
      character(len=512) :: msg
      integer :: ios
      nbytes = 0
      call check_profile_file(path, error)
      if (allocated(error)) return
      open(newunit=unit, file=path, status="old", action="read", access="stream", &
         & form="unformatted", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&surface profile_file = '" // path // "': cannot open (" // &
            & trim(msg) // ")")
         return
      end if
      inquire(unit=unit, size=nbytes)
      if (nbytes < 0) then
         close(unit)
         call fatal_error(error, "&surface profile_file = '" // path // &
            & "': cannot tell its size", stat_io)
      end if
   end subroutine open_stream

   !> Up to len(head) first bytes of a file; `nread` says how many there were.
   subroutine read_file_head(path, head, nread, error)
      character(len=*), intent(in) :: path
      character(len=*), intent(out) :: head
      integer, intent(out) :: nread
      type(error_type), allocatable, intent(out) :: error
      integer(i8) :: nbytes
      integer :: unit, ios
      head = ""
      nread = 0
      call open_stream(path, unit, nbytes, error)
      if (allocated(error)) return
      nread = int(min(nbytes, int(len(head), i8)))
      if (nread > 0) then
         read(unit, iostat=ios) head(1:nread)
         if (ios /= 0) then
            call fatal_error(error, "&surface profile_file = '" // path // "': cannot read", &
               & stat_io)
         end if
      end if
      close(unit)
   end subroutine read_file_head

   !> The whole file as one string, read in one go.
   subroutine read_whole_file(path, buf, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: buf
      type(error_type), allocatable, intent(out) :: error
      character(len=512) :: msg
      integer(i8) :: nbytes
      integer :: unit, ios, st
      call open_stream(path, unit, nbytes, error)
      if (allocated(error)) return
      if (nbytes == 0) then
         ! (the kernel's files, /proc and /sys, report no size either: they
         ! read as empty here, and their text is no profile)
         close(unit)
         call fatal_error(error, "&surface profile_file = '" // path // "': holds no " // &
            & "heights: the file is empty (0 bytes; a file of /proc or /sys reports no " // &
            & "size and is not read: copy it to a file first)")
         return
      end if
      allocate(character(len=nbytes) :: buf, stat=st)
      if (st /= 0) then
         close(unit)
         call fatal_error(error, "&surface profile_file = '" // path // &
            & "': not enough memory to read it (" // to_str(nbytes) // " bytes)", stat_memory)
         return
      end if
      if (nbytes > 0) then
         read(unit, iostat=ios, iomsg=msg) buf
         if (ios /= 0) then
            close(unit)
            call fatal_error(error, "&surface profile_file = '" // path // "': cannot read (" // &
               & trim(msg) // ")", stat_io)
            return
         end if
      end if
      close(unit)
   end subroutine read_whole_file

end module pavefric_profile_file
