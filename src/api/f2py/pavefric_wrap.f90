!> The f2py boundary: plain subroutines with explicit-shape C-typed arrays,
!> explicit sizes, a status and a message. No derived types, allocatables or
!> module state cross it; nothing here can stop the Python process.
!> (real(c_double), not real(wp): f2py maps kind parameters it does not know
!> to C float and returns wrong numbers in silence.)





!> The version of the core and its constants: the spacing of a Circular
!> Track Meter profile (m), the default dx.
subroutine pf_version(version, ctm_dx_out)
   use, intrinsic :: iso_c_binding, only: c_double
   use pavefric_kinds, only: pavefric_version
   use pavefric_run, only: ctm_dx
   implicit none
   character(len=32), intent(out) :: version
   real(c_double), intent(out) :: ctm_dx_out
   version = pavefric_version
   ctm_dx_out = ctm_dx
end subroutine pf_version

!> What a road can be, beyond the declared ranges of the inputs: the RMS
!> height of a texture profile (m) and the largest friction coefficient;
!> outside them a run warns (docs/inputs.md).
subroutine pf_plausibility(rms_low, rms_high, mu_high)
   use, intrinsic :: iso_c_binding, only: c_double
   use pavefric_run, only: rms_plausible_low, rms_plausible_high, mu_plausible_high
   implicit none
   real(c_double), intent(out) :: rms_low, rms_high, mu_high
   rms_low = rms_plausible_low
   rms_high = rms_plausible_high
   mu_high = mu_plausible_high
end subroutine pf_plausibility

!> Number of declared namelist variables and groups (pavefric_model).
subroutine pf_parameter_count(n_parameters_out, n_groups_out)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_model, only: n_parameters, n_groups
   implicit none
   integer(c_int), intent(out) :: n_parameters_out, n_groups_out
   n_parameters_out = n_parameters
   n_groups_out = n_groups
end subroutine pf_parameter_count

!> The declaration of variable i (1-based): texts, kind (1 real, 2 integer,
!> 3 logical, 4 text, 5 list of reals), hard and plausible ranges.
subroutine pf_parameter_info(i, group, name, keyword, scope, unit, default_text, choices, meaning, &
      & kind, bounds, strict, max_values, required)
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use pavefric_model, only: param_spec_type, parameter_table
   implicit none
   integer(c_int), intent(in) :: i
   character(len=32), intent(out) :: group, name, keyword, scope, unit
   character(len=64), intent(out) :: default_text
   character(len=256), intent(out) :: choices
   character(len=4096), intent(out) :: meaning
   integer(c_int), intent(out) :: kind, strict(2), max_values, required
   real(c_double), intent(out) :: bounds(4)
   type(param_spec_type), allocatable :: specs(:)
   specs = parameter_table()
   group = ""; name = ""; keyword = ""; scope = ""; unit = ""; default_text = ""; choices = ""
   meaning = ""; kind = 0; strict = 0; max_values = 0; required = 0; bounds = 0
   if (i < 1 .or. i > size(specs)) return
   associate(sp => specs(i))
      group = sp%group; name = sp%name; keyword = sp%keyword; scope = sp%scope
      unit = sp%unit; default_text = sp%default; choices = sp%choices; meaning = sp%meaning
      kind = sp%kind
      bounds = [sp%lower, sp%upper, sp%plausible_lower, sp%plausible_upper]
      strict = merge(1, 0, [sp%lower_strict, sp%upper_strict])
      max_values = sp%max_values
      required = merge(1, 0, sp%required)
   end associate
end subroutine pf_parameter_info

!> Namelist group i (1-based): name, title and description.
subroutine pf_group_info(i, name, title, description)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_model, only: group_spec_type, group_table, n_groups
   implicit none
   integer(c_int), intent(in) :: i
   character(len=32), intent(out) :: name
   character(len=128), intent(out) :: title
   character(len=4096), intent(out) :: description
   type(group_spec_type) :: g(n_groups)
   name = ""; title = ""; description = ""
   if (i < 1 .or. i > n_groups) return
   g = group_table()
   name = g(i)%name; title = g(i)%title; description = g(i)%description
end subroutine pf_group_info

!> Number of result variables (pavefric_outputs).
subroutine pf_output_count(n)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_outputs, only: n_outputs
   implicit none
   integer(c_int), intent(out) :: n
   n = n_outputs
end subroutine pf_output_count

!> Result variable i (1-based): name, units, long name (a few words, the
!> NetCDF long_name), description (whole, the NetCDF comment where longer),
!> type (1 double, 2 int64, 3 int, 4 flag), dimensions (1 speed, 2 position
!> x speed), when it is written and the component that declares it.
subroutine pf_output_info(i, name, units, long_name, description, var_type, dims, written, &
      & owner)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_outputs, only: output_var_type, output_table, n_outputs, output_condition
   implicit none
   integer(c_int), intent(in) :: i
   character(len=64), intent(out) :: name, units, owner
   character(len=4096), intent(out) :: long_name, description, written
   integer(c_int), intent(out) :: var_type, dims
   type(output_var_type) :: t(n_outputs)
   name = ""; units = ""; long_name = ""; description = ""; var_type = 0; dims = 0
   written = ""; owner = ""
   if (i < 1 .or. i > n_outputs) return
   t = output_table()
   name = t(i)%name; units = t(i)%units; long_name = t(i)%short; owner = t(i)%owner
   description = t(i)%long_name
   var_type = t(i)%type; dims = t(i)%dims
   written = output_condition(i)
end subroutine pf_output_info

!> Scalar i (1-based) of a scene's file (pavefric_outputs' scalar_table:
!> mpd, rms_height, rms_slope, ifi_f60, ifi_sp, speed_constant): name,
!> units, long name (a few words) and description (whole); n the count.
subroutine pf_scalar_info(i, n, name, units, long_name, description)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_outputs, only: output_var_type, scalar_table, n_scalar_outputs
   implicit none
   integer(c_int), intent(in) :: i
   integer(c_int), intent(out) :: n
   character(len=64), intent(out) :: name, units
   character(len=1024), intent(out) :: long_name, description
   type(output_var_type) :: t(n_scalar_outputs)
   n = n_scalar_outputs
   name = ""; units = ""; long_name = ""; description = ""
   if (i < 1 .or. i > n_scalar_outputs) return
   t = scalar_table()
   name = t(i)%name; units = t(i)%units; long_name = t(i)%short
   description = t(i)%long_name
end subroutine pf_scalar_info

!> The friction table the program prints for a scene (pavefric_format's
!> friction_table_text), from a scene file's values: `python -m pavefric run`
!> prints the same text. has_err: the last column (err) is printed.
subroutine pf_friction_table(ns, elements, positions, effects, speed_kmh, mu, wet, &
      & hydroplaning, err, has_err, text, length)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_format, only: friction_table_text
   implicit none
   integer(c_int), intent(in) :: ns, elements, positions, has_err
   character(len=*), intent(in) :: effects
   real(c_double), intent(in) :: speed_kmh(ns), mu(ns), wet(ns), hydroplaning(ns), err(ns)
   character(len=8192), intent(out) :: text
   integer(c_int), intent(out) :: length
   character(len=:), allocatable :: table
   if (has_err /= 0) then
      call friction_table_text(elements, positions, effects, speed_kmh, mu, wet, &
         & hydroplaning, table, err)
   else
      call friction_table_text(elements, positions, effects, speed_kmh, mu, wet, &
         & hydroplaning, table)
   end if
   length = len(table)
   text = table
end subroutine pf_friction_table

!> Pad elements and averaged positions of a profile of np points for the
!> settings (typed items, as pf_simulate takes them), and the number of
!> series variables such a run produces, to size the series.
subroutine pf_layout(t_n, t_ids, t_kinds, t_counts, t_lengths, t_nreal, t_reals, t_text, np, &
      & n_elements, n_positions, n_series, status, message)
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use pavefric_scene, only: scene_type, scene_from_typed
   use pavefric_simulate, only: pad_elements, element_grid
   use pavefric_outputs, only: series_count
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type
   implicit none
   !> The settings as typed items (pavefric_model's apply_typed): variable
   !> ids (1-based, the table's order), kinds, numbers per item and text
   !> characters per item, the numbers and the text.
   integer(c_int), intent(in) :: t_n, t_nreal
   integer(c_int), intent(in) :: t_ids(t_n), t_kinds(t_n), t_counts(t_n), t_lengths(t_n)
   real(c_double), intent(in) :: t_reals(t_nreal)
   character(len=*), intent(in) :: t_text
   integer(c_int), intent(in) :: np
   integer(c_int), intent(out) :: n_elements, n_positions, n_series, status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   integer :: npe
   real(wp) :: dxe
   n_elements = 0; n_positions = 0; n_series = 0; status = 0; message = ""
   call scene_from_typed(t_ids, t_kinds, t_reals, t_counts, t_text, t_lengths, scene, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   call element_grid(scene%model, np, scene%dx, scene%closed, npe, dxe, positions=n_positions)
   n_elements = pad_elements(scene%model, dxe)
   n_series = series_count(scene%model)
end subroutine pf_layout

!> The cost of running pf_simulate on heights z (m) with these settings,
!> before it runs: estimate = element-steps (all speeds, first pass), bytes,
!> seconds on one thread (the program's calibrated rate; with &numerics
!> tolerance, the guess of all its refinement's passes where that is more:
!> what the announcement weighs), the seconds refining the pad; `text` the
!> program's announcement line. A run that would not fit in memory is
!> refused here (status, message), as by the run.
subroutine pf_estimate(np, z, t_n, t_ids, t_kinds, t_counts, t_lengths, t_nreal, t_reals, &
      & t_text, estimate, text, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, scene_from_typed
   use pavefric_simulate, only: cost_estimate_type
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_run, only: checked_estimate
   use pavefric_error, only: error_type
   implicit none
   integer(c_int), intent(in) :: np
   real(c_double), intent(in) :: z(np)
   !> The settings as typed items (as pf_simulate takes them).
   integer(c_int), intent(in) :: t_n, t_nreal
   integer(c_int), intent(in) :: t_ids(t_n), t_kinds(t_n), t_counts(t_n), t_lengths(t_n)
   real(c_double), intent(in) :: t_reals(t_nreal)
   character(len=*), intent(in) :: t_text
   !> Element-steps, bytes, seconds on one thread, and the seconds of them
   !> that refine the pad (pf_simulate's `forecast`: the probe then runs once).
   real(c_double), intent(out) :: estimate(4)
   character(len=1024), intent(out) :: text
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(clean_profile_type) :: clean
   type(cost_estimate_type) :: cost
   type(error_type), allocatable :: error
   character(len=:), allocatable :: line
   estimate = 0; text = ""; status = 0; message = ""
   call scene_from_typed(t_ids, t_kinds, t_reals, t_counts, t_text, t_lengths, scene, error)
   if (allocated(error)) goto 99
   clean%z = z
   clean%dx = scene%dx
   call checked_estimate(scene, clean, cost, line, error)
   if (allocated(error)) goto 99
   text = line
   ! (the seconds the announcement weighs: with a tolerance, its guessed
   ! refinement's where they are more)
   estimate = [real(cost%total_element_steps, c_double), cost%bytes, &
      & max(cost%seconds, cost%tolerance_seconds), cost%refine_seconds]
99 continue
   if (allocated(error)) then
      status = error%stat
      message = error%message
   end if
end subroutine pf_estimate

!> Run the model on heights z (m) with the settings as typed items (t_*:
!> &surface dx and closed, &operation speeds_kmh, &output series and any
!> model variable, checked by their declarations): the same run as the
!> program's (pavefric_run's run_profile). Results come through the output
!> table: per-speed values(ns, n_outputs) and, for the series variables
!> this run produced in the table's order, series(npos, ns, nser) (nser from
!> pf_layout); present(k) /= 0 for the variables this run produced. Texts
!> (effects, warnings, parameters used) come in `texts` with their lengths;
!> when they do not fit, text_lengths says how much room to give and status
!> is 0 (call again); when the series have more positions than npos (a
!> tolerance run refined the step), counts(2) says how many, status 0.
subroutine pf_simulate(np, z, t_n, t_ids, t_kinds, t_counts, t_lengths, t_nreal, t_reals, t_text, &
      & ns, npos, nout, nser, ntext, speed, speed_kmh, values, &
      & forecast, series, present, position, counts, texture, estimate, ifi, texts, &
      & text_lengths, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_kinds, only: wp
   use pavefric_scene, only: scene_type, scene_from_typed
   use pavefric_simulate, only: sim_result_type
   use pavefric_outputs, only: output_metadata_type, output_present, output_values, n_outputs, &
      & output_var_type, output_table, dim_speed
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_run, only: run_profile
   use pavefric_error, only: error_type, stat_internal, stat_memory
   implicit none
   integer(c_int), intent(in) :: np, ns, npos, nout, nser, ntext
   real(c_double), intent(in) :: z(np)
   !> pf_estimate's seconds that refine the pad, recorded as they are (the
   !> probe behind them not run again); < 0: the run probes the profile.
   real(c_double), intent(in) :: forecast
   !> The settings as typed items (pavefric_model's apply_typed): variable
   !> ids (1-based, the table's order), kinds, numbers per item and text
   !> characters per item, the numbers and the text.
   integer(c_int), intent(in) :: t_n, t_nreal
   integer(c_int), intent(in) :: t_ids(t_n), t_kinds(t_n), t_counts(t_n), t_lengths(t_n)
   real(c_double), intent(in) :: t_reals(t_nreal)
   character(len=*), intent(in) :: t_text
   real(c_double), intent(out) :: speed(ns), speed_kmh(ns), values(ns, nout)
   real(c_double), intent(out) :: series(npos, ns, nser), position(npos), texture(3)
   !> The cost estimated before the run: element-steps (all speeds, first
   !> pass), bytes, seconds on one thread; and the spacing of the pad's
   !> elements (m, &pad element_length as resampled).
   real(c_double), intent(out) :: estimate(4)
   !> ASTM E1960: has F60 (1/0), F60, Sp from MPD (km/h), has the model's
   !> speed constant (1/0), that constant (km/h), has Sp (1/0).
   real(c_double), intent(out) :: ifi(6)
   integer(c_int), intent(out) :: present(nout), counts(6), text_lengths(3), status
   character, intent(out) :: texts(ntext)
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(clean_profile_type) :: clean
   type(sim_result_type) :: res
   type(output_metadata_type) :: meta
   type(error_type), allocatable :: error
   type(output_var_type) :: table(n_outputs)
   real(wp), allocatable :: v(:)
   character(len=:), allocatable :: joined
   integer :: k, n_pos, c, slot

   speed = 0; speed_kmh = 0; values = 0; series = 0; present = 0; position = 0; texture = 0
   estimate = 0; ifi = 0; counts = 0; text_lengths = 0; texts = " "; status = 0; message = ""
   call scene_from_typed(t_ids, t_kinds, t_reals, t_counts, t_text, t_lengths, scene, error)
   if (allocated(error)) goto 99
   if (size(scene%speeds_kmh) /= ns .or. nout /= n_outputs) then
      status = stat_internal
      message = "internal: pf_simulate sized for another number of speeds or outputs"
      return
   end if
   clean%z = z
   clean%dx = scene%dx
   call run_profile(scene, clean, res, meta, error, real(forecast, wp))
   if (allocated(error)) goto 99
   n_pos = 0
   if (scene%series) n_pos = res%n_positions
   if (scene%series .and. npos /= n_pos) then
      ! sized from pf_layout at the scene's substeps; with &numerics
      ! tolerance the run chose finer steps (more positions): say how many,
      ! status 0, and the caller calls again with room for them
      counts(2) = n_pos
      return
   end if
   speed = res%speed
   speed_kmh = res%speed_kmh
   table = output_table()
   allocate(v(max(ns, ns * max(n_pos, 1))), stat=c)
   if (c /= 0) then
      status = stat_memory
      message = "not enough memory to return the results"
      return
   end if
   slot = 0
   do k = 1, n_outputs
      if (.not. output_present(res, k, table)) cycle
      present(k) = 1
      call output_values(res, k, v, table)
      if (table(k)%dims == dim_speed) then
         values(:, k) = v(1:ns)
      else
         slot = slot + 1
         if (slot > nser) then
            status = stat_internal
            message = "internal: pf_simulate sized for fewer series variables"
            return
         end if
         series(:, :, slot) = reshape(v(1:n_pos*ns), [n_pos, ns])
      end if
   end do
   if (scene%series) position = res%position
   counts = [res%n_elements, res%n_positions, res%n_spinup, merge(1, 0, meta%has_texture), &
      & meta%texture%n_segments, meta%texture%n_valid]
   estimate = [real(res%estimate%total_element_steps, c_double), res%estimate%bytes, &
      & res%estimate%seconds, real(res%element_spacing, c_double)]
   ifi = [merge(1.0_c_double, 0.0_c_double, meta%ifi%has_f60), meta%ifi%f60, &
      & meta%ifi%sp_texture, merge(1.0_c_double, 0.0_c_double, meta%ifi%has_speed_constant), &
      & meta%ifi%speed_constant, merge(1.0_c_double, 0.0_c_double, meta%ifi%has_sp)]
   if (meta%has_texture) texture = [meta%texture%mpd, meta%texture%rms_height, &
      & meta%texture%rms_slope]
   joined = res%effects // meta%warnings // meta%parameters_text
   text_lengths = [len(res%effects), len(meta%warnings), len(meta%parameters_text)]
   if (len(joined) <= ntext) then
      do c = 1, len(joined)
         texts(c) = joined(c:c)
      end do
   end if
99 continue
   if (allocated(error)) then
      status = error%stat
      message = error%message
   end if
end subroutine pf_simulate

!> The cost of running a scene file (not a batch), before it runs: its scene
!> and profile are read and preprocessed as the run does; estimate and text
!> as pf_estimate's. A scene that cannot be read gives status /= 0 (the run
!> then reports why, in its own order of checks).
subroutine pf_scene_estimate(path, estimate, text, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_simulate, only: cost_estimate_type
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_run, only: checked_estimate, load_scene_profile
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   real(c_double), intent(out) :: estimate(4)
   character(len=1024), intent(out) :: text
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(clean_profile_type) :: clean
   type(cost_estimate_type) :: cost
   type(error_type), allocatable :: error
   character(len=:), allocatable :: line
   estimate = 0; text = ""; status = 0; message = ""
   call read_scene(path, scene, error)
   if (allocated(error)) goto 99
   call load_scene_profile(scene, clean, error)
   if (allocated(error)) goto 99
   call checked_estimate(scene, clean, cost, line, error)
   if (allocated(error)) goto 99
   text = line
   estimate = [real(cost%total_element_steps, c_double), cost%bytes, &
      & max(cost%seconds, cost%tolerance_seconds), cost%refine_seconds]
99 continue
   if (allocated(error)) then
      status = error%stat
      message = error%message
   end if
end subroutine pf_scene_estimate

!> Run a scene file and write its NetCDF output, as the program does; the
!> warnings recorded in it come back in `warnings` (lines, truncated).
subroutine pf_run_scene(path, output, command, forecast, out_path, warnings, status, message)
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use pavefric_kinds, only: wp
   use pavefric_run, only: run_scene
   use pavefric_simulate, only: sim_result_type
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, output, command
   !> pf_scene_estimate's seconds that refine the pad (< 0: the run probes).
   real(c_double), intent(in) :: forecast
   character(len=4096), intent(out) :: out_path
   character(len=8192), intent(out) :: warnings
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(sim_result_type) :: res
   type(error_type), allocatable :: error
   character(len=:), allocatable :: written, warned
   status = 0
   message = ""
   out_path = ""
   warnings = ""
   call run_scene(path, output, command, written, res, error, warnings=warned, &
      & refine_seconds=real(forecast, wp))
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   out_path = written
   if (allocated(warned)) warnings = warned
end subroutine pf_run_scene

!> Read a scene file and its profile as the program does (first pass):
!> sizes, spacing, and the length of the parameters text.
subroutine pf_scene_info(path, np, ns, dx, closed, series, ntext, profile_file, output_file, &
      & status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_run, only: load_scene_profile
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_model, only: parameters_namelist, parameter_table
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(out) :: np, ns, closed, series, ntext, status
   real(c_double), intent(out) :: dx
   character(len=4096), intent(out) :: profile_file, output_file
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   type(clean_profile_type) :: clean
   np = 0; ns = 0; dx = 0; closed = 0; series = 0; ntext = 0; status = 0; message = ""
   profile_file = ""; output_file = ""
   call read_scene(path, scene, error)
   if (.not. allocated(error)) call load_scene_profile(scene, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   np = size(clean%z)
   dx = clean%dx
   ns = size(scene%speeds_kmh)
   closed = merge(1, 0, scene%closed)
   series = merge(1, 0, scene%series)
   ntext = len(parameters_namelist(parameter_table(), scene%parameters))
   profile_file = scene%profile_file
   output_file = scene%output_file
end subroutine pf_scene_info

!> Heights (m), speeds (km/h) and the parameters used (a namelist text) of
!> a scene file (second pass).
subroutine pf_scene_arrays(path, np, ns, ntext, z, speeds_kmh, text, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_run, only: load_scene_profile
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_model, only: parameters_namelist, parameter_table
   use pavefric_error, only: error_type, stat_internal
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(in) :: np, ns, ntext
   real(c_double), intent(out) :: z(np), speeds_kmh(ns)
   character, intent(out) :: text(ntext)
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   type(clean_profile_type) :: clean
   character(len=:), allocatable :: t
   integer :: c
   z = 0; speeds_kmh = 0; text = " "; status = 0; message = ""
   call read_scene(path, scene, error)
   if (.not. allocated(error)) call load_scene_profile(scene, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   t = parameters_namelist(parameter_table(), scene%parameters)
   if (size(clean%z) /= np .or. size(scene%speeds_kmh) /= ns .or. len(t) /= ntext) then
      status = stat_internal
      message = "scene '" // trim(path) // "' changed while it was read"
      return
   end if
   z = clean%z
   speeds_kmh = scene%speeds_kmh
   do c = 1, ntext
      text(c) = t(c:c)
   end do
end subroutine pf_scene_arrays



!> The bearing load (Eq. 15) and its derivative for arrays of outlet films.
!> The core's WLF shift log10 a_T of each temperature (maxwell.f90), for
!> Python's shifting of DMA data onto a master curve. why(i): 0 usable,
!> 1 T - Tref <= -C2 (the equation diverges), 2 more than 100 decades.
subroutine pf_wlf_log10_shift(n, temperature, reference, c1, c2, log_at, why)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_maxwell, only: wlf_log10_shift, wlf_check
   implicit none
   integer(c_int), intent(in) :: n
   real(c_double), intent(in) :: temperature(n), reference, c1, c2
   real(c_double), intent(out) :: log_at(n)
   integer(c_int), intent(out) :: why(n)
   integer :: i
   do i = 1, n
      log_at(i) = wlf_log10_shift(temperature(i), reference, c1, c2)
      select case (wlf_check(temperature(i), reference, c1, c2))
      case ("")
         why(i) = 0
      case ("diverges")
         why(i) = 1
      case default
         why(i) = 2
      end select
   end do
end subroutine pf_wlf_log10_shift

subroutine pf_hydro_load(n, prefactor, h_in, h_out, wh, dwh_dhout)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_bearing, only: hydro_load
   implicit none
   integer(c_int), intent(in) :: n
   real(c_double), intent(in) :: prefactor, h_in, h_out(n)
   real(c_double), intent(out) :: wh(n), dwh_dhout(n)
   integer :: i
   do i = 1, n
      call hydro_load(prefactor, h_in, h_out(i), wh(i), dwh_dhout(i))
   end do
end subroutine pf_hydro_load



!> Texture metrics of heights z (m): MPD (m), segments used, RMS height (m),
!> RMS slope; msd holds each segment's depth (size nseg_max).
subroutine pf_texture(np, z, dx, closed, segment_length, slope_suppression, nseg_max, &
      & use_quality, dropout_fraction, spike, mpd, n_segments, n_valid, rms_height, rms_slope, &
      & msd, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_texture, only: texture_type, texture_metrics
   use pavefric_error, only: error_type
   implicit none
   integer(c_int), intent(in) :: np, closed, slope_suppression, nseg_max, use_quality
   real(c_double), intent(in) :: z(np), dx, segment_length, dropout_fraction(np)
   integer(c_int), intent(in) :: spike(np)
   real(c_double), intent(out) :: mpd, rms_height, rms_slope, msd(nseg_max)
   integer(c_int), intent(out) :: n_segments, n_valid, status
   character(len=2048), intent(out) :: message
   type(texture_type) :: tex
   type(error_type), allocatable :: error
   mpd = 0; rms_height = 0; rms_slope = 0; msd = 0; n_segments = 0; n_valid = 0
   status = 0; message = ""
   if (use_quality /= 0) then
      call texture_metrics(z, dx, closed /= 0, segment_length, slope_suppression /= 0, tex, &
         & error, dropout_fraction=dropout_fraction, spike=spike /= 0, msd=msd)
   else
      call texture_metrics(z, dx, closed /= 0, segment_length, slope_suppression /= 0, tex, &
         & error, msd=msd)
   end if
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   mpd = tex%mpd
   n_segments = tex%n_segments
   n_valid = tex%n_valid
   rms_height = tex%rms_height
   rms_slope = tex%rms_slope
end subroutine pf_texture

!> Whether a scene file is a batch (it has a &batch group).
subroutine pf_scene_is_batch(path, is_batch, status, message)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(out) :: is_batch, status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   is_batch = 0; status = 0; message = ""
   call read_scene(path, scene, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   is_batch = merge(1, 0, scene%is_batch)
end subroutine pf_scene_is_batch

!> Compute up to max_count profiles of a batch not yet in its journal (all
!> when max_count <= 0); write the NetCDF file once every profile is done.
subroutine pf_batch_run(path, output, command, max_count, out_path, computed, finished, &
      & n_total, n_done, status, message)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_batch_run, only: run_batch_serial
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, output, command
   integer(c_int), intent(in) :: max_count
   character(len=4096), intent(out) :: out_path
   integer(c_int), intent(out) :: computed, finished, n_total, n_done, status
   character(len=2048), intent(out) :: message
   type(error_type), allocatable :: error
   character(len=:), allocatable :: written
   logical :: done
   integer :: c, nt, nd
   out_path = ""; computed = 0; finished = 0; n_total = 0; n_done = 0; status = 0; message = ""
   call run_batch_serial(path, output, command, -1, max_count, written, c, done, error, nt, nd)
   if (allocated(written)) out_path = written
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   computed = c
   finished = merge(1, 0, done)
   n_total = nt
   n_done = nd
end subroutine pf_batch_run

! ---------------------------------------------------------------------------
! Profile input (the profiles branch): reading any format, NetCDF profile
! files of many profiles, and the reading benchmark. Python glue:
! python/pavefric/profiles.py.
! ---------------------------------------------------------------------------

!> Read and preprocess a profile (first pass): sizes and spacing.
!> Read and preprocess a profile file as a scene does (first pass): the
!> settings are typed items of &surface (profile_file, format, height_unit,
!> x_column, z_column, profile_name, dx) and &preprocess, checked by the
!> same declarations as a scene file's, and the profile by the program's own routine
!> (pavefric_run's load_scene_profile). Sizes and spacing.
subroutine pf_profile_read_info(t_n, t_ids, t_kinds, t_counts, t_lengths, t_nreal, t_reals, &
      & t_text, n_raw, n_out, dx, has_x, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, scene_from_typed
   use pavefric_run, only: load_scene_profile
   use pavefric_profile, only: raw_profile_type
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_error, only: error_type
   implicit none
   !> The settings as typed items (pavefric_model's apply_typed): variable
   !> ids (1-based, the table's order), kinds, numbers per item and text
   !> characters per item, the numbers and the text.
   integer(c_int), intent(in) :: t_n, t_nreal
   integer(c_int), intent(in) :: t_ids(t_n), t_kinds(t_n), t_counts(t_n), t_lengths(t_n)
   real(c_double), intent(in) :: t_reals(t_nreal)
   character(len=*), intent(in) :: t_text
   integer(c_int), intent(out) :: n_raw, n_out, has_x, status
   real(c_double), intent(out) :: dx
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(error_type), allocatable :: error
   n_raw = 0; n_out = 0; dx = 0; has_x = 0; status = 0; message = ""
   call scene_from_typed(t_ids, t_kinds, t_reals, t_counts, t_text, t_lengths, scene, error, &
      & profile_only=.true.)
   if (.not. allocated(error)) call load_scene_profile(scene, clean, error, raw_out=raw)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   n_raw = size(raw%z)
   n_out = size(clean%z)
   dx = clean%dx
   has_x = merge(1, 0, raw%has_x)
end subroutine pf_profile_read_info

!> Read and preprocess a profile (second pass): the raw points (distances
!> from the file, else from its spacing), the clean heights (m), their
!> quality, and the report.
subroutine pf_profile_read_data(t_n, t_ids, t_kinds, t_counts, t_lengths, t_nreal, t_reals, &
      & t_text, n_raw, n_out, x_raw, z_raw, valid_raw, z, &
      & dropout_fraction, spike, counts, format_read, chainage, has_chainage, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_scene, only: scene_type, scene_from_typed
   use pavefric_run, only: load_scene_profile
   use pavefric_profile, only: raw_profile_type
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_error, only: error_type, stat_internal
   implicit none
   !> The settings as typed items (pavefric_model's apply_typed): variable
   !> ids (1-based, the table's order), kinds, numbers per item and text
   !> characters per item, the numbers and the text.
   integer(c_int), intent(in) :: t_n, t_nreal
   integer(c_int), intent(in) :: t_ids(t_n), t_kinds(t_n), t_counts(t_n), t_lengths(t_n)
   real(c_double), intent(in) :: t_reals(t_nreal)
   character(len=*), intent(in) :: t_text
   integer(c_int), intent(in) :: n_raw, n_out
   real(c_double), intent(out) :: x_raw(n_raw), z_raw(n_raw), z(n_out), dropout_fraction(n_out)
   real(c_double), intent(out) :: chainage
   integer(c_int), intent(out) :: valid_raw(n_raw), spike(n_out), counts(8), has_chainage, status
   character(len=16), intent(out) :: format_read
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(error_type), allocatable :: error
   integer :: i
   x_raw = 0; z_raw = 0; valid_raw = 0; z = 0; dropout_fraction = 0; spike = 0; counts = 0
   chainage = 0; has_chainage = 0; status = 0; message = ""; format_read = ""
   call scene_from_typed(t_ids, t_kinds, t_reals, t_counts, t_text, t_lengths, scene, error, &
      & profile_only=.true.)
   if (.not. allocated(error)) call load_scene_profile(scene, clean, error, raw_out=raw)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   if (size(raw%z) /= n_raw .or. size(clean%z) /= n_out) then
      status = stat_internal
      message = "'" // scene%profile_file // "' changed while it was read"
      return
   end if
   if (raw%has_x) then
      x_raw = raw%x
   else
      do i = 1, n_raw
         x_raw(i) = real(i - 1, c_double) * clean%report%dx_in
      end do
   end if
   z_raw = raw%z
   valid_raw = merge(1, 0, raw%valid)
   z = clean%z
   dropout_fraction = clean%dropout_fraction
   spike = merge(1, 0, clean%spike)
   counts = [clean%report%points_read, clean%report%trimmed_start, clean%report%trimmed_end, &
      & clean%report%dropouts, clean%report%spikes, clean%report%points_out, &
      & merge(1, 0, clean%report%resampled), merge(1, 0, clean%report%filtered)]
   format_read = clean%report%format
   if (raw%has_chainage) then
      has_chainage = 1
      chainage = raw%chainage
   end if
end subroutine pf_profile_read_data

!> How many profiles a NetCDF profile file holds, and the total length of
!> their names (for pf_profile_list).
subroutine pf_profile_list_info(path, n, nchars, has_chainage, status, message)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_profile, only: profile_catalog_type, list_profiles
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(out) :: n, nchars, has_chainage, status
   character(len=2048), intent(out) :: message
   type(profile_catalog_type) :: cat
   type(error_type), allocatable :: error
   integer :: k
   n = 0; nchars = 0; has_chainage = 0; status = 0; message = ""
   call list_profiles(path, cat, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   n = cat%n_profiles
   do k = 1, n
      nchars = nchars + len(cat%names(k)%s)
   end do
   has_chainage = merge(1, 0, cat%has_chainage)
end subroutine pf_profile_list_info

!> The names (character codes, name k ends at ends(k)) and chainage (m) of
!> the profiles of a NetCDF profile file.
subroutine pf_profile_list(path, n, nchars, codes, ends, chainage, status, message)
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use pavefric_profile, only: profile_catalog_type, list_profiles
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(in) :: n, nchars
   integer(c_int), intent(out) :: codes(nchars), ends(n), status
   real(c_double), intent(out) :: chainage(n)
   character(len=2048), intent(out) :: message
   type(profile_catalog_type) :: cat
   type(error_type), allocatable :: error
   integer :: k, j, used
   codes = 0; ends = 0; chainage = 0; status = 0; message = ""
   call list_profiles(path, cat, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   used = 0
   do k = 1, n
      if (k > cat%n_profiles) exit
      do j = 1, len(cat%names(k)%s)
         if (used >= nchars) exit
         used = used + 1
         codes(used) = ichar(cat%names(k)%s(j:j))
      end do
      ends(k) = used
      if (cat%has_chainage) chainage(k) = cat%chainage(k)
   end do
   if (cat%n_profiles /= n .or. used /= nchars) then
      status = 2
      message = "'" // trim(path) // "' changed while it was read"
   end if
end subroutine pf_profile_list

!> Reading benchmark: the best of `repeats` reads of a profile file (no
!> preprocessing): seconds, points and numbers read.
subroutine pf_profile_read_seconds(path, format, height_unit, profile_name, repeats, n_points, &
      & n_numbers, seconds, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use, intrinsic :: iso_fortran_env, only: int64
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, format, height_unit, profile_name
   integer(c_int), intent(in) :: repeats
   integer(c_int), intent(out) :: n_points, n_numbers, status
   real(c_double), intent(out) :: seconds
   character(len=2048), intent(out) :: message
   type(raw_profile_type) :: raw
   type(error_type), allocatable :: error
   integer(int64) :: t0, t1, rate
   integer :: r
   n_points = 0; n_numbers = 0; seconds = huge(1.0_c_double); status = 0; message = ""
   do r = 1, max(1, repeats)
      call system_clock(t0, rate)
      call read_raw_profile(path, format, unit_factor(height_unit), "", "", raw, error, &
         & profile_name=profile_name)
      call system_clock(t1)
      if (allocated(error)) then
         status = error%stat
         message = error%message
         return
      end if
      seconds = min(seconds, real(t1 - t0, c_double) / real(rate, c_double))
   end do
   n_points = size(raw%z)
   n_numbers = n_points
   if (raw%has_x) n_numbers = 2 * n_points
end subroutine pf_profile_read_seconds

!> The rule every writer of pavefric follows (pavefric_fsys), for Python's
!> writers: `path` must be missing or a regular file (never a FIFO, a
!> device or a directory), and not the same file as any of `inputs` (paths
!> separated by newlines: what the data written came from). status 0: the
!> path may be written (through a temporary in its directory and a rename).
subroutine pf_check_output(path, inputs, replaces, writable, status, message)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_fsys, only: output_guard_type, check_output_path
   use pavefric_netcdf, only: check_replaceable, check_text_replaceable, check_png_replaceable
   use pavefric_run, only: check_writable
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, inputs
   !> The kind of file the writer may replace ('results' or 'profiles':
   !> pavefric_netcdf's check_replaceable, the program's own rule), or
   !> 'text:' and the bytes a text writer begins its files with
   !> (check_text_replaceable), or 'png' (a figure pavefric drew:
   !> check_png_replaceable), or blank (no such check).
   character(len=*), intent(in) :: replaces
   !> Non-zero: also that a file can be made beside `path` (its directory
   !> exists and is writable; the program's check_writable).
   integer(c_int), intent(in) :: writable
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(output_guard_type) :: guard
   type(error_type), allocatable :: error
   integer :: start, k
   status = 0; message = ""
   call check_output_path(path, "the output path", guard, error)
   start = 1
   do while (.not. allocated(error) .and. start <= len(inputs))
      k = index(inputs(start:), achar(10))
      if (k == 0) k = len(inputs) - start + 2
      if (k > 1) call guard%check_input(inputs(start:start+k-2), "an input of the data written", &
         & error)
      start = start + k
   end do
   if (.not. allocated(error) .and. len_trim(replaces) > 0) then
      if (index(replaces, "text:") == 1) then
         call check_text_replaceable(path, "the output path", replaces(6:len_trim(replaces)), &
            & error)
      else if (trim(replaces) == "png") then
         call check_png_replaceable(path, "the output path", error)
      else
         call check_replaceable(path, "the output path", error, trim(replaces))
      end if
   end if
   ! a file can be made beside it (the directory exists and is writable:
   ! the program's own check, before any work)
   if (.not. allocated(error) .and. writable /= 0) &
      & call check_writable(path, "the output path", error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
   end if
end subroutine pf_check_output

!> The temporary a writer of `path` uses (path.tmpPID.pavefric, the program's own
!> name), after removing those that writers killed outright left beside
!> `path` (their process is gone): one naming and one clean-up for every
!> writer, Python's included.
subroutine pf_temporary_name(path, tmp)
   use pavefric_netcdf, only: temporary_name
   use pavefric_fsys, only: release_temporary
   implicit none
   character(len=*), intent(in) :: path
   character(len=4096), intent(out) :: tmp
   character(len=:), allocatable :: name
   call temporary_name(path, name)
   ! the caller (Python's atomic_output) removes or renames it, not the
   ! program's signal handlers
   call release_temporary(name)
   tmp = name
end subroutine pf_temporary_name

!> Points of the profile the pad's elements see (&pad element_length) at a
!> phase of their grid: pavefric_heights' resampled_points.
subroutine pf_resampled_points(n, dx, closed, length, phase, m)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_heights, only: resampled_points
   implicit none
   integer(c_int), intent(in) :: n, closed
   real(c_double), intent(in) :: dx, length, phase
   integer(c_int), intent(out) :: m
   m = resampled_points(n, dx, closed /= 0, length, phase)
end subroutine pf_resampled_points

!> The profile the pad's elements see: pavefric_heights' resample_to_length
!> (the core's own filter and resampling), m points from pf_resampled_points.
!> status /= 0: m does not match, or no memory.
subroutine pf_resample_to_length(n, z, dx, closed, length, phase, m, zr, dxr, status)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_heights, only: resample_to_length
   implicit none
   integer(c_int), intent(in) :: n, closed, m
   real(c_double), intent(in) :: z(n), dx, length, phase
   real(c_double), intent(out) :: zr(m), dxr
   integer(c_int), intent(out) :: status
   real(c_double), allocatable :: out(:)
   integer :: stat
   zr = 0
   dxr = 0
   call resample_to_length(z, dx, closed /= 0, length, phase, out, dxr, stat)
   status = stat
   if (stat /= 0) return
   if (size(out) /= m) then
      status = -1
      return
   end if
   zr = out
end subroutine pf_resample_to_length
