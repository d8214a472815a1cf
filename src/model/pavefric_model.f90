!> The one description of pavefric's inputs: every namelist variable is
!> declared once, with its group, unit, default, valid range, plausible
!> range and meaning (the scene's own here, the components' in their
!> modules, gathered here into one table). Namelist reading, validation messages, the echo into
!> the output, docs/inputs.md, the Python keywords and the C API all come
!> from this table, so they cannot drift. The physical parameters are then
!> gathered into `model_type` for the physics modules.
!>
!> The physics components declare their own variables next to their code
!> (the wet models: pavefric_wet_models; the rubber laws and the &rubber
!> group: pavefric_rubber_models; &preprocess: pavefric_preprocess; &pad:
!> pavefric_pad; mu_loc and theta_max_deg: pavefric_facet); their rows
!> follow the scene's own in the table, found by name. A new variable of the scene itself touches this
!> module only: an id, a row in `parameter_table`, and (for a model
!> parameter) a field of model_type and a line in `model_from_parameters`.
module pavefric_model
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error, add_warning
   use pavefric_format, only: to_str, to_lower, round_sig, real_to_str_text
   use pavefric_numbers, only: parse_real, parse_integer
   use pavefric_namelist, only: nml_group_type, nml_item_type, nml_token_type, parse_namelist, at
   use pavefric_maxwell, only: wlf_check, max_log10_shift, max_arms
   use pavefric_rubber_models, only: n_rubber_parameters, n_rubber_shared_parameters, &
      & rubber_parameters, rubber_model_names, check_rubber, rubber_models
   use pavefric_rubber, only: rubber_entry_type, kelvin_voigt_n_parameters
   use pavefric_preprocess, only: preprocess_parameters, preprocess_n_parameters
   use pavefric_pad, only: pad_parameters, pad_n_parameters, check_pad, shape_flat, &
      & shape_rounded, shape_code
   use pavefric_facet, only: facet_parameters, facet_n_parameters
   use pavefric_wet_models, only: n_film_parameters, wet_model_parameters, wet_model_names, &
      & wet_models
   use pavefric_film, only: film_entry_type
   use pavefric_params, only: find_parameter, param_spec_type, param_value_type, &
      & kind_real, kind_integer, kind_logical, kind_text, kind_real_list, base => param_base, &
      & text => text_param, &
      & logical_param, int_param, real_param, list_param
   implicit none
   private

   public :: model_type, validate_model, shape_flat, shape_rounded, shape_code
   public :: param_spec_type, param_value_type, param_set_type, group_spec_type
   public :: parameter_table, group_table, default_parameters, apply_namelist, find_parameter
   public :: typed_value, apply_typed
   !> The kinds of a typed item (apply_typed).
   integer, parameter, public :: typed_real = 1, typed_integer = 2, typed_logical = 3, &
      & typed_text = 4, typed_list = 5
   public :: model_from_parameters, parameters_namelist, plausibility_warnings, format_value, &
      & parameters_namelist_text
   public :: kind_real, kind_integer, kind_logical, kind_text, kind_real_list
   public :: n_parameters, n_groups

   !> The smallest &numerics tolerance (> 0) a run can meet in double
   !> precision: about 45 x machine epsilon, as mu's rounding is ~1e-15.
   real(wp), parameter :: tolerance_floor = 1.0e-14_wp
   !> &pad element_length below this (and above 0) warns: finer than any
   !> road profilometer samples (m).
   real(wp), parameter :: element_length_finest = 1.0e-5_wp
   !> The largest &numerics substeps, also where accuracy on demand stops halving.
   integer, parameter, public :: max_substeps = 4096
   !> The largest &numerics elements_per_sample.
   integer, parameter, public :: max_elements_per_sample = 4096

   !> The values used, as a namelist that reproduces them (defaults
   !> included); optional variables not set are left out. `groups`
   !> (space-separated, optional) selects the groups; default all. Two
   !> specifics: an explicit-length result cannot depend on an optional
   !> argument.
   interface parameters_namelist
      module procedure :: parameters_namelist_all, parameters_namelist_groups
   end interface parameters_namelist


   ! The scene's own variable ids, in the order of the groups and of
   ! docs/inputs.md (numbered by the compiler). The components' variables
   ! (pavefric_wet_models) follow them in the table, found by name.
   enum, bind(c)
      enumerator :: p_profile_file = 1, p_profile_name, p_format, p_height_unit, p_x_column
      enumerator :: p_z_column, p_dx, p_closed, p_microtexture_rms
      enumerator :: p_wet_model, p_depth
      enumerator :: p_water_viscosity, p_speeds_kmh, p_substeps
      enumerator :: p_elements_per_sample, p_position_stride, p_wet_tolerance, p_tolerance
      enumerator :: p_error_estimate, p_min_contacts, p_time_scheme, p_friction_scheme
      enumerator :: p_output_file
      enumerator :: p_series, p_batch_profiles, p_batch_profile_list, p_batch_depths
      enumerator :: p_batch_restart, p_batch_progress_every
   end enum
   public :: p_profile_file, p_profile_name, p_format, p_height_unit, p_x_column
   public :: p_z_column, p_dx, p_closed, p_microtexture_rms
   public :: p_wet_model
   public :: p_depth, p_water_viscosity, p_speeds_kmh, p_substeps
   public :: p_elements_per_sample, p_position_stride, p_wet_tolerance, p_tolerance
   public :: p_error_estimate, p_min_contacts
   public :: p_time_scheme, p_friction_scheme, p_output_file, p_series, p_batch_profiles
   public :: p_batch_profile_list, p_batch_depths, p_batch_restart, p_batch_progress_every
   !> Variables the scene itself declares (the last id), and all of them
   !> with the components'.
   integer, parameter :: n_scene_parameters = p_batch_progress_every
   !> Where the rubber's variables begin (pavefric_rubber_models: the
   !> group's shared ones, then each law's).
   integer, parameter :: rubber_first = n_scene_parameters + n_film_parameters + 1
   !> Where preprocessing's, the pad's and the facets' variables begin
   !> (pavefric_preprocess, pavefric_pad, pavefric_facet).
   integer, parameter :: preprocess_first = rubber_first + n_rubber_parameters
   integer, parameter :: pad_first = preprocess_first + preprocess_n_parameters
   integer, parameter :: facet_first = pad_first + pad_n_parameters
   integer, parameter :: n_parameters = facet_first + facet_n_parameters - 1
   !> The ids of the &rubber variables, kept for code that used these names
   !> (the variables are the rubber components' own, better found by name:
   !> find_parameter(specs, "rubber", "stiffness")).
   integer, parameter, public :: p_rubber_model = rubber_first, p_stiffness = rubber_first + 1, &
      & p_temperature = rubber_first + 2, p_reference_temperature = rubber_first + 3, &
      & p_wlf_c1 = rubber_first + 4, p_wlf_c2 = rubber_first + 5, &
      & p_viscosity = rubber_first + n_rubber_shared_parameters, &
      & p_prony_stiffness = p_viscosity + kelvin_voigt_n_parameters, &
      & p_prony_times = p_prony_stiffness + 1
   !> The ids of the components' other variables, kept likewise (better
   !> found by name).
   integer, parameter, public :: p_dropouts = preprocess_first, &
      & p_trim_plates = preprocess_first + 1, p_plate_threshold = preprocess_first + 2, &
      & p_plate_min_length = preprocess_first + 3, p_plate_buffer = preprocess_first + 4, &
      & p_spike_slope = preprocess_first + 5, p_resample_dx = preprocess_first + 6, &
      & p_lowpass_wavelength = preprocess_first + 7
   integer, parameter, public :: p_length = pad_first, p_width = pad_first + 1, &
      & p_thickness = pad_first + 2, p_load = pad_first + 3, p_shape = pad_first + 4, &
      & p_radius = pad_first + 5, p_element_length = pad_first + 6
   integer, parameter, public :: p_mu_loc = facet_first, p_theta_max_deg = facet_first + 1
   !> Deprecated: &water alpha and beta are the pseudo-bearing's own
   !> (pavefric_film), the first wet model of the registry; their ids,
   !> kept for code that used these names, are better found by name
   !> (find_parameter(specs, "water", "alpha")).
   integer, parameter, public :: p_alpha = n_scene_parameters + 1, p_beta = n_scene_parameters + 2
   integer, parameter :: n_groups = 9
   !> Most arms of a generalised Maxwell element (pavefric_maxwell's).
   public :: max_arms

   !> A namelist group and what it is for (docs/inputs.md sections).
   type :: group_spec_type
      character(len=:), allocatable :: name, title, description
   end type group_spec_type


   !> The values of every variable.
   type :: param_set_type
      type(param_value_type) :: v(n_parameters)
   end type param_set_type

   !> Everything the friction model needs besides the profile and speeds.
   !> SI units; built from the table by model_from_parameters. The
   !> components (rubber law, film, pad checks) build themselves from
   !> `values`, so the fields are a view of them: to change a variable,
   !> change its value in the set (or use the typed setters) and build the
   !> model again, not the field.
   type :: model_type
      real(wp) :: mu_loc = 0.0_wp, microtexture_rms = 0.0_wp
      real(wp) :: length = 0.0_wp, width = 0.0_wp, thickness = 0.0_wp, load = 0.0_wp
      character(len=:), allocatable :: shape
      real(wp) :: radius = 0.0_wp
      !> The pad element's length (m): the profile is low-pass filtered and
      !> resampled to it (0: the profile's own spacing, as the paper).
      real(wp) :: element_length = 0.0_wp
      !> &rubber: 'kelvin_voigt' or 'maxwell'; K (K_inf of a Maxwell element), C;
      !> the Prony arms K_k (N m-3) and tau_k (s, at the reference temperature);
      !> the temperatures (degC) and WLF constants C1 (1), C2 (K).
      character(len=:), allocatable :: rubber_model
      real(wp) :: stiffness = 0.0_wp, viscosity = 0.0_wp
      real(wp), allocatable :: prony_stiffness(:), prony_times(:)
      real(wp) :: temperature = 20.0_wp, reference_temperature = 20.0_wp
      real(wp) :: wlf_c1 = 0.0_wp, wlf_c2 = 1.0_wp
      character(len=:), allocatable :: wet_model
      real(wp) :: depth = 0.0_wp, water_viscosity = 0.0_wp, alpha = 0.0_wp, beta = 0.0_wp
      real(wp) :: theta_max_deg = 0.0_wp
      integer :: substeps = 1, elements_per_sample = 1, position_stride = 1
      real(wp) :: wet_tolerance = 0.0_wp, tolerance = 0.0_wp
      !> &numerics error_estimate: with tolerance = 0, a second pass at half
      !> the step estimates mu's error from the step (mu_error_estimate).
      logical :: error_estimate = .true.
      !> &numerics min_contacts: 0, the pad's elements as elements_per_sample
      !> gives them; n > 0, at each speed they are halved (elements_per_sample
      !> doubled) until the pad stands on n elements in contact on average
      !> (at most pad_levels times), and that run is reported.
      integer :: min_contacts = 4
      !> How the facet friction is computed: 'energy' (the work of the facet
      !> forces balances the elements' stored energy and dissipation) or
      !> 'paper' (Eq. 10 on central-difference slopes).
      character(len=:), allocatable :: friction_scheme
      !> &numerics time_scheme: 'auto', 'extrapolated', 'euler' or 'exact'.
      character(len=:), allocatable :: time_scheme
      !> Every variable's value, in the table's order: components read their
      !> own by group and name (pavefric_wet_models).
      type(param_value_type), allocatable :: values(:)
   end type model_type

contains

   !> The namelist groups, in order.
   pure function group_table() result(g)
      type(group_spec_type) :: g(n_groups)
      g(1) = group_spec_type("surface", "the texture profile", &
         & "The profile file, its units and spacing, and the local friction of its facets.")
      g(2) = group_spec_type("preprocess", "making an instrument profile fit for analysis", &
         & "ISO 13473-1's steps, each optional; docs/profiles.md says what each does.")
      g(3) = group_spec_type("pad", "the DFT rubber slider", &
         & "The pad of N = nint(length / dx) independent elements.")
      g(4) = group_spec_type("rubber", "the rubber elements and their temperature", &
         & "The rubber of each element, per unit length of pad: the paper's " // &
         & "Kelvin–Voigt element (Table 1) or a generalised Maxwell element, its " // &
         & "relaxation times shifted to the temperature by the WLF equation " // &
         & "(docs/rubber.md).")
      g(5) = group_spec_type("water", "water on the road", &
         & "The water film and its model. depth = 0 is a dry road: no film is simulated.")
      g(6) = group_spec_type("operation", "the speeds", "The sliding speeds of the run.")
      g(7) = group_spec_type("numerics", "accuracy knobs", &
         & "With substeps, elements_per_sample and position_stride at 1 the computation " // &
         & "is exactly MODEL.md's; docs/accuracy.md measures what each buys and costs.")
      g(8) = group_spec_type("output", "the NetCDF file", "Where the results go and what they hold.")
      g(9) = group_spec_type("batch", "many profiles into one file", &
         & "A scene with a &batch group runs many profiles at several water depths and " // &
         & "the scene's speeds into one NetCDF file (docs/cluster.md).")
   end function group_table

   !> The declarations of every namelist variable.
   pure function parameter_table() result(s)
      type(param_spec_type) :: s(n_parameters)
      character(len=:), allocatable :: wet_names

      call wet_model_names(wet_names)

      ! &surface
      s(p_profile_file) = text("surface", "profile_file", "", "path", "scene", &
         & "profile file, relative to the namelist's directory: plain text (one column " // &
         & "of heights, or distance and height), CSV with named columns, a laser profiler " // &
         & "export, or NetCDF (docs/profiles.md). Required unless the scene has a &batch group.")
      s(p_profile_file)%required = .true.
      s(p_profile_name) = text("surface", "profile_name", "", "", "scene", &
         & "which profile of a NetCDF file holding several (empty: the file must hold one)")
      s(p_format) = text("surface", "format", "auto", "", "profile", &
         & "profile file format: 'plain', 'captif' (laser profiler export), 'csv' or " // &
         & "'netcdf'; 'auto' detects it (docs/profiles.md)", &
         & choices="auto plain captif csv netcdf")
      s(p_height_unit) = text("surface", "height_unit", "mm", "", "profile", &
         & "unit of the file's heights and distances when the file does not state it: " // &
         & "'mm', 'um' or 'm'", choices="mm um m")
      s(p_x_column) = text("surface", "x_column", "", "", "profile", &
         & "CSV column name of the distance (empty: found by name)")
      s(p_z_column) = text("surface", "z_column", "", "", "profile", &
         & "CSV column name of the height (empty: found by name)")
      s(p_dx) = real_param("surface", "dx", "", "m", "scene", &
         & "sample spacing. Taken from the distances when the file has them (then a " // &
         & "given dx must agree within 1 %); without distances and without dx: 0.87e-3, " // &
         & "a Circular Track Meter's spacing.", lower=0.0_wp, lower_strict=.true., upper=1.0_wp, &
         & plausible_lower=5.0e-6_wp, plausible_upper=5.0e-3_wp, &
         & plausible_note="texture profiles are sampled every 0.005 to 5 mm")
      s(p_closed) = logical_param("surface", "closed", ".true.", "scene", &
         & ".true.: a closed Circular Track Meter circle (the pad wraps round; N spin-up " // &
         & "positions before averaging over all Np positions). .false.: an open profile " // &
         & "(Np - N + 1 positions, elements start relaxed).")
      s(p_microtexture_rms) = real_param("surface", "microtexture_rms", "40e-6", "m", "model", &
         & "RMS height of the microtexture asperities (texture finer than dx) that pierce " // &
         & "the water film left under the contacts, for wet_model = 'squeeze': the share " // &
         & "erfc(h / (sqrt(2) microtexture_rms)) of mu_loc acts through a film h. The default " // &
         & "is the single value fitted to the PIARC speed gradient on its training " // &
         & "profiles, rounded (38.8e-6 fitted; docs/speed_gradient.md). " // &
         & "With wet_model = 'reynolds' it sets the flow factors and the mean gap of a " // &
         & "contact (at least 1e-6 m is used there).", &
         & lower=0.0_wp, upper=1.0_wp, plausible_lower=1.0e-6_wp, plausible_upper=0.5e-3_wp, &
         & plausible_note="road microtexture asperities are 1 to 500 micrometres high")

      ! &water
      s(p_wet_model) = text("water", "wet_model", "kane2017", "", "model", &
         & "what the water does: 'kane2017', the paper's pseudo-bearing (Eqs. 13-15), a " // &
         & "film that lifts the pad; 'squeeze', the film drained from the contact plateaus " // &
         & "by squeeze flow, pierced by the microtexture (lowers the local friction, no " // &
         & "lift; docs/model.md); 'reynolds', the water's flow under the pad (average " // &
         & "Reynolds equation with flow factors, cavitation and the inlet's inertia), a " // &
         & "film that lifts the pad (a first version; docs/model.md)", choices=wet_names)
      s(p_depth) = real_param("water", "depth", "0.0", "m", "model", &
         & "water depth, the bearing's inlet film H_in. 0 = dry: no film is simulated.", &
         & lower=0.0_wp, upper=100.0_wp, plausible_lower=0.0_wp, plausible_upper=0.02_wp, &
         & plausible_note="water films on roads are millimetres deep; depth is in metres")
      s(p_water_viscosity) = real_param("water", "viscosity", "1.0e-3", "Pa s", "model", &
         & "dynamic viscosity of water eta", lower=0.0_wp, lower_strict=.true., &
         & upper=1.0e6_wp, plausible_lower=1.0e-4_wp, plausible_upper=1.0e-2_wp, &
         & plausible_note="water's viscosity is 1.8e-3 at 0 C, 0.3e-3 at 90 C")
      s(p_water_viscosity)%keyword = "water_viscosity"

      ! &operation
      s(p_speeds_kmh) = list_param("operation", "speeds_kmh", "", "km h-1", "scene", &
         & "sliding speeds. 0 is the static limit: no viscous stiffening, no memory, no " // &
         & "film.", lower=0.0_wp, upper=1.0e5_wp, max_values=100000, &
         & plausible_lower=0.0_wp, plausible_upper=400.0_wp, &
         & plausible_note="road vehicles and friction testers slide below 400 km/h")
      s(p_speeds_kmh)%required = .true.

      ! &numerics
      s(p_substeps) = int_param("numerics", "substeps", "1", "model", &
         & "time steps per element spacing: the pad advances dx / substeps per step; " // &
         & "heights and facet tangents are interpolated linearly between samples", 1, &
         & max_substeps)
      s(p_elements_per_sample) = int_param("numerics", "elements_per_sample", "1", "model", &
         & "pad elements per profile spacing: element width dx / elements_per_sample; " // &
         & "heights and facet tangents interpolated linearly between samples", 1, &
         & max_elements_per_sample)
      s(p_position_stride) = int_param("numerics", "position_stride", "1", "model", &
         & "the pad advances this many (refined) samples per step and only those " // &
         & "positions are averaged: exact for elastic dry scenes up to sampling, a " // &
         & "coarser time step otherwise", 1, 1000000)
      s(p_wet_tolerance) = real_param("numerics", "wet_tolerance", "1e-14", "1", "model", &
         & "the wet load balance stops when |residual| <= wet_tolerance x W (or when the " // &
         & "bracket has closed to adjacent doubles)", lower=epsilon(1.0_wp), upper=1.0_wp, &
         & upper_strict=.true., plausible_lower=epsilon(1.0_wp), plausible_upper=1.0e-6_wp, &
         & plausible_note="the balance's residual is then that share of the load, and " // &
         & "the friction off by as much (max_balance_residual)")

      s(p_tolerance) = real_param("numerics", "tolerance", "0", "1", "model", &
         & "accuracy on demand: when > 0, the time step (substeps, from the value given) " // &
         & "is halved until every speed's estimated error (from its last two changes) is at " // &
         & "most this much; the output records the estimate (mu_error_estimate) and the " // &
         & "substeps reached (substeps_used). 0: the knobs as given; at least 1e-14 " // &
         & "(below, double precision cannot meet it); needs substeps <= 1024 (room for the " // &
         & "two halvings the estimate is made of) (docs/accuracy.md)", &
         & lower=0.0_wp, upper=1.0_wp)
      s(p_error_estimate) = logical_param("numerics", "error_estimate", ".true.", "model", &
         & "with tolerance = 0, every speed's error is estimated from more passes: where " // &
         & "the pad stood on 4 elements in contact or more, one at half the step (substeps " // &
         & "doubled; about twice the run's cost), three times its change; where it stood on " // &
         & "fewer, the elements are halved (elements_per_sample doubled, the step with them) " // &
         & "until it stands on 4, at most 4 times, then one more pass, and the estimate is " // &
         & "the change the refinement made plus three times that pass's (up to hundreds of " // &
         & "times the run's cost); speeds the exact integrator ran get the passes that halve " // &
         & "the elements, exact too. Recorded as mu_error_estimate, with a warning where it " // &
         & "exceeds 5 % of mu (and 0.001) naming what to refine. " // &
         & ".false.: no passes and no estimate (docs/accuracy.md)")
      s(p_min_contacts) = int_param("numerics", "min_contacts", "4", "model", &
         & "0: the pad's elements as elements_per_sample gives them (the paper's " // &
         & "discretisation, one element per sample). n > 0 (the default 4): at each speed " // &
         & "where the pad " // &
         & "stood on fewer than n elements in contact on average (positions the film " // &
         & "carried alone left out), its elements are halved (elements_per_sample doubled, " // &
         & "the step with them) until it stands on n, at most 4 times (elements_per_sample " // &
         & "up to 16 times the value given), and that run is reported: mu, its parts and " // &
         & "every per-speed output (elements_per_sample_used says which ran; with series " // &
         & "each speed's series are its own run's, held on the finest run's positions). " // &
         & "Each halving costs about 4 times the run before " // &
         & "it; they are the passes the error estimate would run otherwise, so with it " // &
         & "the default costs about what the paper's discretisation does; the up-front " // &
         & "cost estimate forecasts the halvings from a probe of the profile (runs of " // &
         & "2048 positions or more). 4 resolves the pad's " // &
         & "contacts on the paper's surfaces (docs/accuracy.md, ""The pad's resolution"")", &
         & 0, 1000)
      s(p_time_scheme) = text("numerics", "time_scheme", "extrapolated", "", "model", &
         & "'auto': 'exact' where it applies (the Kelvin-Voigt rubber on a dry road or " // &
         & "under wet_model = 'kane2017', position_stride = 1, friction_scheme = 'energy'), " // &
         & "else 'extrapolated', with no warning; exact_integrator_ran says which ran. " // &
         & "'exact': a Kelvin-Voigt rubber is integrated in closed form from contact event " // &
         & "to event: exactly in time on a dry road; under the paper's film with the " // &
         & "film's load linearised in the mean gap over each part of a step, an error " // &
         & "of second order in the step (about 1e-4 of mu at one step per sample on " // &
         & "inputs/ctm_wet.nml, where backward Euler's is 8e-3); other rubbers and films, " // &
         & "and a film it declines (docs/numerics.md), run backward Euler, with a warning; " // &
         & "needs " // &
         & "position_stride = 1. With tolerance > 0, 'extrapolated' reports the Richardson " // &
         & "value of the last two backward-Euler passes, 2 mu(s) - mu(s/2), where the " // &
         & "passes are in their first-order range and its estimate is the smaller " // &
         & "(mu_extrapolated says where), meeting a tolerance at 2 to 4 times fewer " // &
         & "substeps; 'euler' reports the finest pass: with substeps = 1 the paper's one " // &
         & "step per sample. 'richardson': as 'extrapolated', and at tolerance = 0 the " // &
         & "Richardson value of the run and its error estimate's pass (needs " // &
         & "error_estimate; series stay the run's own pass; docs/model.md)", &
         & choices="auto extrapolated euler exact richardson")
      s(p_friction_scheme) = text("numerics", "friction_scheme", "energy", "", "model", &
         & "'energy': the friction of a step is the work the facet forces do, the " // &
         & "elements' stored energy change plus their dissipation (trapezoidal in time), " // &
         & "plus the facets' local friction; an elastic pad with mu_loc = 0 then has no " // &
         & "friction on a closed profile. 'paper': Eq. 10 on central-difference slopes, " // &
         & "the paper's scheme (docs/model.md)", choices="energy paper")

      ! &output
      s(p_output_file) = text("output", "file", "", "path", "output", &
         & "NetCDF output, relative to the working directory (empty: outputs/<scene " // &
         & "name>.nc, the directory created if missing). The command line's -o overrides it.")
      s(p_series) = logical_param("output", "series", ".false.", "output", &
         & "also write per-position mu_inst, hydro_load, penetration, contact_elements " // &
         & "(memory: 4 x positions x speeds values)")

      ! &batch
      s(p_batch_profiles) = text("batch", "profiles", "", "path", "batch", &
         & "a file-name pattern ('segments/*.txt') or a directory, relative to the " // &
         & "namelist's directory; give this or profile_list")
      s(p_batch_profile_list) = text("batch", "profile_list", "", "path", "batch", &
         & "a file naming one profile a line ('#' comments), relative to the list")
      s(p_batch_depths) = list_param("batch", "depths", "", "m", "batch", &
         & "water depths to run every profile at (empty: &water depth)", lower=0.0_wp, &
         & upper=100.0_wp, max_values=1000, plausible_lower=0.0_wp, plausible_upper=0.02_wp, &
         & plausible_note="water films on roads are millimetres deep; depths are in metres")
      s(p_batch_restart) = logical_param("batch", "restart", ".true.", "batch", &
         & "resume from the journal of an interrupted run")
      s(p_batch_progress_every) = int_param("batch", "progress_every", "0", "batch", &
         & "profiles between progress lines (0: about 20 lines)", 0, huge(1))
      ! the components' own variables, from their declarations
      s(n_scene_parameters + 1:n_scene_parameters + n_film_parameters) = wet_model_parameters()
      s(rubber_first:rubber_first + n_rubber_parameters - 1) = rubber_parameters()
      s(preprocess_first:pad_first - 1) = preprocess_parameters()
      s(pad_first:facet_first - 1) = pad_parameters()
      s(facet_first:n_parameters) = facet_parameters()
   end function parameter_table

   ! --- values ----------------------------------------------------------------

   !> Every variable at its default (optional ones without a default unset).
   pure subroutine default_parameters(specs, set, error)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(out) :: set
      type(error_type), allocatable, intent(out) :: error
      type(nml_token_type) :: tok(1)
      integer :: k
      do k = 1, size(specs)
         if (len(specs(k)%default) == 0) then
            if (specs(k)%kind == kind_real_list) allocate(set%v(k)%list(0))
            cycle
         end if
         tok(1)%text = specs(k)%default
         tok(1)%quoted = specs(k)%kind == kind_text
         if (tok(1)%quoted) tok(1)%text = specs(k)%default(2:len(specs(k)%default)-1)
         call store_scalar(specs(k), tok, 1, "", set%v(k), error)
         if (allocated(error)) then
            error%message = "internal: the default of &" // specs(k)%group // " " // &
               & specs(k)%name // " is not valid: " // error%message
            return
         end if
         set%v(k)%given = .false.
      end do
   end subroutine default_parameters

   !> Apply namelist `text` (from `path`, named in messages) to `set`. Groups
   !> not in `allowed` (space-separated; '' = any) are errors; a group or a
   !> variable given twice in the text is an error.
   pure subroutine apply_namelist(specs, text, path, set, error, allowed, groups_seen)
      type(param_spec_type), intent(in) :: specs(:)
      character(len=*), intent(in) :: text, path
      type(param_set_type), intent(inout) :: set
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: allowed
      !> The groups the text holds, space-separated with blanks around.
      character(len=:), allocatable, intent(out), optional :: groups_seen
      type(nml_group_type), allocatable :: groups(:)
      type(group_spec_type) :: gs(n_groups)
      character(len=:), allocatable :: known, seen, names
      integer :: n, g, j, id, k, first_line(n_groups)
      logical :: assigned(n_parameters)
      ! a list being built: element values and which were given
      real(wp), allocatable :: elems(:, :)
      logical, allocatable :: elem_set(:, :)

      call parse_namelist(text, path, groups, n, error)
      if (allocated(error)) return
      gs = group_table()
      known = " "
      do g = 1, n_groups
         known = known // gs(g)%name // " "
      end do
      if (present(allowed)) then
         if (len_trim(allowed) > 0) known = " " // trim(adjustl(allowed)) // " "
      end if
      seen = " "
      first_line = 0
      assigned = .false.
      allocate(elems(0, 0), elem_set(0, 0))
      do g = 1, n
         associate(grp => groups(g))
            if (index(known, " " // grp%name // " ") == 0) then
               call fatal_error(error, "&" // grp%name // ": unknown namelist group " // &
                  & where(path, grp%line) // "(known:" // known // ")")
               return
            end if
            if (index(seen, " " // grp%name // " ") > 0) then
               do k = 1, n_groups
                  if (gs(k)%name == grp%name) exit
               end do
               call fatal_error(error, "&" // grp%name // ": given twice " // &
                  & where(path, first_line(k)) // "and " // trim(where(path, grp%line)) // &
                  & "; merge the two groups")
               return
            end if
            seen = seen // grp%name // " "
            do k = 1, n_groups
               if (gs(k)%name == grp%name) first_line(k) = grp%line
            end do
            do j = 1, grp%n_items
               associate(item => grp%items(j))
                  id = find_parameter(specs, grp%name, item%name)
                  if (id == 0) then
                     names = ""
                     do k = 1, size(specs)
                        if (specs(k)%group == grp%name) names = names // " " // specs(k)%name
                     end do
                     call fatal_error(error, "&" // grp%name // " " // item%name // " = " // &
                        & item%written // ": unknown variable " // where(path, item%line) // &
                        & "(known:" // names // ")")
                     return
                  end if
                  call apply_item(specs(id), id, item, path, set, assigned, elems, elem_set, &
                     & error)
                  if (allocated(error)) return
               end associate
            end do
         end associate
      end do
      ! lists: the elements given form the new list, without gaps
      do id = 1, size(specs)
         if (specs(id)%kind /= kind_real_list .or. .not. assigned(id)) cycle
         call finish_list(specs(id), id, elems, elem_set, set%v(id), error)
         if (allocated(error)) return
      end do
      if (present(groups_seen)) groups_seen = seen
   end subroutine apply_namelist

   !> One assignment into the set.
   pure subroutine apply_item(spec, id, item, path, set, assigned, elems, elem_set, error)
      type(param_spec_type), intent(in) :: spec
      integer, intent(in) :: id
      type(nml_item_type), intent(in) :: item
      character(len=*), intent(in) :: path
      type(param_set_type), intent(inout) :: set
      logical, intent(inout) :: assigned(:)
      real(wp), allocatable, intent(inout) :: elems(:, :)
      logical, allocatable, intent(inout) :: elem_set(:, :)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: where_
      integer :: n, k, r, pos, total
      real(wp) :: v

      where_ = where(path, item%line)
      ! (a file's line; text given through the API has no file: 0, which
      ! also forgets the file's line of a value the API replaced)
      set%v(id)%line = merge(item%line, 0, len(path) > 0)
      if (spec%kind /= kind_real_list) then
         if (assigned(id)) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // ": given twice " // &
               & "in the group " // trim(where_))
            return
         end if
         if (item%subscript /= 0) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // "(" // &
               & to_str(item%subscript) // ") = " // item%written // ": " // spec%name // &
               & " is not a list " // trim(where_))
            return
         end if
         total = 0
         do k = 1, item%n_values
            total = total + item%values(k)%repeat
         end do
         if (total /= 1) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // " = " // &
               & item%written // ": one value expected, " // to_str(total) // " given " // &
               & trim(where_))
            return
         end if
         call store_scalar(spec, item%values, item%n_values, item%written, set%v(id), error)
         if (allocated(error)) then
            error%message = error%message // " " // trim(where_)
            return
         end if
         assigned(id) = .true.
         return
      end if
      ! a list: collect the elements, from the subscript on
      if (size(elems, 2) < id) call grow_lists(elems, elem_set, n_parameters)
      pos = max(item%subscript, 1)
      do k = 1, item%n_values
         associate(tok => item%values(k))
            call list_element(spec, tok, pos, v, error)
            if (allocated(error)) then
               error%message = error%message // " " // trim(where_)
               return
            end if
            do r = 1, tok%repeat
               if (pos > spec%max_values) then
                  call fatal_error(error, "&" // spec%group // " " // spec%name // ": more " // &
                     & "than " // to_str(spec%max_values) // " values " // trim(where_))
                  return
               end if
               n = size(elems, 1)
               if (pos > n) call grow_rows(elems, elem_set, max(2 * n, pos, 8))
               if (elem_set(pos, id)) then
                  call fatal_error(error, "&" // spec%group // " " // spec%name // "(" // &
                     & to_str(pos) // "): given twice " // trim(where_))
                  return
               end if
               elems(pos, id) = v
               elem_set(pos, id) = .true.
               pos = pos + 1
            end do
         end associate
      end do
      assigned(id) = .true.
   end subroutine apply_item

   !> One element of a list, checked.
   pure subroutine list_element(spec, tok, pos, v, error)
      type(param_spec_type), intent(in) :: spec
      type(nml_token_type), intent(in) :: tok
      integer, intent(in) :: pos
      real(wp), intent(out) :: v
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: label
      integer :: stat
      label = "&" // spec%group // " " // spec%name // "(" // to_str(pos) // ") = "
      v = 0.0_wp
      if (tok%quoted) then
         call fatal_error(error, label // "'" // tok%text // "': " // not_a_number(spec, ""))
         return
      end if
      call parse_real(tok%text, v, stat)
      if (stat /= 0) then
         call fatal_error(error, label // tok%text // ": " // not_a_number(spec, tok%text))
         return
      end if
      call check_range(spec, v, label, error, tok%text)
   end subroutine list_element

   !> The elements given for list `id` become its value; gaps are errors.
   pure subroutine finish_list(spec, id, elems, elem_set, value, error)
      type(param_spec_type), intent(in) :: spec
      integer, intent(in) :: id
      real(wp), intent(in) :: elems(:, :)
      logical, intent(in) :: elem_set(:, :)
      type(param_value_type), intent(inout) :: value
      type(error_type), allocatable, intent(out) :: error
      integer :: n, k
      n = 0
      do k = size(elem_set, 1), 1, -1
         if (elem_set(k, id)) then
            n = k
            exit
         end if
      end do
      do k = 1, n
         if (.not. elem_set(k, id)) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // ": element " // &
               & to_str(k) // " is not given (the list has gaps, up to element " // &
               & to_str(n) // "); give " // spec%name // "(" // to_str(k) // ") too, or " // &
               & "number the elements from 1 without gaps")
            return
         end if
      end do
      value%list = elems(1:n, id)
      value%given = .true.
      value%set = n > 0
   end subroutine finish_list

   !> A scalar value from its token, checked against the declaration.
   pure subroutine store_scalar(spec, toks, n, written, value, error)
      type(param_spec_type), intent(in) :: spec
      type(nml_token_type), intent(in) :: toks(:)
      integer, intent(in) :: n
      character(len=*), intent(in) :: written
      type(param_value_type), intent(inout) :: value
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: label, t, shown
      integer :: stat, i
      real(wp) :: r
      logical :: b
      associate(tok => toks(1))
         shown = written
         if (len(shown) == 0) shown = tok%text
         label = "&" // spec%group // " " // spec%name // " = "
         select case (spec%kind)
         case (kind_real, kind_real_list)
            if (tok%quoted) then
               call fatal_error(error, label // shown // ": " // not_a_number(spec, ""))
               return
            end if
            call parse_real(tok%text, r, stat)
            if (stat /= 0) then
               call fatal_error(error, label // shown // ": " // not_a_number(spec, tok%text))
               return
            end if
            call check_range(spec, r, label, error, tok%text)
            if (allocated(error)) return
            if (spec%kind == kind_real) then
               value%r = r
            else
               value%list = [r]
            end if
         case (kind_integer)
            if (tok%quoted) then
               call fatal_error(error, label // shown // ": " // whole_number_text(spec))
               return
            end if
            call parse_integer(tok%text, i, stat)
            if (stat == 2) then
               call fatal_error(error, label // shown // ": too large (must lie in [" // &
                  & to_str(nint(spec%lower)) // ", " // int_upper(spec) // "])")
               return
            end if
            if (stat /= 0) then
               call fatal_error(error, label // shown // ": " // whole_number_text(spec))
               return
            end if
            call check_integer(spec, i, label, error)
            if (allocated(error)) return
            value%i = i
         case (kind_logical)
            call parse_logical(tok, b, stat)
            if (stat /= 0) then
               call fatal_error(error, label // shown // ": cannot be read as a logical " // &
                  & "(.true. or .false.)")
               return
            end if
            value%b = b
         case (kind_text)
            if (.not. tok%quoted) then
               call fatal_error(error, label // shown // ": text must be quoted ('" // &
                  & tok%text // "')")
               return
            end if
            t = tok%text
            call check_choice(spec, t, label, error)
            if (allocated(error)) return
            value%t = t
         end select
      end associate
      if (n > 1) continue
      value%given = .true.
      value%set = .true.
   end subroutine store_scalar

   !> An integer's range check, with the reader's message (`label` names
   !> the variable: '&group name = ').
   pure subroutine check_integer(spec, i, label, error)
      type(param_spec_type), intent(in) :: spec
      integer, intent(in) :: i
      character(len=*), intent(in) :: label
      type(error_type), allocatable, intent(out) :: error
      if (real(i, wp) >= spec%lower .and. real(i, wp) <= spec%upper) return
      if (spec%upper >= real(huge(1), wp)) then
         call fatal_error(error, label // to_str(i) // ": must be >= " // to_str(nint(spec%lower)))
      else
         call fatal_error(error, label // to_str(i) // ": must lie in [" // &
            & to_str(nint(spec%lower)) // ", " // int_upper(spec) // "]")
      end if
   end subroutine check_integer

   !> A text against the declared choices (any text when there are none).
   pure subroutine check_choice(spec, t, label, error)
      type(param_spec_type), intent(in) :: spec
      character(len=*), intent(in) :: t, label
      type(error_type), allocatable, intent(out) :: error
      if (len(spec%choices) == 0) return
      if (index(" " // spec%choices // " ", " " // t // " ") == 0 .or. &
            & len_trim(t) == 0 .or. index(t, " ") > 0) then
         call fatal_error(error, label // "'" // t // "': unknown (expected " // &
            & choice_list(spec%choices) // ")")
      end if
   end subroutine check_choice

   !> The declared kind, in words, for a message about a value of another
   !> kind (a subroutine: no deferred-length function result, whose length
   !> gfortran keeps in a static variable).
   pure subroutine kind_words(spec, t)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable, intent(out) :: t
      select case (spec%kind)
      case (kind_real)
         t = "a real number"
      case (kind_integer)
         t = "a whole number"
      case (kind_logical)
         t = "a logical"
      case (kind_text)
         t = "a text"
      case default
         t = "a list of real numbers"
      end select
   end subroutine kind_words

   !> A value given as a number, a logical or a text rather than namelist
   !> text (the C API's and the library's typed setters): checked against
   !> the declaration as the namelist reader checks it, with its messages.
   !> Exactly one of r, i, b, t, list is present; a whole number is taken
   !> for a real variable and a single number for a list, as a namelist
   !> takes `load = 10` and `speeds_kmh = 20`. On error `value` is unchanged.
   pure subroutine typed_value(spec, value, error, r, i, b, t, list)
      type(param_spec_type), intent(in) :: spec
      type(param_value_type), intent(inout) :: value
      type(error_type), allocatable, intent(out) :: error
      real(wp), intent(in), optional :: r
      integer, intent(in), optional :: i
      logical, intent(in), optional :: b
      character(len=*), intent(in), optional :: t
      real(wp), intent(in), optional :: list(:)
      type(param_value_type) :: new
      character(len=:), allocatable :: label, expected, given
      real(wp), allocatable :: x(:)
      logical :: as_real, as_list
      integer :: k
      label = "&" // spec%group // " " // spec%name // " = "
      new = value
      ! a whole number for a real (or a list), a single number for a list
      as_real = spec%kind == kind_real .and. (present(r) .or. present(i))
      as_list = spec%kind == kind_real_list .and. (present(r) .or. present(i) .or. present(list))
      if (as_real .or. as_list) then
         if (present(list)) then
            x = list
         else if (present(r)) then
            x = [r]
         else
            x = [real(i, wp)]
         end if
      end if
      if (.not. (as_real .or. as_list .or. &
            & (present(i) .and. spec%kind == kind_integer) .or. &
            & (present(b) .and. spec%kind == kind_logical) .or. &
            & (present(t) .and. spec%kind == kind_text))) then
         call kind_words(spec, expected)
         if (present(r)) given = "a real number"
         if (present(i)) given = "a whole number"
         if (present(b)) given = "a logical"
         if (present(t)) given = "a text"
         if (present(list)) given = "a list of numbers"
         if (.not. allocated(given)) given = "no value"
         call fatal_error(error, "&" // spec%group // " " // spec%name // ": " // &
            & expected // " is expected, not " // given // &
            & " (docs/inputs.md gives each variable's type)")
         return
      end if
      select case (spec%kind)
      case (kind_real)
         call check_range(spec, x(1), label, error)
         if (allocated(error)) return
         new%r = x(1)
      case (kind_integer)
         call check_integer(spec, i, label, error)
         if (allocated(error)) return
         new%i = i
      case (kind_logical)
         new%b = b
      case (kind_text)
         call check_choice(spec, t, label, error)
         if (allocated(error)) return
         new%t = t
      case (kind_real_list)
         if (size(x) == 0 .and. spec%required) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // ": an empty " // &
               & "list (0 values), but the variable is required: give at least one value")
            return
         end if
         if (size(x) > spec%max_values) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // ": more than " // &
               & to_str(spec%max_values) // " values (" // to_str(size(x)) // " given)")
            return
         end if
         do k = 1, size(x)
            call check_range(spec, x(k), "&" // spec%group // " " // spec%name // "(" // &
               & to_str(k) // ") = ", error)
            if (allocated(error)) return
         end do
         new%list = x
      end select
      new%given = .true.
      new%set = .true.
      if (spec%kind == kind_real_list) new%set = size(x) > 0
      value = new
   end subroutine typed_value

   !> Values given as typed items, without namelist text (the Python
   !> layer's keywords): item k sets variable ids(k) of `specs` from a value
   !> of kind kinds(k) (typed_*): counts(k) numbers taken in turn from
   !> `reals` (a real; a whole number; a logical, 0 or 1; a list), or
   !> text_lengths(k) characters taken in turn from `text`. Each is checked
   !> against its declaration by typed_value, as the C API's typed setters
   !> are.
   pure subroutine apply_typed(specs, set, ids, kinds, reals, counts, text, text_lengths, error)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(inout) :: set
      integer, intent(in) :: ids(:), kinds(:), counts(:), text_lengths(:)
      real(wp), intent(in) :: reals(:)
      character(len=*), intent(in) :: text
      type(error_type), allocatable, intent(out) :: error
      integer :: k, id, r0, t0, n, nt
      real(wp) :: x
      r0 = 0
      t0 = 0
      if (size(kinds) /= size(ids) .or. size(counts) /= size(ids) .or. &
            & size(text_lengths) /= size(ids)) then
         call fatal_error(error, "internal: typed items of unequal lengths")
         return
      end if
      do k = 1, size(ids)
         id = ids(k)
         n = counts(k)
         nt = text_lengths(k)
         if (id < 1 .or. id > size(specs) .or. n < 0 .or. nt < 0 .or. &
               & r0 + n > size(reals) .or. t0 + nt > len(text)) then
            call fatal_error(error, "internal: typed item " // to_str(k) // " is malformed")
            return
         end if
         if (kinds(k) /= typed_list .and. kinds(k) /= typed_text .and. n /= 1) then
            call fatal_error(error, "internal: typed item " // to_str(k) // " has " // &
               & to_str(n) // " numbers")
            return
         end if
         select case (kinds(k))
         case (typed_real)
            call typed_value(specs(id), set%v(id), error, r=reals(r0 + 1))
         case (typed_integer)
            x = reals(r0 + 1)
            if (abs(x) < real(huge(1), wp) .and. x == aint(x)) then
               call typed_value(specs(id), set%v(id), error, i=int(x))
            else if (specs(id)%kind == kind_integer) then
               ! 2.9, or beyond the integers: the reader's words for it
               call fatal_error(error, "&" // specs(id)%group // " " // specs(id)%name // &
                  & " = " // to_str(x) // ": must be a whole number in [" // &
                  & to_str(nint(specs(id)%lower)) // ", " // int_upper(specs(id)) // "]")
            else
               call typed_value(specs(id), set%v(id), error, r=x)
            end if
         case (typed_logical)
            call typed_value(specs(id), set%v(id), error, b=reals(r0 + 1) /= 0.0_wp)
         case (typed_text)
            call typed_value(specs(id), set%v(id), error, t=text(t0 + 1:t0 + nt))
         case (typed_list)
            call typed_value(specs(id), set%v(id), error, list=reals(r0 + 1:r0 + n))
         case default
            call fatal_error(error, "internal: typed item " // to_str(k) // " of kind " // &
               & to_str(kinds(k)))
         end select
         if (allocated(error)) return
         r0 = r0 + n
         t0 = t0 + nt
      end do
   end subroutine apply_typed

   !> Hard range check, with the message style of every range error. The
   !> message names the value as `prefix` followed by r (formatted only when
   !> there is an error: a run reads every declared value through here).
   pure subroutine check_range(spec, r, prefix, error, text)
      type(param_spec_type), intent(in) :: spec
      real(wp), intent(in) :: r
      character(len=*), intent(in) :: prefix
      type(error_type), allocatable, intent(out) :: error
      !> The value as written: a nonzero number that underflowed is refused.
      character(len=*), intent(in), optional :: text
      logical :: ok
      integer :: k
      if (present(text) .and. r == 0.0_wp) then
         ! 1e-400 reads as 0: another value than the one written (a
         ! subnormal such as 1e-310 keeps its value, to fewer digits)
         k = scan(text, "eEdD")
         if (k == 0) k = len(text) + 1
         if (scan(text(1:k-1), "123456789") > 0) then
            call fatal_error(error, "&" // spec%group // " " // spec%name // " = " // &
               & trim(text) // ": too small for double precision (it would be read as 0; " // &
               & "the smallest value is about 4.9e-324); write 0 or a larger value")
            return
         end if
      end if
      if (present(text) .and. .not. (abs(r) <= huge(r)) .and. .not. ieee_is_nan(r)) then
         if (scan(to_lower(text), "n") == 0) then
            ! 1e400 overflows to Infinity: say so, with the value as written
            call fatal_error(error, "&" // spec%group // " " // spec%name // " = " // &
               & trim(text) // ": too large for double precision (it would be read as " // &
               & "Infinity); " // range_text(spec))
            return
         end if
      end if
      if (spec%group == "numerics" .and. spec%name == "tolerance" .and. r > 0.0_wp .and. &
            & r < tolerance_floor) then
         call fatal_error(error, prefix // to_str(r) // ": below what double precision can meet (the " // &
            & "rounding of mu alone is about 1e-15, and each halving of the time step " // &
            & "doubles the run); use 0 (off) or a tolerance >= " // to_str(tolerance_floor))
         return
      end if
      ok = .not. ieee_is_nan(r) .and. abs(r) <= huge(r)
      if (ok) then
         if (spec%lower_strict) then
            ok = r > spec%lower
         else
            ok = r >= spec%lower
         end if
      end if
      if (ok) then
         if (spec%upper_strict) then
            ok = r < spec%upper
         else
            ok = r <= spec%upper
         end if
      end if
      if (ok) return
      call fatal_error(error, prefix // to_str(r) // ": " // range_text(spec))
   end subroutine check_range

   !> Why a token is not a number, and what to write: the range for a NaN or
   !> an Infinity written out (Python sends them so), the grammar otherwise
   !> (text: the token; "" for a quoted one).
   pure function not_a_number(spec, text) result(t)
      type(param_spec_type), intent(in) :: spec
      character(len=*), intent(in) :: text
      character(len=not_a_number_len(spec, text)) :: t
      character(len=:), allocatable :: deferred_text
      call not_a_number_text(spec, deferred_text, text)
      t = deferred_text
   end function not_a_number

   !> The length of not_a_number's text.
   pure integer function not_a_number_len(spec, text)
      type(param_spec_type), intent(in) :: spec
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: deferred_text
      call not_a_number_text(spec, deferred_text, text)
      not_a_number_len = len(deferred_text)
   end function not_a_number_len

   !> The text of not_a_number, into a deferred-length argument.
   pure subroutine not_a_number_text(spec, t, text)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable, intent(out) :: t
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: w
      w = to_lower(trim(adjustl(text)))
      if (len(w) > 0) then
         if (w(1:1) == "+" .or. w(1:1) == "-") w = w(2:)
      end if
      if (w == "nan" .or. w == "inf" .or. w == "infinity") then
         t = range_text(spec)
      else
         t = "not a number (write one such as 0.5, 1e-3 or 2.5d3); " // range_text(spec)
      end if
   end subroutine not_a_number_text

   !> 'must be a whole number from 1 to 1024', or '... >= 0'.
   pure function whole_number_text(spec) result(t)
      type(param_spec_type), intent(in) :: spec
      character(len=whole_number_len(spec)) :: t
      character(len=:), allocatable :: deferred_text
      call whole_number_text_text(spec, deferred_text)
      t = deferred_text
   end function whole_number_text

   !> The length of whole_number_text's text.
   pure integer function whole_number_len(spec)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable :: deferred_text
      call whole_number_text_text(spec, deferred_text)
      whole_number_len = len(deferred_text)
   end function whole_number_len

   !> The text of whole_number_text, into a deferred-length argument.
   pure subroutine whole_number_text_text(spec, t)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable, intent(out) :: t
      if (spec%upper >= real(huge(1), wp)) then
         t = "must be a whole number >= " // to_str(nint(spec%lower))
      else
         t = "must be a whole number from " // to_str(nint(spec%lower)) // " to " // &
            & int_upper(spec)
      end if
   end subroutine whole_number_text_text

   !> 'must be finite and > 0', 'must be > 0 and < 90 degree' ...
   pure function range_text(spec) result(t)
      type(param_spec_type), intent(in) :: spec
      character(len=range_text_len(spec)) :: t
      character(len=:), allocatable :: deferred_text
      call range_text_text(spec, deferred_text)
      t = deferred_text
   end function range_text

   !> The length of range_text's text.
   pure integer function range_text_len(spec)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable :: deferred_text
      call range_text_text(spec, deferred_text)
      range_text_len = len(deferred_text)
   end function range_text_len

   !> The text of range_text, into a deferred-length argument.
   pure subroutine range_text_text(spec, t)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable, intent(out) :: t
      character(len=:), allocatable :: unit
      unit = ""
      if (len(spec%unit) > 0 .and. spec%unit /= "1" .and. spec%unit /= "path") &
         & unit = " " // spec%unit
      t = "must be finite and " // trim(merge("> ", ">=", spec%lower_strict)) // " " // &
         & to_str(spec%lower)
      if (spec%upper < huge(1.0_wp)) t = t // " and " // &
         & trim(merge("< ", "<=", spec%upper_strict)) // " " // to_str(spec%upper)
      t = t // unit
   end subroutine range_text_text

   pure function int_upper(spec) result(t)
      type(param_spec_type), intent(in) :: spec
      character(len=int_upper_len(spec)) :: t
      character(len=:), allocatable :: deferred_text
      call int_upper_text(spec, deferred_text)
      t = deferred_text
   end function int_upper

   !> The length of int_upper's text.
   pure integer function int_upper_len(spec)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable :: deferred_text
      call int_upper_text(spec, deferred_text)
      int_upper_len = len(deferred_text)
   end function int_upper_len

   !> The text of int_upper, into a deferred-length argument.
   pure subroutine int_upper_text(spec, t)
      type(param_spec_type), intent(in) :: spec
      character(len=:), allocatable, intent(out) :: t
      if (spec%upper >= real(huge(1), wp)) then
         t = to_str(huge(1))
      else
         t = to_str(nint(spec%upper))
      end if
   end subroutine int_upper_text

   !> "'a', 'b' or 'c'" from "a b c".
   pure function choice_list(choices) result(t)
      character(len=*), intent(in) :: choices
      character(len=choice_list_len(choices)) :: t
      character(len=:), allocatable :: deferred_text
      call choice_list_text(choices, deferred_text)
      t = deferred_text
   end function choice_list

   !> The length of choice_list's text.
   pure integer function choice_list_len(choices)
      character(len=*), intent(in) :: choices
      character(len=:), allocatable :: deferred_text
      call choice_list_text(choices, deferred_text)
      choice_list_len = len(deferred_text)
   end function choice_list_len

   !> The text of choice_list, into a deferred-length argument.
   pure subroutine choice_list_text(choices, t)
      character(len=*), intent(in) :: choices
      character(len=:), allocatable, intent(out) :: t
      character(len=:), allocatable :: rest
      integer :: k, n, total
      total = 0
      rest = trim(adjustl(choices))
      do while (len(rest) > 0)
         total = total + 1
         k = index(rest // " ", " ")
         rest = trim(adjustl(rest(k:)))
      end do
      t = ""
      n = 0
      rest = trim(adjustl(choices))
      do while (len(rest) > 0)
         n = n + 1
         k = index(rest // " ", " ")
         if (n > 1) t = t // trim(merge(" or", ",  ", n == total)) // " "
         t = t // "'" // rest(1:k-1) // "'"
         rest = trim(adjustl(rest(k:)))
      end do
   end subroutine choice_list_text

   !> .true./.false./t/f/true/false/.t./.f. in any case.
   pure subroutine parse_logical(tok, b, stat)
      type(nml_token_type), intent(in) :: tok
      logical, intent(out) :: b
      integer, intent(out) :: stat
      character(len=:), allocatable :: t
      b = .false.
      stat = 1
      if (tok%quoted) return
      t = to_lower(tok%text)
      select case (t)
      case (".true.", "true", "t", ".t.", ".t")
         b = .true.
         stat = 0
      case (".false.", "false", "f", ".f.", ".f")
         b = .false.
         stat = 0
      end select
   end subroutine parse_logical

   pure subroutine grow_lists(elems, elem_set, n)
      real(wp), allocatable, intent(inout) :: elems(:, :)
      logical, allocatable, intent(inout) :: elem_set(:, :)
      integer, intent(in) :: n
      real(wp), allocatable :: e(:, :)
      logical, allocatable :: s(:, :)
      allocate(e(size(elems, 1), n), s(size(elems, 1), n))
      e = 0.0_wp
      s = .false.
      e(:, 1:size(elems, 2)) = elems
      s(:, 1:size(elems, 2)) = elem_set
      call move_alloc(e, elems)
      call move_alloc(s, elem_set)
   end subroutine grow_lists

   pure subroutine grow_rows(elems, elem_set, n)
      real(wp), allocatable, intent(inout) :: elems(:, :)
      logical, allocatable, intent(inout) :: elem_set(:, :)
      integer, intent(in) :: n
      real(wp), allocatable :: e(:, :)
      logical, allocatable :: s(:, :)
      allocate(e(n, size(elems, 2)), s(n, size(elems, 2)))
      e = 0.0_wp
      s = .false.
      e(1:size(elems, 1), :) = elems
      s(1:size(elems, 1), :) = elem_set
      call move_alloc(e, elems)
      call move_alloc(s, elem_set)
   end subroutine grow_rows

   !> "at path:line " (or "in path " without a line) for messages; nothing
   !> for keywords (no file).
   pure function where(path, line) result(t)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=where_len(path, line)) :: t
      character(len=:), allocatable :: deferred_text
      call where_text(path, line, deferred_text)
      t = deferred_text
   end function where

   !> The length of where's text.
   pure integer function where_len(path, line)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=:), allocatable :: deferred_text
      call where_text(path, line, deferred_text)
      where_len = len(deferred_text)
   end function where_len

   !> The text of where, into a deferred-length argument.
   pure subroutine where_text(path, line, t)
      character(len=*), intent(in) :: path
      integer, intent(in) :: line
      character(len=:), allocatable, intent(out) :: t
      if (len(path) == 0) then
         t = ""
      else if (line > 0) then
         t = "at " // path // ":" // to_str(line) // " "
      else
         t = "in " // path // " "
      end if
   end subroutine where_text

   ! --- the model -------------------------------------------------------------

   !> The physical and numerical parameters of a set.
   pure function model_from_parameters(set) result(m)
      type(param_set_type), intent(in) :: set
      type(model_type) :: m
      m%mu_loc = set%v(p_mu_loc)%r
      m%microtexture_rms = set%v(p_microtexture_rms)%r
      m%length = set%v(p_length)%r
      m%width = set%v(p_width)%r
      m%thickness = set%v(p_thickness)%r
      m%load = set%v(p_load)%r
      m%shape = set%v(p_shape)%t
      m%radius = set%v(p_radius)%r
      m%element_length = set%v(p_element_length)%r
      m%rubber_model = set%v(p_rubber_model)%t
      m%stiffness = set%v(p_stiffness)%r
      m%viscosity = set%v(p_viscosity)%r
      m%prony_stiffness = list_or_empty(set%v(p_prony_stiffness))
      m%prony_times = list_or_empty(set%v(p_prony_times))
      m%temperature = set%v(p_temperature)%r
      m%reference_temperature = set%v(p_reference_temperature)%r
      m%wlf_c1 = set%v(p_wlf_c1)%r
      m%wlf_c2 = set%v(p_wlf_c2)%r
      m%wet_model = set%v(p_wet_model)%t
      m%depth = set%v(p_depth)%r
      m%water_viscosity = set%v(p_water_viscosity)%r
      m%values = set%v
      ! kept for code that reads them (the bearing reads its own by name),
      ! through the deprecated ids rather than a second build of the table
      m%alpha = set%v(p_alpha)%r
      m%beta = set%v(p_beta)%r
      m%theta_max_deg = set%v(p_theta_max_deg)%r
      m%substeps = set%v(p_substeps)%i
      m%elements_per_sample = set%v(p_elements_per_sample)%i
      m%position_stride = set%v(p_position_stride)%i
      m%wet_tolerance = set%v(p_wet_tolerance)%r
      m%tolerance = set%v(p_tolerance)%r
      m%error_estimate = set%v(p_error_estimate)%b
      m%min_contacts = set%v(p_min_contacts)%i
      m%friction_scheme = set%v(p_friction_scheme)%t
      m%time_scheme = set%v(p_time_scheme)%t
   end function model_from_parameters

   !> A list's values (none when it has no value).
   pure function list_or_empty(value) result(list)
      type(param_value_type), intent(in) :: value
      real(wp), allocatable :: list(:)
      if (allocated(value%list)) then
         list = value%list
      else
         allocate(list(0))
      end if
   end function list_or_empty


   !> Checks that involve several parameters (each value's own range is
   !> checked when it is read).
   pure subroutine validate_model(m, error)
      type(model_type), intent(in) :: m
      type(error_type), allocatable, intent(out) :: error
      type(param_spec_type), allocatable :: specs(:)
      if (.not. allocated(m%shape)) then
         call fatal_error(error, "internal: a model_type not made by model_from_parameters")
         return
      end if
      if (.not. allocated(m%values)) then
         call fatal_error(error, "internal: a model_type not made by model_from_parameters")
         return
      end if
      specs = parameter_table()
      call check_pad(specs, m%values, error)
      if (allocated(error)) return
      ! accuracy on demand estimates the error from two successive halvings
      ! of the step: a start that leaves room for fewer would report no
      ! estimate (it was written as 1.797e308)
      if (m%tolerance > 0.0_wp .and. 4 * m%substeps > max_substeps) then
         call fatal_error(error, "&numerics substeps = " // to_str(m%substeps) // &
            & " with tolerance = " // to_str(m%tolerance) // ": accuracy on demand halves " // &
            & "the step at least twice to estimate the error, and substeps may not pass " // &
            & to_str(max_substeps) // "; give substeps <= " // to_str(max_substeps / 4) // &
            & " (or tolerance = 0 to run substeps as given)")
         return
      end if
      if (allocated(m%time_scheme)) then
         if (m%time_scheme == "richardson" .and. m%tolerance <= 0.0_wp .and. &
            & .not. m%error_estimate) then
            call fatal_error(error, "&numerics time_scheme = 'richardson' with " // &
               & "error_estimate = .false. (and tolerance = 0): the Richardson value " // &
               & "combines the run with the error estimate's pass at half the step; give " // &
               & "error_estimate = .true. (or time_scheme = 'euler' for the run's own pass)")
            return
         end if
         if (m%time_scheme == "exact" .and. m%position_stride /= 1) then
            call fatal_error(error, "&numerics time_scheme = 'exact' with position_stride = " // &
               & to_str(m%position_stride) // ": the exact integrator follows the road " // &
               & "through every position; give position_stride = 1 (or another time_scheme)")
            return
         end if
         if (m%time_scheme == "exact" .and. allocated(m%friction_scheme)) then
            if (m%friction_scheme == "paper") then
               call fatal_error(error, "&numerics time_scheme = 'exact' with friction_scheme " // &
                  & "= 'paper': the exact integrator gives the energy scheme's friction " // &
                  & "(the facets' work); give friction_scheme = 'energy' (or another " // &
                  & "time_scheme)")
               return
            end if
         end if
      end if
      call validate_rubber(m, specs, error)
   end subroutine validate_model

   !> The rubber's cross-checks: a law the registry knows, each law's own
   !> (pavefric_rubber_models: the Maxwell arms in pairs, at least one), and
   !> a temperature where the WLF equation holds.
   pure subroutine validate_rubber(m, specs, error)
      type(model_type), intent(in) :: m
      type(param_spec_type), intent(in) :: specs(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: why, names, listed
      real(wp) :: dt
      if (.not. allocated(m%rubber_model) .or. .not. allocated(m%values)) then
         call fatal_error(error, "internal: a model_type not made by model_from_parameters")
         return
      end if
      call rubber_model_names(names)
      call choice_list_text(names, listed)
      if (index(" " // names // " ", " " // m%rubber_model // " ") == 0) then
         call fatal_error(error, "&rubber model = '" // m%rubber_model // "': unknown " // &
            & "(expected " // listed // ")")
         return
      end if
      call check_rubber(m%rubber_model, specs, m%values, error)
      if (allocated(error)) return
      why = wlf_check(m%temperature, m%reference_temperature, m%wlf_c1, m%wlf_c2)
      dt = m%temperature - m%reference_temperature
      if (why == "diverges") then
         call fatal_error(error, "&rubber temperature = " // to_str(m%temperature) // &
            & ": T - reference_temperature = " // to_str(dt) // " K must be > -wlf_c2 = " // &
            & to_str(-m%wlf_c2) // " K (the WLF equation diverges at T = Tref - C2; it " // &
            & "holds above the glass transition); give a temperature above " // &
            & to_str(m%reference_temperature - m%wlf_c2) // " C, or the WLF constants " // &
            & "of a fit that reaches it")
      else if (why == "too far") then
         call fatal_error(error, "&rubber temperature = " // to_str(m%temperature) // &
            & ": the WLF shift at T - reference_temperature = " // to_str(dt) // " K " // &
            & "(wlf_c1 = " // to_str(m%wlf_c1) // ", wlf_c2 = " // to_str(m%wlf_c2) // &
            & ") is log10 a_T = " // to_str(round_sig(-m%wlf_c1 * dt / (m%wlf_c2 + dt), 4)) // &
            & ", beyond +-" // to_str(nint(max_log10_shift)) // " decades: no WLF fit " // &
            & "holds that far from its reference temperature; give a temperature nearer " // &
            & "reference_temperature = " // to_str(m%reference_temperature) // " C, or " // &
            & "the reference_temperature and WLF constants of a fit near " // &
            & to_str(m%temperature) // " C")
      end if
   end subroutine validate_rubber

   ! --- echo and plausibility -------------------------------------------------

   !> A value as namelist text (shortest round-trip numbers).
   pure function format_value(spec, value) result(t)
      type(param_spec_type), intent(in) :: spec
      type(param_value_type), intent(in) :: value
      character(len=format_value_len(spec, value)) :: t
      character(len=:), allocatable :: deferred_text
      call format_value_text(spec, value, deferred_text)
      t = deferred_text
   end function format_value

   !> The length of format_value's text.
   pure integer function format_value_len(spec, value)
      type(param_spec_type), intent(in) :: spec
      type(param_value_type), intent(in) :: value
      character(len=:), allocatable :: deferred_text
      call format_value_text(spec, value, deferred_text)
      format_value_len = len(deferred_text)
   end function format_value_len

   !> The text of format_value, into a deferred-length argument.
   pure subroutine format_value_text(spec, value, t)
      type(param_spec_type), intent(in) :: spec
      type(param_value_type), intent(in) :: value
      character(len=:), allocatable, intent(out) :: t
      character(len=:), allocatable :: number
      integer :: k
      select case (spec%kind)
      case (kind_real)
         call real_to_str_text(value%r, t)
      case (kind_integer)
         t = to_str(value%i)
      case (kind_logical)
         t = to_str(value%b)
      case (kind_text)
         t = "'" // doubled_quotes(value%t) // "'"
      case default
         t = ""
         do k = 1, size(value%list)
            if (k > 1) t = t // ", "
            call real_to_str_text(value%list(k), number)
            t = t // number
         end do
      end select
   end subroutine format_value_text

   !> The values used, as a namelist that reproduces them (defaults
   !> included); optional variables not set are left out. `groups`
   !> (space-separated) selects the groups; default all.
   pure function parameters_namelist_all(specs, set) result(t)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=parameters_namelist_all_len(specs, set)) :: t
      character(len=:), allocatable :: deferred_text
      call parameters_namelist_text(specs, set, deferred_text)
      t = deferred_text
   end function parameters_namelist_all

   !> The length of parameters_namelist_all's text.
   pure integer function parameters_namelist_all_len(specs, set)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=:), allocatable :: deferred_text
      call parameters_namelist_text(specs, set, deferred_text)
      parameters_namelist_all_len = len(deferred_text)
   end function parameters_namelist_all_len

   !> parameters_namelist with `groups` given.
   pure function parameters_namelist_groups(specs, set, groups) result(t)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: groups
      character(len=parameters_namelist_groups_len(specs, set, groups)) :: t
      character(len=:), allocatable :: deferred_text
      call parameters_namelist_text(specs, set, deferred_text, groups)
      t = deferred_text
   end function parameters_namelist_groups

   !> The length of parameters_namelist_groups's text.
   pure integer function parameters_namelist_groups_len(specs, set, groups)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: groups
      character(len=:), allocatable :: deferred_text
      call parameters_namelist_text(specs, set, deferred_text, groups)
      parameters_namelist_groups_len = len(deferred_text)
   end function parameters_namelist_groups_len

   !> The text of parameters_namelist, into a deferred-length argument.
   pure subroutine parameters_namelist_text(specs, set, t, groups)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=:), allocatable, intent(out) :: t
      character(len=*), intent(in), optional :: groups
      type(group_spec_type) :: gs(n_groups)
      integer :: g, k
      logical :: any_value
      character(len=:), allocatable :: body, value_text
      gs = group_table()
      t = ""
      do g = 1, n_groups
         if (present(groups)) then
            if (index(" " // groups // " ", " " // gs(g)%name // " ") == 0) cycle
         end if
         body = ""
         any_value = .false.
         do k = 1, size(specs)
            if (specs(k)%group /= gs(g)%name) cycle
            if (.not. set%v(k)%set) cycle
            call format_value_text(specs(k), set%v(k), value_text)
            body = body // "  " // specs(k)%name // " = " // value_text // achar(10)
            any_value = .true.
         end do
         if (any_value) t = t // "&" // gs(g)%name // achar(10) // body // "/" // achar(10)
      end do
   end subroutine parameters_namelist_text

   pure function doubled_quotes(s) result(t)
      character(len=*), intent(in) :: s
      character(len=doubled_quotes_len(s)) :: t
      character(len=:), allocatable :: deferred_text
      call doubled_quotes_text(s, deferred_text)
      t = deferred_text
   end function doubled_quotes

   !> The length of doubled_quotes's text.
   pure integer function doubled_quotes_len(s)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: deferred_text
      call doubled_quotes_text(s, deferred_text)
      doubled_quotes_len = len(deferred_text)
   end function doubled_quotes_len

   !> The text of doubled_quotes, into a deferred-length argument.
   pure subroutine doubled_quotes_text(s, t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable, intent(out) :: t
      integer :: k
      t = ""
      do k = 1, len(s)
         t = t // s(k:k)
         if (s(k:k) == "'") t = t // "'"
      end do
   end subroutine doubled_quotes_text

   !> Warnings for values outside what a road, its water or a friction
   !> tester can be (the declarations' plausible ranges).
   pure subroutine plausibility_warnings(specs, set, warnings)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_set_type), intent(in) :: set
      character(len=:), allocatable, intent(inout) :: warnings
      type(film_entry_type), allocatable :: models(:)
      type(rubber_entry_type), allocatable :: laws(:)
      integer :: k, j
      do k = 1, size(specs)
         if (.not. set%v(k)%set) cycle
         select case (specs(k)%kind)
         case (kind_real)
            if (.not. plausible(specs(k), set%v(k)%r)) &
               & call add_warning(warnings, implausible(specs(k), set%v(k)%r, ""))
         case (kind_real_list)
            do j = 1, size(set%v(k)%list)
               if (.not. plausible(specs(k), set%v(k)%list(j))) call add_warning(warnings, &
                  & implausible(specs(k), set%v(k)%list(j), "(" // to_str(j) // ")"))
            end do
         end select
      end do
      if (set%v(p_speeds_kmh)%set .and. allocated(set%v(p_speeds_kmh)%list)) &
         & call repeated_speed_warning(set%v(p_speeds_kmh)%list, warnings)
      ! variables given that the chosen rubber law or wet model does not
      ! use (another law's or model's own)
      laws = rubber_models()
      do j = 1, size(laws)
         if (laws(j)%name /= set%v(p_rubber_model)%t) call warn_unused(specs, set, &
            & laws(j)%parameters, "&rubber model", set%v(p_rubber_model)%t, "model", &
            & laws(j)%name, warnings)
      end do
      models = wet_models()
      do j = 1, size(models)
         if (models(j)%name /= set%v(p_wet_model)%t) call warn_unused(specs, set, &
            & models(j)%parameters, "&water wet_model", set%v(p_wet_model)%t, "wet_model", &
            & models(j)%name, warnings)
      end do
      if (set%v(p_wet_model)%t /= "squeeze" .and. set%v(p_wet_model)%t /= "reynolds" .and. &
            & given_other(specs(p_microtexture_rms), set%v(p_microtexture_rms))) then
         call add_warning(warnings, "&surface microtexture_rms = " // &
            & to_str(set%v(p_microtexture_rms)%r) // " is not used with &water wet_model = '" // &
            & set%v(p_wet_model)%t // "' (only wet_model = 'squeeze' and 'reynolds' use the " // &
            & "microtexture)")
      end if
      if (set%v(p_shape)%t /= "rounded" .and. given_other(specs(p_radius), set%v(p_radius))) &
         & call add_warning(warnings, "&pad radius = " // to_str(set%v(p_radius)%r) // &
         & " is not used with &pad shape = '" // set%v(p_shape)%t // "' (only a rounded " // &
         & "pad has a radius; set shape = 'rounded' to use it)")
      ! 0 is the profile's own spacing (the plausible range starts there);
      ! a positive length finer than any profilometer samples makes a pad of
      ! tens of thousands of elements per centimetre
      if (set%v(p_element_length)%r > 0.0_wp .and. &
            & set%v(p_element_length)%r < element_length_finest) then
         call add_warning(warnings, "&pad element_length = " // &
            & to_str(set%v(p_element_length)%r) // " m: finer than " // &
            & to_str(element_length_finest) // " m, the finest spacing a road profilometer " // &
            & "samples (laser profilometers: 0.01 to 1 mm), so the pad has " // &
            & to_str(nint(min(set%v(p_length)%r / set%v(p_element_length)%r, 2.0e9_wp))) // &
            & " elements; its run's cost grows with their square (0 = the profile's own " // &
            & "spacing)")
      end if
      ! longer than the pad: one element (or none: refused by the run), a
      ! pad longer than &pad length
      if (set%v(p_element_length)%r > set%v(p_length)%r .and. &
            & set%v(p_element_length)%r <= 2.0_wp * set%v(p_length)%r) then
         call add_warning(warnings, "&pad element_length = " // &
            & to_str(set%v(p_element_length)%r) // " m is longer than &pad length = " // &
            & to_str(set%v(p_length)%r) // " m: the pad is one element of that length, " // &
            & "longer than the pad given")
      end if
   end subroutine plausibility_warnings

   !> A warning where &operation speeds_kmh gives a speed more than once
   !> (speeds_kmh = 20, 20, 60 or 3*20): each is computed again and the
   !> output's speed_kmh coordinate repeats the value, which xarray's
   !> ds.sel(speed_kmh=20) then returns twice. Names the first repeat and how
   !> many there are; sorting keeps it O(n log n) for the longest lists.
   pure subroutine repeated_speed_warning(speeds, warnings)
      real(wp), intent(in) :: speeds(:)
      character(len=:), allocatable, intent(inout) :: warnings
      real(wp), allocatable :: v(:)
      integer, allocatable :: at(:)
      integer :: n, j, k, lo, low, second, first, earlier, repeats
      character(len=:), allocatable :: count
      n = size(speeds)
      if (n < 2) return
      v = speeds
      at = [(j, j = 1, n)]
      call sort_with_index(v, at)
      repeats = 0
      first = n + 1
      earlier = 0
      lo = 1
      ! each run of equal values (in any order of index): its smallest index
      ! is the speed given, the second smallest its first repeat
      do j = 2, n + 1
         if (j <= n) then
            if (v(j) == v(j - 1)) cycle
         end if
         if (j - lo > 1) then
            repeats = repeats + (j - lo - 1)
            low = minloc(at(lo:j-1), dim=1) + lo - 1
            second = huge(1)
            do k = lo, j - 1
               if (k /= low) second = min(second, at(k))
            end do
            if (second < first) then
               first = second
               earlier = at(low)
            end if
         end if
         lo = j
      end do
      if (repeats == 0) return
      count = ""
      if (repeats > 1) count = " (" // to_str(repeats) // " repeated values in all)"
      call add_warning(warnings, "&operation speeds_kmh(" // to_str(first) // ") = " // &
         & to_str(speeds(first)) // " repeats speeds_kmh(" // to_str(earlier) // ")" // &
         & count // ": each is computed again and the output's speed_kmh " // &
         & "coordinate holds the value more than once; give each speed once")
   end subroutine repeated_speed_warning

   !> Heap sort of `v` ascending, `at` permuted alongside (ties in any order).
   pure subroutine sort_with_index(v, at)
      real(wp), intent(inout) :: v(:)
      integer, intent(inout) :: at(:)
      integer :: n, k, m
      real(wp) :: t
      n = size(v)
      do k = n / 2, 1, -1
         call sift_down(v, at, k, n)
      end do
      do k = n, 2, -1
         t = v(1); v(1) = v(k); v(k) = t
         m = at(1); at(1) = at(k); at(k) = m
         call sift_down(v, at, 1, k - 1)
      end do
   end subroutine sort_with_index

   !> Restore the heap below `start` in v(1:last) (sort_with_index).
   pure subroutine sift_down(v, at, start, last)
      real(wp), intent(inout) :: v(:)
      integer, intent(inout) :: at(:)
      integer, intent(in) :: start, last
      integer :: root, child, m
      real(wp) :: t
      root = start
      do while (2 * root <= last)
         child = 2 * root
         if (child < last) then
            if (v(child + 1) > v(child)) child = child + 1
         end if
         if (v(root) >= v(child)) return
         t = v(root); v(root) = v(child); v(child) = t
         m = at(root); at(root) = at(child); at(child) = m
         root = child
      end do
   end subroutine sift_down

   !> A warning for each variable of a component that is not the chosen
   !> one (`own`: its declarations; `owner` its name, `key` the variable
   !> that selects it, `selector` that variable as "&group name", `chosen`
   !> its value) given a value other than its default.
   pure subroutine warn_unused(specs, set, own, selector, chosen, key, owner, warnings)
      type(param_spec_type), intent(in) :: specs(:), own(:)
      type(param_set_type), intent(in) :: set
      character(len=*), intent(in) :: selector, chosen, key, owner
      character(len=:), allocatable, intent(inout) :: warnings
      character(len=:), allocatable :: given
      integer :: i, k
      do i = 1, size(own)
         k = find_parameter(specs, own(i)%group, own(i)%name)
         if (k == 0) cycle
         if (specs(k)%kind == kind_real_list) then
            if (.not. set%v(k)%set .or. .not. allocated(set%v(k)%list)) cycle
            if (size(set%v(k)%list) == 0) cycle
            given = ""
         else
            if (.not. given_other(specs(k), set%v(k))) cycle
            given = " = " // to_str(set%v(k)%r)
         end if
         call add_warning(warnings, "&" // specs(k)%group // " " // specs(k)%name // given // &
            & " is not used with " // selector // " = '" // chosen // "' (a variable of " // &
            & key // " = '" // owner // "'; set it to use it)")
      end do
   end subroutine warn_unused

   !> Whether a real variable was given a value other than its default (a
   !> value given equal to the default changes nothing: Python passes every
   !> variable of a scene, the defaults among them).
   pure logical function given_other(spec, value)
      type(param_spec_type), intent(in) :: spec
      type(param_value_type), intent(in) :: value
      real(wp) :: d
      integer :: ios
      given_other = value%given
      if (.not. given_other .or. len_trim(spec%default) == 0) return
      read(spec%default, *, iostat=ios) d
      if (ios == 0) given_other = value%r /= d
   end function given_other

   pure logical function plausible(spec, r)
      type(param_spec_type), intent(in) :: spec
      real(wp), intent(in) :: r
      plausible = r >= spec%plausible_lower .and. r <= spec%plausible_upper
   end function plausible

   !> The warning for value r (element `sub`) outside the plausible range.
   pure function implausible(spec, r, sub) result(line)
      type(param_spec_type), intent(in) :: spec
      real(wp), intent(in) :: r
      character(len=*), intent(in) :: sub
      character(len=implausible_len(spec, r, sub)) :: line
      character(len=:), allocatable :: deferred_text
      call implausible_text(spec, r, sub, deferred_text)
      line = deferred_text
   end function implausible

   !> The length of implausible's text.
   pure integer function implausible_len(spec, r, sub)
      type(param_spec_type), intent(in) :: spec
      real(wp), intent(in) :: r
      character(len=*), intent(in) :: sub
      character(len=:), allocatable :: deferred_text
      call implausible_text(spec, r, sub, deferred_text)
      implausible_len = len(deferred_text)
   end function implausible_len

   !> The text of implausible, into a deferred-length argument.
   pure subroutine implausible_text(spec, r, sub, line)
      type(param_spec_type), intent(in) :: spec
      real(wp), intent(in) :: r
      character(len=*), intent(in) :: sub
      character(len=:), allocatable, intent(out) :: line
      character(len=:), allocatable :: unit
      unit = ""
      if (len(spec%unit) > 0 .and. spec%unit /= "1") unit = " " // spec%unit
      line = "&" // spec%group // " " // spec%name // sub // " = " // to_str(r) // unit // &
         & ": outside the plausible range [" // to_str(spec%plausible_lower) // ", " // &
         & to_str(spec%plausible_upper) // "]" // unit // " (" // spec%plausible_note // ")"
   end subroutine implausible_text

end module pavefric_model
