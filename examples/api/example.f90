!> pavefric from Fortran: the program's path from a scene file to the
!> friction per speed and the NetCDF output (docs/api.md).
!>
!>   gfortran example.f90 $(pkg-config --cflags --libs pavefric) -o example
!>   ./example scene.nml [output.nc]
program example
   use pavefric, only: wp, error_type, scene_type, clean_profile_type, sim_result_type, &
      & output_metadata_type, read_scene, load_scene_profile, run_profile, write_results
   implicit none
   type(scene_type) :: scene
   type(clean_profile_type) :: profile
   type(sim_result_type) :: res
   type(output_metadata_type) :: meta
   type(error_type), allocatable :: error
   character(len=4096) :: path, output
   integer :: j

   if (command_argument_count() < 1) then
      write(*, '(a)') "usage: example scene.nml [output.nc]"
      stop 2
   end if
   call get_command_argument(1, path)
   output = ""
   if (command_argument_count() > 1) call get_command_argument(2, output)

   ! the namelist, checked; the profile file, read and preprocessed; the run
   call read_scene(trim(path), scene, error)
   if (.not. allocated(error)) call load_scene_profile(scene, profile, error)
   if (.not. allocated(error)) call run_profile(scene, profile, res, meta, error)
   if (.not. allocated(error) .and. len_trim(output) > 0) &
      & call write_results(trim(output), res, meta, error)
   if (allocated(error)) then
      write(*, '(a)') "error: " // error%message
      stop 1
   end if
   do j = 1, size(res%mu)
      write(*, '(g0, a, es26.17e3)') res%speed_kmh(j), " km/h: mu = ", res%mu(j)
   end do
   if (len(meta%warnings) > 0) write(*, '(a)') "warnings:" // new_line("a") // meta%warnings
end program example
