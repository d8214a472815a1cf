!> The f2py boundary: plain subroutines with explicit-shape C-typed arrays,
!> explicit sizes, a status and a message. No derived types, allocatables or
!> module state cross it; nothing here can stop the Python process.
!> (real(c_double), not real(wp): f2py maps kind parameters it does not know
!> to C float and returns wrong numbers in silence.)

!> Default parameters of the model, as the namelist has them.
subroutine pf_defaults(mu_loc, length, width, thickness, load, radius, stiffness, viscosity, &
      & depth, water_viscosity, alpha, beta, theta_max_deg, substeps, elements_per_sample, &
      & position_stride, wet_tolerance, ctm_dx_out, version)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_model, only: model_type
   use pavefric_run, only: ctm_dx
   use pavefric_kinds, only: pavefric_version
   implicit none
   real(c_double), intent(out) :: mu_loc, length, width, thickness, load, radius, stiffness
   real(c_double), intent(out) :: viscosity, depth, water_viscosity, alpha, beta, theta_max_deg
   real(c_double), intent(out) :: wet_tolerance, ctm_dx_out
   integer(c_int), intent(out) :: substeps, elements_per_sample, position_stride
   character(len=32), intent(out) :: version
   type(model_type) :: m
   mu_loc = m%mu_loc; length = m%length; width = m%width; thickness = m%thickness
   load = m%load; radius = m%radius; stiffness = m%stiffness; viscosity = m%viscosity
   depth = m%depth; water_viscosity = m%water_viscosity; alpha = m%alpha; beta = m%beta
   theta_max_deg = m%theta_max_deg; substeps = m%substeps
   elements_per_sample = m%elements_per_sample; position_stride = m%position_stride
   wet_tolerance = m%wet_tolerance; ctm_dx_out = ctm_dx
   version = pavefric_version
end subroutine pf_defaults

!> Pad elements and averaged positions of a scene (to size the series).
subroutine pf_layout(np, dx, closed, length, elements_per_sample, substeps, position_stride, &
      & n_elements, n_positions)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_model, only: model_type
   use pavefric_simulate, only: pad_elements, averaged_positions
   implicit none
   integer(c_int), intent(in) :: np, closed, elements_per_sample, substeps, position_stride
   real(c_double), intent(in) :: dx, length
   integer(c_int), intent(out) :: n_elements, n_positions
   type(model_type) :: m
   m%length = length
   m%elements_per_sample = max(1, elements_per_sample)
   m%substeps = max(1, substeps)
   m%position_stride = max(1, position_stride)
   n_elements = 0
   n_positions = 0
   if (.not. (dx > 0.0_c_double) .or. .not. (length > 0.0_c_double)) return
   if (length / dx * m%elements_per_sample > 2.0e9_c_double) return
   n_elements = pad_elements(m, dx)
   n_positions = averaged_positions(m, np, dx, closed /= 0)
end subroutine pf_layout

!> Run the model on heights z (m); see pavefric.simulate for the arguments.
subroutine pf_simulate(np, z, dx, closed, ns, speeds_kmh, mu_loc, length, width, thickness, &
      & load, pad_shape, radius, stiffness, viscosity, depth, water_viscosity, alpha, beta, &
      & theta_max_deg, substeps, elements_per_sample, position_stride, wet_tolerance, &
      & want_series, npos, mu, hydroplaning_fraction, wet_fraction, max_balance_residual, &
      & mean_hydro_load, max_compression, n_clamped, bearing_evaluations, memory_updates, &
      & viscous_memory_ran, &
      & bearing_ran, position, mu_inst, hydro_load, penetration, contact_elements, n_elements, &
      & n_positions, n_spinup, effects, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int, c_int64_t
   use pavefric_model, only: model_type
   use pavefric_simulate, only: sim_result_type, simulate, effects_text
   use pavefric_error, only: error_type
   implicit none
   integer(c_int), intent(in) :: np, ns, closed, substeps, elements_per_sample, position_stride
   integer(c_int), intent(in) :: want_series, npos
   real(c_double), intent(in) :: z(np), dx, speeds_kmh(ns), mu_loc, length, width, thickness
   real(c_double), intent(in) :: load, radius, stiffness, viscosity, depth, water_viscosity
   real(c_double), intent(in) :: alpha, beta, theta_max_deg, wet_tolerance
   character(len=*), intent(in) :: pad_shape
   real(c_double), intent(out) :: mu(ns), hydroplaning_fraction(ns), wet_fraction(ns)
   real(c_double), intent(out) :: max_balance_residual(ns), mean_hydro_load(ns)
   real(c_double), intent(out) :: max_compression(ns)
   integer(c_int64_t), intent(out) :: n_clamped(ns), bearing_evaluations(ns), memory_updates(ns)
   integer(c_int), intent(out) :: viscous_memory_ran(ns), bearing_ran(ns)
   real(c_double), intent(out) :: position(npos), mu_inst(npos, ns), hydro_load(npos, ns)
   real(c_double), intent(out) :: penetration(npos, ns)
   integer(c_int), intent(out) :: contact_elements(npos, ns)
   integer(c_int), intent(out) :: n_elements, n_positions, n_spinup, status
   character(len=256), intent(out) :: effects
   character(len=2048), intent(out) :: message
   type(model_type) :: m
   type(sim_result_type) :: res
   type(error_type), allocatable :: error

   status = 0
   message = ""
   effects = ""
   mu = 0; hydroplaning_fraction = 0; wet_fraction = 0; max_balance_residual = 0
   mean_hydro_load = 0; max_compression = 0; n_clamped = 0; bearing_evaluations = 0
   memory_updates = 0
   viscous_memory_ran = 0; bearing_ran = 0; position = 0; mu_inst = 0; hydro_load = 0
   penetration = 0; contact_elements = 0; n_elements = 0; n_positions = 0; n_spinup = 0
   m%mu_loc = mu_loc; m%length = length; m%width = width; m%thickness = thickness
   m%load = load; m%shape = pad_shape; m%radius = radius; m%stiffness = stiffness
   m%viscosity = viscosity; m%depth = depth; m%water_viscosity = water_viscosity
   m%alpha = alpha; m%beta = beta; m%theta_max_deg = theta_max_deg; m%substeps = substeps
   m%elements_per_sample = elements_per_sample; m%position_stride = position_stride
   m%wet_tolerance = wet_tolerance

   call simulate(m, z, dx, closed /= 0, speeds_kmh, want_series /= 0, res, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   if (want_series /= 0 .and. npos /= res%n_positions) then
      status = 2
      message = "internal: series sized for a different number of positions"
      return
   end if
   mu = res%mu
   hydroplaning_fraction = res%hydroplaning_fraction
   wet_fraction = res%wet_fraction
   max_balance_residual = res%max_balance_residual
   mean_hydro_load = res%mean_hydro_load
   max_compression = res%max_compression
   n_clamped = res%n_clamped
   bearing_evaluations = res%bearing_evaluations
   memory_updates = res%memory_updates
   viscous_memory_ran = merge(1, 0, res%viscous_memory_ran)
   bearing_ran = merge(1, 0, res%bearing_ran)
   n_elements = res%n_elements
   n_positions = res%n_positions
   n_spinup = res%n_spinup
   effects = effects_text(res)
   if (want_series /= 0) then
      position = res%position
      mu_inst = res%mu_inst
      hydro_load = res%hydro_load
      penetration = res%penetration
      contact_elements = res%contact_elements
   end if
end subroutine pf_simulate

!> Run a scene file and write its NetCDF output, as the program does.
subroutine pf_run_scene(path, output, command, out_path, status, message)
   use, intrinsic :: iso_c_binding, only: c_int
   use pavefric_run, only: run_scene
   use pavefric_simulate, only: sim_result_type
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, output, command
   character(len=4096), intent(out) :: out_path
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(sim_result_type) :: res
   type(error_type), allocatable :: error
   character(len=:), allocatable :: written
   status = 0
   message = ""
   out_path = ""
   call run_scene(path, output, command, written, res, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   out_path = written
end subroutine pf_run_scene

!> Read and preprocess a profile file (first pass): sizes and spacing.
subroutine pf_profile_info(path, format, height_unit, x_column, z_column, dx_default, &
      & dropouts, trim_plates, plate_threshold, plate_min_length, plate_buffer, spike_slope, &
      & resample_dx, lowpass_wavelength, n_raw, n_out, dx, has_x, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_preprocess, only: preprocess_type, clean_profile_type, preprocess
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, format, height_unit, x_column, z_column, dropouts
   real(c_double), intent(in) :: dx_default, plate_threshold, plate_min_length, plate_buffer
   real(c_double), intent(in) :: spike_slope, resample_dx, lowpass_wavelength
   integer(c_int), intent(in) :: trim_plates
   integer(c_int), intent(out) :: n_raw, n_out, has_x, status
   real(c_double), intent(out) :: dx
   character(len=2048), intent(out) :: message
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(preprocess_type) :: p
   type(error_type), allocatable :: error
   n_raw = 0; n_out = 0; dx = 0; has_x = 0; status = 0; message = ""
   p = preprocess_type(dropouts, trim_plates /= 0, plate_threshold, plate_min_length, &
      & plate_buffer, spike_slope, resample_dx, lowpass_wavelength)
   if (unit_factor(height_unit) <= 0) then
      status = 1
      message = "&surface height_unit = '" // trim(height_unit) // "': unknown (expected " // &
         & "'mm', 'um' or 'm')"
      return
   end if
   call read_raw_profile(path, format, unit_factor(height_unit), x_column, z_column, raw, error)
   if (.not. allocated(error)) call preprocess(raw, dx_default, p, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   n_raw = size(raw%z)
   n_out = size(clean%z)
   dx = clean%dx
   has_x = merge(1, 0, raw%has_x)
end subroutine pf_profile_info

!> Read and preprocess a profile file (second pass): the raw points, the
!> clean heights (m), their quality, and the report.
subroutine pf_read_profile(path, format, height_unit, x_column, z_column, dx_default, &
      & dropouts, trim_plates, plate_threshold, plate_min_length, plate_buffer, spike_slope, &
      & resample_dx, lowpass_wavelength, n_raw, n_out, x_raw, z_raw, valid_raw, z, &
      & dropout_fraction, spike, counts, format_read, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_preprocess, only: preprocess_type, clean_profile_type, preprocess
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, format, height_unit, x_column, z_column, dropouts
   real(c_double), intent(in) :: dx_default, plate_threshold, plate_min_length, plate_buffer
   real(c_double), intent(in) :: spike_slope, resample_dx, lowpass_wavelength
   integer(c_int), intent(in) :: trim_plates, n_raw, n_out
   real(c_double), intent(out) :: x_raw(n_raw), z_raw(n_raw), z(n_out), dropout_fraction(n_out)
   integer(c_int), intent(out) :: valid_raw(n_raw), spike(n_out), counts(8), status
   character(len=16), intent(out) :: format_read
   character(len=2048), intent(out) :: message
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(preprocess_type) :: p
   type(error_type), allocatable :: error
   integer :: i
   x_raw = 0; z_raw = 0; valid_raw = 0; z = 0; dropout_fraction = 0; spike = 0; counts = 0
   status = 0; message = ""; format_read = ""
   p = preprocess_type(dropouts, trim_plates /= 0, plate_threshold, plate_min_length, &
      & plate_buffer, spike_slope, resample_dx, lowpass_wavelength)
   call read_raw_profile(path, format, unit_factor(height_unit), x_column, z_column, raw, error)
   if (.not. allocated(error)) call preprocess(raw, dx_default, p, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   if (size(raw%z) /= n_raw .or. size(clean%z) /= n_out) then
      status = 2
      message = "'" // trim(path) // "' changed while it was read"
      return
   end if
   if (raw%has_x) then
      x_raw = raw%x
   else
      x_raw = [(real(i - 1, c_double) * dx_default, i = 1, n_raw)]
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
end subroutine pf_read_profile

!> The bearing load (Eq. 15) and its derivative for arrays of outlet films.
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

!> Read a scene file as the program does (first pass): sizes, spacing and
!> parameters. The heights and speeds come from pf_scene_arrays.
subroutine pf_scene_info(path, np, ns, dx, closed, series, mu_loc, length, width, thickness, &
      & load, pad_shape, radius, stiffness, viscosity, depth, water_viscosity, alpha, beta, &
      & theta_max_deg, substeps, elements_per_sample, position_stride, wet_tolerance, &
      & profile_file, output_file, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_kinds, only: wp
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_run, only: load_scene_profile
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(out) :: np, ns, closed, series, substeps, elements_per_sample
   integer(c_int), intent(out) :: position_stride, status
   real(c_double), intent(out) :: dx, mu_loc, length, width, thickness, load, radius, stiffness
   real(c_double), intent(out) :: viscosity, depth, water_viscosity, alpha, beta, theta_max_deg
   real(c_double), intent(out) :: wet_tolerance
   character(len=16), intent(out) :: pad_shape
   character(len=4096), intent(out) :: profile_file, output_file
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   type(clean_profile_type) :: clean
   np = 0; ns = 0; dx = 0; closed = 0; series = 0; status = 0; message = ""
   profile_file = ""; output_file = ""; pad_shape = ""
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
   associate(m => scene%model)
      mu_loc = m%mu_loc; length = m%length; width = m%width; thickness = m%thickness
      load = m%load; pad_shape = m%shape; radius = m%radius; stiffness = m%stiffness
      viscosity = m%viscosity; depth = m%depth; water_viscosity = m%water_viscosity
      alpha = m%alpha; beta = m%beta; theta_max_deg = m%theta_max_deg
      substeps = m%substeps; elements_per_sample = m%elements_per_sample
      position_stride = m%position_stride; wet_tolerance = m%wet_tolerance
   end associate
   profile_file = scene%profile_file
   output_file = scene%output_file
end subroutine pf_scene_info

!> Heights (m) and speeds (km/h) of a scene file (second pass).
subroutine pf_scene_arrays(path, np, ns, z, speeds_kmh, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_kinds, only: wp
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_run, only: load_scene_profile
   use pavefric_preprocess, only: clean_profile_type
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path
   integer(c_int), intent(in) :: np, ns
   real(c_double), intent(out) :: z(np), speeds_kmh(ns)
   integer(c_int), intent(out) :: status
   character(len=2048), intent(out) :: message
   type(scene_type) :: scene
   type(error_type), allocatable :: error
   type(clean_profile_type) :: clean
   z = 0; speeds_kmh = 0; status = 0; message = ""
   call read_scene(path, scene, error)
   if (.not. allocated(error)) call load_scene_profile(scene, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   if (size(clean%z) /= np .or. size(scene%speeds_kmh) /= ns) then
      status = 2
      message = "scene '" // trim(path) // "' changed while it was read"
      return
   end if
   z = clean%z
   speeds_kmh = scene%speeds_kmh
end subroutine pf_scene_arrays

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
!> profile_name chooses a profile of a NetCDF file (empty: its only one).
subroutine pf_profile_read_info(path, format, height_unit, x_column, z_column, profile_name, &
      & dx_default, dropouts, trim_plates, plate_threshold, plate_min_length, plate_buffer, &
      & spike_slope, resample_dx, lowpass_wavelength, n_raw, n_out, dx, has_x, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_preprocess, only: preprocess_type, clean_profile_type, preprocess
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, format, height_unit, x_column, z_column, profile_name
   character(len=*), intent(in) :: dropouts
   real(c_double), intent(in) :: dx_default, plate_threshold, plate_min_length, plate_buffer
   real(c_double), intent(in) :: spike_slope, resample_dx, lowpass_wavelength
   integer(c_int), intent(in) :: trim_plates
   integer(c_int), intent(out) :: n_raw, n_out, has_x, status
   real(c_double), intent(out) :: dx
   character(len=2048), intent(out) :: message
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(preprocess_type) :: p
   type(error_type), allocatable :: error
   n_raw = 0; n_out = 0; dx = 0; has_x = 0; status = 0; message = ""
   p = preprocess_type(dropouts, trim_plates /= 0, plate_threshold, plate_min_length, &
      & plate_buffer, spike_slope, resample_dx, lowpass_wavelength)
   if (unit_factor(height_unit) <= 0) then
      status = 1
      message = "&surface height_unit = '" // trim(height_unit) // "': unknown (expected " // &
         & "'mm', 'um' or 'm')"
      return
   end if
   call read_raw_profile(path, format, unit_factor(height_unit), x_column, z_column, raw, error, &
      & profile_name=profile_name)
   if (.not. allocated(error)) call preprocess(raw, dx_default, p, clean, error)
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
!> from the file, else from its spacing or dx_default), the clean heights
!> (m), their quality, and the report.
subroutine pf_profile_read_data(path, format, height_unit, x_column, z_column, profile_name, &
      & dx_default, dropouts, trim_plates, plate_threshold, plate_min_length, plate_buffer, &
      & spike_slope, resample_dx, lowpass_wavelength, n_raw, n_out, x_raw, z_raw, valid_raw, z, &
      & dropout_fraction, spike, counts, format_read, chainage, has_chainage, status, message)
   use, intrinsic :: iso_c_binding, only: c_double, c_int
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_preprocess, only: preprocess_type, clean_profile_type, preprocess
   use pavefric_error, only: error_type
   implicit none
   character(len=*), intent(in) :: path, format, height_unit, x_column, z_column, profile_name
   character(len=*), intent(in) :: dropouts
   real(c_double), intent(in) :: dx_default, plate_threshold, plate_min_length, plate_buffer
   real(c_double), intent(in) :: spike_slope, resample_dx, lowpass_wavelength
   integer(c_int), intent(in) :: trim_plates, n_raw, n_out
   real(c_double), intent(out) :: x_raw(n_raw), z_raw(n_raw), z(n_out), dropout_fraction(n_out)
   real(c_double), intent(out) :: chainage
   integer(c_int), intent(out) :: valid_raw(n_raw), spike(n_out), counts(8), has_chainage, status
   character(len=16), intent(out) :: format_read
   character(len=2048), intent(out) :: message
   type(raw_profile_type) :: raw
   type(clean_profile_type) :: clean
   type(preprocess_type) :: p
   type(error_type), allocatable :: error
   real(c_double) :: spacing
   integer :: i
   x_raw = 0; z_raw = 0; valid_raw = 0; z = 0; dropout_fraction = 0; spike = 0; counts = 0
   chainage = 0; has_chainage = 0; status = 0; message = ""; format_read = ""
   p = preprocess_type(dropouts, trim_plates /= 0, plate_threshold, plate_min_length, &
      & plate_buffer, spike_slope, resample_dx, lowpass_wavelength)
   call read_raw_profile(path, format, unit_factor(height_unit), x_column, z_column, raw, error, &
      & profile_name=profile_name)
   if (.not. allocated(error)) call preprocess(raw, dx_default, p, clean, error)
   if (allocated(error)) then
      status = error%stat
      message = error%message
      return
   end if
   if (size(raw%z) /= n_raw .or. size(clean%z) /= n_out) then
      status = 2
      message = "'" // trim(path) // "' changed while it was read"
      return
   end if
   if (raw%has_x) then
      x_raw = raw%x
   else
      spacing = dx_default
      if (raw%dx > 0) spacing = raw%dx
      do i = 1, n_raw
         x_raw(i) = real(i - 1, c_double) * spacing
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
