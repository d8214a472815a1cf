!> The registry of rubber laws (&rubber model): each law declares its name,
!> its variables, its builder and its checks next to its code
!> (rubber_entry_type: pavefric_rubber, pavefric_maxwell); this list is the
!> one place that names them. The &rubber group's shared variables, which
!> every law is built with (the spring, the temperature and its WLF shift),
!> are declared here, before the laws' own. A new law is its module plus its
!> line in `rubber_models` and its count in `n_rubber_law_parameters`; its
!> variables then join the scene's table, the namelist reader, the Python
!> keywords and the C API, and `model` accepts its name.
module pavefric_rubber_models
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type
   use pavefric_params, only: param_spec_type, param_value_type, text_param, real_param, &
      & real_value
   use pavefric_rubber, only: rubber_model, rubber_entry_type, rubber_context_type, &
      & kelvin_voigt_entry, kelvin_voigt_n_parameters
   use pavefric_maxwell, only: maxwell_entry, maxwell_n_parameters, wlf_shift
   implicit none
   private

   public :: rubber_models, rubber_model_names, rubber_parameters, build_rubber, check_rubber
   public :: n_rubber_parameters, n_rubber_shared_parameters

   !> The group's shared variables: model, stiffness, temperature,
   !> reference_temperature, wlf_c1, wlf_c2.
   integer, parameter :: n_rubber_shared_parameters = 6
   !> The variables the laws declare, all together.
   integer, parameter :: n_rubber_law_parameters = kelvin_voigt_n_parameters + &
      & maxwell_n_parameters
   !> Every &rubber variable.
   integer, parameter :: n_rubber_parameters = n_rubber_shared_parameters + &
      & n_rubber_law_parameters

contains

   !> Every rubber law, the default (the paper's) first.
   pure function rubber_models() result(e)
      type(rubber_entry_type), allocatable :: e(:)
      ! (one by one: an array constructor of these leaks their allocatable
      ! components in gfortran 12, about 190 KB a run with the other tables;
      ! tests/test_leaks.py)
      allocate(e(2))
      e(1) = kelvin_voigt_entry()
      e(2) = maxwell_entry()
   end function rubber_models

   !> Their names, space-separated (the choices of &rubber model). A
   !> subroutine: gfortran keeps a deferred-length function result's length
   !> in a static variable, which threads would share.
   pure subroutine rubber_model_names(names)
      character(len=:), allocatable, intent(out) :: names
      type(rubber_entry_type), allocatable :: e(:)
      integer :: k
      e = rubber_models()
      names = e(1)%name
      do k = 2, size(e)
         names = names // " " // e(k)%name
      end do
   end subroutine rubber_model_names

   !> The &rubber group: its shared variables, then each law's in the
   !> registry's order.
   pure function rubber_parameters() result(s)
      type(param_spec_type) :: s(n_rubber_parameters)
      type(rubber_entry_type), allocatable :: e(:)
      character(len=:), allocatable :: names
      integer :: k, n, m
      call rubber_model_names(names)
      s(1) = text_param("rubber", "model", "kelvin_voigt", "", "model", &
         & "the element's law: 'kelvin_voigt', the paper's spring K and dashpot C in " // &
         & "parallel (Eq. 3); 'maxwell', a generalised Maxwell (Prony) element: the " // &
         & "equilibrium spring stiffness in parallel with the arms prony_stiffness, " // &
         & "prony_times (docs/rubber.md)", choices=names)
      s(1)%keyword = "rubber_model"
      s(2) = real_param("rubber", "stiffness", "1.4e8", "N m-3", "model", &
         & "spring modulus per unit length K (paper, Table 1); with model = 'maxwell' the " // &
         & "equilibrium (long-time) spring K_inf. A layer of thickness h and Young's " // &
         & "modulus E gives about E / h. At least 1 N m-3: below, the load over a " // &
         & "spring of one element overflows the static balance.", lower=1.0_wp, &
         & upper=1.0e15_wp, plausible_lower=1.0e5_wp, &
         & plausible_upper=1.0e11_wp, plausible_note="tread rubber gives about 1e7 to 1e9")
      s(3) = real_param("rubber", "temperature", "20", "degC", "model", &
         & "rubber temperature T: every relaxation time (and the Kelvin-Voigt C) is " // &
         & "multiplied by the WLF shift a_T, log10 a_T = -C1 (T - Tref) / (C2 + T - Tref)", &
         & lower=-273.15_wp, lower_strict=.true., upper=1000.0_wp, plausible_lower=-40.0_wp, &
         & plausible_upper=100.0_wp, plausible_note="road and tyre temperatures lie " // &
         & "between -40 and 100 C")
      s(4) = real_param("rubber", "reference_temperature", "20", &
         & "degC", "model", "reference temperature Tref of the relaxation times, the " // &
         & "viscosity and the WLF constants", lower=-273.15_wp, lower_strict=.true., &
         & upper=1000.0_wp)
      s(5) = real_param("rubber", "wlf_c1", "8.86", "1", "model", &
         & "WLF constant C1 at the reference temperature (default: Williams, Landel & " // &
         & "Ferry 1955 for Tref about 50 K above the glass transition)", lower=0.0_wp, &
         & upper=1000.0_wp, plausible_lower=1.0_wp, plausible_upper=50.0_wp, &
         & plausible_note="WLF fits of elastomers give C1 of about 3 to 30")
      s(6) = real_param("rubber", "wlf_c2", "101.6", "K", "model", &
         & "WLF constant C2 at the reference temperature (default: Williams, Landel & " // &
         & "Ferry 1955); temperatures at or below Tref - C2 are refused", lower=0.0_wp, &
         & lower_strict=.true., upper=1.0e4_wp, plausible_lower=10.0_wp, &
         & plausible_upper=1000.0_wp, plausible_note="WLF fits of elastomers give C2 of " // &
         & "about 30 to 300 K")
      e = rubber_models()
      n = n_rubber_shared_parameters
      do k = 1, size(e)
         m = size(e(k)%parameters)
         s(n + 1:n + m) = e(k)%parameters
         n = n + m
      end do
   end function rubber_parameters

   !> The rubber law called `name`, built from the scene's values (none
   !> for an unknown name: the reader has refused it already).
   subroutine build_rubber(name, specs, values, rubber)
      character(len=*), intent(in) :: name
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(rubber_model), allocatable, intent(out) :: rubber
      type(rubber_entry_type), allocatable :: e(:)
      type(rubber_context_type) :: context
      integer :: k
      ! the WLF shift of every relaxation time (exactly 1 at the reference temperature)
      context = rubber_context_type(stiffness=real_value(specs, values, "rubber", "stiffness"), &
         & shift=wlf_shift(real_value(specs, values, "rubber", "temperature"), &
         & real_value(specs, values, "rubber", "reference_temperature"), &
         & real_value(specs, values, "rubber", "wlf_c1"), &
         & real_value(specs, values, "rubber", "wlf_c2")))
      e = rubber_models()
      do k = 1, size(e)
         if (e(k)%name == name) then
            call e(k)%build(context, specs, values, rubber)
            return
         end if
      end do
   end subroutine build_rubber

   !> Every law's own cross-checks (`name` the chosen law's).
   pure subroutine check_rubber(name, specs, values, error)
      character(len=*), intent(in) :: name
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      type(error_type), allocatable, intent(out) :: error
      type(rubber_entry_type), allocatable :: e(:)
      integer :: k
      e = rubber_models()
      do k = 1, size(e)
         if (.not. associated(e(k)%check)) cycle
         call e(k)%check(specs, values, e(k)%name == name, error)
         if (allocated(error)) return
      end do
   end subroutine check_rubber

end module pavefric_rubber_models
