! The Fortran API after a run that failed (an attack of 2026-12-07): its
! result is intent(out), left empty, and write_results on it died of SIGSEGV
! in output_present. It must return an error, as the C API's
! pavefric_write_output does. Run in a directory holding short.txt (3
! points, too short for the pad) and s.nml naming it.
program write_after_failed_run
   use pavefric
   implicit none
   type(scene_type) :: scene
   type(clean_profile_type) :: prof
   type(sim_result_type) :: res
   type(output_metadata_type) :: meta
   type(error_type), allocatable :: error
   call read_scene("s.nml", scene, error)
   if (.not. allocated(error)) call load_scene_profile(scene, prof, error)
   if (.not. allocated(error)) call run_profile(scene, prof, res, meta, error)
   if (allocated(error)) print '(a)', "run_profile error: " // error%message
   call write_results("out.nc", res, meta, error)
   if (allocated(error)) then
      print '(a)', "write_results error: " // error%message
   else
      print '(a)', "write_results: no error"
   end if
end program write_after_failed_run
