!> The one table of a run's result variables: each is declared by the
!> component that produces it (pavefric_output_spec: name, units, meaning,
!> type, dimensions, when it is written): the pad and its load balance and
!> the numerics here, the facets in pavefric_facet, the rubber in
!> pavefric_rubber, any load-carrying film in pavefric_film, each wet model's
!> own in its registry entry (pavefric_wet_models). `file_order` lists their
!> names in the order of the output file (and of the C API's indices); the
!> values come from a sim_result_type. The NetCDF writer, the Python layer
!> (through f2py) and the C API all read results through this table, so
!> every output variable is the same bits whichever way it is read.
module pavefric_outputs
   use pavefric_kinds, only: wp
   use pavefric_results, only: sim_result_type
   use pavefric_texture, only: texture_type
   use pavefric_ifi, only: ifi_type
   use pavefric_preprocess, only: preprocess_report_type
   use pavefric_model, only: param_set_type, model_type
   use pavefric_components, only: make_components
   use pavefric_rubber, only: rubber_model, rubber_outputs, n_rubber_outputs
   use pavefric_film, only: film_model, film_entry_type, film_outputs, n_film_outputs
   use pavefric_facet, only: facet_outputs, n_facet_outputs
   use pavefric_wet_models, only: wet_models
   use pavefric_output_spec, only: output_var_type, output_var, out_double, out_int64, out_int, &
      & out_flag, dim_speed, dim_position_speed, when_always, when_series, when_friction_film, &
      & when_friction_film_series, when_error_estimate, when_film_report_series
   implicit none
   private

   public :: output_var_type, output_table, output_present, output_values, n_outputs
   public :: output_metadata_type, series_count
   public :: out_double, out_int64, out_int, out_flag, dim_speed, dim_position_speed
   public :: output_condition, scalar_table, n_scalar_outputs, output_short_name

   !> The scalars of a scene's file (and results of the C and Fortran APIs):
   !> the texture's and the friction index's (scalar_table).
   integer, parameter :: n_scalar_outputs = 6

   !> The variables the pad, its balance and the numerics declare (below).
   integer, parameter :: n_pad_outputs = 7, n_numerics_outputs = 6
   !> The wet models' own (their registry entries): the squeeze film's 5,
   !> the Reynolds film's 2.
   integer, parameter :: n_wet_model_outputs = 7
   integer, parameter :: n_outputs = n_pad_outputs + n_facet_outputs + n_rubber_outputs + &
      & n_film_outputs + n_wet_model_outputs + n_numerics_outputs

   !> The output file's order of the variables (and the C API's indices).
   character(len=*), parameter :: file_order(n_outputs) = [character(len=32) :: &
      & "mu", "n_clamped", "hydroplaning_fraction", "wet_fraction", "max_balance_residual", &
      & "mean_hydro_load", "max_compression", "bearing_evaluations", "memory_updates", &
      & "viscous_memory_ran", "bearing_ran", "squeeze_film_ran", "mean_local_friction", &
      & "mean_film_thickness", "mu_inst", "hydro_load", "penetration", "contact_elements", &
      & "film_thickness", "local_friction", "mu_error_estimate", "substeps_used", &
      & "mu_hysteresis", "mu_adhesion", "mu_extrapolated", "exact_integrator_ran", &
      & "contact_fraction", "film_load_share", "mean_water_thickness", "film_unsettled", &
      & "film_pressure_max", "water_thickness", "estimate_elements_per_sample", &
      & "elements_per_sample_used", "film_root_jumps"]

   !> What the output says besides the result variables: where the results
   !> came from, the profile, its texture, the parameters used, warnings.
   type :: output_metadata_type
      character(len=:), allocatable :: title, history, input_namelist, profile_file
      !> The scene file the results came from (when they came from one): with
      !> profile_file, an input the output must never be written over.
      character(len=:), allocatable :: scene_file
      real(wp) :: dx = 0.0_wp
      integer :: profile_points = 0
      logical :: closed = .true.
      !> Texture metrics of the profile, when they could be computed.
      logical :: has_texture = .false.
      type(texture_type) :: texture
      character(len=:), allocatable :: texture_note
      !> What preprocessing did to the profile (none for arrays given directly).
      type(preprocess_report_type) :: preprocess
      character(len=:), allocatable :: preprocessing
      !> The parameters used (defaults included), as values and as a namelist.
      logical :: has_parameters = .false.
      type(param_set_type) :: parameters
      character(len=:), allocatable :: parameters_text
      !> Warnings about the input and the results, one a line ('' = none).
      character(len=:), allocatable :: warnings
      !> The International Friction Index of the speed sweep (ASTM E1960)
      !> and the model's own speed constant.
      type(ifi_type) :: ifi
   end type output_metadata_type

contains

   !> Every result variable, in the order of the output file: each
   !> component's declarations, placed by `file_order`.
   pure function output_table() result(t)
      type(output_var_type) :: t(n_outputs)
      type(output_var_type), allocatable :: declared(:)
      type(film_entry_type), allocatable :: films(:)
      integer :: k, j
      ! (appended, not joined by array constructors: those leak the
      ! variables' allocatable components in gfortran 12; tests/test_leaks.py)
      allocate(declared(0))
      call append(declared, pad_outputs())
      call append(declared, facet_outputs())
      call append(declared, rubber_outputs())
      call append(declared, film_outputs())
      call append(declared, numerics_outputs())
      films = wet_models()
      do j = 1, size(films)
         if (allocated(films(j)%outputs)) call append(declared, films(j)%outputs)
      end do
      do k = 1, n_outputs
         do j = 1, size(declared)
            if (declared(j)%name == trim(file_order(k))) then
               t(k) = declared(j)
               exit
            end if
         end do
      end do
   contains
      pure subroutine append(list, more)
         type(output_var_type), allocatable, intent(inout) :: list(:)
         type(output_var_type), intent(in) :: more(:)
         type(output_var_type), allocatable :: grown(:)
         integer :: n
         n = size(list)
         allocate(grown(n + size(more)))
         grown(1:n) = list
         grown(n + 1:) = more
         call move_alloc(grown, list)
      end subroutine append
   end function output_table

   !> The file's scalars, in its order: mpd, rms_height, rms_slope (when the
   !> profile holds a 100 mm segment), ifi_f60, ifi_sp, speed_constant
   !> (when pavefric_ifi forms them); the program's writer and Python's
   !> dataset take their names, units and descriptions from here.
   pure function scalar_table() result(t)
      type(output_var_type) :: t(n_scalar_outputs)
      t(1) = output_var("texture", "mpd", "m", "mean profile depth (ISO 13473-1 / " // &
         & "ASTM E1845, 100 mm segments, slope suppression)", &
         & short="mean profile depth (ISO 13473-1 / ASTM E1845)")
      t(2) = output_var("texture", "rms_height", "m", "RMS profile height about the mean")
      t(3) = output_var("texture", "rms_slope", "1", "RMS slope between neighbouring " // &
         & "samples at the profile spacing")
      t(4) = output_var("ifi", "ifi_f60", "1", "International Friction Index F60 (ASTM " // &
         & "E1960): the computed friction at 20 km/h as a DFT value, carried to 60 km/h " // &
         & "with ifi_sp", short="International Friction Index F60 (ASTM E1960)")
      t(5) = output_var("ifi", "ifi_sp", "km h-1", "speed constant Sp of ASTM E1960 from " // &
         & "the mean profile depth (14.2 + 89.7 MPD in mm)", &
         & short="speed constant Sp of ASTM E1960 from the mean profile depth")
      t(6) = output_var("ifi", "speed_constant", "km h-1", "the model's own speed " // &
         & "constant: -1 / slope of ln(mu) fitted by least squares against speed (to " // &
         & "compare with ifi_sp)")
   end function scalar_table

   !> The long_name (a few words) of result or scalar `name`, as a scene's
   !> file gives it ('' for a name of neither table): a batch's file names
   !> the same variables alike.
   pure subroutine output_short_name(name, short)
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: short
      type(output_var_type) :: t(n_outputs), s(n_scalar_outputs)
      integer :: k
      short = ""
      t = output_table()
      do k = 1, n_outputs
         if (t(k)%name == name) short = t(k)%short
      end do
      s = scalar_table()
      do k = 1, n_scalar_outputs
         if (s(k)%name == name) short = s(k)%short
      end do
   end subroutine output_short_name

   !> What the pad and its load balance report.
   pure function pad_outputs() result(t)
      type(output_var_type) :: t(n_pad_outputs)
      t(1) = output_var("pad", "mu", "1", "friction coefficient averaged over the profile " // &
         & "(Kane et al. 2017, Eq. 12)")
      t(2) = output_var("pad", "hydroplaning_fraction", "1", "share of averaged positions " // &
         & "where no element touched the profile")
      t(3) = output_var("pad", "max_balance_residual", "1", "largest |sum F + Wh - W| / W " // &
         & "over averaged positions")
      t(4) = output_var("pad", "mu_inst", "1", "instantaneous friction coefficient (Kane " // &
         & "et al. 2017, Eq. 11)", dims=dim_position_speed, when=when_series)
      t(5) = output_var("pad", "penetration", "m", "global penetration delta of the pad " // &
         & "(Eq. 4)", dims=dim_position_speed, when=when_series)
      t(6) = output_var("pad", "contact_elements", "1", "pad elements in contact with the " // &
         & "profile", out_int, dim_position_speed, when=when_series)
      t(7) = output_var("pad", "contact_fraction", "1", "share of the pad's elements in " // &
         & "contact with the profile, averaged over positions")
   end function pad_outputs

   !> What the numerics report of their accuracy.
   pure function numerics_outputs() result(t)
      type(output_var_type) :: t(n_numerics_outputs)
      t(1) = output_var("numerics", "mu_error_estimate", "1", "estimated error of mu from " // &
         & "the time step (the pad's step along the road) and the pad's elements. At " // &
         & "tolerance = 0 (&numerics error_estimate): three times the change of mu at half " // &
         & "the step where the pad stood on 4 elements in contact or more; where it stood on " // &
         & "fewer, the change of mu as the elements were halved until it stood on 4 (at most " // &
         & "4 times) plus three times the change of one more halving; speeds the exact " // &
         & "integrator ran: from halving the elements; where time_scheme = 'richardson' " // &
         & "extrapolated mu (mu_extrapolated), twice the change of mu at half the step, " // &
         & "the correction it made. " // &
         & "With &numerics tolerance: twice the larger of its last " // &
         & "two changes as the step was halved, or where mu is extrapolated, the larger of " // &
         & "the extrapolated value's change and the last change", when=when_error_estimate, &
         & short="estimated error of mu")
      t(2) = output_var("numerics", "substeps_used", "1", "time steps per element spacing " // &
         & "of the reported mu: the tolerance's choice, or substeps as given at tolerance " // &
         & "= 0", out_int64, when=when_error_estimate)
      t(3) = output_var("numerics", "mu_extrapolated", "1", "1 where mu (and its parts) is " // &
         & "the Richardson value 2 mu(s) - mu(s/2) of two Euler passes (with a tolerance: " // &
         & "the last two; time_scheme 'richardson' at tolerance = 0: the run and its error " // &
         & "estimate's pass), 0 where it is one pass's own", out_int64, &
         & when=when_error_estimate, short="whether mu is the Richardson value of two passes")
      t(4) = output_var("numerics", "exact_integrator_ran", "", "whether the rubber was " // &
         & "integrated exactly in time, from contact event to event (&numerics time_scheme " // &
         & "= 'auto' or 'exact': a Kelvin-Voigt rubber with memory on a road " // &
         & "without a film), else backward Euler", out_flag)
      t(5) = output_var("numerics", "estimate_elements_per_sample", "1", &
         & "elements_per_sample of the finest pass mu_error_estimate was made from: the " // &
         & "run's where it halved the time step only (substeps doubled), more where the " // &
         & "pad's elements were halved (the pad stood on fewer than 4 elements in contact, " // &
         & "or the exact integrator ran); with &numerics tolerance the run's (the tolerance " // &
         & "refines the time step only)", out_int64, when=when_error_estimate)
      t(6) = output_var("numerics", "elements_per_sample_used", "1", &
         & "elements_per_sample of the run each speed's results come from: the value given, " // &
         & "or more where &numerics min_contacts halved the pad's elements until it stood " // &
         & "on that many in contact (the global attribute pad_elements counts the elements " // &
         & "at the value given)", out_int64)
   end function numerics_outputs

   !> Variable k's declaration: from `table` (output_table(), when the
   !> caller has it), else from a table built here.
   pure function declaration(k, table) result(v)
      integer, intent(in) :: k
      type(output_var_type), intent(in), optional :: table(:)
      type(output_var_type) :: v
      type(output_var_type) :: t(n_outputs)
      if (present(table)) then
         v = table(k)
      else
         t = output_table()
         v = t(k)
      end if
   end function declaration

   !> When variable k is written (docs/outputs.md), as output_present decides.
   pure function output_condition(k) result(text)
      integer, intent(in) :: k
      character(len=output_condition_len(k)) :: text
      character(len=:), allocatable :: deferred_text
      call output_condition_text(k, deferred_text)
      text = deferred_text
   end function output_condition

   !> The length of output_condition's text.
   pure integer function output_condition_len(k)
      integer, intent(in) :: k
      character(len=:), allocatable :: deferred_text
      call output_condition_text(k, deferred_text)
      output_condition_len = len(deferred_text)
   end function output_condition_len

   !> The text of output_condition, into a deferred-length argument.
   pure subroutine output_condition_text(k, text)
      integer, intent(in) :: k
      character(len=:), allocatable, intent(out) :: text
      type(output_var_type) :: v
      v = declaration(k)
      select case (v%when)
      case (when_friction_film)
         text = "when the drainage film (&water wet_model = 'squeeze') ran at any speed"
      case (when_series)
         text = "with &output series = .true."
      case (when_friction_film_series)
         text = "with &output series = .true. and the drainage film"
      case (when_film_report_series)
         text = "with &output series = .true. and the Reynolds film (&water wet_model = " // &
            & "'reynolds', depth > 0)"
      case (when_error_estimate)
         text = "when mu's error was estimated (&numerics tolerance > 0, or error_estimate " // &
            & "at tolerance = 0)"
      case default
         text = "always"
      end select
   end subroutine output_condition_text

   !> Whether variable k is part of this run's results, by its declaration's
   !> condition: series variables only with series, the friction film's
   !> only when it ran, the error estimate's only when it was made.
   pure logical function output_present(res, k, table)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: k
      !> output_table(), when the caller has it (building it costs tens of
      !> microseconds: a loop over the variables passes it).
      type(output_var_type), intent(in), optional :: table(:)
      type(output_var_type) :: v
      v = declaration(k, table)
      select case (v%when)
      case (when_friction_film)
         output_present = any(res%friction_film_ran)
      case (when_series)
         output_present = allocated(res%mu_inst)
      case (when_friction_film_series)
         output_present = allocated(res%film_thickness)
      case (when_film_report_series)
         output_present = allocated(res%film_pressure_max)
      case (when_error_estimate)
         output_present = allocated(res%mu_error)
      case default
         output_present = .true.
      end select
   end function output_present

   !> How many series variables a run of model `m` with series produces
   !> (to size arrays before the run).
   function series_count(m) result(n)
      type(model_type), intent(in) :: m
      integer :: n
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      call make_components(m, rubber, film)
      n = 4
      if (allocated(film)) then
         if (film%changes_friction()) n = n + 2
         if (film%carries_load() .and. film%reports()) n = n + 2
      end if
   end function series_count

   !> Values of variable k as reals (exact for the integers and flags),
   !> speed-major for per-speed variables, (position, speed) for series.
   pure subroutine output_values(res, k, values, table)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: k
      real(wp), intent(out) :: values(:)
      !> output_table(), when the caller has it (as for output_present).
      type(output_var_type), intent(in), optional :: table(:)
      type(output_var_type) :: v
      integer :: ns, np
      ns = size(res%mu)
      np = 0
      if (allocated(res%mu_inst)) np = size(res%mu_inst, 1)
      v = declaration(k, table)
      select case (v%name)
      case ("mu")
         values(1:ns) = res%mu
      case ("n_clamped")
         values(1:ns) = real(res%n_clamped, wp)
      case ("hydroplaning_fraction")
         values(1:ns) = res%hydroplaning_fraction
      case ("wet_fraction")
         values(1:ns) = res%wet_fraction
      case ("max_balance_residual")
         values(1:ns) = res%max_balance_residual
      case ("mean_hydro_load")
         values(1:ns) = res%mean_hydro_load
      case ("max_compression")
         values(1:ns) = res%max_compression
      case ("bearing_evaluations")
         values(1:ns) = real(res%bearing_evaluations, wp)
      case ("memory_updates")
         values(1:ns) = real(res%memory_updates, wp)
      case ("viscous_memory_ran")
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%viscous_memory_ran)
      case ("bearing_ran")
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%bearing_ran)
      case ("squeeze_film_ran")
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%friction_film_ran)
      case ("mean_local_friction")
         values(1:ns) = res%mean_local_friction
      case ("mean_film_thickness")
         values(1:ns) = res%mean_film_thickness
      case ("mu_inst")
         values(1:np*ns) = reshape(res%mu_inst, [np*ns])
      case ("hydro_load")
         values(1:np*ns) = reshape(res%hydro_load, [np*ns])
      case ("penetration")
         values(1:np*ns) = reshape(res%penetration, [np*ns])
      case ("contact_elements")
         values(1:np*ns) = real(reshape(res%contact_elements, [np*ns]), wp)
      case ("film_thickness")
         values(1:np*ns) = reshape(res%film_thickness, [np*ns])
      case ("local_friction")
         values(1:np*ns) = reshape(res%local_friction, [np*ns])
      case ("mu_error_estimate")
         values(1:ns) = res%mu_error
      case ("substeps_used")
         values(1:ns) = real(res%substeps_used, wp)
      case ("mu_hysteresis")
         values(1:ns) = res%mu_hysteresis
      case ("mu_adhesion")
         values(1:ns) = res%mu_adhesion
      case ("mu_extrapolated")
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%extrapolated)
      case ("exact_integrator_ran")
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%exact_integrator_ran)
      case ("estimate_elements_per_sample")
         values(1:ns) = real(res%estimate_elements_per_sample, wp)
      case ("elements_per_sample_used")
         values(1:ns) = real(res%elements_per_sample_used, wp)
      case ("contact_fraction")
         values(1:ns) = res%contact_fraction
      case ("film_load_share")
         values(1:ns) = res%film_load_share
      case ("mean_water_thickness")
         values(1:ns) = res%mean_water_thickness
      case ("film_unsettled")
         values(1:ns) = real(res%film_unsettled, wp)
      case ("film_root_jumps")
         values(1:ns) = real(res%film_root_jumps, wp)
      case ("film_pressure_max")
         values(1:np*ns) = reshape(res%film_pressure_max, [np*ns])
      case ("water_thickness")
         values(1:np*ns) = reshape(res%water_thickness, [np*ns])
      end select
   end subroutine output_values

end module pavefric_outputs
