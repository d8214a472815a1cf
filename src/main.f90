!> The pavefric program: `pavefric SCENE.nml [-o OUT.nc]`. No Python needed.
program pavefric_main
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use pavefric, only: pavefric_version, error_type, sim_result_type, run_scene, effects_text
   use pavefric_format, only: to_str
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_batch_mpi, only: run_batch_program, parallel_init, parallel_finalize, is_root
   use pavefric_fsys, only: install_signal_cleanup
   implicit none
   type(sim_result_type) :: res
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   logical :: finished
   integer :: max_profiles, ios
   character(len=:), allocatable :: scene_path, out_override, out_path, arg, command, warnings
   integer :: i, nargs, j

   max_profiles = 0
   nargs = command_argument_count()
   scene_path = ""
   out_override = ""
   command = "pavefric"
   i = 1
   do while (i <= nargs)
      call get_arg(i, arg)
      command = command // " " // arg
      select case (arg)
      case ("-h", "--help")
         call usage(output_unit)
         stop
      case ("-V", "--version")
         write(output_unit, '(a)') "pavefric " // pavefric_version
         stop
      case ("--max-profiles")
         if (i == nargs) call fail("option " // arg // " needs a number")
         i = i + 1
         call get_arg(i, arg)
         command = command // " " // arg
         read(arg, *, iostat=ios) max_profiles
         if (ios /= 0 .or. max_profiles < 0) call fail("--max-profiles '" // arg // &
            & "': not a count of profiles")
      case ("-o", "--output")
         if (i == nargs) call fail("option " // arg // " needs a file name")
         i = i + 1
         call get_arg(i, out_override)
         command = command // " " // out_override
      case default
         if (arg(1:1) == "-" .and. len(arg) > 1) call fail("unknown option '" // arg // &
            & "' (see pavefric --help)")
         if (len(scene_path) > 0) call fail("more than one scene file given ('" // scene_path // &
            & "', '" // arg // "')")
         scene_path = arg
      end select
      i = i + 1
   end do
   if (len(scene_path) == 0) then
      call usage(error_unit)
      stop 2, quiet=.true.
   end if

   call parallel_init()
   call install_signal_cleanup()   ! temp outputs removed on SIGTERM/SIGINT/SIGHUP (files)
   call read_scene(scene_path, scene, error)
   if (allocated(error)) call fail(error%message)
   if (scene%is_batch) then
      call run_batch_program(scene_path, out_override, command, max_profiles, out_path, &
         & finished, error)
      if (allocated(error)) call fail(error%message)
      if (is_root()) then
         if (finished) then
            write(output_unit, '(a)') "pavefric " // pavefric_version // ": batch " // &
               & scene_path // " -> " // out_path
         else
            write(error_unit, '(a)') "pavefric: batch stopped before the end " // &
               & "(--max-profiles); run it again to resume from its journal"
         end if
      end if
      call parallel_finalize()
      if (.not. finished) stop 3, quiet=.true.
   else if (.not. is_root()) then
      call parallel_finalize()       ! a single scene runs on rank 0 only
   else
      call run_scene(scene_path, out_override, command, out_path, res, error, warnings=warnings)
      if (allocated(error)) call fail(error%message)
      call parallel_finalize()
      call report_scene()
   end if

contains

   subroutine report_scene()

   call print_warnings(warnings)
   write(output_unit, '(a)') "pavefric " // pavefric_version // ": " // scene_path // " -> " // &
      & out_path
   write(output_unit, '(a, i0, a, i0, a)') "  pad elements: ", res%n_elements, &
      & ", averaged positions: ", res%n_positions, ", effects: " // effects_text(res)
   write(output_unit, '(a)') "  speed_kmh          mu   wet_fraction  hydroplaning"
   do j = 1, size(res%mu)
      write(output_unit, '(f11.3, f12.5, f15.4, f14.4)') res%speed_kmh(j), res%mu(j), &
         & res%wet_fraction(j), res%hydroplaning_fraction(j)
   end do
   end subroutine report_scene

   !> Each warning line on stderr (they are also in the output's `warnings`).
   subroutine print_warnings(text)
      character(len=*), intent(in) :: text
      integer :: start, k
      start = 1
      do while (start <= len(text))
         k = index(text(start:), achar(10))
         if (k == 0) k = len(text) - start + 2
         write(error_unit, '(a)') "pavefric: warning: " // text(start:start+k-2)
         start = start + k
      end do
      flush(error_unit)
   end subroutine print_warnings

   subroutine get_arg(k, value)
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: value
      integer :: n
      call get_command_argument(k, length=n)
      allocate(character(len=n) :: value)
      call get_command_argument(k, value)
   end subroutine get_arg

   subroutine fail(message)
      character(len=*), intent(in) :: message
      if (is_root()) write(error_unit, '(a)') "pavefric: error: " // message
      flush(error_unit)   ! before any exit handler can fail (files)
      call parallel_finalize()
      stop 1, quiet=.true.
   end subroutine fail

   subroutine usage(unit)
      integer, intent(in) :: unit
      write(unit, '(a)') &
         & "usage: pavefric SCENE.nml [-o OUT.nc]", &
         & "", &
         & "Predict tyre-rubber/pavement friction (Kane et al. 2017) from a texture", &
         & "profile, dry and wet, at the speeds of the scene's &operation speeds_kmh.", &
         & "", &
         & "  SCENE.nml          scene namelist (groups &surface &pad &rubber &water", &
         & "                     &operation &numerics &output; see docs/inputs.md)", &
         & "  -o, --output FILE  NetCDF output (default: &output file, else", &
         & "                     outputs/<scene name>.nc)", &
         & "  --max-profiles N   batch: stop after computing N profiles (resume later)", &
         & "  -h, --help         this help", &
         & "  -V, --version      the version", &
         & "", &
         & "A scene with a &batch group runs many profiles into one NetCDF file;", &
         & "under mpirun the profiles are shared among the ranks (docs/cluster.md).", &
         & "", &
         & "Exit status: 0 on success, 1 on bad input or a failed run (one line on", &
         & "stderr names the group, variable and value), 2 on bad usage, 3 when a", &
         & "batch stopped early (--max-profiles) and can be resumed."
   end subroutine usage

end program pavefric_main
