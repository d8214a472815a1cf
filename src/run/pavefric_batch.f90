!> Batch runs: many profiles, several water depths and speeds, one NetCDF.
!>
!> Finished profiles are recorded in a plain-text journal beside the output
!> (one flushed line a profile, at full precision), so a run that is killed
!> resumes where it stopped; the NetCDF file is built from the journal at the
!> end, indexed by profile, so the result does not depend on the order the
!> profiles finished in, on the number of MPI ranks, or on restarts.
!>
!> The journal is trusted line by line, never as a whole: its header holds
!> the SHA-256 fingerprint of the scene text, the profile paths, depths and
!> speeds; each line holds the SHA-256 of its profile file's bytes and a
!> SHA-256 checksum of itself. On resume a line is taken only when its
!> checksum, its values (finite, index in range, a valid status) and its
!> profile's current content all agree; any other line is recomputed.
module pavefric_batch
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_null_char
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use pavefric_kinds, only: wp, i8, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_io, add_warning, add_warnings, &
      & stat_memory, stat_input
   use pavefric_format, only: to_str
   use pavefric_numbers, only: parse_real
   use pavefric_scene, only: scene_type, read_scene, read_text_file
   use pavefric_run, only: load_scene_profile, texture_warning, result_warnings
   use pavefric_profile, only: raw_profile_type, detect_format, open_profile_catalog, &
      & read_catalog_profile, unit_factor, profile_label_type, first_duplicate_label
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_simulate, only: sim_result_type, simulate
   use pavefric_texture, only: texture_type, texture_metrics
   use pavefric_fsys, only: dir_name, base_name, join_path, make_directory
   use pavefric_fsys, only: output_guard_type, check_output_path, os_message, is_symlink, &
      & setting, canonical_path, is_temporary_name, file_identity
   use pavefric_netcdf, only: check_replaceable
   use pavefric_batch_hash, only: sha256_hex, sha256_file, digest_len, no_digest
   use pavefric_batch_types, only: batch_type, block_type, string_type, block_pack, &
      & block_unpack, block_values, block_allocate, block_clear, status_computed, status_failed, &
      & printable_utf8
   implicit none
   private

   !> Warnings of a profile kept as text in its block (all are counted).
   integer, parameter :: max_block_warnings = 5

   public :: batch_type, block_type, string_type, batch_setup, batch_prepare, batch_compute, &
      & journal_append, journal_close, block_pack, block_unpack, block_values, &
      & batch_output_path, profile_cost, status_computed, status_failed

   interface
      function c_glob(pattern, out, outlen, count) bind(C, name="pavefric_glob") result(need)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: pattern(*)
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int), value :: outlen
         integer(c_int), intent(out) :: count
         integer(c_int) :: need
      end function c_glob
      function c_journal_open(path, create) bind(C, name="pavefric_journal_open") result(fd)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: create
         integer(c_int) :: fd
      end function c_journal_open
      function c_journal_write(fd, buf, n) bind(C, name="pavefric_journal_write") result(err)
         import :: c_int, c_char, c_long
         integer(c_int), value :: fd
         character(kind=c_char), intent(in) :: buf(*)
         integer(c_long), value :: n
         integer(c_int) :: err
      end function c_journal_write
      function c_journal_close(fd) bind(C, name="pavefric_journal_close") result(err)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: err
      end function c_journal_close
   end interface

   character(len=*), parameter :: journal_magic = "pavefric-journal"
   !> Version of the journal's format (1: pavefric 0.1.0, no checksums).
   character(len=*), parameter :: journal_version = "3"

contains

   !> Where a batch writes: the override, the scene's &output file, or
   !> outputs/<scene name>.nc.
   subroutine batch_output_path(scene, output_override, out)
      type(scene_type), intent(in) :: scene
      character(len=*), intent(in) :: output_override
      character(len=:), allocatable, intent(out) :: out
      logical :: ok
      if (len_trim(output_override) > 0) then
         out = trim(output_override)
      else if (len(scene%output_file) > 0) then
         out = scene%output_file
      else
         ok = make_directory("outputs")
         out = "outputs/" // scene%name // ".nc"
      end if
   end subroutine batch_output_path

   !> Remove from `paths` (a pattern's or a directory's files) the batch's
   !> own files: its output where it is a pavefric output and its journal
   !> where it is a pavefric journal (the same files, links seen through),
   !> and its temporaries (`<output>.tmp<digits>.pavefric` in the output's
   !> directory). A file of the user's at either path stays a profile, so
   !> that the output checks refuse it as an input. Refused when nothing
   !> else is left.
   subroutine drop_own_files(paths, output, error)
      type(string_type), allocatable, intent(inout) :: paths(:)
      character(len=*), intent(in) :: output
      type(error_type), allocatable, intent(out) :: error
      type(output_guard_type) :: own(2)
      type(error_type), allocatable :: clash
      type(string_type), allocatable :: kept(:)
      character(len=:), allocatable :: out_dir, out_name, dir, name
      logical :: keep, ours(2)
      integer :: i, k, n
      ! (check_output_path's identity of each; an error there is the
      ! output check's, made later)
      call check_output_path(output, "-o", own(1), clash)
      ours(1) = own(1)%exists .and. .not. allocated(clash)
      if (allocated(clash)) deallocate(clash)
      if (ours(1)) then
         call check_replaceable(output, "-o", clash)
         ours(1) = .not. allocated(clash)
         if (allocated(clash)) deallocate(clash)
      end if
      call check_output_path(output // ".journal", "-o", own(2), clash)
      ours(2) = own(2)%exists .and. .not. allocated(clash)
      if (allocated(clash)) deallocate(clash)
      if (ours(2)) then
         call check_journal_replaceable(output // ".journal", "-o", clash)
         ours(2) = .not. allocated(clash)
         if (allocated(clash)) deallocate(clash)
      end if
      call dir_of(output, dir)
      call canonical_path(dir, out_dir)
      call file_of(output, out_name)
      allocate(kept(size(paths)))
      n = 0
      do i = 1, size(paths)
         keep = .true.
         do k = 1, 2
            if (.not. ours(k)) cycle
            call own(k)%check_input(paths(i)%s, "", clash)
            if (allocated(clash)) then
               keep = .false.
               deallocate(clash)
            end if
         end do
         if (keep) then
            call file_of(paths(i)%s, name)
            if (is_temporary_name(out_name, name)) then
               call dir_of(paths(i)%s, dir)
               call canonical_path(dir, name)
               keep = len(name) == 0 .or. name /= out_dir
            end if
         end if
         if (.not. keep) cycle
         n = n + 1
         kept(n)%s = paths(i)%s
      end do
      if (n == 0) then
         call fatal_error(error, "&batch profiles: the files it names are this batch's own " // &
            & "output, journal or temporaries ('" // output // "'); no profile is left", &
            & stat_input)
         return
      end if
      paths = kept(1:n)
   contains
      ! (subroutines, not functions of deferred length: gfortran keeps such a
      ! result's length in a static, which threads race on;
      ! tests/test_threads.py)
      !> A path's last component, its extension kept.
      subroutine file_of(p, f)
         character(len=*), intent(in) :: p
         character(len=:), allocatable, intent(out) :: f
         f = p(index(p, "/", back=.true.) + 1:)
      end subroutine file_of

      !> The directory of a path, '.' for a bare name.
      subroutine dir_of(p, d)
         character(len=*), intent(in) :: p
         character(len=:), allocatable, intent(out) :: d
         d = dir_name(p)
         if (len(d) == 0) d = "."
      end subroutine dir_of

   end subroutine drop_own_files

   !> Read a batch scene and expand its profiles: everything but the journal
   !> (MPI ranks other than 0 stop here; rank 0 alone reads the journal).
   subroutine batch_setup(path, output_override, batch, error)
      character(len=*), intent(in) :: path, output_override
      type(batch_type), intent(out) :: batch
      type(error_type), allocatable, intent(out) :: error

      call read_scene(path, batch%scene, error)
      if (allocated(error)) return
      if (.not. batch%scene%is_batch) then
         call fatal_error(error, "scene '" // path // "' has no &batch group")
         return
      end if
      call netcdf_source(batch, error)
      if (allocated(error)) return
      if (batch%from_netcdf) then
         batch%n_profiles = batch%catalog%n_profiles
      else
         call expand_profiles(batch%scene, batch%paths, batch%chainage, error)
         if (allocated(error)) return
         ! a pattern or a directory that also holds this batch's output: its
         ! output, journal and temporaries are not profiles (an attack of
         ! 2026-12-07: after an interruption the rerun took the journal for
         ! profile 1 and refused to resume)
         if (len(batch%scene%batch_profile_list) == 0) then
            call batch_output_path(batch%scene, output_override, batch%output)
            call drop_own_files(batch%paths, batch%output, error)
            if (allocated(error)) return
         end if
         batch%n_profiles = size(batch%paths)
         batch%has_chainage = allocated(batch%chainage)
         call profile_names(batch%scene, batch%paths, batch%names, error)
         if (allocated(error)) return
      end if
      if (allocated(batch%scene%batch_depths)) then
         batch%depths = batch%scene%batch_depths
      else
         batch%depths = [batch%scene%model%depth]
      end if
      batch%speeds = batch%scene%speeds_kmh
      batch%n_depths = size(batch%depths)
      batch%n_speeds = size(batch%speeds)
      call batch_output_path(batch%scene, output_override, batch%output)
      batch%journal = batch%output // ".journal"
      call check_batch_outputs(path, output_override, batch, error); if (allocated(error)) return
      batch%fingerprint = batch_fingerprint(batch)
   end subroutine batch_setup

   !> Read a batch scene, expand its profiles, and read the journal of an
   !> earlier, interrupted run (`blocks(i)%status` > 0 for profiles done), or
   !> start a new journal.
   subroutine batch_prepare(path, output_override, batch, blocks, error)
      character(len=*), intent(in) :: path, output_override
      type(batch_type), intent(out) :: batch
      type(block_type), allocatable, intent(out) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      integer :: i
      logical :: exists

      call batch_setup(path, output_override, batch, error)
      if (allocated(error)) return
      allocate(blocks(batch%n_profiles), stat=i)
      if (i /= 0) then
         call no_memory(batch%n_profiles, "profiles' results", error)
         return
      end if
      do i = 1, batch%n_profiles
         blocks(i)%index = i
      end do
      inquire(file=batch%journal, exist=exists)
      if (exists .and. batch%scene%batch_restart) then
         call journal_read(batch, blocks, error)
      else
         call journal_start(batch, error)
      end if
   end subroutine batch_prepare

   !> `&batch profiles` naming one NetCDF file of many profiles (a survey):
   !> its catalogue opened once (names, chainage), every profile read from it
   !> by index, and the file hashed once for the journal.
   subroutine netcdf_source(batch, error)
      type(batch_type), intent(inout) :: batch
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: path, fmt
      logical :: exists, is_dir
      integer :: i
      path = batch%scene%batch_profiles
      if (len(path) == 0) return
      if (scan(path, "*?[") > 0) return
      inquire(file=path // "/.", exist=is_dir)
      if (is_dir) return
      inquire(file=path, exist=exists)
      if (.not. exists) return
      call detect_format(path, fmt, error)
      if (allocated(error)) then
         error%message = "&batch profiles = '" // path // "': " // error%message
         return
      end if
      if (fmt /= "netcdf") return
      call open_profile_catalog(path, batch%catalog, error)
      if (allocated(error)) then
         error%message = "&batch profiles = '" // path // "': " // error%message
         return
      end if
      batch%from_netcdf = .true.
      allocate(batch%paths(batch%catalog%n_profiles), batch%names(batch%catalog%n_profiles), &
         & stat=i)
      if (i /= 0) then
         call no_memory(batch%catalog%n_profiles, "profile names", error)
         return
      end if
      do i = 1, batch%catalog%n_profiles
         batch%paths(i)%s = path
         batch%names(i)%s = batch%catalog%names(i)%s
      end do
      batch%has_chainage = batch%catalog%has_chainage
      if (batch%has_chainage) batch%chainage = batch%catalog%chainage
      call sha256_file(path, batch%source_digest)
   end subroutine netcdf_source

   !> The profiles of a batch: a pattern, a directory (all its files), or a
   !> list file. A list names one profile a line, relative to the list, with
   !> an optional second column, the chainage in m (on every line or none);
   !> '#' starts a comment; a path with blanks is quoted ('...' or "...").
   !> Reading is linear in the list's length.
   subroutine expand_profiles(scene, paths, chainage, error)
      type(scene_type), intent(in) :: scene
      type(string_type), allocatable, intent(out) :: paths(:)
      real(wp), allocatable, intent(out) :: chainage(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text, pattern, list, dir, entry
      real(wp), allocatable :: chain(:)
      integer, allocatable :: line_of(:)
      integer :: n, start, last, k, count, need, line_no, n_chain, first_with, first_without
      logical :: is_dir, has
      real(wp) :: c
      if (len(scene%batch_profile_list) > 0) then
         list = scene%batch_profile_list
         call read_text_file(list, text, error)
         if (allocated(error)) then
            error%message = "&batch profile_list: " // error%message
            return
         end if
         ! a UTF-8 byte-order mark (an editor's) is not part of the first path
         if (len(text) >= 3) then
            if (text(1:3) == achar(239) // achar(187) // achar(191)) text = text(4:)
         end if
         ! at most one entry a line: size the arrays once
         count = 1
         do k = 1, len(text)
            if (text(k:k) == achar(10)) count = count + 1
         end do
         allocate(paths(count), chain(count), line_of(count), stat=n)
         if (n /= 0) then
            call no_memory(count, "lines of the profile list", error)
            return
         end if
         dir = dir_name(list)
         n = 0
         n_chain = 0
         first_with = 0
         first_without = 0
         line_no = 0
         start = 1
         do while (start <= len(text))
            k = index(text(start:), achar(10))
            if (k == 0) then
               last = len(text)
            else
               last = start + k - 2
            end if
            line_no = line_no + 1
            call list_entry(text(start:last), entry, has, c, error)
            start = last + 2
            if (allocated(error)) then
               error%message = list // ":" // to_str(line_no) // ": " // error%message
               return
            end if
            if (len(entry) == 0) cycle
            n = n + 1
            paths(n)%s = join_path(dir, entry)
            line_of(n) = line_no
            chain(n) = c
            if (has) then
               n_chain = n_chain + 1
               if (first_with == 0) first_with = line_no
            else if (first_without == 0) then
               first_without = line_no
            end if
         end do
         if (n == 0) then
            call fatal_error(error, "&batch profile_list = '" // list // "': names no profile")
            return
         end if
         if (n_chain > 0 .and. n_chain < n) then
            call fatal_error(error, list // ":" // to_str(first_without) // ": no chainage, " // &
               & "but line " // to_str(first_with) // " gives one: give a chainage (m) on " // &
               & "every line or on none")
            return
         end if
         paths = paths(1:n)
         if (n_chain == n) chainage = chain(1:n)
         return
      end if
      pattern = scene%batch_profiles
      inquire(file=pattern // "/.", exist=is_dir)
      if (is_dir) pattern = pattern // "/*"
      allocate(character(len=65536) :: text)
      need = c_glob(pattern // c_null_char, text, len(text), count)
      if (need > len(text)) then
         deallocate(text)
         allocate(character(len=need) :: text)
         need = c_glob(pattern // c_null_char, text, len(text), count)
      end if
      if (need < 0) then
         call fatal_error(error, "&batch profiles = '" // scene%batch_profiles // &
            & "': cannot read the matching files")
         return
      end if
      if (count == 0) then
         call fatal_error(error, "&batch profiles = '" // scene%batch_profiles // &
            & "': matches no file; check the pattern, or give a directory or &batch " // &
            & "profile_list")
         return
      end if
      allocate(paths(count), stat=n)
      if (n /= 0) then
         call no_memory(count, "profile paths", error)
         return
      end if
      start = 1
      do n = 1, count
         k = index(text(start:need), achar(10))
         paths(n)%s = text(start:start+k-2)
         start = start + k
      end do
   end subroutine expand_profiles

   !> One line of a profile list: the path (empty for a blank or comment
   !> line) and the chainage when a second column gives one.
   subroutine list_entry(line, path, has_chainage, chainage, error)
      character(len=*), intent(in) :: line
      character(len=:), allocatable, intent(out) :: path
      logical, intent(out) :: has_chainage
      real(wp), intent(out) :: chainage
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: blanks = " " // achar(9) // achar(13)
      character(len=:), allocatable :: rest, token
      integer :: p, q, stat
      path = ""
      has_chainage = .false.
      chainage = 0
      p = verify(line, blanks)
      if (p == 0) return
      if (line(p:p) == "#") return
      if (line(p:p) == "'" .or. line(p:p) == '"') then
         q = index(line(p+1:), line(p:p))
         if (q == 0) then
            call fatal_error(error, "the quoted path has no closing " // line(p:p))
            return
         end if
         path = line(p+1:p+q-1)
         rest = line(p+q+1:)
      else
         q = scan(line(p:), blanks // "#")
         if (q == 0) then
            path = line(p:)
            rest = ""
         else
            path = line(p:p+q-2)
            rest = line(p+q-1:)
         end if
      end if
      if (len(path) == 0) then
         call fatal_error(error, "an empty path")
         return
      end if
      ! an optional chainage, then nothing but a comment
      q = index(rest, "#")
      if (q > 0) rest = rest(1:q-1)
      p = verify(rest, blanks)
      if (p == 0) return
      q = scan(rest(p:), blanks)
      if (q == 0) then
         token = rest(p:)
         rest = ""
      else
         token = rest(p:p+q-2)
         rest = rest(p+q-1:)
      end if
      call parse_real(token, chainage, stat)
      if (stat /= 0) then
         call fatal_error(error, "chainage '" // token // "' is not a finite number (m)")
         return
      end if
      if (.not. ieee_is_finite(chainage)) then
         call fatal_error(error, "chainage '" // token // "' must be finite")
         return
      end if
      if (verify(rest, blanks) /= 0) then
         call fatal_error(error, "'" // trim(adjustl(rest)) // "' after the chainage: a line " // &
            & "holds a path and an optional chainage (m)")
         return
      end if
      has_chainage = .true.
   end subroutine list_entry

   !> Profile names: the file names without directory and extension, or,
   !> when two files share a name, their paths below the common directory,
   !> each path read without its "." components and doubled slashes (so
   !> that 'seg/a.txt' and './seg/a.txt' are one profile). A profile given
   !> twice is an error (names index the output), and so is one file given
   !> by two names (symbolic or hard links: the same device and inode).
   subroutine profile_names(scene, paths_given, names, error)
      type(scene_type), intent(in) :: scene
      type(string_type), intent(in) :: paths_given(:)
      type(string_type), allocatable, intent(out) :: names(:)
      type(error_type), allocatable, intent(out) :: error
      type(string_type), allocatable :: paths(:)
      integer :: i, j, n, common
      character(len=:), allocatable :: where
      n = size(paths_given)
      allocate(names(n), paths(n), stat=i)
      if (i /= 0) then
         call no_memory(n, "profile names", error)
         return
      end if
      where = "&batch profiles = '" // scene%batch_profiles // "'"
      if (len(scene%batch_profile_list) > 0) where = "&batch profile_list = '" // &
         & scene%batch_profile_list // "'"
      ! one file by two names (symbolic or hard links) is one profile too
      do i = 1, n
         call file_identity(paths_given(i)%s, names(i)%s)
         if (len(names(i)%s) == 0) names(i)%s = "#" // to_str(i)     ! read later, or refused
      end do
      if (.not. looked(i, j)) return
      if (i > 0) then
         call given_twice(i, j)
         return
      end if
      do i = 1, n
         call tidy_path(paths_given(i)%s, paths(i)%s)
         names(i)%s = base_name(paths(i)%s)
      end do
      if (.not. looked(i, j)) return
      if (i == 0) return
      ! the longest directory prefix every path shares
      common = 0
      if (n > 0) common = index(paths(1)%s, "/", back=.true.)
      do i = 2, n
         do while (common > 0)
            if (len(paths(i)%s) >= common) then
               if (paths(i)%s(1:common) == paths(1)%s(1:common)) exit
            end if
            common = index(paths(1)%s(1:common-1), "/", back=.true.)
         end do
      end do
      do i = 1, n
         names(i)%s = strip_extension(paths(i)%s(common+1:))
      end do
      if (.not. looked(i, j)) return
      if (i == 0) return
      call given_twice(i, j)
   contains
      !> The first two equal entries of names (i = 0: none); .false. when
      !> there was no memory to look (the error set).
      logical function looked(i, j)
         integer, intent(out) :: i, j
         call first_duplicate(names, i, j)
         looked = i >= 0
         if (.not. looked) call no_memory(n, "profile names", error)
      end function looked

      !> The error for entries i and j naming one profile (one name, or one
      !> file by two names).
      subroutine given_twice(i, j)
         integer, intent(in) :: i, j
         where = where // ": profile '" // paths_given(i)%s // "' is given twice (entries " // &
            & to_str(min(i, j)) // " and " // to_str(max(i, j)) // ")"
         if (paths_given(i)%s /= paths_given(j)%s) where = where // ", as '" // &
            & paths_given(min(i, j))%s // "' and '" // paths_given(max(i, j))%s // &
            & "' (one file)"
         call fatal_error(error, where)
      end subroutine given_twice
   end subroutine profile_names

   !> `path` without its "." components ("./a", "a/./b") and doubled
   !> slashes: the same file by its text alone ("a/../b" is left as it is:
   !> a link would make it another file).
   pure subroutine tidy_path(path, tidy)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: tidy
      integer :: k
      tidy = path
      do
         k = index(tidy, "//")
         if (k == 0) exit
         tidy = tidy(1:k) // tidy(k+2:)
      end do
      do
         k = index(tidy, "/./")
         if (k == 0) exit
         tidy = tidy(1:k) // tidy(k+3:)
      end do
      do while (len(tidy) > 2)
         if (tidy(1:2) /= "./") exit
         tidy = tidy(3:)
      end do
   end subroutine tidy_path

   pure function strip_extension(path) result(out)
      character(len=*), intent(in) :: path
      character(len=strip_extension_len(path)) :: out
      character(len=:), allocatable :: deferred_text
      call strip_extension_text(path, deferred_text)
      out = deferred_text
   end function strip_extension

   !> The length of strip_extension's text.
   pure integer function strip_extension_len(path)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: deferred_text
      call strip_extension_text(path, deferred_text)
      strip_extension_len = len(deferred_text)
   end function strip_extension_len

   !> The text of strip_extension, into a deferred-length argument.
   pure subroutine strip_extension_text(path, out)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: out
      integer :: dot, slash
      out = path
      dot = index(path, ".", back=.true.)
      slash = index(path, "/", back=.true.)
      if (dot > slash + 1) out = path(1:dot-1)
   end subroutine strip_extension_text

   !> Indices of two equal names (i = 0 when all differ; i = -1 when memory
   !> is short), as `first_duplicate_label` finds them.
   subroutine first_duplicate(s, i, j)
      type(string_type), intent(in) :: s(:)
      integer, intent(out) :: i, j
      type(profile_label_type), allocatable :: labels(:)
      integer :: k
      i = -1
      j = 0
      allocate(labels(size(s)), stat=k)
      if (k /= 0) return
      do k = 1, size(s)
         labels(k)%s = s(k)%s
      end do
      call first_duplicate_label(labels, i, j)
   end subroutine first_duplicate

   !> SHA-256 of what a journal must agree with besides the profiles'
   !> contents: the version, the scene text, the profile paths and chainages,
   !> the depths and speeds (as exact bit patterns). Built in one buffer of
   !> known length, so linear in the number of profiles.
   function batch_fingerprint(batch) result(hex)
      type(batch_type), intent(in) :: batch
      character(len=digest_len) :: hex
      character(len=:), allocatable :: buf
      integer :: i, n, pos
      n = len(pavefric_version) + len(batch%scene%text) + 64 + 17 * (batch%n_profiles + &
         & batch%n_depths + batch%n_speeds)
      do i = 1, batch%n_profiles
         n = n + len(batch%paths(i)%s) + len(batch%names(i)%s) + 2
      end do
      allocate(character(len=n) :: buf)
      pos = 0
      call put("pavefric " // pavefric_version // achar(10))
      call put(batch%scene%text // achar(0))
      call put(to_str(batch%n_profiles) // " " // to_str(batch%n_depths) // " " // &
         & to_str(batch%n_speeds) // achar(10))
      do i = 1, batch%n_profiles
         call put(batch%paths(i)%s // achar(0))
         if (batch%from_netcdf) call put(batch%names(i)%s // achar(0))
      end do
      if (batch%has_chainage) then
         do i = 1, batch%n_profiles
            call put(bits(batch%chainage(i)))
         end do
      end if
      do i = 1, batch%n_depths
         call put(bits(batch%depths(i)))
      end do
      do i = 1, batch%n_speeds
         call put(bits(batch%speeds(i)))
      end do
      hex = sha256_hex(buf(1:pos))
   contains
      subroutine put(s)
         character(len=*), intent(in) :: s
         buf(pos+1:pos+len(s)) = s
         pos = pos + len(s)
      end subroutine put
      function bits(x) result(s)
         real(wp), intent(in) :: x
         character(len=17) :: s
         write(s, '(z16.16, a)') transfer(x, 0_i8), " "
      end function bits
   end function batch_fingerprint

   !> The journal's first line.
   pure function journal_header(batch) result(line)
      type(batch_type), intent(in) :: batch
      character(len=journal_header_len(batch)) :: line
      character(len=:), allocatable :: deferred_text
      call journal_header_text(batch, deferred_text)
      line = deferred_text
   end function journal_header

   !> The length of journal_header's text.
   pure integer function journal_header_len(batch)
      type(batch_type), intent(in) :: batch
      character(len=:), allocatable :: deferred_text
      call journal_header_text(batch, deferred_text)
      journal_header_len = len(deferred_text)
   end function journal_header_len

   !> The text of journal_header, into a deferred-length argument.
   pure subroutine journal_header_text(batch, line)
      type(batch_type), intent(in) :: batch
      character(len=:), allocatable, intent(out) :: line
      line = journal_magic // " " // journal_version // " " // batch%fingerprint // " " // &
         & to_str(batch%n_profiles) // " " // to_str(batch%n_depths) // " " // &
         & to_str(batch%n_speeds)
   end subroutine journal_header_text

   !> A new journal (replacing any old one).
   subroutine journal_start(batch, error)
      type(batch_type), intent(inout) :: batch
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: fd, err
      fd = c_journal_open(batch%journal // c_null_char, 1_c_int)
      if (fd < 0) then
         call fatal_error(error, "&output file = '" // batch%output // "': cannot write the " // &
            & "journal '" // batch%journal // "' (" // os_message(-fd) // ")", stat_io)
         return
      end if
      err = c_journal_write(fd, journal_header(batch) // achar(10), &
         & int(len(journal_header(batch)) + 1, c_long))
      if (err == 0) then
         err = c_journal_close(fd)
      else
         fd = c_journal_close(fd)
      end if
      if (err /= 0) call journal_error(batch, os_message(err), error)
      batch%journal_cut = .false.
   end subroutine journal_start

   subroutine journal_error(batch, msg, error)
      type(batch_type), intent(in) :: batch
      character(len=*), intent(in) :: msg
      type(error_type), allocatable, intent(out) :: error
      call fatal_error(error, "&output file = '" // batch%output // "': writing the journal '" // &
         & batch%journal // "' failed (" // trim(msg) // "); the batch stops (the profiles " // &
         & "recorded so far are kept: run it again to resume once the disk has room)", stat_io)
   end subroutine journal_error

   !> Profiles recorded in the journal, each line checked (see the module's
   !> comment); a line that fails a check is counted and recomputed.
   subroutine journal_read(batch, blocks, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(inout) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text, header
      character(len=digest_len), allocatable :: current(:)
      logical, allocatable :: hashed(:), changed(:)
      type(block_type) :: blk
      integer :: start, k, i, last
      logical :: ok
      call read_text_file(batch%journal, text, error)
      if (allocated(error)) then
         error%stat = stat_io
         return
      end if
      k = index(text, achar(10))
      if (k == 0) then                    ! empty, or a header cut short: start again
         call journal_start(batch, error)
         return
      end if
      header = text(1:k-1)
      if (header /= journal_header(batch)) then
         if (index(header, journal_magic // " ") == 1 .and. &
               & index(header, journal_magic // " " // journal_version // " ") /= 1) then
            call fatal_error(error, "&batch restart: the journal '" // batch%journal // &
               & "' was written by another version of pavefric; delete it, or set " // &
               & "&batch restart = .false. to start again")
         else
            call fatal_error(error, "&batch restart: the journal '" // batch%journal // &
               & "' belongs to another batch (its inputs changed); delete it, or set " // &
               & "&batch restart = .false. to start again")
         end if
         return
      end if
      allocate(current(size(blocks)), hashed(size(blocks)), changed(size(blocks)), stat=i)
      if (i /= 0) then
         call no_memory(size(blocks), "journal entries", error)
         return
      end if
      hashed = .false.
      changed = .false.
      start = k + 1
      do while (start <= len(text))
         k = index(text(start:), achar(10))
         if (k == 0) then                 ! no newline: cut short by a kill
            batch%journal_cut = .true.
            exit
         end if
         last = start + k - 2
         if (last >= start) then
            call parse_line(batch, text(start:last), blk, ok)
            if (.not. ok) then
               batch%journal_damaged = batch%journal_damaged + 1
            else
               i = blk%index
               if (.not. hashed(i)) then
                  if (batch%from_netcdf) then
                     current(i) = batch%source_digest      ! hashed once in setup
                  else
                     call sha256_file(batch%paths(i)%s, current(i))
                  end if
                  hashed(i) = .true.
               end if
               if (blk%digest /= current(i)) then
                  changed(i) = .true.
               else
                  call move_alloc_block(blk, blocks(i))
                  changed(i) = .false.
               end if
            end if
         end if
         start = last + 2
      end do
      batch%journal_taken = count([(blocks(i)%status /= 0, i = 1, size(blocks))])
      batch%journal_changed = count(changed .and. [(blocks(i)%status == 0, i = 1, size(blocks))])
   end subroutine journal_read

   subroutine move_alloc_block(from, to)
      type(block_type), intent(inout) :: from
      type(block_type), intent(inout) :: to
      to%index = from%index
      to%status = from%status
      to%digest = from%digest
      to%has_texture = from%has_texture
      to%mpd = from%mpd
      to%rms_height = from%rms_height
      to%rms_slope = from%rms_slope
      to%points_read = from%points_read
      to%trimmed_start = from%trimmed_start
      to%trimmed_end = from%trimmed_end
      to%dropouts = from%dropouts
      to%spikes = from%spikes
      to%points_used = from%points_used
      to%resampled = from%resampled
      to%filtered = from%filtered
      to%dx_in = from%dx_in
      to%dx = from%dx
      to%viscous = from%viscous
      to%bearing = from%bearing
      to%n_warnings = from%n_warnings
      call move_alloc(from%mu, to%mu)
      call move_alloc(from%wet, to%wet)
      call move_alloc(from%hydroplaning, to%hydroplaning)
      call move_alloc(from%residual, to%residual)
      call move_alloc(from%n_clamped, to%n_clamped)
      call move_alloc(from%mu_hysteresis, to%mu_hysteresis)
      call move_alloc(from%mu_adhesion, to%mu_adhesion)
      call move_alloc(from%mu_error, to%mu_error)
      call move_alloc(from%estimate_eps, to%estimate_eps)
      call move_alloc(from%eps_used, to%eps_used)
      call move_alloc(from%message, to%message)
   end subroutine move_alloc_block

   !> One journal line: `P <checksum> <digest> <values...> ;<message>`, the
   !> checksum the SHA-256 of everything after it.
   subroutine journal_line(batch, blk, line)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blk
      character(len=:), allocatable, intent(out) :: line
      character(len=:), allocatable :: body, message
      real(wp), allocatable :: values(:)
      integer, parameter :: w = 26
      integer :: k, nv
      nv = block_values(batch)
      allocate(values(nv))
      call block_pack(batch, blk, values)
      message = ""
      if (allocated(blk%message)) call escape_newlines(blk%message, message)
      allocate(character(len=digest_len + w * nv + 2 + len(message)) :: body)
      body(1:digest_len) = blk%digest
      do k = 1, nv
         write(body(digest_len+(k-1)*w+1:digest_len+k*w), '(1x, es25.17e3)') values(k)
      end do
      body(digest_len+nv*w+1:) = " ;" // message
      line = "P " // sha256_hex(body) // " " // body
   end subroutine journal_line

   !> Parse and check one journal line; `ok` false when any check fails.
   subroutine parse_line(batch, line, blk, ok)
      type(batch_type), intent(in) :: batch
      character(len=*), intent(in) :: line
      type(block_type), intent(out) :: blk
      logical, intent(out) :: ok
      integer, parameter :: b0 = 2 + digest_len + 2   ! where the body starts
      real(wp), allocatable :: values(:)
      integer :: nv, k, pos, e, stat
      ok = .false.
      if (len(line) < b0 + digest_len + 1) return
      if (line(1:2) /= "P " .or. line(b0-1:b0-1) /= " ") return
      if (sha256_hex(line(b0:)) /= line(3:2+digest_len)) return
      blk%digest = line(b0:b0+digest_len-1)
      if (blk%digest /= no_digest .and. verify(blk%digest, "0123456789abcdef") /= 0) return
      nv = block_values(batch)
      allocate(values(nv))
      pos = b0 + digest_len
      do k = 1, nv
         e = verify(line(pos:), " ")
         if (e == 0) return
         pos = pos + e - 1
         e = index(line(pos:), " ")
         if (e <= 1) return
         call parse_real(line(pos:pos+e-2), values(k), stat)
         if (stat /= 0) return
         if (.not. ieee_is_finite(values(k))) return
         pos = pos + e - 1
      end do
      if (len(line) < pos + 1) return
      if (line(pos:pos+1) /= " ;") return
      call block_allocate(batch, blk)
      call block_unpack(batch, values, blk, ok)
      if (.not. ok) return
      call unescape_newlines(line(pos+2:), blk%message)
   end subroutine parse_line

   !> Append a finished profile to the journal: one line in one checked
   !> write(2), so a kill loses at most the line being written (recomputed on
   !> restart) and a full disk stops the batch.
   subroutine journal_append(batch, blk, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(in) :: blk
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: line
      integer(c_int) :: fd, err
      if (.not. batch%journal_open) then
         fd = c_journal_open(batch%journal // c_null_char, 0_c_int)
         if (fd < 0) then
            call journal_error(batch, os_message(-fd), error)
            return
         end if
         batch%journal_unit = fd
         batch%journal_open = .true.
      end if
      call journal_line(batch, blk, line)
      line = line // achar(10)
      if (batch%journal_cut) line = achar(10) // line   ! end the line a kill cut short
      err = c_journal_write(int(batch%journal_unit, c_int), line, int(len(line), c_long))
      if (err /= 0) then
         call journal_error(batch, os_message(err), error)
         return
      end if
      batch%journal_cut = .false.
   end subroutine journal_append

   !> Close the journal if it is open.
   subroutine journal_close(batch, error)
      type(batch_type), intent(inout) :: batch
      type(error_type), allocatable, intent(out), optional :: error
      integer(c_int) :: err
      err = 0
      if (batch%journal_open) err = c_journal_close(int(batch%journal_unit, c_int))
      batch%journal_open = .false.
      if (err /= 0 .and. present(error)) call journal_error(batch, os_message(err), error)
   end subroutine journal_close

   !> A text on one journal line: a backslash doubled, a line feed as `\n`,
   !> a carriage return as a blank (the inverse: unescape_newlines). A
   !> subroutine, not a function: gfortran keeps the length of a
   !> deferred-length function result in static storage (not thread-safe).
   pure subroutine escape_newlines(s, t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable, intent(out) :: t
      integer :: i
      t = ""
      do i = 1, len(s)
         select case (iachar(s(i:i)))
         case (92)
            t = t // achar(92) // achar(92)
         case (10)
            t = t // achar(92) // "n"
         case (13)
            t = t // " "
         case default
            t = t // s(i:i)
         end select
      end do
   end subroutine escape_newlines

   pure subroutine unescape_newlines(s, t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable, intent(out) :: t
      integer :: i
      t = ""
      i = 1
      do while (i <= len(s))
         if (s(i:i) == achar(92) .and. i < len(s)) then
            if (s(i+1:i+1) == "n") then
               t = t // achar(10)
            else
               t = t // s(i+1:i+1)
            end if
            i = i + 2
         else
            t = t // s(i:i)
            i = i + 1
         end if
      end do
   end subroutine unescape_newlines

   !> An estimate of profile i's cost for scheduling: its file's size in
   !> bytes (0 when unknown).
   function profile_cost(batch, i) result(cost)
      type(batch_type), intent(in) :: batch
      integer, intent(in) :: i
      integer(i8) :: cost
      integer :: ios
      cost = 0
      if (batch%from_netcdf) then
         cost = 8 * batch%catalog%count(i)
         return
      end if
      inquire(file=batch%paths(i)%s, size=cost, iostat=ios)
      if (ios /= 0 .or. cost < 0) cost = 0
   end function profile_cost

   !> Compute profile i at every depth and speed. Never fails: a profile that
   !> cannot be read or run, or whose result is not finite, is returned with
   !> status_failed and the reason.
   subroutine batch_compute(batch, i, blk)
      type(batch_type), intent(inout) :: batch
      integer, intent(in) :: i
      type(block_type), intent(out) :: blk
      type(scene_type) :: scene
      type(clean_profile_type) :: clean
      type(raw_profile_type) :: raw
      type(sim_result_type) :: res
      type(texture_type) :: tex
      type(error_type), allocatable :: error, texture_error
      character(len=:), allocatable :: warnings
      logical :: has_texture
      integer :: d, s
      blk%index = i
      blk%message = ""
      call block_allocate(batch, blk)
      scene = batch%scene
      scene%profile_file = batch%paths(i)%s
      if (batch%from_netcdf) then
         ! one file of many profiles: its digest, and the profile by index
         blk%digest = batch%source_digest
         call read_catalog_profile(batch%catalog, i, unit_factor(scene%height_unit), raw, error)
         if (.not. allocated(error)) call load_scene_profile(scene, clean, error, raw_in=raw)
      else
         ! the digest first: an edit after it is found on resume
         call sha256_file(batch%paths(i)%s, blk%digest)
         call load_scene_profile(scene, clean, error)
      end if
      if (.not. allocated(error)) then
         blk%points_read = clean%report%points_read
         blk%trimmed_start = clean%report%trimmed_start
         blk%trimmed_end = clean%report%trimmed_end
         blk%dropouts = clean%report%dropouts
         blk%spikes = clean%report%spikes
         blk%points_used = clean%report%points_out
         blk%resampled = clean%report%resampled
         blk%filtered = clean%report%filtered
         blk%dx_in = clean%report%dx_in
         blk%dx = clean%dx
         ! the texture first: the wet model's regime warnings compare depth and MPD
         call texture_metrics(clean%z, clean%dx, scene%closed, 0.1_wp, .true., tex, &
            & texture_error, dropout_fraction=clean%dropout_fraction, spike=clean%spike)
         has_texture = .not. allocated(texture_error)
         if (has_texture) has_texture = ieee_is_finite(tex%mpd) .and. &
            & ieee_is_finite(tex%rms_height) .and. ieee_is_finite(tex%rms_slope)
         ! the warnings a single scene of this profile records, at each depth
         warnings = ""
         call texture_warning(clean%z, warnings)
         do d = 1, batch%n_depths
            scene%model%depth = batch%depths(d)
            call simulate(scene%model, clean%z, clean%dx, scene%closed, batch%speeds, .false., &
               & res, error)
            if (allocated(error)) exit
            blk%mu(:, d) = res%mu
            blk%mu_hysteresis(:, d) = res%mu_hysteresis
            blk%mu_adhesion(:, d) = res%mu_adhesion
            if (allocated(res%mu_error)) then
               blk%mu_error(:, d) = res%mu_error
               blk%estimate_eps(:, d) = real(res%estimate_elements_per_sample, wp)
            end if
            blk%eps_used(:, d) = real(res%elements_per_sample_used, wp)
            blk%wet(:, d) = res%wet_fraction
            blk%hydroplaning(:, d) = res%hydroplaning_fraction
            blk%residual(:, d) = res%max_balance_residual
            blk%n_clamped(:, d) = real(res%n_clamped, wp)
            blk%viscous = blk%viscous .or. any(res%viscous_memory_ran)
            ! a film ran: one that carried load or one that changed the friction
            blk%bearing = blk%bearing .or. any(res%bearing_ran) .or. any(res%friction_film_ran)
            if (len(res%warnings) > 0) call add_warnings(warnings, res%warnings)
            call result_warnings(scene, res, has_texture, tex%mpd, " and water depth " // &
               & to_str(batch%depths(d)) // " m", warnings)
            do s = 1, batch%n_speeds
               if (.not. (ieee_is_finite(res%mu(s)) .and. ieee_is_finite(res%wet_fraction(s)) &
                     & .and. ieee_is_finite(res%hydroplaning_fraction(s)) .and. &
                     & ieee_is_finite(res%max_balance_residual(s)))) then
                  call fatal_error(error, "'" // batch%paths(i)%s // "': the result is not " // &
                     & "finite (mu = " // to_str(res%mu(s)) // ") at water depth " // &
                     & to_str(batch%depths(d)) // " m and " // to_str(batch%speeds(s)) // " km/h")
                  exit
               end if
            end do
            if (allocated(error)) exit
         end do
      end if
      if (allocated(error)) then
         blk%status = status_failed
         blk%message = printable_utf8(error%message)
         call block_clear(blk)
         return
      end if
      blk%status = status_computed
      call record_warnings(warnings, blk)
      blk%has_texture = has_texture
      if (blk%has_texture) then
         blk%mpd = tex%mpd
         blk%rms_height = tex%rms_height
         blk%rms_slope = tex%rms_slope
      end if
   end subroutine batch_compute

   !> A profile's warnings (lines) into its block: distinct lines, printable
   !> UTF-8, counted; the first `max_block_warnings` kept as text, so that a
   !> survey whose every profile warns at every depth and speed does not make
   !> the output's warning_message column huge.
   subroutine record_warnings(warnings, blk)
      character(len=*), intent(in) :: warnings
      type(block_type), intent(inout) :: blk
      type(string_type), allocatable :: seen(:)
      character(len=:), allocatable :: line
      integer :: start, k, n, j
      logical :: new
      allocate(seen(0))
      blk%n_warnings = 0
      blk%message = ""
      start = 1
      n = len(warnings)
      do while (start <= n)
         k = index(warnings(start:), achar(10))
         if (k == 0) k = n - start + 2
         line = printable_utf8(warnings(start:start+k-2))
         start = start + k
         if (len_trim(line) == 0) cycle
         new = .true.
         do j = 1, size(seen)
            if (seen(j)%s == line) new = .false.
         end do
         if (.not. new) cycle
         call remember(line)
         blk%n_warnings = blk%n_warnings + 1
         if (blk%n_warnings > max_block_warnings) cycle
         if (len(blk%message) > 0) blk%message = blk%message // achar(10)
         blk%message = blk%message // line
      end do
      if (blk%n_warnings > max_block_warnings) blk%message = blk%message // achar(10) // &
         & "... " // to_str(blk%n_warnings - max_block_warnings) // " more warnings (n_warnings)"
   contains
      !> `seen` grown by one (not `seen = [seen, string_type(line)]`: an array
      !> constructor of these leaks their text in gfortran 12).
      subroutine remember(text)
         character(len=*), intent(in) :: text
         type(string_type), allocatable :: grown(:)
         integer :: m
         m = size(seen)
         allocate(grown(m + 1))
         grown(1:m) = seen
         grown(m + 1)%s = text
         call move_alloc(grown, seen)
      end subroutine remember
   end subroutine record_warnings

   !> (files) Refuse a batch output or journal that is not a regular file, or
   !> that is the same file as an input: the scene, the profile list or any
   !> profile (symbolic links, '..' and hard links seen through). Runs before
   !> the journal is (re)started, on every rank alike.
   subroutine check_batch_outputs(path, output_override, batch, error)
      character(len=*), intent(in) :: path, output_override
      type(batch_type), intent(in) :: batch
      type(error_type), allocatable, intent(out) :: error
      type(output_guard_type) :: guard(2)
      character(len=:), allocatable :: what
      integer :: k, i
      what = "&output file"
      if (len_trim(output_override) > 0) what = "-o"
      call check_output_path(batch%output, what, guard(1), error)
      if (allocated(error)) return
      call check_output_path(batch%journal, "the journal of " // what, guard(2), error)
      if (allocated(error)) return
      do k = 1, 2
         call guard(k)%check_input(path, "the scene file", error)
         if (allocated(error)) return
         call guard(k)%check_input(batch%scene%batch_profile_list, &
            & "the profile list (&batch profile_list)", error)
         if (allocated(error)) return
         do i = 1, batch%n_profiles
            call guard(k)%check_input(batch%paths(i)%s, "profile " // to_str(i) // &
               & " of the batch", error)
            if (allocated(error)) return
         end do
      end do
      ! an input is named as such first; any other file there must be an
      ! earlier pavefric output (or empty), and the journal's path a journal
      call check_replaceable(batch%output, what, error)
      if (allocated(error)) return
      call check_journal_replaceable(batch%journal, "the journal of " // what, error)
   end subroutine check_batch_outputs

   !> (files) The journal's path may hold nothing, an empty file or a
   !> journal pavefric wrote (its first bytes journal_magic): never a
   !> symbolic link (the journal would be written through it, into the file
   !> it names, and the link removed at the end) nor a file of the user's,
   !> which restart = .false. would truncate and the batch's end delete (an
   !> attack of 2026-12-07: both happened, and restart = .true. called such
   !> a file a journal of another batch, advising restart = .false.).
   subroutine check_journal_replaceable(journal, what, error)
      character(len=*), intent(in) :: journal, what
      type(error_type), allocatable, intent(out) :: error
      character(len=len(journal_magic)) :: head
      character(len=*), parameter :: advice = "; pavefric replaces only its own journals: " // &
         & "remove or rename it, or choose another output"
      integer :: u, stat
      integer(i8) :: size
      logical :: exists
      if (is_symlink(journal)) then
         call fatal_error(error, setting(what, journal) // ": is a symbolic link; the " // &
            & "journal must be a regular file pavefric writes itself (it would be written " // &
            & "through the link into the file it names)" // advice, stat_input)
         return
      end if
      inquire(file=journal, exist=exists, size=size)
      if (.not. exists .or. size == 0) return
      head = ""
      open(newunit=u, file=journal, access="stream", form="unformatted", action="read", &
         & status="old", iostat=stat)
      if (stat == 0) then
         if (size >= len(head)) read(u, iostat=stat) head
         close(u)
      end if
      if (head == journal_magic) return
      call fatal_error(error, setting(what, journal) // ": exists and is not a pavefric " // &
         & "batch journal (it does not start '" // journal_magic // "')" // advice, stat_input)
   end subroutine check_journal_replaceable

   !> The error of a batch whose `n` somethings do not fit in memory.
   pure subroutine no_memory(n, what, error)
      integer, intent(in) :: n
      character(len=*), intent(in) :: what
      type(error_type), allocatable, intent(out) :: error
      call fatal_error(error, "&batch: not enough memory for " // to_str(n) // " " // what // &
         & "; split the batch into parts (python -m pavefric merge joins their outputs, " // &
         & "docs/cluster.md)", stat_memory)
   end subroutine no_memory

end module pavefric_batch
