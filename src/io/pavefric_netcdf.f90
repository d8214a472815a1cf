!> NetCDF-4 output of a scene's results, with CF-1.10 metadata, and the
!> checked writer type every NetCDF output goes through. Every
!> netCDF call goes through `check`, which adds context to nf90_strerror.
!> The file is built in memory, written under a temporary name when it is
!> complete and renamed on success, so a failed run leaves no half-written
!> output and HDF5 never sees a failing disk (src/io/pavefric_ncmem.c); the
!> temporary name is on the list a fatal signal cleans up (pavefric_fsys).
module pavefric_netcdf
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use netcdf
   use pavefric_kinds, only: wp, i8, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_io, stat_memory, stat_input
   use pavefric_results, only: sim_result_type
   use pavefric_outputs, only: output_metadata_type, output_var_type, output_table, &
      & output_present, output_values, n_outputs, out_double, out_int64, out_int, out_flag, &
      & dim_speed, scalar_table, n_scalar_outputs
   use pavefric_model, only: param_spec_type, param_set_type, parameter_table, kind_real, &
      & kind_integer, kind_logical, kind_text, kind_real_list
   use pavefric_fsys, only: rename_file, remove_file, register_temporary, &
      & release_temporary, test_pause, output_guard_type, check_output_path, &
      & remove_stale_temporaries, setting, temporary_path
   use pavefric_format, only: to_str
   use pavefric_output_spec, only: short_long_name
   implicit none
   private

   public :: write_results, temporary_name, commit_temporary, check_replaceable
   public :: check_text_replaceable, check_png_replaceable, put_parameter_attributes

   !> What check_replaceable and check_text_replaceable advise when they
   !> refuse a file.
   character(len=*), parameter :: advice = "; pavefric replaces only its own outputs: " // &
      & "remove or rename the file, or choose another path"
   public :: nc_writer_type

   !> A NetCDF file being written and the first error met: every call goes
   !> through `check`, which adds context to nf90_strerror; after an error the
   !> remaining calls do nothing.
   !> A text too long for an attribute, kept for its variable until the
   !> definitions end (long_text_limit).
   type :: pending_text_type
      integer :: varid = -1
      character(len=:), allocatable :: text
   end type pending_text_type

   !> Texts longer than this (bytes) are written as a character variable of
   !> the attribute's name, the attribute then saying where they are: HDF5
   !> keeps attributes in an object header of at most 64 KiB, so a scene of
   !> 200 KB (long comments, a long list of speeds) failed at the end of a
   !> run. pavefric.open_dataset restores such attributes.
   integer, parameter, public :: long_text_limit = 16384
   character(len=*), parameter, public :: long_text_note = "in the variable of this name: "

   type :: nc_writer_type
      integer :: ncid = -1
      character(len=:), allocatable :: path
      type(error_type), allocatable :: error
      !> Long texts to write as variables once the definitions end.
      type(pending_text_type), allocatable :: pending(:)
   contains
      procedure :: create => writer_create
      procedure :: check => writer_check
      procedure :: def => writer_def
      procedure, private :: gatt_text, gatt_int, gatt_real
      generic :: gatt => gatt_text, gatt_int, gatt_real
      procedure :: close => writer_close
   end type nc_writer_type

   interface
      function c_nc_create_mem(path, ncid) bind(C, name="pavefric_nc_create_mem") result(status)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: ncid
         integer(c_int) :: status
      end function c_nc_create_mem
      subroutine c_nc_close_to_file(ncid, path, nc_status, errno) &
            & bind(C, name="pavefric_nc_close_to_file")
         import :: c_int, c_char
         integer(c_int), value :: ncid
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: nc_status, errno
      end subroutine c_nc_close_to_file
      function c_strerror(errno, out, outlen) bind(C, name="pavefric_strerror") result(n)
         import :: c_int, c_char
         integer(c_int), value :: errno, outlen
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int) :: n
      end function c_strerror
   end interface

contains

   !> Start the NetCDF-4 file that `close` will write to `path`. The file is
   !> built in memory and written by pavefric at `close`, so that HDF5 never
   !> meets a failing disk (see src/io/pavefric_ncmem.c): a full disk is then an
   !> ordinary write error, and the process stays sound.
   subroutine writer_create(w, path)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: path
      integer(c_int) :: status, ncid
      w%path = path
      status = c_nc_create_mem(path // c_null_char, ncid)
      if (status /= nf90_noerr) then
         w%ncid = -1
         call fatal_error(w%error, "&output file: cannot create '" // path // "' (" // &
            & trim(nf90_strerror(int(status))) // ")", stat_of(int(status)))
         return
      end if
      w%ncid = int(ncid)
   end subroutine writer_create

   subroutine writer_check(w, status, what)
      class(nc_writer_type), intent(inout) :: w
      integer, intent(in) :: status
      character(len=*), intent(in) :: what
      if (allocated(w%error)) return
      if (status /= nf90_noerr) call fatal_error(w%error, "&output file: writing " // what // &
         & " to '" // w%path // "' failed (" // trim(nf90_strerror(status)) // ")", &
         & stat_of(status))
   end subroutine writer_check

   !> The status kind of a failed netCDF call: out of memory, or a file that
   !> could not be written (disk full, permissions, file-size limit).
   pure function stat_of(status) result(stat)
      integer, intent(in) :: status
      integer :: stat
      stat = stat_io
      if (status == nf90_enomem) stat = stat_memory
   end function stat_of

   !> Define a variable with its units (none if empty) and long name: a
   !> description longer than a name gives its first words as long_name
   !> (xarray's axis label: `short`, else, absent or empty, short_long_name's)
   !> and is whole in comment.
   subroutine writer_def(w, name, xtype, dims, units, long_name, varid, short)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name, units, long_name
      integer, intent(in) :: xtype, dims(:)
      integer, intent(out) :: varid
      character(len=*), intent(in), optional :: short
      character(len=:), allocatable :: label
      varid = -1
      if (allocated(w%error)) return
      call w%check(nf90_def_var(w%ncid, name, xtype, dims, varid), "variable " // name)
      if (len(units) > 0) call w%check(nf90_put_att(w%ncid, varid, "units", units), &
         & name // " units")
      label = ""
      if (present(short)) label = short
      if (len(label) == 0) call short_long_name(long_name, label)
      call w%check(nf90_put_att(w%ncid, varid, "long_name", label), name // " long_name")
      if (label /= long_name) call w%check(nf90_put_att(w%ncid, varid, "comment", long_name), &
         & name // " comment")
   end subroutine writer_def

   !> A global text attribute; a text longer than long_text_limit becomes a
   !> character variable of the same name (the attribute says so).
   subroutine gatt_text(w, name, text)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name, text
      type(pending_text_type), allocatable :: grown(:)
      integer :: dimid, varid, n
      if (len(text) <= long_text_limit) then
         call w%check(nf90_put_att(w%ncid, nf90_global, name, text), "attribute " // name)
         return
      end if
      if (allocated(w%error)) return
      call w%check(nf90_def_dim(w%ncid, name // "_strlen", len(text), dimid), name // " length")
      call w%check(nf90_def_var(w%ncid, name, nf90_char, [dimid], varid), "variable " // name)
      call w%check(nf90_put_att(w%ncid, varid, "long_name", "the global attribute " // name // &
         & ", too long for an attribute"), name // " long_name")
      call w%check(nf90_put_att(w%ncid, nf90_global, name, long_text_note // &
         & to_str(len(text)) // " characters"), "attribute " // name)
      if (allocated(w%error)) return
      n = 0
      if (allocated(w%pending)) n = size(w%pending)
      allocate(grown(n + 1))
      if (n > 0) grown(1:n) = w%pending
      grown(n + 1)%varid = varid
      grown(n + 1)%text = text
      call move_alloc(grown, w%pending)
   end subroutine gatt_text

   !> Write the long texts gatt_text kept (after the definitions end).
   subroutine writer_put_pending(w)
      class(nc_writer_type), intent(inout) :: w
      integer :: k
      if (.not. allocated(w%pending)) return
      do k = 1, size(w%pending)
         call w%check(nf90_put_var(w%ncid, w%pending(k)%varid, w%pending(k)%text), &
            & "a long attribute")
      end do
      deallocate(w%pending)
   end subroutine writer_put_pending

   subroutine gatt_int(w, name, value)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name
      integer, intent(in) :: value
      call w%check(nf90_put_att(w%ncid, nf90_global, name, value), "attribute " // name)
   end subroutine gatt_int

   subroutine gatt_real(w, name, value)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value
      call w%check(nf90_put_att(w%ncid, nf90_global, name, value), "attribute " // name)
   end subroutine gatt_real

   !> Write the file to its path and close it; `error` receives the first
   !> error met, if any. After an error the file is abandoned (nf90_abort)
   !> and nothing is written; the caller removes what a failed write left.
   subroutine writer_close(w, error)
      class(nc_writer_type), intent(inout) :: w
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: status, errno, n
      character(len=256) :: text
      if (w%ncid >= 0) then
         if (.not. allocated(w%error)) call writer_put_pending(w)
         if (allocated(w%error)) then
            status = nf90_abort(w%ncid)
         else
            call c_nc_close_to_file(int(w%ncid, c_int), w%path // c_null_char, status, errno)
            if (status /= nf90_noerr) then
               call fatal_error(w%error, "&output file: closing '" // w%path // "' failed (" // &
                  & trim(nf90_strerror(int(status))) // ")", stat_of(int(status)))
            else if (errno /= 0) then
               text = ""
               n = c_strerror(errno, text, len(text, c_int))
               call fatal_error(w%error, "&output file: writing '" // w%path // "' failed (" // &
                  & text(1:n) // ")", stat_io)
            end if
         end if
         w%ncid = -1
      end if
      if (allocated(w%error)) call move_alloc(w%error, error)
   end subroutine writer_close

   !> The temporary name a final path is first written under,
   !> `<path>.tmp<PID>.pavefric` (the suffix tells pavefric's temporaries
   !> from a user's file of a like name, which the sweep below never
   !> touches). The name goes on the list of temporary files a fatal signal
   !> removes (in the program); `commit_temporary` takes it off. Temporaries
   !> of `path` left by writers killed outright (SIGKILL: no handler ran) are
   !> removed first.
   subroutine temporary_name(path, tmp)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: tmp
      integer :: removed
      removed = remove_stale_temporaries(path)
      call temporary_path(path, tmp)
      call register_temporary(tmp)
   end subroutine temporary_name

   !> Write `res` to `path` (NetCDF-4), via a temporary file and a rename.
   subroutine write_results(path, res, meta, error)
      character(len=*), intent(in) :: path
      type(sim_result_type), intent(in) :: res
      type(output_metadata_type), intent(in) :: meta
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      type(output_guard_type) :: guard
      ! results of no run (a run that failed leaves its intent(out) result
      ! empty; the Fortran API's write_results then died of SIGSEGV, an
      ! attack of 2026-12-07): an error, as the C API's
      if (.not. allocated(res%mu)) then
         call fatal_error(error, "&output file = '" // path // "': no results to write (run " // &
            & "first; the last run failed)", stat_input)
         return
      end if
      ! The rule of every writer (program, Python, C and Fortran API alike):
      ! never onto a FIFO, a device or a directory, never over a file the
      ! results came from; then a temporary in the same directory, renamed.
      call check_output_path(path, "&output file", guard, error)
      if (allocated(error)) return
      if (allocated(meta%scene_file)) then
         call guard%check_input(meta%scene_file, "the scene file", error)
         if (allocated(error)) return
      end if
      if (allocated(meta%profile_file)) then
         call guard%check_input(meta%profile_file, "the profile (&surface profile_file)", error)
         if (allocated(error)) return
      end if
      call check_replaceable(path, "&output file", error)
      if (allocated(error)) return
      call temporary_name(path, tmp)
      call write_file(tmp, res, meta, error)
      call commit_temporary(tmp, path, error)
   end subroutine write_results

   !> Refuse to replace an existing file at `path` that pavefric did not
   !> write: a non-empty file is replaced only if it is a NetCDF file whose
   !> global attribute `source` names pavefric (an earlier run's output); an
   !> empty file (from touch or mktemp) holds nothing to lose. `what` names
   !> the setting that gave the path ("-o", "&output file"). The user's notes,
   !> a profile of another run or another tool's NetCDF named by mistake stay
   !> as they are. Opens the file with netCDF: callers that may run on
   !> several threads hold the files lock (pavefric_files_lock.c).
   subroutine check_replaceable(path, what, error, replaces)
      character(len=*), intent(in) :: path, what
      type(error_type), allocatable, intent(out) :: error
      !> What the writer writes, and so what it may replace: 'results' (the
      !> default: the program's, the batch's and merge's outputs, source
      !> 'pavefric <version>') or 'profiles' (pavefric.write_profiles's
      !> surveys, source 'pavefric.write_profiles'). A writer replaces only
      !> a file of its own kind: a survey is an input, which a results
      !> writer must not destroy (an attack of 2026-12-07: `-o` replaced a
      !> survey whose source began 'pavefric').
      character(len=*), intent(in), optional :: replaces
      character(len=*), parameter :: survey = "pavefric.write_profiles"
      integer :: ncid, status, n, xtype
      integer(i8) :: size
      logical :: exists, profiles
      character(len=:), allocatable :: source
      profiles = .false.
      if (present(replaces)) profiles = replaces == "profiles"
      inquire(file=path, exist=exists, size=size)
      if (.not. exists .or. size == 0) return
      status = nf90_open(path, nf90_nowrite, ncid)
      if (status /= nf90_noerr) then
         call fatal_error(error, setting(what, path) // ": exists and is not a NetCDF file (" // &
            & trim(nf90_strerror(status)) // ")" // advice, stat_input)
         return
      end if
      status = nf90_inquire_attribute(ncid, nf90_global, "source", xtype=xtype, len=n)
      if (status == nf90_noerr .and. xtype == nf90_char .and. n > 0 .and. n < 4096) then
         allocate(character(len=n) :: source)
         if (nf90_get_att(ncid, nf90_global, "source", source) /= nf90_noerr) source = ""
      else
         source = ""
      end if
      status = nf90_close(ncid)
      if (profiles) then
         if (source == survey) return
         if (index(source, "pavefric ") == 1) then
            call fatal_error(error, setting(what, path) // ": exists and is a pavefric " // &
               & "results file (source '" // source // "'), not a profile file " // survey // &
               & " wrote" // advice, stat_input)
            return
         end if
      else
         if (index(source, "pavefric ") == 1) return
         if (source == survey) then
            call fatal_error(error, setting(what, path) // ": exists and is a profile file " // &
               & "(source '" // survey // "': measured profiles, an input, not an output " // &
               & "of a run)" // advice, stat_input)
            return
         end if
      end if
      if (len(source) == 0) then
         source = "it has no global attribute source"
      else
         source = "its global attribute source is '" // source // "', not 'pavefric ...'"
      end if
      call fatal_error(error, setting(what, path) // ": exists and is a NetCDF file " // &
         & "pavefric did not write (" // source // ")" // advice, stat_input)
   end subroutine check_replaceable

   !> check_replaceable for a writer of text (a namelist, a CSV, JSON):
   !> an existing non-empty file at `path` is replaced only if it begins with
   !> `signature`, the bytes that writer puts first in every file it writes
   !> (`python -m pavefric prony -o` a namelist beginning "! Prony series
   !> fitted by `python -m pavefric prony", `calibrate -o` JSON beginning
   !> with its "written_by" member). A user's scene, data or notes named by
   !> mistake stay as they are.
   subroutine check_text_replaceable(path, what, signature, error)
      character(len=*), intent(in) :: path, what, signature
      type(error_type), allocatable, intent(out) :: error
      character(len=len(signature)) :: head, shown
      integer(i8) :: size
      integer :: unit, status, k
      logical :: exists
      inquire(file=path, exist=exists, size=size)
      if (.not. exists .or. size == 0) return
      head = ""
      if (size >= len(signature)) then
         open(newunit=unit, file=path, access="stream", form="unformatted", action="read", &
            & status="old", iostat=status)
         if (status /= 0) then
            call fatal_error(error, setting(what, path) // ": exists and cannot be read " // &
               & "to tell whether pavefric wrote it" // advice, stat_input)
            return
         end if
         read(unit, iostat=status) head
         close(unit)
         if (status /= 0) head = ""
      end if
      if (head == signature) return
      ! the signature on one line (JSON's spans two)
      shown = signature
      do k = 1, len(shown)
         if (shown(k:k) == achar(10)) shown(k:k) = " "
      end do
      call fatal_error(error, setting(what, path) // ": exists and is not a file this " // &
         & "command wrote (it does not begin with '" // shown // "')" // advice, stat_input)
   end subroutine check_text_replaceable

   !> check_replaceable for a figure (Python's plots, matplotlib's PNG): an
   !> existing non-empty file at `path` is replaced only if it is a PNG
   !> whose text chunk "Software", before its image data, begins with
   !> "pavefric" (what pavefric's plots write there). Any other file, a
   !> figure of the user's included, is refused.
   subroutine check_png_replaceable(path, what, error)
      character(len=*), intent(in) :: path, what
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: software
      integer(i8) :: size
      logical :: exists
      inquire(file=path, exist=exists, size=size)
      if (.not. exists .or. size == 0) return
      call png_software(path, software)
      if (index(software, "pavefric") == 1) return
      call fatal_error(error, setting(what, path) // ": exists and is not a figure " // &
         & "pavefric drew (a PNG whose text 'Software' begins with 'pavefric')" // advice, &
         & stat_input)
   end subroutine check_png_replaceable

   !> The text of a PNG file's "Software" chunk (tEXt, or iTXt uncompressed)
   !> found before its image data in its first 64 KiB; "" when the file
   !> cannot be read, is not a PNG or has none. The chunks are walked by
   !> their lengths, each checked against what was read, so a truncated or
   !> forged file ends the walk. (A subroutine: a deferred-length function
   !> result costs a static length per call site, which threads share.)
   subroutine png_software(path, text)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      character(len=8), parameter :: magic = achar(137) // "PNG" // achar(13) // achar(10) // &
         & achar(26) // achar(10)
      character(len=*), parameter :: key = "Software" // achar(0)
      integer, parameter :: most = 65536
      character(len=:), allocatable :: buf
      integer(i8) :: size
      integer :: unit, status, n, at, length, j, k, data_end
      character(len=4) :: kind
      text = ""
      inquire(file=path, size=size)
      if (size < 8) return
      n = int(min(size, int(most, i8)))
      allocate(character(len=n) :: buf)
      open(newunit=unit, file=path, access="stream", form="unformatted", action="read", &
         & status="old", iostat=status)
      if (status /= 0) return
      read(unit, iostat=status) buf
      close(unit)
      if (status /= 0 .or. buf(1:8) /= magic) return
      at = 9
      do while (at + 7 <= n)
         length = 0
         do k = 0, 3
            length = 256 * length + ichar(buf(at+k:at+k))
            if (length > most) return                ! (a chunk longer than what is read)
         end do
         kind = buf(at+4:at+7)
         if (kind == "IDAT" .or. kind == "IEND") return
         data_end = at + 7 + length
         if (data_end > n) return
         if ((kind == "tEXt" .or. kind == "iTXt") .and. length >= len(key)) then
            if (buf(at+8:at+7+len(key)) == key) then
               k = at + 8 + len(key)
               if (kind == "iTXt") then
                  ! compression flag (0: none), method, language tag \0,
                  ! translated keyword \0, then the text
                  if (k + 1 > data_end) return
                  if (ichar(buf(k:k)) /= 0) return
                  k = k + 2
                  j = index(buf(k:data_end), achar(0))        ! the language tag
                  if (j == 0) return
                  k = k + j
                  j = index(buf(k:data_end), achar(0))        ! the translated keyword
                  if (j == 0) return
                  k = k + j
               end if
               text = buf(k:data_end)
               return
            end if
         end if
         at = data_end + 5                           ! past the chunk's CRC
      end do
   end subroutine png_software

   !> Rename a finished temporary file onto `path`; remove it when writing
   !> failed (`error` allocated on entry) or the rename fails. An existing
   !> `path` is replaced only by a complete file. The temporary name leaves
   !> the list a fatal signal cleans up.
   subroutine commit_temporary(tmp, path, error)
      character(len=*), intent(in) :: tmp, path
      type(error_type), allocatable, intent(inout) :: error
      logical :: ok
      integer :: k
      if (.not. allocated(error)) then
         call test_pause("commit")
         if (.not. rename_file(tmp, path)) call fatal_error(error, "&output file = '" // path // &
            & "': cannot rename the finished temporary file onto it", stat_io)
      end if
      if (allocated(error)) then
         ok = remove_file(tmp)
         ! the user knows the output by its name, not by the temporary one
         k = index(error%message, "'" // tmp // "'")
         if (k > 0) error%message = error%message(1:k) // path // &
            & error%message(k + len(tmp) + 1:)
      end if
      call release_temporary(tmp)
   end subroutine commit_temporary

   !> The scene file: dimension speed_kmh (a coordinate in km/h, so that
   !> ds.sel(speed_kmh=60) works) with the speed in m/s as an auxiliary
   !> coordinate; every result variable of pavefric_outputs that the run
   !> produced; texture metrics; the parameters used (defaults included).
   subroutine write_file(path, res, meta, error)
      character(len=*), intent(in) :: path
      type(sim_result_type), intent(in) :: res
      type(output_metadata_type), intent(in) :: meta
      type(error_type), allocatable, intent(out) :: error
      type(nc_writer_type) :: w
      type(output_var_type) :: table(n_outputs), sc(n_scalar_outputs)
      integer :: d_speed, d_pos, stat, k, ns, np
      integer :: v_speed, v_kmh, v_pos, v_mpd, v_rh, v_rs, ids(n_outputs), v_f60, v_sp, v_spm
      real(wp), allocatable :: values(:)
      logical :: series

      table = output_table()
      series = allocated(res%mu_inst)
      ns = size(res%mu)
      np = 0
      if (series) np = res%n_positions
      call w%create(path)
      if (allocated(w%error)) goto 99

      call w%check(nf90_def_dim(w%ncid, "speed_kmh", ns, d_speed), "dimension speed_kmh")
      if (series) call w%check(nf90_def_dim(w%ncid, "position", np, d_pos), "dimension position")
      if (allocated(w%error)) goto 99
      call w%def("speed_kmh", nf90_double, [d_speed], "km h-1", "sliding speed of the pad", &
         & v_kmh)
      call w%def("speed", nf90_double, [d_speed], "m s-1", "sliding speed of the pad", v_speed)
      if (series) call w%def("position", nf90_double, [d_pos], "m", &
         & "distance slid from the first averaged position", v_pos)
      ids = -1
      do k = 1, n_outputs
         if (.not. output_present(res, k, table)) cycle
         associate(v => table(k))
            ! long_name: a few words (xarray's axis label); the whole
            ! description in comment where it says more
            if (v%dims == dim_speed) then
               call w%def(v%name, xtype(v%type), [d_speed], v%units, v%long_name, ids(k), &
                  & v%short)
            else
               call w%def(v%name, xtype(v%type), [d_pos, d_speed], v%units, v%long_name, &
                  & ids(k), v%short)
            end if
            call w%check(nf90_put_att(w%ncid, ids(k), "coordinates", "speed"), v%name)
            if (v%type == out_flag) then
               call w%check(nf90_put_att(w%ncid, ids(k), "flag_values", [0_1, 1_1]), v%name)
               call w%check(nf90_put_att(w%ncid, ids(k), "flag_meanings", "no yes"), v%name)
            end if
         end associate
      end do
      ! the scalars, each as the scalar table declares it
      sc = scalar_table()
      if (meta%ifi%has_f60) call def_scalar(sc(4), v_f60)
      if (meta%ifi%has_sp) call def_scalar(sc(5), v_sp)
      if (meta%ifi%has_speed_constant) call def_scalar(sc(6), v_spm)
      if (meta%has_texture) then
         call def_scalar(sc(1), v_mpd)
         call w%check(nf90_put_att(w%ncid, v_mpd, "n_segments", meta%texture%n_segments), "mpd")
         call w%check(nf90_put_att(w%ncid, v_mpd, "n_valid_segments", meta%texture%n_valid), "mpd")
         call def_scalar(sc(2), v_rh)
         call def_scalar(sc(3), v_rs)
      end if
      if (allocated(w%error)) goto 99

      call w%gatt("Conventions", "CF-1.10")
      call w%gatt("title", meta%title)
      call w%gatt("institution", "pavefric (open-source pavement friction model)")
      call w%gatt("source", "pavefric " // pavefric_version)
      call w%gatt("pavefric_version", pavefric_version)
      call w%gatt("references", "Kane, Do, Cerezo, Rado & Khelifi (2017), Contribution to " // &
         & "pavement friction modelling: an introduction of the wetting effect, " // &
         & "Int. J. Pavement Eng., doi:10.1080/10298436.2017.1369776")
      call w%gatt("history", meta%history)
      call w%gatt("comment", "Friction of a Dynamic Friction Tester pad on a texture profile; " // &
         & "parameters in the attribute 'parameters' (a namelist) and param_<group>_<name>")
      call w%gatt("effects", res%effects)
      call w%gatt("warnings", meta%warnings)
      call w%gatt("profile_file", meta%profile_file)
      call w%gatt("input_namelist", meta%input_namelist)
      call put_parameters(w, meta)
      if (allocated(meta%texture_note)) call w%gatt("texture_note", meta%texture_note)
      if (allocated(meta%preprocessing)) then
         call w%gatt("preprocessing", meta%preprocessing)
         call w%gatt("preprocess_format", meta%preprocess%format)
         call w%gatt("preprocess_points_read", meta%preprocess%points_read)
         call w%gatt("preprocess_trimmed_start", meta%preprocess%trimmed_start)
         call w%gatt("preprocess_trimmed_end", meta%preprocess%trimmed_end)
         call w%gatt("preprocess_dropouts", meta%preprocess%dropouts)
         call w%gatt("preprocess_spikes", meta%preprocess%spikes)
         call w%gatt("preprocess_points_out", meta%preprocess%points_out)
         call w%gatt("preprocess_resampled", merge(1, 0, meta%preprocess%resampled))
         call w%gatt("preprocess_filtered", merge(1, 0, meta%preprocess%filtered))
         call w%gatt("preprocess_dx_in", meta%preprocess%dx_in)
      end if
      call w%gatt("profile_points", meta%profile_points)
      call w%gatt("profile_dx", meta%dx)
      call w%gatt("profile_closed", merge(1, 0, meta%closed))
      call w%gatt("pad_elements", res%n_elements)
      call w%gatt("pad_element_spacing", res%element_spacing)
      call w%gatt("averaged_positions", res%n_positions)
      call w%gatt("spinup_positions", res%n_spinup)
      call w%gatt("estimated_element_steps", real(res%estimate%total_element_steps, wp))
      call w%gatt("estimated_memory_bytes", res%estimate%bytes)
      call w%gatt("estimated_seconds", res%estimate%seconds)
      if (allocated(w%error)) goto 99
      call w%check(nf90_enddef(w%ncid), "end of definitions")
      if (allocated(w%error)) goto 99

      call w%check(nf90_put_var(w%ncid, v_kmh, res%speed_kmh), "speed_kmh")
      call w%check(nf90_put_var(w%ncid, v_speed, res%speed), "speed")
      if (series) call w%check(nf90_put_var(w%ncid, v_pos, res%position), "position")
      allocate(values(max(ns, ns * np)), stat=stat)
      if (stat /= 0) then
         call fatal_error(w%error, "&output file: not enough memory to write '" // path // "'", &
            & stat_memory)
         goto 99
      end if
      do k = 1, n_outputs
         if (ids(k) < 0) cycle
         call output_values(res, k, values, table)
         associate(v => table(k))
            select case (v%type)
            case (out_double)
               if (v%dims == dim_speed) then
                  call w%check(nf90_put_var(w%ncid, ids(k), values(1:ns)), v%name)
               else
                  call w%check(nf90_put_var(w%ncid, ids(k), reshape(values(1:np*ns), [np, ns])), &
                     & v%name)
               end if
            case (out_int64)
               call w%check(nf90_put_var(w%ncid, ids(k), nint(values(1:ns), i8)), v%name)
            case (out_int)
               call w%check(nf90_put_var(w%ncid, ids(k), reshape(nint(values(1:np*ns)), &
                  & [np, ns])), v%name)
            case (out_flag)
               call w%check(nf90_put_var(w%ncid, ids(k), nint(values(1:ns))), v%name)
            end select
         end associate
      end do
      if (meta%ifi%has_f60) call w%check(nf90_put_var(w%ncid, v_f60, meta%ifi%f60), "ifi_f60")
      if (meta%ifi%has_sp) call w%check(nf90_put_var(w%ncid, v_sp, meta%ifi%sp_texture), &
         & "ifi_sp")
      if (meta%ifi%has_speed_constant) call w%check(nf90_put_var(w%ncid, v_spm, &
         & meta%ifi%speed_constant), "speed_constant")
      if (meta%has_texture) then
         call w%check(nf90_put_var(w%ncid, v_mpd, meta%texture%mpd), "mpd")
         call w%check(nf90_put_var(w%ncid, v_rh, meta%texture%rms_height), "rms_height")
         call w%check(nf90_put_var(w%ncid, v_rs, meta%texture%rms_slope), "rms_slope")
      end if
99    continue
      call w%close(error)
   contains
      !> A scalar as the scalar table declares it.
      subroutine def_scalar(v, varid)
         type(output_var_type), intent(in) :: v
         integer, intent(out) :: varid
         call w%def(v%name, nf90_double, [integer ::], v%units, v%long_name, varid, v%short)
      end subroutine def_scalar
   end subroutine write_file

   !> The NetCDF type of an output type.
   pure integer function xtype(type)
      integer, intent(in) :: type
      select case (type)
      case (out_int64)
         xtype = nf90_int64
      case (out_int)
         xtype = nf90_int
      case (out_flag)
         xtype = nf90_byte
      case default
         xtype = nf90_double
      end select
   end function xtype

   !> A scene's parameters used (put_parameter_attributes).
   subroutine put_parameters(w, meta)
      type(nc_writer_type), intent(inout) :: w
      type(output_metadata_type), intent(in) :: meta
      if (.not. meta%has_parameters) return
      call put_parameter_attributes(w, meta%parameters, meta%parameters_text)
   end subroutine put_parameters

   !> The parameters used: `text`, the namelist of `set`, as `parameters`, and
   !> one typed attribute each (param_<group>_<name>) of the groups `text`
   !> holds (a scene's leaves &batch out), defaults included; optional ones
   !> not set are left out. A scene's file and a batch's alike.
   subroutine put_parameter_attributes(w, set, text)
      type(nc_writer_type), intent(inout) :: w
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: text
      type(param_spec_type), allocatable :: specs(:)
      character(len=:), allocatable :: name
      integer :: k
      call w%gatt("parameters", text)
      specs = parameter_table()
      do k = 1, size(specs)
         associate(v => set%v(k))
            if (.not. v%set) cycle
            if (index(text, "&" // specs(k)%group // achar(10)) == 0) cycle
            name = "param_" // specs(k)%group // "_" // specs(k)%name
            select case (specs(k)%kind)
            case (kind_real)
               call w%gatt(name, v%r)
            case (kind_integer)
               call w%gatt(name, v%i)
            case (kind_logical)
               call w%gatt(name, merge(1, 0, v%b))
            case (kind_text)
               call w%gatt(name, v%t)
            case (kind_real_list)
               ! a long list (speeds) stays in `parameters` alone: HDF5 attributes
               ! share an object header of 64 KiB
               if (8 * size(v%list) <= long_text_limit) &
                  & call w%check(nf90_put_att(w%ncid, nf90_global, name, v%list), name)
            end select
         end associate
      end do
   end subroutine put_parameter_attributes

end module pavefric_netcdf
