!> Water drained from the contact plateaus (`&water wet_model = 'squeeze'`),
!> a film component beside the paper's pseudo-bearing (MODEL.md section 8,
!> docs/model.md). After Moore's three zones: the water under each contact
!> patch is squeezed out while the patch passes, and friction returns where
!> the microtexture pierces what is left of the film.
!>
!> The film h on each road sample enters under the pad's leading edge at the
!> water depth H_in (times &water squeeze_inlet_fraction, 1 by default).
!> Contiguous elements in contact form a plateau of length b along the profile (capped at the pad width l: water also leaves
!> sideways; a plateau at the pad's edge ends there) carrying the mean
!> pressure p of its elements; the film under it thins by Reynolds squeeze
!> flow between parallel faces, p = eta b**2 (-dh/dt) / h**3, which over a
!> step of constant p integrates exactly as
!>     h**-2 <- h**-2 + 2 p dt / (eta b**2)
!> (the state kept per road sample is h**-2). Out of contact a sample keeps
!> its film. Microtexture asperities of RMS height sigma pierce the film in
!> the share erfc(h / (sqrt(2) sigma)) (Gaussian heights, Greenwood &
!> Williamson 1966; |height| > h), and the local friction of the element is
!> mu_loc times that share. The film carries no load: the contact is the
!> dry one (a classical film of this geometry carries under 6 % of the load
!> at 80 km/h; MODEL.md section 8).
module pavefric_squeeze
   use pavefric_kinds, only: wp
   use pavefric_film, only: film_model, film_step_type, film_context_type, film_entry_type
   use pavefric_params, only: param_spec_type, param_value_type, real_param, real_value
   use pavefric_output_spec, only: output_var, out_flag, dim_position_speed, &
      & when_friction_film, when_friction_film_series
   implicit none
   private

   public :: squeeze_film, squeeze_entry, squeeze_n_parameters

   !> Variables the squeeze film declares (squeeze_entry); it takes the
   !> water, the pad and &surface microtexture_rms from the scene.
   integer, parameter :: squeeze_n_parameters = 1

   !> The drainage film.
   type, extends(film_model) :: squeeze_film
      !> Water depth H_in (m), water viscosity eta (Pa s), microtexture RMS
      !> height sigma (m), pad width l (m).
      real(wp) :: depth = 0.0_wp, eta = 0.0_wp, sigma = 0.0_wp, width = 0.0_wp
      !> Share of the water depth that enters under the pad's leading edge
      !> (&water squeeze_inlet_fraction; 1: all of it).
      real(wp) :: inlet_fraction = 1.0_wp
   contains
      procedure :: prepare => squeeze_prepare
      procedure :: carries_load => squeeze_carries_load
      procedure :: changes_friction => squeeze_changes_friction
      procedure :: effect => squeeze_effect
      procedure :: state_size => squeeze_state_size
      procedure :: reset => squeeze_reset
      procedure :: enter => squeeze_enter
      procedure :: friction => squeeze_friction
   end type squeeze_film

contains

   !> &water wet_model = 'squeeze'.
   pure function squeeze_entry() result(e)
      type(film_entry_type) :: e
      e%name = "squeeze"
      allocate(e%parameters(squeeze_n_parameters))
      e%parameters(1) = real_param("water", "squeeze_inlet_fraction", "1", "1", "model", &
         & "share of the water depth that enters under the pad's leading edge with " // &
         & "wet_model = 'squeeze' (the entering film is this times depth; the rest is " // &
         & "pushed ahead or aside). 1: all the water enters, as Moore's first zone " // &
         & "assumes; lower it for a pad that sweeps water away.", lower=0.0_wp, &
         & lower_strict=.true., upper=1.0_wp, plausible_lower=0.05_wp, plausible_upper=1.0_wp, &
         & plausible_note="below 0.05 almost no water would reach the contact")
      e%build => squeeze_build
      ! what only this film produces (written when it ran at any speed)
      allocate(e%outputs(5))
      e%outputs(1) = output_var("squeeze", "squeeze_film_ran", "", "whether the film " // &
         & "drained from the contact plateaus changed the local friction", out_flag, &
         & when=when_friction_film)
      e%outputs(2) = output_var("squeeze", "mean_local_friction", "1", "local friction " // &
         & "mu_loc times the share of microtexture piercing the film, force-weighted over " // &
         & "contacts and positions", when=when_friction_film)
      e%outputs(3) = output_var("squeeze", "mean_film_thickness", "m", "water film left " // &
         & "between the rubber and the road where they touch: mean over the elements in " // &
         & "contact, averaged over positions (a position without contact counts 0)", &
         & when=when_friction_film)
      e%outputs(4) = output_var("squeeze", "film_thickness", "m", "water film left between " // &
         & "the rubber and the road, mean over the elements in contact (0 without contact)", &
         & dims=dim_position_speed, when=when_friction_film_series)
      e%outputs(5) = output_var("squeeze", "local_friction", "1", "local friction of the " // &
         & "contacts, force-weighted (mu_loc times the share of microtexture piercing the " // &
         & "film)", dims=dim_position_speed, when=when_friction_film_series)
   end function squeeze_entry

   subroutine squeeze_build(context, specs, values, film)
      type(film_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(film_model), allocatable, intent(out) :: film
      allocate(film, source=squeeze_film(depth=context%depth, eta=context%eta, &
         & sigma=context%microtexture_rms, width=context%width, &
         & inlet_fraction=real_value(specs, values, "water", "squeeze_inlet_fraction")))
   end subroutine squeeze_build

   !> Active with water and motion; dt = advance / V; coef(1) = 2 dt / eta,
   !> coef(2) = 1 / (f H_in)**2 (the entering film, f the inlet fraction),
   !> coef(3) = 1 / (sqrt(2) sigma).
   pure subroutine squeeze_prepare(self, speed, advance, step)
      class(squeeze_film), intent(in) :: self
      real(wp), intent(in) :: speed, advance
      type(film_step_type), intent(out) :: step
      allocate(step%coef(3))
      step%coef = 0.0_wp
      step%active = self%depth > 0.0_wp .and. speed > 0.0_wp
      if (.not. step%active) return
      step%dt = advance / speed
      step%coef(1) = 2.0_wp * step%dt / self%eta
      step%coef(2) = 1.0_wp / (self%inlet_fraction * self%depth)**2
      if (self%sigma > 0.0_wp) step%coef(3) = 1.0_wp / (sqrt(2.0_wp) * self%sigma)
   end subroutine squeeze_prepare

   pure logical function squeeze_carries_load(self)
      class(squeeze_film), intent(in) :: self
      squeeze_carries_load = .false.
   end function squeeze_carries_load

   pure logical function squeeze_changes_friction(self)
      class(squeeze_film), intent(in) :: self
      squeeze_changes_friction = .true.
   end function squeeze_changes_friction

   pure subroutine squeeze_effect(self, name)
      class(squeeze_film), intent(in) :: self
      character(len=:), allocatable, intent(out) :: name
      name = "squeeze_film"
   end subroutine squeeze_effect

   !> One value per road sample: h**-2 (m**-2).
   pure integer function squeeze_state_size(self)
      class(squeeze_film), intent(in) :: self
      squeeze_state_size = 1
   end function squeeze_state_size

   pure subroutine squeeze_reset(self, step, state)
      class(squeeze_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(inout) :: state(:, :)
      state = step%coef(2)
   end subroutine squeeze_reset

   !> Fresh water at the depth H_in ahead of the pad.
   pure subroutine squeeze_enter(self, step, state, sample)
      class(squeeze_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(inout) :: state(:, :)
      integer, intent(in) :: sample
      state(1, sample) = step%coef(2)
   end subroutine squeeze_enter

   !> Squeeze the film under each plateau for one step, then the share of
   !> microtexture piercing it under each element in contact (1 elsewhere:
   !> an element out of contact pushes on nothing).
   pure subroutine squeeze_friction(self, step, state, first, footprint, closed, pressure, &
         & element_length, share, thickness)
      class(squeeze_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(inout) :: state(:, :)
      integer, intent(in) :: first(:), footprint
      logical, intent(in) :: closed
      real(wp), intent(in) :: pressure(:), element_length
      real(wp), intent(out) :: share(:), thickness(:)
      real(wp) :: p_sum, b, c, h
      integer :: n, i, j, e, k, a, z, np
      n = size(pressure)
      share = 1.0_wp
      thickness = 0.0_wp
      i = 1
      do while (i <= n)
         if (.not. pressure(i) > 0.0_wp) then
            i = i + 1
            cycle
         end if
         ! the plateau i .. j-1 and its mean pressure
         p_sum = 0.0_wp
         j = i
         do while (j <= n)
            if (.not. pressure(j) > 0.0_wp) exit
            p_sum = p_sum + pressure(j)
            j = j + 1
         end do
         b = min(real(j - i, wp) * element_length, self%width)
         c = step%coef(1) * (p_sum / real(j - i, wp)) / b**2       ! 2 p dt / (eta b**2)
         if (footprint > 1) then
            ! the plateau's samples, one run of the road from its first
            ! element's start: vector adds (a closed profile's run may wrap
            ! round its end; an open profile's samples beyond its last are
            ! that sample, once each)
            np = size(state, 2)
            a = first(i)
            z = a + (j - i) * footprint - 1
            if (z <= np) then
               state(1, a:z) = state(1, a:z) + c
            else if (closed) then
               state(1, a:np) = state(1, a:np) + c
               state(1, 1:z - np) = state(1, 1:z - np) + c
            else
               state(1, a:np) = state(1, a:np) + c
               state(1, np) = state(1, np) + real(z - np, wp) * c
            end if
         end if
         ! (not vectorised: a vector erfc is libmvec's, a library a wheel
         ! may not find, with other last bits than libm's)
         !GCC$ novector
         do e = i, j - 1
            ! the film's state on the element's first sample
            k = first(e)
            ! one sample an element (the paper's grid): no run above
            if (footprint == 1) state(1, k) = state(1, k) + c
            ! the film's thickness on the element's first sample: h = (h**-2)**-1/2
            h = 1.0_wp / sqrt(state(1, k))
            thickness(e) = h
            if (step%coef(3) > 0.0_wp) then
               share(e) = erfc(h * step%coef(3))
            else
               share(e) = 0.0_wp                  ! no microtexture: nothing pierces
            end if
         end do
         i = j
      end do
   end subroutine squeeze_friction

end module pavefric_squeeze
