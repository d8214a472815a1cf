!> SHA-256 digests for the batch journal (src/io/pavefric_sha256.c): the
!> fingerprint of a batch's inputs, each profile file's content, and a
!> checksum of each journal line. Digests are 64 lower-case hex characters.
module pavefric_batch_hash
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_long, c_null_char
   implicit none
   private

   public :: sha256_hex, sha256_file, digest_len, no_digest

   !> Characters of a hex digest.
   integer, parameter :: digest_len = 64
   !> What stands for the digest of a file that cannot be read (missing, a
   !> directory, a device): a profile that failed because its file was
   !> missing stays failed on resume only while it is still missing.
   character(len=digest_len), parameter :: no_digest = repeat("-", digest_len)

   interface
      subroutine c_sha256_bytes(data, n, hex) bind(C, name="pavefric_sha256_bytes")
         import :: c_char, c_long
         character(kind=c_char), intent(in) :: data(*)
         integer(c_long), value :: n
         character(kind=c_char), intent(out) :: hex(*)
      end subroutine c_sha256_bytes
      function c_sha256_file(path, hex) bind(C, name="pavefric_sha256_file") result(stat)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: hex(*)
         integer(c_int) :: stat
      end function c_sha256_file
   end interface

contains

   !> SHA-256 of the bytes of `text`.
   function sha256_hex(text) result(hex)
      character(len=*), intent(in) :: text
      character(len=digest_len) :: hex
      call c_sha256_bytes(text, int(len(text), c_long), hex)
   end function sha256_hex

   !> SHA-256 of the bytes of the file at `path`; `no_digest` when it cannot
   !> be read or is not a regular file (`ok` false).
   subroutine sha256_file(path, hex, ok)
      character(len=*), intent(in) :: path
      character(len=digest_len), intent(out) :: hex
      logical, intent(out), optional :: ok
      integer(c_int) :: stat
      hex = no_digest
      stat = c_sha256_file(path // c_null_char, hex)
      if (stat /= 0) hex = no_digest
      if (present(ok)) ok = stat == 0
   end subroutine sha256_file

end module pavefric_batch_hash
