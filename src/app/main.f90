!> The pavefric program: `pavefric SCENE.nml [-o OUT.nc] [-q]`. No Python needed.
!>
!> Results go to stdout; progress (the cost estimate, a batch's progress
!> lines), warnings and errors to stderr. --quiet drops the progress only.
!>
!> Exit status: 0 success; 1 error (bad input, a failed run); 2 bad usage;
!> 3 a batch stopped early (--max-profiles), resumable; 4 a batch finished
!> but some profiles failed (the output is written, the summary says how
!> many). Under MPI every rank exits with the same status.
program pavefric_main
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use pavefric, only: pavefric_version, error_type, sim_result_type, run_scene, effects_text
   use pavefric_format, only: to_str, friction_table_text
   use pavefric_numbers, only: parse_integer
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_batch_run, only: batch_summary_type
   use pavefric_batch_mpi, only: run_batch_program, parallel_init, parallel_finalize, is_root, &
      & agree_error
   use pavefric_fsys, only: install_signal_cleanup
   implicit none
   integer, parameter :: exit_error = 1, exit_usage = 2, exit_stopped = 3, exit_failures = 4
   type(sim_result_type) :: res
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   type(batch_summary_type) :: summary
   integer :: max_profiles, stat
   !> --quiet: no progress lines and no estimate (warnings and errors stay).
   logical :: quiet
   character(len=:), allocatable :: scene_path, out_override, out_path, arg, command, warnings
   integer :: i, nargs

   max_profiles = 0
   quiet = .false.
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
      case ("-q", "--quiet")
         quiet = .true.
      case ("--max-profiles")
         if (i == nargs) call usage_error("option " // arg // " needs a number")
         i = i + 1
         call get_arg(i, arg)
         command = command // " " // arg
         call parse_integer(arg, max_profiles, stat)
         if (stat /= 0 .or. max_profiles < 0) call usage_error("--max-profiles '" // arg // &
            & "': must be a whole number >= 0 (profiles to compute before stopping; 0: " // &
            & "no limit)")
      case ("-o", "--output")
         if (i == nargs) call usage_error("option " // arg // " needs a file name")
         i = i + 1
         call get_arg(i, out_override)
         command = command // " " // out_override
      case default
         if (len(arg) > 1) then
            if (arg(1:1) == "-") call usage_error("unknown option '" // arg // &
               & "' (see pavefric --help)")
         end if
         if (len(scene_path) > 0) call usage_error("more than one scene file given ('" // &
            & scene_path // "', '" // arg // "'): pavefric runs one scene; name the " // &
            & "output with -o (pavefric " // scene_path // " -o out.nc)")
         scene_path = arg
      end select
      i = i + 1
   end do
   if (len(scene_path) == 0) then
      call usage(error_unit)
      stop exit_usage, quiet=.true.
   end if

   call parallel_init()
   call install_signal_cleanup()   ! temp outputs removed on SIGTERM/SIGINT/SIGHUP
   call read_scene(scene_path, scene, error)
   call agree_error(error)                ! every rank ends alike
   if (allocated(error)) call fail(error%message)
   if (scene%is_batch) then
      if (is_root()) call print_warnings(scene%warnings)   ! the scene's; profiles' at the end
      call run_batch_program(scene_path, out_override, command, max_profiles, &
         & merge(-1, error_unit, quiet), summary, error)
      if (allocated(error)) call fail(error%message)
      if (is_root()) call report_batch()
      call parallel_finalize()
      if (.not. summary%finished) stop exit_stopped, quiet=.true.
      if (summary%failed > 0) stop exit_failures, quiet=.true.
   else if (.not. is_root()) then
      call parallel_finalize()       ! a single scene runs on rank 0 only
   else
      ! (print_estimate and print_nothing read nothing of the program's: an
      ! internal procedure passed as an argument that did would need a
      ! trampoline, an executable stack; with --quiet the estimate is still
      ! made, and checked, but not printed)
      if (quiet) then
         call run_scene(scene_path, out_override, command, out_path, res, error, &
            & warnings=warnings, announce=print_nothing)
      else
         call run_scene(scene_path, out_override, command, out_path, res, error, &
            & warnings=warnings, announce=print_estimate)
      end if
      if (allocated(error)) call fail(error%message)
      call parallel_finalize()
      call report_scene()
   end if

contains

   !> The batch's last lines: a summary on stdout; failures and an early
   !> stop on stderr.
   subroutine report_batch()
      integer :: k
      character(len=:), allocatable :: counts
      counts = to_str(summary%total) // " profiles: " // to_str(summary%computed) // &
         & " done in this run (failed included), " // to_str(summary%from_journal) // &
         & " taken from the journal, " // to_str(summary%failed) // " failed, " // &
         & to_str(summary%warned) // " with warnings"
      if (summary%finished) then
         write(output_unit, '(a)') "pavefric " // pavefric_version // ": batch " // &
            & scene_path // " -> " // summary%output // ": " // counts
      else
         write(output_unit, '(a)') "pavefric " // pavefric_version // ": batch " // &
            & scene_path // " stopped: " // counts // ", " // to_str(summary%left) // " left"
         write(error_unit, '(a)') "pavefric: batch stopped before the end (--max-profiles " // &
            & to_str(max_profiles) // "); run it again to resume from its journal '" // &
            & summary%output // ".journal'"
      end if
      if (quiet) then       ! the journal's news that are warnings (else in the progress)
         if (summary%damaged > 0) write(error_unit, '(a)') "pavefric: warning: " // &
            & to_str(summary%damaged) // " damaged journal line(s) ignored (their profiles " // &
            & "are recomputed)"
         if (summary%changed > 0) write(error_unit, '(a)') "pavefric: warning: " // &
            & to_str(summary%changed) // " profile file(s) changed since the journal " // &
            & "(recomputed)"
      end if
      if (summary%warned > 0) then
         do k = 1, size(summary%warned_profiles)
            write(error_unit, '(a)') "pavefric: warning: profile " // summary%warned_profiles(k)%s
         end do
         if (summary%warned > size(summary%warned_profiles)) write(error_unit, '(a)') &
            & "pavefric: warning: ... " // to_str(summary%warned - size(summary%warned_profiles)) &
            & // " more profiles with warnings"
         if (summary%finished) write(error_unit, '(a)') "pavefric: warning: " // &
            & to_str(summary%warned) // " of " // to_str(summary%total) // " profiles have " // &
            & "warnings (" // to_str(summary%warnings) // " in all: n_warnings and " // &
            & "warning_message in " // summary%output // "); warnings leave the exit status as it is"
      end if
      if (summary%failed > 0) then
         do k = 1, size(summary%failures)
            write(error_unit, '(a)') "pavefric: profile " // summary%failures(k)%s
         end do
         if (summary%failed > size(summary%failures)) write(error_unit, '(a)') "pavefric: ... " // &
            & to_str(summary%failed - size(summary%failures)) // " more"
         if (summary%finished) write(error_unit, '(a)') "pavefric: " // to_str(summary%failed) // &
            & " of " // to_str(summary%total) // " profiles failed (status = 2 and " // &
            & "error_message in " // summary%output // "); exit status 4"
      end if
   end subroutine report_batch

   !> The cost estimate, on stderr before the model runs (progress, not
   !> results; none with --quiet).
   subroutine print_estimate(text)
      character(len=*), intent(in) :: text
      write(error_unit, '(a)') "pavefric: " // text
      flush(error_unit)
   end subroutine print_estimate

   !> The cost estimate with --quiet: made and checked, not printed.
   subroutine print_nothing(text)
      character(len=*), intent(in) :: text
      ! (never true: it only uses `text`, which -Wall would call unused)
      if (len(text) < 0) write(error_unit, '(a)') text
   end subroutine print_nothing

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

   subroutine report_scene()
   character(len=:), allocatable :: table

   call print_warnings(warnings)
   write(output_unit, '(a)') "pavefric " // pavefric_version // ": " // scene_path // " -> " // &
      & out_path
   ! the last column: mu's estimated error, when the run made one
   if (allocated(res%mu_error)) then
      call friction_table_text(res%n_elements, res%n_positions, effects_text(res), &
         & res%speed_kmh, res%mu, res%wet_fraction, res%hydroplaning_fraction, table, &
         & res%mu_error)
   else
      call friction_table_text(res%n_elements, res%n_positions, effects_text(res), &
         & res%speed_kmh, res%mu, res%wet_fraction, res%hydroplaning_fraction, table)
   end if
   write(output_unit, '(a)', advance='no') table
   end subroutine report_scene

   subroutine get_arg(k, value)
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: value
      integer :: n
      call get_command_argument(k, length=n)
      allocate(character(len=n) :: value)
      call get_command_argument(k, value)
   end subroutine get_arg

   !> An error: one line on stderr (rank 0), exit status 1 on every rank.
   subroutine fail(message)
      character(len=*), intent(in) :: message
      if (is_root()) write(error_unit, '(a)') "pavefric: error: " // message
      flush(error_unit)   ! before any exit handler can fail
      call parallel_finalize()
      stop exit_error, quiet=.true.
   end subroutine fail

   !> Bad usage (before MPI starts): exit status 2.
   subroutine usage_error(message)
      character(len=*), intent(in) :: message
      write(error_unit, '(a)') "pavefric: error: " // message
      stop exit_usage, quiet=.true.
   end subroutine usage_error

   subroutine usage(unit)
      integer, intent(in) :: unit
      write(unit, '(a)') &
         & "usage: pavefric SCENE.nml [-o OUT.nc] [-q] [--max-profiles N]", &
         & "", &
         & "Predict tyre-rubber/pavement friction (Kane et al. 2017) from a texture", &
         & "profile, dry and wet, at the speeds of the scene's &operation speeds_kmh.", &
         & "", &
         & "  SCENE.nml          scene namelist (groups &surface &pad &rubber &water", &
         & "                     &operation &numerics &output; see docs/inputs.md)", &
         & "  -o, --output FILE  NetCDF output (default: &output file, else", &
         & "                     outputs/<scene name>.nc)", &
         & "  -q, --quiet        no progress: neither the cost estimate nor a batch's", &
         & "                     progress lines (warnings and errors still on stderr)", &
         & "  --max-profiles N   batch: stop after computing N profiles (resume later)", &
         & "  -h, --help         this help", &
         & "  -V, --version      the version", &
         & "", &
         & "A scene with a &batch group runs many profiles into one NetCDF file;", &
         & "under mpirun the profiles are shared among the ranks (docs/cluster.md).", &
         & "A batch ends with a summary line: profiles done in this run, taken from", &
         & "the journal of an earlier run, failed, with warnings, and the output file.", &
         & "", &
         & "Results (the friction table, a batch's summary line) go to stdout;", &
         & "progress (the cost estimate of a run of a second or more, a batch's", &
         & "progress lines), warnings and errors to stderr.", &
         & "", &
         & "Exit status (every MPI rank exits with the same):", &
         & "  0  success (a batch: every profile computed)", &
         & "  1  error: bad input or a failed run; one line on stderr names the", &
         & "     group, variable and value, or the file and line", &
         & "  2  bad usage (options)", &
         & "  3  a batch stopped early (--max-profiles); run it again to resume", &
         & "  4  a batch finished but some profiles failed: the output is written,", &
         & "     its status and error_message variables say which and why", &
         & "Warnings (on stderr; a batch's per profile in n_warnings and", &
         & "warning_message) do not change the exit status."
   end subroutine usage

end program pavefric_main
