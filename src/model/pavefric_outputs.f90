!> The one description of a run's result variables: name, dimensions,
!> units, meaning and type, and their values taken from a sim_result_type.
!> The NetCDF writer, the Python layer (through f2py) and the C API all read
!> results through this table, so every output variable is the same bits
!> whichever way it is read.
module pavefric_outputs
   use pavefric_kinds, only: wp
   use pavefric_results, only: sim_result_type
   use pavefric_texture, only: texture_type
   use pavefric_ifi, only: ifi_type
   use pavefric_preprocess, only: preprocess_report_type
   use pavefric_model, only: param_set_type, model_type
   use pavefric_components, only: make_components
   use pavefric_rubber, only: rubber_model
   use pavefric_film, only: film_model
   implicit none
   private

   public :: output_var_type, output_table, output_present, output_values, n_outputs
   public :: output_metadata_type, series_count
   public :: out_double, out_int64, out_int, out_flag, dim_speed, dim_position_speed
   public :: output_condition

   !> Storage types (NetCDF: double, int64, int, byte 0/1 with flag meanings).
   integer, parameter :: out_double = 1, out_int64 = 2, out_int = 3, out_flag = 4
   !> Dimensions: per speed, or per position and speed (series).
   integer, parameter :: dim_speed = 1, dim_position_speed = 2

   integer, parameter :: n_outputs = 26

   !> One result variable.
   type :: output_var_type
      character(len=:), allocatable :: name, units, long_name
      integer :: type = out_double
      integer :: dims = dim_speed
   end type output_var_type

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

   !> Every result variable, in the order of the output file.
   pure function output_table() result(t)
      type(output_var_type) :: t(n_outputs)
      t(1) = var("mu", "1", "friction coefficient averaged over the profile (Kane et al. " // &
         & "2017, Eq. 12)")
      t(2) = var("n_clamped", "1", "contacts on facets clamped at theta_max, summed over " // &
         & "averaged positions", out_int64)
      t(3) = var("hydroplaning_fraction", "1", "share of averaged positions where no " // &
         & "element touched the profile")
      t(4) = var("wet_fraction", "1", "share of averaged positions where the water film " // &
         & "carried load")
      t(5) = var("max_balance_residual", "1", "largest |sum F + Wh - W| / W over averaged " // &
         & "positions")
      t(6) = var("mean_hydro_load", "N", "load carried by the water film, averaged over " // &
         & "positions")
      t(7) = var("max_compression", "m", "largest compression of a rubber element " // &
         & "(compare with the pad thickness)")
      t(8) = var("bearing_evaluations", "1", "evaluations of the film's load (0: no film " // &
         & "took part in the balance)", out_int64)
      t(9) = var("memory_updates", "1", "element-steps that updated the rubber's memory " // &
         & "(0: no memory kept)", out_int64)
      t(10) = var("viscous_memory_ran", "", "whether the rubber elements carried memory", &
         & out_flag)
      t(11) = var("bearing_ran", "", "whether a load-carrying water film took part in the " // &
         & "load balance", out_flag)
      t(12) = var("squeeze_film_ran", "", "whether the film drained from the contact " // &
         & "plateaus changed the local friction", out_flag)
      t(13) = var("mean_local_friction", "1", "local friction mu_loc times the share of " // &
         & "microtexture piercing the film, force-weighted over contacts and positions")
      t(14) = var("mean_film_thickness", "m", "water film left under the pad, averaged " // &
         & "over elements and positions")
      t(21) = var("mu_error_estimate", "1", "estimated error of mu from the time step " // &
         & "(the pad's step along the road). At tolerance = 0 (&numerics error_estimate): " // &
         & "three times the change of mu at half the step, 0 where the exact integrator " // &
         & "ran. With &numerics tolerance: twice the larger of its last two changes as the " // &
         & "step was halved, or where mu is extrapolated, the larger of the extrapolated " // &
         & "value's change and the last change")
      t(22) = var("substeps_used", "1", "time steps per element spacing of the reported " // &
         & "mu: the tolerance's choice, or substeps as given at tolerance = 0", out_int64)
      t(23) = var("mu_hysteresis", "1", "the rubber's part of mu: the work of the facet " // &
         & "forces on the rubber (its stored energy returned over a closed profile, its " // &
         & "dissipation kept) per unit load and distance slid; 0 for an elastic pad on " // &
         & "a closed profile (docs/model.md)")
      t(24) = var("mu_adhesion", "1", "the local friction's part of mu: the work of " // &
         & "mu_loc on the facets per unit load and distance slid (0 with mu_loc = 0); " // &
         & "mu = mu_hysteresis + mu_adhesion")
      t(25) = var("mu_extrapolated", "1", "1 where mu (and its parts) is the Richardson " // &
         & "value 2 mu(s) - mu(s/2) of the last two passes, 0 where it is the finest " // &
         & "pass (&numerics tolerance, time_scheme)", out_int64)
      t(26) = var("exact_integrator_ran", "", "whether the rubber was integrated exactly in " // &
         & "time, from contact event to event (&numerics time_scheme = 'exact': a " // &
         & "Kelvin-Voigt rubber with memory on a road without a film), else backward Euler", &
         & out_flag)
      t(15) = var("mu_inst", "1", "instantaneous friction coefficient (Kane et al. 2017, " // &
         & "Eq. 11)", dims=dim_position_speed)
      t(16) = var("hydro_load", "N", "load carried by the water film (Eq. 15)", &
         & dims=dim_position_speed)
      t(17) = var("penetration", "m", "global penetration delta of the pad (Eq. 4)", &
         & dims=dim_position_speed)
      t(18) = var("contact_elements", "1", "pad elements in contact with the profile", &
         & out_int, dim_position_speed)
      t(19) = var("film_thickness", "m", "water film under the pad, mean over its elements", &
         & dims=dim_position_speed)
      t(20) = var("local_friction", "1", "local friction of the contacts, force-weighted " // &
         & "(mu_loc times the share of microtexture piercing the film)", &
         & dims=dim_position_speed)
   contains
      pure function var(name, units, long_name, type, dims) result(v)
         character(len=*), intent(in) :: name, units, long_name
         integer, intent(in), optional :: type, dims
         type(output_var_type) :: v
         v%name = name
         v%units = units
         v%long_name = long_name
         if (present(type)) v%type = type
         if (present(dims)) v%dims = dims
      end function var
   end function output_table

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
      select case (k)
      case (12:14)
         text = "when the drainage film (&water wet_model = 'squeeze') ran at any speed"
      case (15:18)
         text = "with &output series = .true."
      case (19:20)
         text = "with &output series = .true. and the drainage film"
      case (21:22)
         text = "with &numerics tolerance > 0"
      case default
         text = "always"
      end select
   end subroutine output_condition_text

   !> Whether variable k is part of this run's results: series variables
   !> only with series, the squeeze film's only when it ran.
   pure logical function output_present(res, k)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: k
      select case (k)
      case (12:14)
         output_present = any(res%friction_film_ran)
      case (15:18)
         output_present = allocated(res%mu_inst)
      case (19:20)
         output_present = allocated(res%film_thickness)
      case (21:22, 25)
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
         if (film%changes_friction()) n = 6
      end if
   end function series_count

   !> Values of variable k as reals (exact for the integers and flags),
   !> speed-major for per-speed variables, (position, speed) for series.
   pure subroutine output_values(res, k, values)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: k
      real(wp), intent(out) :: values(:)
      integer :: ns, np
      ns = size(res%mu)
      np = 0
      if (allocated(res%mu_inst)) np = size(res%mu_inst, 1)
      select case (k)
      case (1)
         values(1:ns) = res%mu
      case (2)
         values(1:ns) = real(res%n_clamped, wp)
      case (3)
         values(1:ns) = res%hydroplaning_fraction
      case (4)
         values(1:ns) = res%wet_fraction
      case (5)
         values(1:ns) = res%max_balance_residual
      case (6)
         values(1:ns) = res%mean_hydro_load
      case (7)
         values(1:ns) = res%max_compression
      case (8)
         values(1:ns) = real(res%bearing_evaluations, wp)
      case (9)
         values(1:ns) = real(res%memory_updates, wp)
      case (10)
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%viscous_memory_ran)
      case (11)
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%bearing_ran)
      case (12)
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%friction_film_ran)
      case (13)
         values(1:ns) = res%mean_local_friction
      case (14)
         values(1:ns) = res%mean_film_thickness
      case (15)
         values(1:np*ns) = reshape(res%mu_inst, [np*ns])
      case (16)
         values(1:np*ns) = reshape(res%hydro_load, [np*ns])
      case (17)
         values(1:np*ns) = reshape(res%penetration, [np*ns])
      case (18)
         values(1:np*ns) = real(reshape(res%contact_elements, [np*ns]), wp)
      case (19)
         values(1:np*ns) = reshape(res%film_thickness, [np*ns])
      case (20)
         values(1:np*ns) = reshape(res%local_friction, [np*ns])
      case (21)
         values(1:ns) = res%mu_error
      case (22)
         values(1:ns) = real(res%substeps_used, wp)
      case (23)
         values(1:ns) = res%mu_hysteresis
      case (24)
         values(1:ns) = res%mu_adhesion
      case (25)
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%extrapolated)
      case (26)
         values(1:ns) = merge(1.0_wp, 0.0_wp, res%exact_integrator_ran)
      end select
   end subroutine output_values

end module pavefric_outputs
