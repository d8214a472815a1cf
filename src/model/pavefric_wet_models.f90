!> The registry of wet models (&water wet_model): each film component
!> declares its name, its variables and its builder next to its code
!> (film_entry_type); this list is the one place that names them. A new wet
!> model is its module plus its line in `wet_models` and its count in
!> `n_film_parameters`; its variables then join the scene's table (after the
!> scene's own, so docs/inputs.md lists them in their group), the namelist
!> reader, the Python keywords and the C API, and `wet_model` accepts its
!> name.
module pavefric_wet_models
   use pavefric_params, only: param_spec_type, param_value_type
   use pavefric_film, only: film_model, film_context_type, film_entry_type, &
      & pseudo_bearing_entry, pseudo_bearing_n_parameters
   use pavefric_squeeze, only: squeeze_entry, squeeze_n_parameters
   use pavefric_reynolds, only: reynolds_entry, reynolds_n_parameters
   implicit none
   private

   public :: wet_models, wet_model_names, wet_model_parameters, build_film, n_film_parameters

   !> The variables the wet models declare, all together.
   integer, parameter :: n_film_parameters = pseudo_bearing_n_parameters + squeeze_n_parameters &
      & + reynolds_n_parameters

contains

   !> Every wet model, the default first.
   pure function wet_models() result(e)
      type(film_entry_type), allocatable :: e(:)
      ! (one by one: an array constructor of these leaks their allocatable
      ! components in gfortran 12; tests/test_leaks.py)
      allocate(e(3))
      e(1) = pseudo_bearing_entry()
      e(2) = squeeze_entry()
      e(3) = reynolds_entry()
   end function wet_models

   !> Their names, space-separated (the choices of &water wet_model). A
   !> subroutine: gfortran keeps a deferred-length function result's length
   !> in a static variable, which threads would share.
   pure subroutine wet_model_names(names)
      character(len=:), allocatable, intent(out) :: names
      type(film_entry_type), allocatable :: e(:)
      integer :: k
      e = wet_models()
      names = e(1)%name
      do k = 2, size(e)
         names = names // " " // e(k)%name
      end do
   end subroutine wet_model_names

   !> The variables they declare, in the registry's order.
   pure function wet_model_parameters() result(s)
      type(param_spec_type) :: s(n_film_parameters)
      type(film_entry_type), allocatable :: e(:)
      integer :: k, n, m
      e = wet_models()
      n = 0
      do k = 1, size(e)
         m = size(e(k)%parameters)
         s(n + 1:n + m) = e(k)%parameters
         n = n + m
      end do
   end function wet_model_parameters

   !> The film of the wet model called `name` (none for an unknown name:
   !> the reader has refused it already).
   subroutine build_film(name, context, specs, values, film)
      character(len=*), intent(in) :: name
      type(film_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(film_model), allocatable, intent(out) :: film
      type(film_entry_type), allocatable :: e(:)
      integer :: k
      e = wet_models()
      do k = 1, size(e)
         if (e(k)%name == name) then
            call e(k)%build(context, specs, values, film)
            return
         end if
      end do
   end subroutine build_film

end module pavefric_wet_models
