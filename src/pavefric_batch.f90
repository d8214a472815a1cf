!> Batch runs: many profiles, several water depths and speeds, one NetCDF.
!>
!> Finished profiles are recorded in a plain-text journal beside the output
!> (one flushed line a profile, at full precision), so a run that is killed
!> resumes where it stopped; the NetCDF file is built from the journal at the
!> end, indexed by profile, so the result does not depend on the order the
!> profiles finished in, on the number of MPI ranks, or on restarts.
module pavefric_batch
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use pavefric_kinds, only: wp, i8
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_scene, only: scene_type, read_scene, read_text_file
   use pavefric_run, only: load_scene_profile
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_simulate, only: sim_result_type, simulate
   use pavefric_texture, only: texture_type, texture_metrics
   use pavefric_fsys, only: dir_name, base_name, join_path, remove_file, make_directory
   use pavefric_fsys, only: output_guard_type, check_output_path   ! (files)
   use pavefric_batch_types, only: batch_type, block_type, string_type, block_pack, &
      & block_unpack, block_values
   implicit none
   private

   public :: batch_type, block_type, string_type, batch_prepare, batch_compute, &
      & journal_append, journal_close, block_pack, block_unpack, block_values, batch_output_path

   interface
      function c_glob(pattern, out, outlen, count) bind(C, name="pavefric_glob") result(need)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: pattern(*)
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int), value :: outlen
         integer(c_int), intent(out) :: count
         integer(c_int) :: need
      end function c_glob
   end interface

contains

   !> Where a batch writes: the override, the scene's &output file, or
   !> outputs/<scene name>.nc.
   function batch_output_path(scene, output_override) result(out)
      type(scene_type), intent(in) :: scene
      character(len=*), intent(in) :: output_override
      character(len=:), allocatable :: out
      logical :: ok
      if (len_trim(output_override) > 0) then
         out = trim(output_override)
      else if (len(scene%output_file) > 0) then
         out = scene%output_file
      else
         ok = make_directory("outputs")
         out = "outputs/" // scene%name // ".nc"
      end if
   end function batch_output_path

   !> Read a batch scene, expand its profiles, and read the journal of an
   !> earlier, interrupted run: `blocks(i)%status` > 0 for profiles done.
   subroutine batch_prepare(path, output_override, batch, blocks, error, read_only)
      character(len=*), intent(in) :: path, output_override
      type(batch_type), intent(out) :: batch
      type(block_type), allocatable, intent(out) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      !> Only read the journal, never (re)start it (MPI ranks > 0).
      logical, intent(in), optional :: read_only
      integer :: i
      logical :: exists, ro

      call read_scene(path, batch%scene, error)
      if (allocated(error)) return
      if (.not. batch%scene%is_batch) then
         call fatal_error(error, "scene '" // path // "' has no &batch group")
         return
      end if
      call expand_profiles(batch%scene, batch%paths, error)
      if (allocated(error)) return
      batch%n_profiles = size(batch%paths)
      allocate(batch%names(batch%n_profiles))
      do i = 1, batch%n_profiles
         batch%names(i)%s = base_name(batch%paths(i)%s)
      end do
      if (allocated(batch%scene%batch_depths)) then
         batch%depths = batch%scene%batch_depths
      else
         batch%depths = [batch%scene%model%depth]
      end if
      batch%speeds = batch%scene%speeds_kmh
      batch%n_depths = size(batch%depths)
      batch%n_speeds = size(batch%speeds)
      batch%output = batch_output_path(batch%scene, output_override)
      batch%journal = batch%output // ".journal"
      call check_batch_outputs(path, output_override, batch, error); if (allocated(error)) return
      batch%fingerprint = fingerprint(batch)

      allocate(blocks(batch%n_profiles))
      do i = 1, batch%n_profiles
         blocks(i)%index = i
      end do
      ro = .false.
      if (present(read_only)) ro = read_only
      inquire(file=batch%journal, exist=exists)
      if (ro) then
         if (exists) call journal_read(batch, blocks, error)
      else if (exists .and. batch%scene%batch_restart) then
         call journal_read(batch, blocks, error)
      else
         call journal_start(batch, error)
      end if
   end subroutine batch_prepare

   !> The profiles of a batch: a pattern, a directory (all its files), or a
   !> list file (one path a line, '#' comments, relative to the list).
   subroutine expand_profiles(scene, paths, error)
      type(scene_type), intent(in) :: scene
      type(string_type), allocatable, intent(out) :: paths(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text, pattern, line
      integer :: n, start, k, count, need, pos
      logical :: is_dir
      if (len(scene%batch_profile_list) > 0) then
         call read_text_file(scene%batch_profile_list, text, error)
         if (allocated(error)) then
            error%message = "&batch profile_list: " // error%message
            return
         end if
         allocate(paths(0))
         start = 1
         do while (start <= len(text))
            k = index(text(start:), achar(10))
            if (k == 0) then
               line = text(start:)
               start = len(text) + 1
            else
               line = text(start:start+k-2)
               start = start + k
            end if
            pos = index(line, "#")
            if (pos > 0) line = line(1:pos-1)
            line = trim(adjustl(replace_newlines(line)))
            if (len(line) == 0) cycle
            paths = [paths, string_type(join_path(dir_name(scene%batch_profile_list), line))]
         end do
         if (size(paths) == 0) call fatal_error(error, "&batch profile_list = '" // &
            & scene%batch_profile_list // "': names no profile")
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
            & "': matches no file")
         return
      end if
      allocate(paths(count))
      start = 1
      do n = 1, count
         k = index(text(start:need), achar(10))
         paths(n)%s = text(start:start+k-2)
         start = start + k
      end do
   end subroutine expand_profiles


   !> Adler-32 of the scene text, profile paths, depths and speeds, in hex:
   !> a journal only resumes the batch it was written for.
   function fingerprint(batch) result(hex)
      type(batch_type), intent(in) :: batch
      character(len=:), allocatable :: hex
      integer(i8) :: a, b
      integer :: i
      character(len=16) :: buf
      a = 1
      b = 0
      call add(batch%scene%text)
      do i = 1, batch%n_profiles
         call add(batch%paths(i)%s // achar(10))
      end do
      call add(to_str(batch%n_depths) // to_str(batch%n_speeds))
      do i = 1, batch%n_depths
         call add(to_str(batch%depths(i)))
      end do
      write(buf, '(z8.8)') b * 65536_i8 + a
      hex = trim(buf)
   contains
      subroutine add(s)
         character(len=*), intent(in) :: s
         integer :: j
         do j = 1, len(s)
            a = mod(a + iachar(s(j:j)), 65521_i8)
            b = mod(b + a, 65521_i8)
         end do
      end subroutine add
   end function fingerprint

   !> A new journal (replacing any old one).
   subroutine journal_start(batch, error)
      type(batch_type), intent(in) :: batch
      type(error_type), allocatable, intent(out) :: error
      integer :: unit, ios
      character(len=512) :: msg
      open(newunit=unit, file=batch%journal, status="replace", action="write", iostat=ios, &
         & iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&output file = '" // batch%output // "': cannot write the " // &
            & "journal '" // batch%journal // "' (" // trim(msg) // ")")
         return
      end if
      write(unit, '(a)') "pavefric-journal 1 " // batch%fingerprint // " " // &
         & to_str(batch%n_profiles) // " " // to_str(batch%n_depths) // " " // &
         & to_str(batch%n_speeds)
      close(unit)
   end subroutine journal_start

   !> Profiles recorded in the journal. A line cut short by a kill is ignored.
   subroutine journal_read(batch, blocks, error)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(inout) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text, line, header, message
      real(wp), allocatable :: values(:)
      integer :: start, k, ios, i, nv
      call read_text_file(batch%journal, text, error)
      if (allocated(error)) return
      k = index(text, achar(10))
      if (k == 0) then
         call journal_start(batch, error)
         return
      end if
      header = text(1:k-1)
      if (header /= "pavefric-journal 1 " // batch%fingerprint // " " // &
            & to_str(batch%n_profiles) // " " // to_str(batch%n_depths) // " " // &
            & to_str(batch%n_speeds)) then
         call fatal_error(error, "&batch restart: the journal '" // batch%journal // &
            & "' belongs to another batch (its inputs changed); delete it, or set " // &
            & "&batch restart = .false. to start again")
         return
      end if
      nv = block_values(batch)
      allocate(values(nv))
      message = ""
      start = k + 1
      do while (start <= len(text))
         k = index(text(start:), achar(10))
         if (k == 0) exit                       ! no newline: cut short, ignore
         line = text(start:start+k-2)
         start = start + k
         if (len(line) < 3) cycle
         if (line(1:2) == "E ") then
            message = line(index(line(3:), " ") + 3:)
         else if (line(1:2) == "P ") then
            read(line(3:), *, iostat=ios) values
            if (ios /= 0) cycle
            i = nint(values(1))
            if (i < 1 .or. i > size(blocks)) cycle
            call block_unpack(batch, values, blocks(i))
            if (blocks(i)%status == 2) blocks(i)%message = message
            message = ""
         end if
      end do
   end subroutine journal_read

   !> Append a finished profile to the journal: one line, flushed at once, so
   !> a kill loses at most the line being written (ignored on restart).
   subroutine journal_append(batch, blk, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(in) :: blk
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: values(:)
      integer :: unit, ios
      character(len=512) :: msg
      allocate(values(block_values(batch)))
      call block_pack(batch, blk, values)
      if (.not. batch%journal_open) then
         open(newunit=unit, file=batch%journal, status="old", position="append", &
            & action="write", iostat=ios, iomsg=msg)
         if (ios /= 0) then
            call fatal_error(error, "cannot append to the journal '" // batch%journal // &
               & "' (" // trim(msg) // ")")
            return
         end if
         batch%journal_unit = unit
         batch%journal_open = .true.
      end if
      unit = batch%journal_unit
      if (blk%status == 2) write(unit, '(a)') "E " // to_str(blk%index) // " " // &
         & replace_newlines(blk%message)
      write(unit, '(a, *(1x, es25.17e3))') "P", values
      flush(unit)
   end subroutine journal_append

   !> Close the journal if it is open.
   subroutine journal_close(batch)
      type(batch_type), intent(inout) :: batch
      if (batch%journal_open) close(batch%journal_unit)
      batch%journal_open = .false.
   end subroutine journal_close

   !> Line breaks (LF, CR) as blanks.
   pure function replace_newlines(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i
      t = s
      do i = 1, len(t)
         if (t(i:i) == achar(10) .or. t(i:i) == achar(13)) t(i:i) = " "
      end do
   end function replace_newlines

   !> Compute profile i at every depth and speed. Never fails: a profile that
   !> cannot be read or run is returned with status 2 and the reason.
   subroutine batch_compute(batch, i, blk)
      type(batch_type), intent(in) :: batch
      integer, intent(in) :: i
      type(block_type), intent(out) :: blk
      type(scene_type) :: scene
      type(clean_profile_type) :: clean
      type(sim_result_type) :: res
      type(texture_type) :: tex
      type(error_type), allocatable :: error, texture_error
      integer :: d
      blk%index = i
      blk%message = ""
      allocate(blk%mu(batch%n_speeds, batch%n_depths), blk%wet(batch%n_speeds, batch%n_depths), &
         & blk%hydroplaning(batch%n_speeds, batch%n_depths), &
         & blk%residual(batch%n_speeds, batch%n_depths), &
         & blk%n_clamped(batch%n_speeds, batch%n_depths))
      blk%mu = 0; blk%wet = 0; blk%hydroplaning = 0; blk%residual = 0; blk%n_clamped = 0
      scene = batch%scene
      scene%profile_file = batch%paths(i)%s
      call load_scene_profile(scene, clean, error)
      if (.not. allocated(error)) then
         do d = 1, batch%n_depths
            scene%model%depth = batch%depths(d)
            call simulate(scene%model, clean%z, clean%dx, scene%closed, batch%speeds, .false., &
               & res, error)
            if (allocated(error)) exit
            blk%mu(:, d) = res%mu
            blk%wet(:, d) = res%wet_fraction
            blk%hydroplaning(:, d) = res%hydroplaning_fraction
            blk%residual(:, d) = res%max_balance_residual
            blk%n_clamped(:, d) = real(res%n_clamped, wp)
            blk%viscous = blk%viscous .or. any(res%viscous_memory_ran)
            blk%bearing = blk%bearing .or. any(res%bearing_ran)
         end do
      end if
      if (allocated(error)) then
         blk%status = 2
         blk%message = error%message
         blk%mu = 0; blk%wet = 0; blk%hydroplaning = 0; blk%residual = 0; blk%n_clamped = 0
         return
      end if
      blk%status = 1
      call texture_metrics(clean%z, clean%dx, scene%closed, 0.1_wp, .true., tex, texture_error, &
         & dropout_fraction=clean%dropout_fraction, spike=clean%spike)
      blk%has_texture = .not. allocated(texture_error)
      if (blk%has_texture) then
         blk%mpd = tex%mpd
         blk%rms_height = tex%rms_height
         blk%rms_slope = tex%rms_slope
      end if
   end subroutine batch_compute

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
   end subroutine check_batch_outputs

end module pavefric_batch
