!> The component factory: the rubber law and the film a scene's model calls
!> for, built by name from their registries (pavefric_rubber_models,
!> pavefric_wet_models), each reading its own variables. The time loop works through the
!> components' abstract types (rubber_model, film_model) and never asks
!> which ones it has.
module pavefric_components
   use pavefric_kinds, only: wp
   use pavefric_model, only: model_type, parameter_table
   use pavefric_params, only: param_spec_type
   use pavefric_rubber, only: rubber_model
   use pavefric_rubber_models, only: build_rubber
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
      character(len=:), allocatable :: law, wet_model
      type(film_context_type) :: context
      type(param_spec_type), allocatable :: specs(:)
      specs = parameter_table()
      ! the rubber law by name, from the registry (pavefric_rubber_models):
      ! it reads its own variables from the scene's values
      law = "kelvin_voigt"
      if (allocated(m%rubber_model)) law = m%rubber_model
      call build_rubber(law, specs, m%values, rubber)
      if (.not. m%depth > 0.0_wp) return
      ! the wet model by name, from the registry (pavefric_wet_models): it
      ! reads its own variables from the scene's values
      context = film_context_type(depth=m%depth, eta=m%water_viscosity, width=m%width, &
         & length=m%length, microtexture_rms=m%microtexture_rms)
      wet_model = "kane2017"
      if (allocated(m%wet_model)) wet_model = m%wet_model
      call build_film(wet_model, context, specs, m%values, film)
   end subroutine make_components

end module pavefric_components
