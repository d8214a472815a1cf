!> The C API (src/api/pavefric.h): bind(C) procedures over opaque handles, in
!> the manner of dftd4's api.f90. An error handle carries the last call's
!> error; a scene handle is a pavefric_session session_type (a scene, its
!> profile, its last results). Handles are heap objects owned by the
!> caller, created by pavefric_new_error / pavefric_load_scene /
!> pavefric_new_scene and freed by pavefric_delete_*. No module variables:
!> different handles may be used from different threads at once.
!>
!> Nothing here stops the process: every failure sets the error handle
!> (cleared at the start of every call that takes it) with a message naming
!> the input. A NULL error handle makes a call do nothing (and return NULL
!> or 0); a NULL scene, string or array sets the error. Text goes out
!> NUL-terminated, truncated to the buffer given; the functions returning
!> text lengths tell how much room the whole text needs.
module pavefric_api
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_f_pointer, c_loc, &
      & c_int, c_double, c_char, c_null_char, c_size_t
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_memory
   use pavefric_format, only: to_str
   use pavefric_numbers, only: parse_integer
   use pavefric_session, only: session_type, load_session, session_from_text, &
      & session_set_parameter, session_set_value, session_get_parameter, session_set_profile, &
      & session_run, &
      & session_result_size, session_get_result, session_write, session_warnings, &
      & n_scene_results, scene_results
   use pavefric_outputs, only: output_var_type, output_table, n_outputs
   implicit none
   private

   public :: vp_error, vp_scene

   !> What an error handle points to.
   type :: vp_error
      type(error_type), allocatable :: ptr
   end type vp_error

   !> What a scene handle points to.
   type :: vp_scene
      type(session_type) :: ptr
   end type vp_scene

   !> Result names besides the output table's, in the order of the C API.
   integer, parameter :: n_coordinates = 3
   character(len=*), parameter :: coordinates(n_coordinates) = &
      & [character(len=9) :: "speed_kmh", "speed", "position"]

   interface
      pure function c_strlen(s) result(n) bind(C, name="strlen")
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

contains

   ! --- version ---------------------------------------------------------------

   !> The library's version as 10000 * major + 100 * minor + patch.
   function get_version_api() result(version) bind(C, name="pavefric_get_version")
      integer(c_int) :: version
      integer :: part(3), k, dot, stat
      character(len=:), allocatable :: rest
      part = 0
      rest = pavefric_version
      do k = 1, 3
         dot = index(rest, ".")
         if (dot == 0) dot = len(rest) + 1
         call parse_integer(rest(1:dot-1), part(k), stat)
         if (dot > len(rest)) exit
         rest = rest(dot+1:)
      end do
      version = int(10000 * part(1) + 100 * part(2) + part(3), c_int)
   end function get_version_api

   ! --- errors -----------------------------------------------------------------

   !> A new error handle (no error set); NULL when memory is exhausted.
   function new_error_api() result(verror) bind(C, name="pavefric_new_error")
      type(c_ptr) :: verror
      type(vp_error), pointer :: error
      integer :: stat
      verror = c_null_ptr
      allocate(error, stat=stat)
      if (stat /= 0) return
      verror = c_loc(error)
   end function new_error_api

   !> Free an error handle and set the caller's pointer to NULL.
   subroutine delete_error_api(pverror) bind(C, name="pavefric_delete_error")
      !> Address of the caller's handle (pavefric_error *).
      type(c_ptr), value :: pverror
      type(c_ptr), pointer :: verror
      type(vp_error), pointer :: error
      if (.not. c_associated(pverror)) return
      call c_f_pointer(pverror, verror)
      if (c_associated(verror)) then
         call c_f_pointer(verror, error)
         deallocate(error)
      end if
      verror = c_null_ptr
   end subroutine delete_error_api

   !> 1 if the last call set an error, 0 if not, 2 for a NULL handle.
   function check_error_api(verror) result(status) bind(C, name="pavefric_check_error")
      type(c_ptr), value :: verror
      integer(c_int) :: status
      type(vp_error), pointer :: error
      status = 2
      if (.not. c_associated(verror)) return
      call c_f_pointer(verror, error)
      status = merge(1, 0, allocated(error%ptr))
   end function check_error_api

   !> The error's kind: 0 none, 1 bad input, 2 internal, 3 memory, 4 I/O;
   !> -1 for a NULL handle.
   function get_error_status_api(verror) result(status) bind(C, name="pavefric_get_error_status")
      type(c_ptr), value :: verror
      integer(c_int) :: status
      type(vp_error), pointer :: error
      status = -1
      if (.not. c_associated(verror)) return
      call c_f_pointer(verror, error)
      status = 0
      if (allocated(error%ptr)) status = int(error%ptr%stat, c_int)
   end function get_error_status_api

   !> The error message (empty when none), NUL-terminated, truncated to
   !> buffer_size - 1 bytes. Nothing is written for a NULL handle or buffer
   !> or a buffer_size < 1.
   subroutine get_error_api(verror, buffer, buffer_size) bind(C, name="pavefric_get_error")
      type(c_ptr), value :: verror, buffer
      integer(c_int), value :: buffer_size
      type(vp_error), pointer :: error
      if (.not. c_associated(verror)) return
      call c_f_pointer(verror, error)
      if (allocated(error%ptr)) then
         call put_text(error%ptr%message, buffer, buffer_size)
      else
         call put_text("", buffer, buffer_size)
      end if
   end subroutine get_error_api

   !> Length of the error message in bytes without the NUL (0 when none or
   !> for a NULL handle).
   function get_error_length_api(verror) result(length) bind(C, name="pavefric_get_error_length")
      type(c_ptr), value :: verror
      integer(c_int) :: length
      type(vp_error), pointer :: error
      length = 0
      if (.not. c_associated(verror)) return
      call c_f_pointer(verror, error)
      if (allocated(error%ptr)) length = clamp(len(error%ptr%message))
   end function get_error_length_api

   ! --- scenes -----------------------------------------------------------------

   !> Read and check the scene namelist at `path` as the program does; its
   !> profile file is read at the first run unless pavefric_set_profile
   !> gives the heights. NULL (error set) on failure.
   function load_scene_api(verror, path) result(vscene) bind(C, name="pavefric_load_scene")
      type(c_ptr), value :: verror, path
      type(c_ptr) :: vscene
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fpath
      vscene = c_null_ptr
      if (.not. open_error(verror, error)) return
      if (.not. get_text(path, "scene file: the path", fpath, error)) return
      if (.not. new_scene(scene, error)) return
      call load_session(fpath, scene%ptr, error%ptr)
      if (allocated(error%ptr)) then
         deallocate(scene)
         return
      end if
      vscene = c_loc(scene)
   end function load_scene_api

   !> A scene from namelist text (the groups of a scene file, no file read);
   !> the heights come from pavefric_set_profile. &operation speeds_kmh and
   !> &surface dx are required. NULL (error set) on failure.
   function new_scene_api(verror, text) result(vscene) bind(C, name="pavefric_new_scene")
      type(c_ptr), value :: verror, text
      type(c_ptr) :: vscene
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: ftext
      vscene = c_null_ptr
      if (.not. open_error(verror, error)) return
      if (.not. get_text(text, "scene: the namelist text", ftext, error)) return
      if (.not. new_scene(scene, error)) return
      call session_from_text(ftext, scene%ptr, error%ptr)
      if (allocated(error%ptr)) then
         deallocate(scene)
         return
      end if
      vscene = c_loc(scene)
   end function new_scene_api

   !> Free a scene handle and set the caller's pointer to NULL.
   subroutine delete_scene_api(pvscene) bind(C, name="pavefric_delete_scene")
      !> Address of the caller's handle (pavefric_scene *).
      type(c_ptr), value :: pvscene
      type(c_ptr), pointer :: vscene
      type(vp_scene), pointer :: scene
      if (.not. c_associated(pvscene)) return
      call c_f_pointer(pvscene, vscene)
      if (c_associated(vscene)) then
         call c_f_pointer(vscene, scene)
         deallocate(scene)
      end if
      vscene = c_null_ptr
   end subroutine delete_scene_api

   !> Number of speeds of the scene (&operation speeds_kmh); 0 for NULL.
   function get_speed_count_api(vscene) result(n) bind(C, name="pavefric_get_speed_count")
      type(c_ptr), value :: vscene
      integer(c_int) :: n
      type(vp_scene), pointer :: scene
      n = 0
      if (.not. c_associated(vscene)) return
      call c_f_pointer(vscene, scene)
      if (allocated(scene%ptr%scene%speeds_kmh)) n = clamp(size(scene%ptr%scene%speeds_kmh))
   end function get_speed_count_api

   !> The scene's speeds (km/h) in its order into speeds_kmh[size].
   subroutine get_speeds_api(verror, vscene, speeds_kmh, size_) bind(C, name="pavefric_get_speeds")
      type(c_ptr), value :: verror, vscene, speeds_kmh
      integer(c_int), value :: size_
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      real(c_double), pointer :: out(:)
      integer :: ns
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      ns = size(scene%ptr%scene%speeds_kmh)
      if (.not. room(speeds_kmh, size_, ns, "speeds_kmh", error)) return
      call c_f_pointer(speeds_kmh, out, [ns])
      out = scene%ptr%scene%speeds_kmh
   end subroutine get_speeds_api

   !> Set `&group name = value` (value as namelist text) through the
   !> program's namelist reader: its checks, its messages.
   subroutine set_parameter_api(verror, vscene, group, name, value) &
         & bind(C, name="pavefric_set_parameter")
      type(c_ptr), value :: verror, vscene, group, name, value
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname, fvalue
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_name(group, "pavefric_set_parameter: the group", fgroup, error)) return
      if (.not. get_name(name, "pavefric_set_parameter: the name", fname, error)) return
      if (.not. get_text(value, "pavefric_set_parameter: the value", fvalue, error)) return
      call session_set_parameter(scene%ptr, fgroup, fname, fvalue, error%ptr)
   end subroutine set_parameter_api

   !> Typed setters: `&group name = value` from a C value, checked against
   !> the variable's declaration as the namelist reader checks it, without
   !> namelist text. A double sets a real (or a one-element list), an int a
   !> whole number (or a real), a bool (0 or 1) a logical, a string a text
   !> variable, n doubles a list (n = 0 unsets it).
   subroutine set_double_api(verror, vscene, group, name, value) &
         & bind(C, name="pavefric_set_parameter_double")
      type(c_ptr), value :: verror, vscene, group, name
      real(c_double), value :: value
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname
      if (.not. open_typed(verror, vscene, group, name, "pavefric_set_parameter_double", &
         & error, scene, fgroup, fname)) return
      call session_set_value(scene%ptr, fgroup, fname, error%ptr, r=real(value, wp))
   end subroutine set_double_api

   subroutine set_int_api(verror, vscene, group, name, value) &
         & bind(C, name="pavefric_set_parameter_int")
      type(c_ptr), value :: verror, vscene, group, name
      integer(c_int), value :: value
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname
      if (.not. open_typed(verror, vscene, group, name, "pavefric_set_parameter_int", &
         & error, scene, fgroup, fname)) return
      call session_set_value(scene%ptr, fgroup, fname, error%ptr, i=int(value))
   end subroutine set_int_api

   subroutine set_bool_api(verror, vscene, group, name, value) &
         & bind(C, name="pavefric_set_parameter_bool")
      type(c_ptr), value :: verror, vscene, group, name
      integer(c_int), value :: value
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname
      if (.not. open_typed(verror, vscene, group, name, "pavefric_set_parameter_bool", &
         & error, scene, fgroup, fname)) return
      if (value /= 0 .and. value /= 1) then
         call fatal_error(error%ptr, "pavefric_set_parameter_bool: &" // fgroup // " " // &
            & fname // " = " // to_str(int(value)) // ": must be 1 (.true.) or 0 (.false.)")
         return
      end if
      call session_set_value(scene%ptr, fgroup, fname, error%ptr, b=value == 1)
   end subroutine set_bool_api

   subroutine set_text_api(verror, vscene, group, name, value) &
         & bind(C, name="pavefric_set_parameter_text")
      type(c_ptr), value :: verror, vscene, group, name, value
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname, fvalue
      if (.not. open_typed(verror, vscene, group, name, "pavefric_set_parameter_text", &
         & error, scene, fgroup, fname)) return
      if (.not. get_text(value, "pavefric_set_parameter_text: the value", fvalue, error)) return
      call session_set_value(scene%ptr, fgroup, fname, error%ptr, t=fvalue)
   end subroutine set_text_api

   subroutine set_doubles_api(verror, vscene, group, name, n, values) &
         & bind(C, name="pavefric_set_parameter_doubles")
      type(c_ptr), value :: verror, vscene, group, name, values
      integer(c_int), value :: n
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname
      real(c_double), pointer :: v(:)
      real(wp), allocatable :: list(:)
      if (.not. open_typed(verror, vscene, group, name, "pavefric_set_parameter_doubles", &
         & error, scene, fgroup, fname)) return
      if (n < 0) then
         call fatal_error(error%ptr, "pavefric_set_parameter_doubles: n = " // to_str(int(n)) // &
            & ": must be >= 0")
         return
      end if
      allocate(list(n))
      if (n > 0) then
         if (.not. c_associated(values)) then
            call fatal_error(error%ptr, "pavefric_set_parameter_doubles: values is NULL")
            return
         end if
         call c_f_pointer(values, v, [n])
         list = v
      end if
      call session_set_value(scene%ptr, fgroup, fname, error%ptr, list=list)
   end subroutine set_doubles_api

   !> The handles and the variable's group and name of a typed setter.
   logical function open_typed(verror, vscene, group, name, what, error, scene, fgroup, fname)
      type(c_ptr), intent(in) :: verror, vscene, group, name
      character(len=*), intent(in) :: what
      type(vp_error), pointer, intent(out) :: error
      type(vp_scene), pointer, intent(out) :: scene
      character(len=:), allocatable, intent(out) :: fgroup, fname
      open_typed = .false.
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_name(group, what // ": the group", fgroup, error)) return
      if (.not. get_name(name, what // ": the name", fname, error)) return
      open_typed = .true.
   end function open_typed

   !> The value of `&group name` the scene uses, as namelist text
   !> (NUL-terminated, truncated); returns its whole length ('' and 0 for an
   !> optional variable not set; 0 on error).
   function get_parameter_api(verror, vscene, group, name, buffer, buffer_size) result(length) &
         & bind(C, name="pavefric_get_parameter")
      type(c_ptr), value :: verror, vscene, group, name, buffer
      integer(c_int), value :: buffer_size
      integer(c_int) :: length
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fgroup, fname, fvalue
      length = 0
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_name(group, "pavefric_get_parameter: the group", fgroup, error)) return
      if (.not. get_name(name, "pavefric_get_parameter: the name", fname, error)) return
      call session_get_parameter(scene%ptr, fgroup, fname, fvalue, error%ptr)
      if (allocated(error%ptr)) return
      call put_text(fvalue, buffer, buffer_size)
      length = clamp(len(fvalue))
   end function get_parameter_api

   !> Give the profile: n heights (m) at spacing dx_m (m), closed (1) or
   !> open (0); dx and closed become the scene's &surface dx and closed.
   subroutine set_profile_api(verror, vscene, n, heights_m, dx_m, closed) &
         & bind(C, name="pavefric_set_profile")
      type(c_ptr), value :: verror, vscene, heights_m
      integer(c_int), value :: n, closed
      real(c_double), value :: dx_m
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      real(c_double), pointer :: z(:)
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (n < 1) then
         call fatal_error(error%ptr, "pavefric_set_profile: n = " // to_str(int(n)) // &
            & ": at least one height is needed")
         return
      end if
      if (.not. c_associated(heights_m)) then
         call fatal_error(error%ptr, "pavefric_set_profile: heights_m is NULL")
         return
      end if
      if (closed /= 0 .and. closed /= 1) then
         call fatal_error(error%ptr, "pavefric_set_profile: closed = " // to_str(int(closed)) // &
            & ": must be 1 (a closed CTM circle) or 0 (an open profile)")
         return
      end if
      call c_f_pointer(heights_m, z, [n])
      call session_set_profile(scene%ptr, z, real(dx_m, wp), closed == 1, error%ptr)
   end subroutine set_profile_api

   !> Run the model; mu[speed count] receives the scene-averaged friction per
   !> speed in the scene's speed order (mu may be NULL: results through
   !> pavefric_get_result).
   subroutine run_api(verror, vscene, mu) bind(C, name="pavefric_run")
      type(c_ptr), value :: verror, vscene, mu
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      real(c_double), pointer :: out(:)
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      call session_run(scene%ptr, error%ptr)
      if (allocated(error%ptr)) return
      if (.not. c_associated(mu)) return
      call c_f_pointer(mu, out, [size(scene%ptr%res%mu)])
      out = scene%ptr%res%mu
   end subroutine run_api

   !> Number of result names: the coordinates speed_kmh, speed, position,
   !> then every variable of the output table, then the scene's scalars
   !> (mpd .. speed_constant: pavefric_session's scene_results).
   function get_result_count_api() result(n) bind(C, name="pavefric_get_result_count")
      integer(c_int) :: n
      n = n_coordinates + n_outputs + n_scene_results
   end function get_result_count_api

   !> Result name number `index` (0-based, < pavefric_get_result_count()),
   !> NUL-terminated, truncated; returns its length (0 when out of range).
   function get_result_name_api(index, buffer, buffer_size) result(length) &
         & bind(C, name="pavefric_get_result_name")
      integer(c_int), value :: index, buffer_size
      type(c_ptr), value :: buffer
      integer(c_int) :: length
      type(output_var_type) :: table(n_outputs)
      character(len=:), allocatable :: name
      length = 0
      if (index < 0 .or. index >= n_coordinates + n_outputs + n_scene_results) then
         call put_text("", buffer, buffer_size)
         return
      end if
      if (index < n_coordinates) then
         name = trim(coordinates(index + 1))
      else if (index < n_coordinates + n_outputs) then
         table = output_table()
         name = table(index - n_coordinates + 1)%name
      else
         name = trim(scene_results(index - n_coordinates - n_outputs + 1))
      end if
      call put_text(name, buffer, buffer_size)
      length = clamp(len(name))
   end function get_result_name_api

   !> Number of values of result `name` after the last run (speeds; positions
   !> x speeds for series; 0 when not part of this run or before a run);
   !> -1 and the error set for an unknown name.
   function get_result_size_api(verror, vscene, name) result(n) &
         & bind(C, name="pavefric_get_result_size")
      type(c_ptr), value :: verror, vscene, name
      integer(c_int) :: n
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fname
      real(wp) :: none(0)
      n = -1
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_name(name, "pavefric_get_result_size: the name", fname, error)) return
      n = clamp(session_result_size(scene%ptr, fname))
      if (n < 0) call session_get_result(scene%ptr, fname, none, error%ptr)
   end function get_result_size_api

   !> Values of result `name` of the last run into values[size] (size at
   !> least pavefric_get_result_size): per speed in the scene's speed
   !> order; series (position, speed) with the position varying fastest;
   !> integers and flags as exact doubles.
   subroutine get_result_api(verror, vscene, name, values, size_) &
         & bind(C, name="pavefric_get_result")
      type(c_ptr), value :: verror, vscene, name, values
      integer(c_int), value :: size_
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fname
      real(c_double), pointer :: out(:)
      integer :: n
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_name(name, "pavefric_get_result: the name", fname, error)) return
      n = session_result_size(scene%ptr, fname)
      if (n <= 0) then
         ! the session names what is wrong
         block
            real(wp) :: none(0)
            call session_get_result(scene%ptr, fname, none, error%ptr)
         end block
      end if
      if (n <= 0) return
      if (.not. room(values, size_, n, "result '" // fname // "'", error)) return
      call c_f_pointer(values, out, [n])
      call session_get_result(scene%ptr, fname, out, error%ptr)
   end subroutine get_result_api

   !> The warnings about the scene and, after a run, its results (one a
   !> line, as the program prints and records them), NUL-terminated,
   !> truncated; returns their whole length (0: none).
   function get_warnings_api(verror, vscene, buffer, buffer_size) result(length) &
         & bind(C, name="pavefric_get_warnings")
      type(c_ptr), value :: verror, vscene, buffer
      integer(c_int), value :: buffer_size
      integer(c_int) :: length
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: text
      length = 0
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      text = session_warnings(scene%ptr)
      call put_text(text, buffer, buffer_size)
      length = clamp(len(text))
   end function get_warnings_api

   !> Write the last run's results to the NetCDF file `path`: the program's
   !> file (variables, parameters used, warnings), via a temporary file.
   subroutine write_output_api(verror, vscene, path) bind(C, name="pavefric_write_output")
      type(c_ptr), value :: verror, vscene, path
      type(vp_error), pointer :: error
      type(vp_scene), pointer :: scene
      character(len=:), allocatable :: fpath
      if (.not. open_error(verror, error)) return
      if (.not. open_scene(vscene, scene, error)) return
      if (.not. get_text(path, "&output file: the path", fpath, error)) return
      call session_write(scene%ptr, fpath, error%ptr)
   end subroutine write_output_api

   ! --- helpers ------------------------------------------------------------------

   !> The error handle behind verror, cleared; .false. for NULL.
   logical function open_error(verror, error)
      type(c_ptr), intent(in) :: verror
      type(vp_error), pointer, intent(out) :: error
      open_error = c_associated(verror)
      nullify(error)
      if (.not. open_error) return
      call c_f_pointer(verror, error)
      if (allocated(error%ptr)) deallocate(error%ptr)
   end function open_error

   !> The scene behind vscene; .false. and the error set for NULL.
   logical function open_scene(vscene, scene, error)
      type(c_ptr), intent(in) :: vscene
      type(vp_scene), pointer, intent(out) :: scene
      type(vp_error), intent(inout) :: error
      open_scene = c_associated(vscene)
      nullify(scene)
      if (.not. open_scene) then
         call fatal_error(error%ptr, "scene: a NULL handle (pavefric_load_scene or " // &
            & "pavefric_new_scene failed, or the scene was deleted)")
         return
      end if
      call c_f_pointer(vscene, scene)
   end function open_scene

   !> A new scene object; .false. and the error set when memory is exhausted.
   logical function new_scene(scene, error)
      type(vp_scene), pointer, intent(out) :: scene
      type(vp_error), intent(inout) :: error
      integer :: stat
      allocate(scene, stat=stat)
      new_scene = stat == 0
      if (.not. new_scene) call fatal_error(error%ptr, "scene: not enough memory for a " // &
         & "scene handle", stat_memory)
   end function new_scene

   !> A C string as Fortran text; .false. and the error set for NULL.
   logical function get_text(cstr, what, text, error)
      type(c_ptr), intent(in) :: cstr
      character(len=*), intent(in) :: what
      character(len=:), allocatable, intent(out) :: text
      type(vp_error), intent(inout) :: error
      character(kind=c_char), pointer :: chars(:)
      integer :: n, k
      get_text = c_associated(cstr)
      if (.not. get_text) then
         call fatal_error(error%ptr, what // " is NULL")
         return
      end if
      n = int(c_strlen(cstr))
      call c_f_pointer(cstr, chars, [n])
      allocate(character(len=n) :: text)
      do k = 1, n
         text(k:k) = chars(k)
      end do
   end function get_text

   !> A name (of a group, a variable or a result) from C: get_text's, refused
   !> when it begins or ends with a blank (Fortran's comparison would ignore
   !> trailing blanks: "mpd " read as "mpd").
   logical function get_name(cstr, what, text, error)
      type(c_ptr), intent(in) :: cstr
      character(len=*), intent(in) :: what
      character(len=:), allocatable, intent(out) :: text
      type(vp_error), intent(inout) :: error
      get_name = get_text(cstr, what, text, error)
      if (.not. get_name) return
      if (len(text) == 0) return
      if (text(1:1) == " " .or. text(len(text):len(text)) == " ") then
         call fatal_error(error%ptr, what // " '" // text // "' begins or ends with a " // &
            & "blank: a name has none")
         get_name = .false.
      end if
   end function get_name

   !> Copy text into a C buffer of `size` bytes, NUL-terminated, truncated.
   subroutine put_text(text, buffer, size_)
      character(len=*), intent(in) :: text
      type(c_ptr), intent(in) :: buffer
      integer(c_int), intent(in) :: size_
      character(kind=c_char), pointer :: chars(:)
      integer :: n, k
      if (.not. c_associated(buffer) .or. size_ < 1) return
      call c_f_pointer(buffer, chars, [int(size_)])
      n = min(len(text), int(size_) - 1)
      do k = 1, n
         chars(k) = text(k:k)
      end do
      chars(n + 1) = c_null_char
   end subroutine put_text

   !> Whether an output array of `size_` doubles holds n values; else the
   !> error names what and how many.
   logical function room(array, size_, n, what, error)
      type(c_ptr), intent(in) :: array
      integer(c_int), intent(in) :: size_
      integer, intent(in) :: n
      character(len=*), intent(in) :: what
      type(vp_error), intent(inout) :: error
      room = .false.
      if (.not. c_associated(array)) then
         call fatal_error(error%ptr, what // ": the output array is NULL")
         return
      end if
      if (size_ < n) then
         call fatal_error(error%ptr, what // ": " // to_str(n) // " values, room for " // &
            & to_str(int(size_)) // " given")
         return
      end if
      room = .true.
   end function room

   !> A length as a C int (texts beyond 2 GiB are not expected).
   pure integer(c_int) function clamp(n)
      integer, intent(in) :: n
      clamp = int(min(n, int(huge(1_c_int))), c_int)
   end function clamp

end module pavefric_api
