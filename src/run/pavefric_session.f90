!> A scene, its profile and its last results: what a handle of the C API
!> holds, usable from Fortran as well. Every step goes through the core's
!> one path: parameters through the one table (pavefric_model), as
!> namelist text or as typed values checked against the same declarations, the profile through load_scene_profile, the run
!> through run_profile, results through the output table and the file
!> through write_results. So the program, Python and the C API give the
!> same bits. No module variables: sessions are independent; their file
!> I/O alone goes one at a time (pavefric_files_lock.c), their runs in
!> parallel.
module pavefric_session
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_input, stat_internal, stat_memory
   use pavefric_format, only: to_str, to_lower
   use pavefric_namelist, only: nml_group_type, parse_namelist
   use pavefric_model, only: param_spec_type, param_set_type, parameter_table, &
      & default_parameters, apply_namelist, find_parameter, format_value, typed_value
   use pavefric_scene, only: scene_type, read_scene, scene_from_text, scene_from_parameters
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_simulate, only: sim_result_type
   use pavefric_outputs, only: output_var_type, output_table, output_present, output_values, &
      & output_metadata_type, n_outputs, dim_speed
   use pavefric_run, only: load_scene_profile, run_profile, preprocess_summary, timestamp
   use pavefric_netcdf, only: write_results
   implicit none
   private

   public :: session_type, load_session, session_from_text, session_set_parameter
   public :: session_set_value
   public :: session_get_parameter, session_set_profile, session_run, session_result_size
   public :: session_get_result, session_write, session_warnings
   public :: coordinate_names, n_scene_results, scene_results

   !> Result names besides the output table's: the coordinates of a run.
   character(len=*), parameter :: coordinate_names = "speed_kmh speed position"

   !> Results of a run that are one value for the scene (the NetCDF file's
   !> scalars; docs/outputs.md): the texture's metrics where the profile
   !> has them, the IFI where its texture depth is known, the model's own
   !> speed constant where friction falls over two speeds or more.
   integer, parameter :: n_scene_results = 6
   character(len=*), parameter :: scene_results(n_scene_results) = [character(len=14) :: &
      & "mpd", "rms_height", "rms_slope", "ifi_f60", "ifi_sp", "speed_constant"]

   interface
      !> The lock around file I/O (pavefric_files_lock.c): one file cannot be
      !> open on two Fortran units at once, and netCDF-C is not thread-safe.
      subroutine lock_files() bind(C, name="pavefric_lock_files")
      end subroutine lock_files
      subroutine unlock_files() bind(C, name="pavefric_unlock_files")
      end subroutine unlock_files
   end interface

   !> A scene with its profile and last results.
   type :: session_type
      !> The scene: namelist values, model, speeds.
      type(scene_type) :: scene
      !> Whether the scene came from text (then the profile must be set).
      logical :: from_text = .false.
      !> The scene file read (when the session came from a file): an input
      !> that session_write must never write over.
      character(len=:), allocatable :: scene_path
      !> The scene's input text, and the changes made since (one line per
      !> change, the latest of each variable): the output's input_namelist.
      character(len=:), allocatable :: input_text, changes
      !> The profile: given by session_set_profile, or the scene's file read
      !> at the first run after the scene changed.
      type(clean_profile_type) :: clean
      logical :: profile_given = .false., profile_loaded = .false.
      !> The last run's results and what the output file says besides them.
      logical :: has_results = .false.
      type(sim_result_type) :: res
      type(output_metadata_type) :: meta
   end type session_type

contains

   !> A session on the scene file `path` (read and checked as the program
   !> reads it; the profile file is read at the first run, unless a profile
   !> is set first).
   subroutine load_session(path, s, error)
      character(len=*), intent(in) :: path
      type(session_type), intent(out) :: s
      type(error_type), allocatable, intent(out) :: error
      call lock_files()
      call read_scene(path, s%scene, error)
      call unlock_files()
      s%scene_path = path
   end subroutine load_session

   !> A session on namelist text (the groups of a scene file); the profile
   !> comes from session_set_profile. &operation speeds_kmh and &surface dx
   !> are required (session_set_profile's dx then replaces dx).
   pure subroutine session_from_text(text, s, error)
      character(len=*), intent(in) :: text
      type(session_type), intent(out) :: s
      type(error_type), allocatable, intent(out) :: error
      call scene_from_text(text, "", s%scene, error, arrays=.true.)
      s%from_text = .true.
   end subroutine session_from_text

   !> Set one namelist variable, `&group name = value` (value as namelist
   !> text: `1e-3`, `.true.`, `'rounded'`, `20, 40, 60`), read by the
   !> program's reader with its checks and messages. On error the session
   !> is unchanged.
   pure subroutine session_set_parameter(s, group, name, value, error)
      type(session_type), intent(inout) :: s
      character(len=*), intent(in) :: group, name, value
      type(error_type), allocatable, intent(out) :: error
      type(nml_group_type), allocatable :: parsed(:)
      character(len=:), allocatable :: assignment
      integer :: n
      logical :: single
      assignment = "&" // to_lower(trim(adjustl(group))) // " " // to_lower(trim(adjustl(name))) &
         & // " = " // trim(adjustl(value)) // " /"
      ! exactly one assignment: a value cannot smuggle in another variable
      call parse_namelist(assignment, "", parsed, n, error)
      if (allocated(error)) then
         error%message = assignment // ": " // error%message
         return
      end if
      single = n == 1
      if (single) single = parsed(1)%n_items == 1
      if (.not. single) then
         call fatal_error(error, assignment // ": one variable and its value (or list) " // &
            & "are expected")
         return
      end if
      ! the program's reader: its checks and messages
      call change_scene(s, assignment, error)
   end subroutine session_set_parameter

   !> Set one variable to a typed value (the C API's pavefric_set_parameter_double,
   !> _int, _bool, _text and _doubles): exactly one of r, i, b, t, list,
   !> checked against the variable's declaration as the namelist reader
   !> checks it (range, choices, list length; a whole number for a real, a
   !> single number for a list), then the checks across variables. No
   !> namelist text is built or read. On error the session is unchanged.
   pure subroutine session_set_value(s, group, name, error, r, i, b, t, list)
      type(session_type), intent(inout) :: s
      character(len=*), intent(in) :: group, name
      type(error_type), allocatable, intent(out) :: error
      real(wp), intent(in), optional :: r
      integer, intent(in), optional :: i
      logical, intent(in), optional :: b
      character(len=*), intent(in), optional :: t
      real(wp), intent(in), optional :: list(:)
      type(param_spec_type), allocatable :: specs(:)
      type(param_set_type) :: set
      integer :: id
      call find_variable(group, name, specs, id, error)
      if (allocated(error)) return
      set = s%scene%parameters
      call typed_value(specs(id), set%v(id), error, r, i, b, t, list)
      if (allocated(error)) return
      ! (no longer the file's value: a check across variables must not name
      ! the file's line for it)
      set%v(id)%line = 0
      call commit_change(s, set, "! set through the API: &" // specs(id)%group // " " // &
         & specs(id)%name // " = " // format_value(specs(id), set%v(id)) // " /", error)
   end subroutine session_set_value

   !> The value of `&group name` used by the session, as namelist text
   !> ('' for an optional variable not set).
   pure subroutine session_get_parameter(s, group, name, value, error)
      type(session_type), intent(in) :: s
      character(len=*), intent(in) :: group, name
      character(len=:), allocatable, intent(out) :: value
      type(error_type), allocatable, intent(out) :: error
      type(param_spec_type), allocatable :: specs(:)
      integer :: id
      value = ""
      call find_variable(group, name, specs, id, error)
      if (allocated(error)) return
      if (s%scene%parameters%v(id)%set) value = format_value(specs(id), s%scene%parameters%v(id))
   end subroutine session_get_parameter

   !> The table and the id of `&group name` (any case, blanks around), or an
   !> error naming it.
   pure subroutine find_variable(group, name, specs, id, error)
      character(len=*), intent(in) :: group, name
      type(param_spec_type), allocatable, intent(out) :: specs(:)
      integer, intent(out) :: id
      type(error_type), allocatable, intent(out) :: error
      specs = parameter_table()
      id = find_parameter(specs, to_lower(trim(adjustl(group))), to_lower(trim(adjustl(name))))
      if (id == 0) call fatal_error(error, "&" // trim(group) // " " // trim(name) // &
         & ": unknown variable (docs/inputs.md lists them: group and name in lower case)")
   end subroutine find_variable

   !> Give the profile as heights z (m) at spacing dx (m), closed or open;
   !> dx and closed become the scene's &surface dx and closed (checked by the
   !> reader). The heights are checked here (finite), the rest at the run.
   pure subroutine session_set_profile(s, z, dx, closed, error)
      type(session_type), intent(inout) :: s
      real(wp), intent(in) :: z(:), dx
      logical, intent(in) :: closed
      type(error_type), allocatable, intent(out) :: error
      type(clean_profile_type) :: fresh
      integer :: k, stat
      if (size(z) < 1) then
         call fatal_error(error, "profile: no heights given (n = " // to_str(size(z)) // ")")
         return
      end if
      do k = 1, size(z)
         if (.not. ieee_is_finite(z(k))) then
            call fatal_error(error, "profile height " // to_str(k) // " = " // to_str(z(k)) // &
               & ": heights must be finite numbers (m)")
            return
         end if
      end do
      if (.not. (ieee_is_finite(dx) .and. dx > 0.0_wp)) then
         call fatal_error(error, "&surface dx = " // to_str(dx) // ": must be finite and > 0 " // &
            & "(the spacing of the heights, m)")
         return
      end if
      call change_scene(s, "&surface dx = " // to_str(dx) // ", closed = " // &
         & trim(merge(".true. ", ".false.", closed)) // " /", error)
      if (allocated(error)) return
      ! as Python's simulate: the heights and the spacing, no quality flags
      s%clean = fresh
      allocate(s%clean%z(size(z)), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, "profile: " // to_str(size(z)) // " heights do not fit in " // &
            & "memory", stat_memory)
         s%profile_given = .false.
         return
      end if
      s%clean%z = z
      s%clean%dx = dx
      s%profile_given = .true.
      s%profile_loaded = .false.
   end subroutine session_set_profile

   !> Change the scene by namelist text (one or more assignments), read by
   !> the program's reader into the scene's values. On error the session is
   !> unchanged.
   pure subroutine change_scene(s, text, error)
      type(session_type), intent(inout) :: s
      character(len=*), intent(in) :: text
      type(error_type), allocatable, intent(out) :: error
      type(param_spec_type), allocatable :: specs(:)
      type(param_set_type) :: set
      specs = parameter_table()
      set = s%scene%parameters
      call apply_namelist(specs, text, "", set, error)
      if (allocated(error)) then
         ! without a file the reader's messages end in the blank before its place
         error%message = trim(error%message)
         return
      end if
      call commit_change(s, set, "! set through the API: " // text, error)
   end subroutine change_scene

   !> The scene from the changed values `set` (the checks across variables
   !> and the model, as a scene file gets them), recording `line` among the
   !> changes (the output's input_namelist). No namelist text is written
   !> and read back: the values go in as they are. On error the session is
   !> unchanged.
   pure subroutine commit_change(s, set, line, error)
      type(session_type), intent(inout) :: s
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: line
      type(error_type), allocatable, intent(out) :: error
      type(param_spec_type), allocatable :: specs(:)
      type(param_set_type) :: values, defaults
      type(scene_type) :: scene
      integer :: id
      values = set
      if (.not. s%scene%is_batch) then
         ! &batch only in a batch scene: its variables set on another keep
         ! their defaults (they would make it a batch)
         specs = parameter_table()
         call default_parameters(specs, defaults, error)
         if (allocated(error)) return
         do id = 1, size(specs)
            if (specs(id)%group == "batch") values%v(id) = defaults%v(id)
         end do
      end if
      call scene_from_parameters(values, s%scene%path, s%scene%is_batch, scene, error, &
         & arrays=s%from_text)
      if (allocated(error)) return
      scene%name = s%scene%name
      ! the input as given, and the latest change of each variable changed
      ! since (one line each: a loop over values does not grow the text)
      if (.not. allocated(s%input_text)) s%input_text = s%scene%text
      call record_change(s%changes, line)
      scene%text = s%input_text
      if (len(scene%text) > 0) then
         if (scene%text(len(scene%text):) /= achar(10)) scene%text = scene%text // achar(10)
      end if
      scene%text = scene%text // s%changes
      s%scene = scene
      s%profile_loaded = .false.
      s%has_results = .false.
   end subroutine commit_change

   !> Add `line` to the change lines, replacing an earlier line that set the
   !> same variable (the same text up to its first ' = ').
   pure subroutine record_change(changes, line)
      character(len=:), allocatable, intent(inout) :: changes
      character(len=*), intent(in) :: line
      character(len=:), allocatable :: key, kept, old
      integer :: start, eol
      if (.not. allocated(changes)) changes = ""
      key = line(1:index(line, " = ") + 2)
      kept = ""
      start = 1
      do while (start <= len(changes))
         eol = index(changes(start:), achar(10)) + start - 1
         old = changes(start:eol)
         if (index(old, key) /= 1) kept = kept // old
         start = eol + 1
      end do
      changes = kept // line // achar(10)
   end subroutine record_change

   !> Run the model on the session's profile: the one the caller set, else
   !> the scene's profile file, read and preprocessed as the program does.
   subroutine session_run(s, error)
      type(session_type), intent(inout) :: s
      type(error_type), allocatable, intent(out) :: error
      s%has_results = .false.
      if (.not. (s%profile_given .or. s%profile_loaded)) then
         if (s%from_text) then
            call fatal_error(error, "profile: not set (a scene from namelist text needs " // &
               & "its heights from pavefric_set_profile / session_set_profile)")
            return
         end if
         if (s%scene%is_batch) then
            call fatal_error(error, "scene '" // s%scene%path // "' is a batch (&batch): " // &
               & "set each profile with pavefric_set_profile, or run the batch with the " // &
               & "pavefric program")
            return
         end if
         call lock_files()
         call load_scene_profile(s%scene, s%clean, error)
         call unlock_files()
         if (allocated(error)) return
         s%profile_loaded = .true.
      end if
      ! a given profile's spacing is the scene's dx (set with it, or changed since)
      if (s%profile_given) s%clean%dx = s%scene%dx
      call run_profile(s%scene, s%clean, s%res, s%meta, error)
      if (allocated(error)) return
      s%meta%title = "pavefric friction-speed curve of scene " // s%scene%name
      if (s%profile_given) then
         s%meta%profile_file = ""
      else
         s%meta%preprocess = s%clean%report
         s%meta%preprocessing = preprocess_summary(s%clean%report)
      end if
      s%has_results = .true.
   end subroutine session_run

   !> Number of values of result `name` after a run: speeds for per-speed
   !> variables and speed_kmh/speed, positions x speeds for series, positions
   !> for position; 0 when this run has no such variable (series not asked,
   !> a film that did not run); -1 when no variable has that name.
   !> Whether `name` is one of scene_results, whether the last run has it
   !> (docs/outputs.md says when each exists) and its value: the one place
   !> session_result_size and session_get_result read them.
   pure subroutine scene_scalar(s, name, is_scalar, has, value)
      type(session_type), intent(in) :: s
      character(len=*), intent(in) :: name
      logical, intent(out) :: is_scalar, has
      real(wp), intent(out) :: value
      is_scalar = .true.
      has = .false.
      value = 0.0_wp
      select case (trim(name))
      case ("mpd")
         has = s%meta%has_texture
         value = s%meta%texture%mpd
      case ("rms_height")
         has = s%meta%has_texture
         value = s%meta%texture%rms_height
      case ("rms_slope")
         has = s%meta%has_texture
         value = s%meta%texture%rms_slope
      case ("ifi_f60")
         has = s%meta%ifi%has_f60
         value = s%meta%ifi%f60
      case ("ifi_sp")
         has = s%meta%ifi%has_sp
         value = s%meta%ifi%sp_texture
      case ("speed_constant")
         has = s%meta%ifi%has_speed_constant
         value = s%meta%ifi%speed_constant
      case default
         is_scalar = .false.
      end select
      has = has .and. s%has_results
   end subroutine scene_scalar

   pure integer function session_result_size(s, name) result(n)
      type(session_type), intent(in) :: s
      character(len=*), intent(in) :: name
      type(output_var_type) :: table(n_outputs)
      integer :: k, ns
      logical :: is_scalar, has
      real(wp) :: value
      n = -1
      ns = 0
      if (s%has_results) ns = size(s%res%mu)
      select case (trim(name))
      case ("speed_kmh", "speed")
         n = ns
         return
      case ("position")
         n = 0
         if (s%has_results) then
            if (allocated(s%res%position)) n = size(s%res%position)
         end if
         return
      end select
      call scene_scalar(s, name, is_scalar, has, value)
      if (is_scalar) then
         n = merge(1, 0, has)
         return
      end if
      table = output_table()
      do k = 1, n_outputs
         if (table(k)%name /= trim(name)) cycle
         n = 0
         if (.not. s%has_results) return
         if (.not. output_present(s%res, k, table)) return
         if (table(k)%dims == dim_speed) then
            n = ns
         else
            n = ns * s%res%n_positions
         end if
         return
      end do
   end function session_result_size

   !> Values of result `name` of the last run, as reals (exact for integers
   !> and flags), in the scene's speed order; series (position, speed) with
   !> the position varying fastest. `values` must hold session_result_size.
   pure subroutine session_get_result(s, name, values, error)
      type(session_type), intent(in) :: s
      character(len=*), intent(in) :: name
      real(wp), intent(out) :: values(:)
      type(error_type), allocatable, intent(out) :: error
      type(output_var_type) :: table(n_outputs)
      integer :: k, n
      logical :: is_scalar, has
      real(wp) :: value
      character(len=:), allocatable :: known, scalars
      n = session_result_size(s, name)
      if (n < 0) then
         table = output_table()
         call names(table, known)
         call scene_names(scalars)
         call fatal_error(error, "result '" // trim(name) // "': no such variable (known: " // &
            & coordinate_names // known // scalars // ")")
         return
      end if
      if (.not. s%has_results) then
         call fatal_error(error, "result '" // trim(name) // "': no results (run first; the " // &
            & "last run failed, or the scene changed since)")
         return
      end if
      if (n == 0) then
         call fatal_error(error, "result '" // trim(name) // "': not part of this run " // &
            & "(series variables need &output series = .true.; the squeeze-film ones a " // &
            & "film that ran; mpd, rms_height and rms_slope a profile of at least one " // &
            & "100 mm segment; ifi_sp its texture depth and water on the road, ifi_f60 " // &
            & "also friction at 20 km/h or a line of it reaching within 20 km/h; " // &
            & "speed_constant " // &
            & "friction falling over two speeds or more)")
         return
      end if
      if (size(values) < n) then
         call fatal_error(error, "result '" // trim(name) // "': " // to_str(n) // &
            & " values, room for " // to_str(size(values)) // " given")
         return
      end if
      select case (trim(name))
      case ("speed_kmh")
         values(1:n) = s%res%speed_kmh
      case ("speed")
         values(1:n) = s%res%speed
      case ("position")
         values(1:n) = s%res%position
      case default
         call scene_scalar(s, name, is_scalar, has, value)
         if (is_scalar) then
            values(1) = value
            return
         end if
         table = output_table()
         do k = 1, n_outputs
            if (table(k)%name == trim(name)) call output_values(s%res, k, values, table)
         end do
      end select
   contains
      ! (subroutines, not functions of deferred length: gfortran keeps such
      ! a result's length in a static variable)
      pure subroutine scene_names(list)
         character(len=:), allocatable, intent(out) :: list
         integer :: j
         list = ""
         do j = 1, n_scene_results
            list = list // " " // trim(scene_results(j))
         end do
      end subroutine scene_names

      pure subroutine names(t, list)
         type(output_var_type), intent(in) :: t(:)
         character(len=:), allocatable, intent(out) :: list
         integer :: j
         list = ""
         do j = 1, size(t)
            list = list // " " // t(j)%name
         end do
      end subroutine names
   end subroutine session_get_result

   !> Write the last run's results to NetCDF file `path`, the program's file
   !> (a temporary file renamed when complete).
   subroutine session_write(s, path, error)
      type(session_type), intent(inout) :: s
      character(len=*), intent(in) :: path
      type(error_type), allocatable, intent(out) :: error
      if (.not. s%has_results) then
         call fatal_error(error, "&output file = '" // path // "': no results to write (run " // &
            & "first; the last run failed, or the scene changed since)")
         return
      end if
      if (len_trim(path) == 0) then
         call fatal_error(error, "&output file: an empty path")
         return
      end if
      ! write_results refuses an input of the run (the scene file, the
      ! profile file), a FIFO, a device or a directory
      if (allocated(s%scene_path)) s%meta%scene_file = s%scene_path
      s%meta%history = timestamp() // " pavefric " // pavefric_version // ": API run of scene " // &
         & s%scene%name
      call lock_files()
      call write_results(path, s%res, s%meta, error)
      call unlock_files()
   end subroutine session_write

   !> The warnings about the scene and, after a run, its results (one a line).
   pure function session_warnings(s) result(text)
      type(session_type), intent(in) :: s
      character(len=session_warnings_len(s)) :: text
      character(len=:), allocatable :: deferred_text
      call session_warnings_text(s, deferred_text)
      text = deferred_text
   end function session_warnings

   !> The length of session_warnings's text.
   pure integer function session_warnings_len(s)
      type(session_type), intent(in) :: s
      character(len=:), allocatable :: deferred_text
      call session_warnings_text(s, deferred_text)
      session_warnings_len = len(deferred_text)
   end function session_warnings_len

   !> The text of session_warnings, into a deferred-length argument.
   pure subroutine session_warnings_text(s, text)
      type(session_type), intent(in) :: s
      character(len=:), allocatable, intent(out) :: text
      text = ""
      if (s%has_results) then
         if (allocated(s%meta%warnings)) text = s%meta%warnings
      else if (allocated(s%scene%warnings)) then
         text = s%scene%warnings
      end if
   end subroutine session_warnings_text

end module pavefric_session
