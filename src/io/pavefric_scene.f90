!> A scene: one namelist file holding the surface, preprocess, pad, rubber,
!> water, operation, numerics, output and batch groups. Reading only; no
!> physics. Every variable is declared once in pavefric_model; this module
!> reads the file, applies it to the declarations' defaults, and lays the
!> values out for the program (paths resolved against the namelist's
!> directory).
module pavefric_scene
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error, stat_memory
   use pavefric_format, only: to_str
   use pavefric_model, only: model_type, param_spec_type, param_set_type, parameter_table, &
      & apply_typed, find_parameter, &
      & default_parameters, apply_namelist, model_from_parameters, validate_model, &
      & plausibility_warnings, &
      & p_profile_file, p_profile_name, p_format, p_height_unit, p_x_column, p_z_column, &
      & p_dx, p_closed, p_speeds_kmh, &
      & p_output_file, p_series, p_batch_profiles, p_batch_profile_list, p_batch_depths, &
      & p_batch_restart, p_batch_progress_every
   use pavefric_fsys, only: dir_name, base_name, join_path
   use pavefric_preprocess, only: preprocess_type, preprocess_from_values
   use pavefric_profile_file, only: not_regular
   implicit none
   private

   public :: scene_type, read_scene, scene_from_text, scene_from_parameters, read_text_file
   public :: scene_from_typed

   !> A scene read from a namelist file.
   type :: scene_type
      !> Scene name: the namelist file's name without extension.
      character(len=:), allocatable :: name
      !> The namelist file's path and its whole text.
      character(len=:), allocatable :: path, text
      !> Every variable's value (defaults included): what the output echoes.
      type(param_set_type) :: parameters
      !> Physical and numerical parameters.
      type(model_type) :: model
      !> &surface profile_file, resolved against the namelist's directory.
      character(len=:), allocatable :: profile_file
      !> &surface profile_name: which profile of a multi-profile NetCDF file.
      character(len=:), allocatable :: profile_name
      !> &surface height_unit: 'mm', 'um' or 'm'.
      character(len=:), allocatable :: height_unit
      !> &surface dx (m); -1 when not given (then the file's or 0.87e-3).
      real(wp) :: dx = -1.0_wp
      !> &surface closed: a closed CTM circle (.true.) or an open profile.
      logical :: closed = .true.
      !> &surface format, x_column, z_column.
      character(len=:), allocatable :: format, x_column, z_column
      !> &preprocess: making an instrument profile fit for analysis.
      type(preprocess_type) :: preprocess
      !> &operation speeds_kmh.
      real(wp), allocatable :: speeds_kmh(:)
      !> &output file ('' = outputs/<name>.nc) and series.
      character(len=:), allocatable :: output_file
      logical :: series = .false.
      !> Whether the scene is a batch (it has a &batch group).
      logical :: is_batch = .false.
      !> &batch profiles (pattern or directory) and profile_list, resolved
      !> against the namelist's directory.
      character(len=:), allocatable :: batch_profiles, batch_profile_list
      !> &batch depths (m); not allocated when not given (then &water depth).
      real(wp), allocatable :: batch_depths(:)
      !> &batch restart and progress_every.
      logical :: batch_restart = .true.
      integer :: batch_progress_every = 0
      !> Warnings about plausible-but-suspicious values, one a line ('' = none).
      character(len=:), allocatable :: warnings
   end type scene_type

contains

   !> Read a whole text file into one string.
   subroutine read_text_file(path, text, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      type(error_type), allocatable, intent(out) :: error
      integer :: unit, ios, fsize, stat
      character(len=512) :: msg
      character(len=:), allocatable :: what
      ! (a pipe reads as empty here, its size 0; a FIFO without a writer
      ! blocked the open forever: an attack of 2026-12-07)
      call not_regular(path, what)
      if (len(what) > 0) then
         call fatal_error(error, "'" // path // "': " // what // ", not a regular file " // &
            & "(scenes and profile lists are read from regular files only)")
         return
      end if
      open(newunit=unit, file=path, status="old", action="read", access="stream", &
         & form="unformatted", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "cannot open '" // path // "' (" // trim(msg) // ")")
         return
      end if
      inquire(unit=unit, size=fsize)
      allocate(character(len=max(fsize, 0)) :: text, stat=stat)
      if (stat /= 0) then
         close(unit)
         call fatal_error(error, "'" // path // "' (" // to_str(fsize) // " bytes) does not " // &
            & "fit in memory", stat_memory)
         return
      end if
      ios = 0
      if (fsize > 0) read(unit, iostat=ios, iomsg=msg) text
      close(unit)
      if (ios /= 0) call fatal_error(error, "cannot read '" // path // "' (" // trim(msg) // ")")
   end subroutine read_text_file

   !> Read and check a scene file.
   subroutine read_scene(path, scene, error)
      character(len=*), intent(in) :: path
      type(scene_type), intent(out) :: scene
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text
      call read_text_file(path, text, error)
      if (allocated(error)) then
         error%message = "scene file: " // error%message
         return
      end if
      call scene_from_text(text, path, scene, error)
   end subroutine read_scene

   !> A scene from namelist text; `path` names it in messages and relative
   !> paths are resolved against its directory. With `arrays`, the profile
   !> comes as arrays (Python, the C API): no profile file is required, and
   !> `path` may be empty (messages then name no file).
   pure subroutine scene_from_text(text, path, scene, error, arrays, profile_only)
      character(len=*), intent(in) :: text, path
      type(scene_type), intent(out) :: scene
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in), optional :: arrays
      !> Only the profile is wanted (&surface and &preprocess; Python's
      !> read_profile): no speeds are required.
      logical, intent(in), optional :: profile_only
      logical :: only_profile
      type(param_spec_type), allocatable :: specs(:)
      type(param_set_type) :: set
      character(len=:), allocatable :: groups

      only_profile = .false.
      if (present(profile_only)) only_profile = profile_only
      specs = parameter_table()
      call default_parameters(specs, set, error)
      if (allocated(error)) return
      if (only_profile) then
         call apply_namelist(specs, text, path, set, error, groups_seen=groups, &
            & allowed="surface preprocess")
      else
         call apply_namelist(specs, text, path, set, error, groups_seen=groups)
      end if
      if (allocated(error)) return
      call scene_from_parameters(set, path, index(groups, " batch ") > 0, scene, error, arrays, &
         & profile_only)
      scene%text = text
   end subroutine scene_from_text

   !> A scene from values given as typed items (apply_typed: the Python
   !> layer's keywords, without namelist text), over the defaults; the
   !> profile comes as arrays unless `profile_only` (then only &surface and
   !> &preprocess may be given). The scene's text is left empty (the
   !> values used are echoed from the set, as for every scene).
   pure subroutine scene_from_typed(ids, kinds, reals, counts, text, text_lengths, scene, &
         & error, profile_only)
      integer, intent(in) :: ids(:), kinds(:), counts(:), text_lengths(:)
      real(wp), intent(in) :: reals(:)
      character(len=*), intent(in) :: text
      type(scene_type), intent(out) :: scene
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in), optional :: profile_only
      type(param_spec_type), allocatable :: specs(:)
      type(param_set_type) :: set
      logical :: only_profile
      integer :: k
      only_profile = .false.
      if (present(profile_only)) only_profile = profile_only
      specs = parameter_table()
      call default_parameters(specs, set, error)
      if (allocated(error)) return
      if (only_profile) then
         do k = 1, size(ids)
            if (ids(k) < 1 .or. ids(k) > size(specs)) cycle
            if (specs(ids(k))%group /= "surface" .and. specs(ids(k))%group /= "preprocess") then
               call fatal_error(error, "&" // specs(ids(k))%group // " " // &
                  & specs(ids(k))%name // ": reading a profile takes only &surface and " // &
                  & "&preprocess variables")
               return
            end if
         end do
      end if
      call apply_typed(specs, set, ids, kinds, reals, counts, text, text_lengths, error)
      if (allocated(error)) return
      if (only_profile) then
         call scene_from_parameters(set, "", .false., scene, error, profile_only=.true.)
      else
         call scene_from_parameters(set, "", .false., scene, error, arrays=.true.)
      end if
   end subroutine scene_from_typed

   !> A scene from its variables' values (`set`, checked value by value as
   !> the namelist reader or the typed setters check them): the scene's
   !> fields, its model and the checks across variables. `path` and `arrays`
   !> as for scene_from_text; `is_batch`: the scene has a &batch group.
   !> The scene's text is left empty (its caller's to record).
   pure subroutine scene_from_parameters(set, path, is_batch, scene, error, arrays, profile_only)
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: path
      logical, intent(in) :: is_batch
      type(scene_type), intent(out) :: scene
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in), optional :: arrays, profile_only
      logical :: from_arrays, only_profile
      character(len=:), allocatable :: from
      type(param_spec_type), allocatable :: specs(:)

      from_arrays = .false.
      if (present(arrays)) from_arrays = arrays
      only_profile = .false.
      if (present(profile_only)) only_profile = profile_only
      scene%text = ""
      scene%path = path
      scene%name = base_name(path)
      if (len(path) == 0) scene%name = "arrays"
      scene%parameters = set
      scene%is_batch = is_batch
      specs = parameter_table()
      call lay_out(scene, specs)
      scene%model = model_from_parameters(scene%parameters)
      call validate_model(scene%model, error)
      if (allocated(error)) then
         ! the checks across variables name the first; where the file gave
         ! it, say where, as the checks of single values do
         call place_error(error, scene%parameters, specs, path)
         return
      end if

      if (only_profile) then
         if (len(scene%profile_file) == 0) then
            call fatal_error(error, "&surface profile_file: no profile file given")
            return
         end if
         scene%profile_file = join_path(dir_name(path), scene%profile_file)
         return
      end if
      call source_name(path, from)
      if (.not. scene%parameters%v(p_speeds_kmh)%set) then
         call fatal_error(error, "&operation speeds_kmh: not given in " // from // &
            & " (a list of sliding speeds in km/h is required)")
         return
      end if
      if (from_arrays) then
         if (scene%dx <= 0.0_wp) then
            call fatal_error(error, "&surface dx: not given (the spacing of the heights)")
            return
         end if
      else if (scene%is_batch) then
         if (len(scene%batch_profiles) == 0 .eqv. len(scene%batch_profile_list) == 0) then
            call fatal_error(error, "&batch: give exactly one of profiles (a pattern or " // &
               & "directory) and profile_list (a file) in " // from)
            return
         end if
         if (len(scene%batch_profiles) > 0) scene%batch_profiles = &
            & join_path(dir_name(path), scene%batch_profiles)
         if (len(scene%batch_profile_list) > 0) scene%batch_profile_list = &
            & join_path(dir_name(path), scene%batch_profile_list)
      else
         if (len(scene%profile_file) == 0) then
            call fatal_error(error, "&surface profile_file: not given in " // from // &
               & "; give the profile, e.g. &surface profile_file = 'profile.txt' " // &
               & "(relative to the scene's directory), or a &batch group to run many profiles")
            return
         end if
         scene%profile_file = join_path(dir_name(path), scene%profile_file)
      end if
      call plausibility_warnings(specs, scene%parameters, scene%warnings)
   end subroutine scene_from_parameters

   !> How a message names where the scene came from: its file, quoted, or
   !> "the scene text" for a scene given as text (pavefric_new_scene, Python's
   !> keywords), which has no file.
   !> (A subroutine: a function returning a deferred length keeps a hidden
   !> static per call site, docs/api.md.)
   pure subroutine source_name(path, name)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: name
      if (len(path) == 0) then
         name = "the scene text"
      else
         name = "'" // path // "'"
      end if
   end subroutine source_name

   !> The scene's fields from its parameter values.
   pure subroutine lay_out(scene, specs)
      type(scene_type), intent(inout) :: scene
      !> The table (parameter_table): preprocessing reads its own variables by name.
      type(param_spec_type), intent(in) :: specs(:)
      associate(v => scene%parameters%v)
         scene%profile_file = v(p_profile_file)%t
         scene%profile_name = v(p_profile_name)%t
         scene%format = v(p_format)%t
         scene%height_unit = v(p_height_unit)%t
         scene%x_column = v(p_x_column)%t
         scene%z_column = v(p_z_column)%t
         scene%dx = -1.0_wp
         if (v(p_dx)%set) scene%dx = v(p_dx)%r
         scene%closed = v(p_closed)%b
         scene%preprocess = preprocess_from_values(specs, v)
         if (v(p_speeds_kmh)%set) scene%speeds_kmh = v(p_speeds_kmh)%list
         scene%output_file = v(p_output_file)%t
         scene%series = v(p_series)%b
         scene%batch_profiles = v(p_batch_profiles)%t
         scene%batch_profile_list = v(p_batch_profile_list)%t
         if (v(p_batch_depths)%set) scene%batch_depths = v(p_batch_depths)%list
         scene%batch_restart = v(p_batch_restart)%b
         scene%batch_progress_every = v(p_batch_progress_every)%i
      end associate
      if (.not. allocated(scene%warnings)) scene%warnings = ""
   end subroutine lay_out

   !> An error whose message begins "&group name" about a variable the
   !> file `path` gave on a line: " at path:line" added.
   pure subroutine place_error(error, set, specs, path)
      type(error_type), intent(inout) :: error
      type(param_set_type), intent(in) :: set
      type(param_spec_type), intent(in) :: specs(:)
      character(len=*), intent(in) :: path
      integer :: space, stop, k
      if (len(path) == 0 .or. len(error%message) < 2) return
      if (error%message(1:1) /= "&") return
      ! "&group name" and what follows the name (" =", "(", ":" or " ")
      space = index(error%message, " ")
      if (space < 3) return
      stop = scan(error%message(space + 1:), " =(:")
      if (stop == 0) stop = len(error%message) - space + 1
      k = find_parameter(specs, error%message(2:space - 1), &
         & error%message(space + 1:space + stop - 1))
      if (k == 0 .or. k > size(set%v)) return
      if (set%v(k)%line > 0 .and. index(error%message, " at " // path // ":") == 0) &
         & error%message = error%message // " at " // path // ":" // to_str(set%v(k)%line)
   end subroutine place_error

end module pavefric_scene
