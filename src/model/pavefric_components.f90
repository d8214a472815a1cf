!> The component factory: the rubber law and the film a scene's model calls
!> for, built from its parameters. The time loop works through the
!> components' abstract types (rubber_model, film_model) and never asks
!> which ones it has; this is the one place that knows them by name.
module pavefric_components
   use pavefric_kinds, only: wp
   use pavefric_model, only: model_type
   use pavefric_rubber, only: rubber_model, kelvin_voigt_rubber
   use pavefric_maxwell, only: maxwell_rubber, wlf_shift
   use pavefric_film, only: film_model, pseudo_bearing_film
   use pavefric_squeeze, only: squeeze_film
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
      character(len=:), allocatable :: law
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
      select case (m%wet_model)
      case ("squeeze")
         allocate(film, source=squeeze_film(depth=m%depth, eta=m%water_viscosity, &
            & sigma=m%microtexture_rms, width=m%width))
      case default
         allocate(film, source=pseudo_bearing_film(depth=m%depth, eta=m%water_viscosity, &
            & alpha=m%alpha, beta=m%beta, width=m%width, length=m%length))
      end select
   end subroutine make_components

end module pavefric_components
