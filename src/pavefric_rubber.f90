!> Kelvin-Voigt rubber elements, backward Euler in time (paper Eqs. 3, 8).
module pavefric_rubber
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: kv_step_type, kv_step

   !> Coefficients of one time step of length dt = advance/V.
   type :: kv_step_type
      !> Effective stiffness K + C/dt (N m-3): the slope of p(u) over a step.
      real(wp) :: k_eff = 0.0_wp
      !> Relaxation factor: free compression u_free = relax * u_prev (Eq. 8).
      real(wp) :: relax = 0.0_wp
      !> True when the elements carry viscous memory (C > 0 and V > 0).
      logical :: memory = .false.
   end type kv_step_type

contains

   !> Step coefficients for stiffness K, viscosity C, speed V and the distance
   !> the pad advances in one step. Backward Euler of K u + C du/dt = 0 gives
   !> u_free = u_prev / (1 + K dt/C) = u_prev C V / (C V + K advance), which is
   !> 0 for C = 0 or V = 0 (no division by zero in either limit).
   pure function kv_step(stiffness, viscosity, speed, advance) result(step)
      real(wp), intent(in) :: stiffness, viscosity, speed, advance
      type(kv_step_type) :: step
      real(wp) :: cv
      cv = viscosity * speed
      step%k_eff = stiffness + cv / advance            ! K + C/dt
      step%memory = cv > 0.0_wp
      if (step%memory) then
         step%relax = cv / (cv + stiffness * advance)
      else
         step%relax = 0.0_wp
      end if
   end function kv_step

end module pavefric_rubber
