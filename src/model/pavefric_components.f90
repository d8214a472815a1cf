!> The component factory: the rubber law and the film a scene's model calls
!> for, built from its parameters (the film by name from the wet-model
!> registry, pavefric_wet_models). The time loop works through the
!> components' abstract types (rubber_model, film_model) and never asks
!> which ones it has.
module pavefric_components
   use pavefric_kinds, only: wp
   use pavefric_model, only: model_type, parameter_table
   use pavefric_rubber, only: rubber_model, kelvin_voigt_rubber
   use pavefric_maxwell, only: maxwell_rubber, wlf_shift
   use pavefric_film, only: film_model, film_context_type
   use pavefric_wet_models, only: build_film
   implicit none
   private

   public :: make_components

contains

   !> The rubber and film components a model calls for: a film only with
   !> water (depth > 0), so a dry scene simulates no film at all.
   subroutine make_components(m, rubber, film)
      type(model_type), intent(in) :: m
      class(rubber_model), allocatable, intent(out) :: rubber
      class(film_model), allocatable, intent(out) :: film
      real(wp) :: a_t
      character(len=:), allocatable :: law, wet_model
      type(film_context_type) :: context
      law = "kelvin_voigt"
      if (allocated(m%rubber_model)) law = m%rubber_model
      ! the WLF shift of every relaxation time (exactly 1 at the reference temperature)
      a_t = wlf_shift(m%temperature, m%reference_temperature, m%wlf_c1, m%wlf_c2)
      select case (law)
      case ("maxwell")
         allocate(rubber, source=maxwell_rubber(stiffness=m%stiffness, &
            & arm_stiffness=m%prony_stiffness, arm_times=a_t * m%prony_times))
      case default
         allocate(rubber, source=kelvin_voigt_rubber(stiffness=m%stiffness, &
            & viscosity=a_t * m%viscosity))
      end select
      if (.not. m%depth > 0.0_wp) return
      ! the wet model by name, from the registry (pavefric_wet_models): it
      ! reads its own variables from the scene's values
      context = film_context_type(depth=m%depth, eta=m%water_viscosity, width=m%width, &
         & length=m%length, microtexture_rms=m%microtexture_rms)
      wet_model = "kane2017"
      if (allocated(m%wet_model)) wet_model = m%wet_model
      call build_film(wet_model, context, parameter_table(), m%values, film)
   end subroutine make_components

end module pavefric_components
