!> Running a scene file end to end: namelist, profile, model, NetCDF output.
!> Shared by the program and the Python layer, so both give the same numbers.
module pavefric_run
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_profile, only: profile_type, read_profile_text, unit_factor
   use pavefric_simulate, only: sim_result_type, simulate
   use pavefric_netcdf, only: write_results, output_metadata_type, temporary_name
   use pavefric_fsys, only: make_directory, dir_name, remove_file
   use pavefric_texture, only: texture_metrics
   implicit none
   private

   public :: run_scene, load_scene_profile, ctm_dx

   !> Spacing of a Circular Track Meter profile (m), the default dx.
   real(wp), parameter :: ctm_dx = 0.87e-3_wp

contains

   !> Read the scene's profile and settle its spacing.
   subroutine load_scene_profile(scene, z, dx, error)
      type(scene_type), intent(in) :: scene
      real(wp), allocatable, intent(out) :: z(:)
      real(wp), intent(out) :: dx
      type(error_type), allocatable, intent(out) :: error
      type(profile_type) :: prof
      call read_profile_text(scene%profile_file, unit_factor(scene%height_unit), prof, error)
      if (allocated(error)) return
      if (prof%has_x) then
         if (scene%dx > 0.0_wp .and. abs(scene%dx - prof%dx) > 0.01_wp * prof%dx) then
            call fatal_error(error, "&surface dx = " // to_str(scene%dx) // ": disagrees with " // &
               & "the spacing " // to_str(prof%dx) // " m of the distances in '" // &
               & scene%profile_file // "'")
            return
         end if
         dx = prof%dx
      else if (scene%dx > 0.0_wp) then
         dx = scene%dx
      else
         dx = ctm_dx
      end if
      call move_alloc(prof%z, z)
   end subroutine load_scene_profile

   !> Run the scene in `path`; write its NetCDF output to `output_override`
   !> when that is not empty, else to the namelist's &output file, else to
   !> outputs/<scene name>.nc. `command` goes into the history attribute.
   subroutine run_scene(path, output_override, command, out_path, res, error)
      character(len=*), intent(in) :: path, output_override, command
      character(len=:), allocatable, intent(out) :: out_path
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      type(scene_type) :: scene
      type(output_metadata_type) :: meta
      type(error_type), allocatable :: texture_error
      real(wp), allocatable :: z(:)
      real(wp) :: dx

      call read_scene(path, scene, error)
      if (allocated(error)) return
      if (len_trim(output_override) > 0) then
         out_path = trim(output_override)
      else if (len(scene%output_file) > 0) then
         out_path = scene%output_file
      else
         if (.not. make_directory("outputs")) then
            call fatal_error(error, "&output file: the default directory 'outputs' cannot " // &
               & "be created here; set &output file or use -o")
            return
         end if
         out_path = "outputs/" // scene%name // ".nc"
      end if
      ! Find an unwritable output before spending time on the model.
      call check_writable(out_path, error)
      if (allocated(error)) return

      call load_scene_profile(scene, z, dx, error)
      if (allocated(error)) return
      call simulate(scene%model, z, dx, scene%closed, scene%speeds_kmh, scene%series, res, error)
      if (allocated(error)) return

      meta%title = "pavefric friction-speed curve of scene " // scene%name
      meta%history = timestamp() // " pavefric " // pavefric_version // ": " // command
      meta%input_namelist = scene%text
      meta%profile_file = scene%profile_file
      meta%dx = dx
      meta%profile_points = size(z)
      meta%closed = scene%closed
      ! Texture metrics: reported when the profile holds a whole segment.
      call texture_metrics(z, dx, scene%closed, 0.1_wp, .true., meta%texture, texture_error)
      meta%has_texture = .not. allocated(texture_error)
      if (allocated(texture_error)) meta%texture_note = texture_error%message
      call write_results(out_path, res, meta, error)
   end subroutine run_scene

   !> Error unless a file can be created beside `path`.
   subroutine check_writable(path, error)
      character(len=*), intent(in) :: path
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      character(len=512) :: msg
      integer :: unit, ios
      logical :: ok
      tmp = temporary_name(path)
      open(newunit=unit, file=tmp, status="replace", action="write", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "&output file = '" // path // "': cannot write in directory '" // &
            & dir_name(path) // "' (" // trim(msg) // ")")
         return
      end if
      close(unit, status="delete")
      ok = remove_file(tmp)
   end subroutine check_writable

   !> Local time as ISO 8601.
   function timestamp() result(text)
      character(len=:), allocatable :: text
      character(len=8) :: d
      character(len=10) :: t
      character(len=5) :: zone
      call date_and_time(d, t, zone)
      text = d(1:4) // "-" // d(5:6) // "-" // d(7:8) // "T" // t(1:2) // ":" // t(3:4) // ":" // &
         & t(5:6) // zone(1:3) // ":" // zone(4:5)
   end function timestamp

end module pavefric_run
