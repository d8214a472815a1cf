!> The generalised Maxwell (Prony) rubber element and the WLF temperature
!> shift (MODEL.md section 9; docs/rubber.md derives every line).
!>
!> Per unit length, like K: an equilibrium spring K_inf in parallel with arms
!> k = 1..n, each a spring K_k in series with a dashpot of relaxation time
!> tau_k. With v_k the dashpot's displacement (the arm's relaxed compression),
!>     p = K_inf u + sum_k K_k (u - v_k),   dv_k/dt = (u - v_k) / tau_k.
!> Over a step of length dt in which u goes linearly from u0 to u1 the arm
!> equation integrates exactly (r = dt/tau, E = exp(-r), G = (1 - E)/r):
!>     v_k(1) = (1 - G) u1 + (G - E) u0 + E v_k(0),
!> a convex combination (all three weights >= 0, sum 1), so v_k stays
!> between the compressions seen. The pressure at the step's end is then
!>     p = k_eff (u1 - u_free),  k_eff = K_inf + sum_k K_k G_k,
!>     u_free = sum_k K_k [(G_k - E_k) u0 + E_k v_k(0)] / k_eff >= 0,
!> the form of every rubber component (pavefric_rubber): the element touches
!> iff its geometric compression g > u_free, else it recovers to u_free.
!>
!> Numerics: r = dt/tau = advance / (V tau) spans any range (tau from 1e-300
!> to 1e30 s), so the weights are computed without cancellation: below r = 1
!> from the series of 1 - G = sum_{n>=1} (-1)^(n+1) r^n / (n+1)!, above it
!> from G = (1 - E)/r directly; r beyond 1e300 (or V = 0) is the fully
!> relaxed limit E = G = 0 and r = 0 the glassy limit E = G = 1, with no
!> division by zero or overflow on the way.
module pavefric_maxwell
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_params, only: param_spec_type, param_value_type, list_param, list_value
   use pavefric_rubber, only: rubber_model, rubber_step_type, rubber_context_type, &
      & rubber_entry_type
   implicit none
   private

   public :: maxwell_rubber, arm_weights, wlf_log10_shift, wlf_shift, wlf_check
   public :: max_log10_shift, maxwell_entry, maxwell_n_parameters

   !> The variables the generalised Maxwell law declares (maxwell_entry).
   integer, parameter :: maxwell_n_parameters = 2
   !> Most arms of a generalised Maxwell element.
   integer, parameter, public :: max_arms = 100

   !> Largest |log10 a_T| accepted: no WLF fit holds this far, and the
   !> shifted times stay far from overflow.
   real(wp), parameter :: max_log10_shift = 100.0_wp

   !> Terms of the series of 1 - G below r = 1 (1/19! = 8e-18).
   integer, parameter :: n_series = 18

   !> The generalised Maxwell element, its relaxation times already at the
   !> scene's temperature (tau_k(T) = a_T tau_k(Tref)).
   type, extends(rubber_model) :: maxwell_rubber
      !> Equilibrium spring K_inf (N m-3), per unit length.
      real(wp) :: stiffness = 0.0_wp
      !> Arm springs K_k (N m-3) and relaxation times tau_k (s).
      real(wp), allocatable :: arm_stiffness(:), arm_times(:)
   contains
      procedure :: state_size => mx_state_size
      procedure :: prepare => mx_prepare
      procedure :: free_compression => mx_free
      procedure :: update => mx_update
      procedure :: mean_push => mx_mean
      procedure :: memory_effect => mx_memory_effect
      procedure :: stored_energy => mx_stored_energy
   end type maxwell_rubber

contains

   !> The generalised Maxwell (Prony) law: the context's spring as K_inf in
   !> parallel with the arms prony_stiffness, prony_times, every time
   !> shifted to the temperature (tau_k(T) = a_T tau_k(Tref)).
   pure function maxwell_entry() result(e)
      type(rubber_entry_type) :: e
      e%name = "maxwell"
      allocate(e%parameters(maxwell_n_parameters))
      e%parameters(1) = list_param("rubber", "prony_stiffness", "", "N m-3", "model", &
         & "spring K_k of each Maxwell arm, per unit length like stiffness (model = " // &
         & "'maxwell'; one per relaxation time; python -m pavefric prony fits them to " // &
         & "dynamic mechanical data)", lower=0.0_wp, upper=1.0e15_wp, max_values=max_arms, &
         & plausible_lower=0.0_wp, plausible_upper=1.0e13_wp, &
         & plausible_note="glassy tread rubber is about 1e3 times stiffer than rubbery")
      e%parameters(2) = list_param("rubber", "prony_times", "", "s", "model", &
         & "relaxation time tau_k of each Maxwell arm at the reference temperature " // &
         & "(model = 'maxwell')", lower=0.0_wp, upper=1.0e30_wp, max_values=max_arms, &
         & plausible_lower=1.0e-15_wp, plausible_upper=1.0e10_wp, &
         & plausible_note="master curves of elastomers span about 1e-14 to 1e8 s")
      e%parameters(2)%lower_strict = .true.
      e%build => maxwell_build
      e%check => maxwell_check
   end function maxwell_entry

   subroutine maxwell_build(context, specs, values, rubber)
      type(rubber_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(rubber_model), allocatable, intent(out) :: rubber
      allocate(rubber, source=maxwell_rubber(stiffness=context%stiffness, &
         & arm_stiffness=list_value(specs, values, "rubber", "prony_stiffness"), &
         & arm_times=context%shift * list_value(specs, values, "rubber", "prony_times")))
   end subroutine maxwell_build

   !> The arms come in pairs (whichever law is chosen: a list without its
   !> partner is a mistake), and the law needs at least one.
   pure subroutine maxwell_check(specs, values, chosen, error)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      logical, intent(in) :: chosen
      type(error_type), allocatable, intent(out) :: error
      integer :: n_k, n_t
      n_k = size(list_value(specs, values, "rubber", "prony_stiffness"))
      n_t = size(list_value(specs, values, "rubber", "prony_times"))
      if (n_k /= n_t) then
         call fatal_error(error, "&rubber prony_stiffness has " // to_str(n_k) // &
            & " values and prony_times " // to_str(n_t) // ": give one relaxation time " // &
            & "per arm stiffness")
      else if (chosen .and. n_k < 1) then
         call fatal_error(error, "&rubber model = 'maxwell': prony_stiffness and " // &
            & "prony_times are empty; give at least one arm (python -m pavefric prony " // &
            & "fits them to dynamic mechanical data)")
      end if
   end subroutine maxwell_check

   !> The compression u and each arm's relaxed compression v_k.
   pure integer function mx_state_size(self)
      class(maxwell_rubber), intent(in) :: self
      mx_state_size = 1 + size(self%arm_stiffness)
   end function mx_state_size

   !> Step coefficients per lane. coef(:, 1) = sum_k K_k (G_k - E_k) / k_eff
   !> and coef(:, 1+k) = K_k E_k / k_eff give u_free; coef(:, 1+n+k) = 1 - G_k,
   !> coef(:, 1+2n+k) = G_k - E_k and coef(:, 1+3n+k) = E_k update v_k;
   !> coef(:, 2+4n) = K_inf / k_eff, coef(:, 2+4n+k) = K_k H_k / k_eff and
   !> coef(:, 2+5n+k) = K_k G_k / k_eff give the step's mean pressure
   !> (mx_mean; H = (1 - G)/r).
   !> V = 0 is the static limit: every arm relaxed, k_eff = K_inf, no memory.
   pure subroutine mx_prepare(self, speeds, advance, elements, step, stat)
      class(maxwell_rubber), intent(in) :: self
      real(wp), intent(in) :: speeds(:), advance
      integer, intent(in) :: elements
      type(rubber_step_type), intent(out) :: step
      integer, intent(out) :: stat
      real(wp) :: e, g, one_g, g_e, k_eff, a, h, creep_time, long
      real(wp), allocatable :: ke(:), kh(:), kg(:)
      integer :: j, k, n, i, nl
      n = size(self%arm_stiffness)
      allocate(step%k_eff(size(speeds)), step%memory(size(speeds)), &
         & step%coef(size(speeds), n_coef(n)), ke(n), kh(n), kg(n), &
         & step%mode_decay(size(speeds), n), step%mode_weight(size(speeds), n), &
         & step%creep_decay(size(speeds)), step%push_slope(size(speeds)), &
         & step%creep_weight(size(speeds)), stat=stat)
      if (stat /= 0) return
      ! the pad's creep under its load decays with the retardation times,
      ! the roots x of K_inf = sum_k K_k tau_k / (x - tau_k), one between
      ! each two relaxation times and one above the longest; there every
      ! x - tau_k >= x - tau_max, so the longest is at most tau_max +
      ! sum_k K_k tau_k / K_inf: exp(-dt / that) a step. The step's own
      ! recurrence (u and the arms' v_k under a constant force) decays more
      ! slowly where dt is long beside an arm's time (as backward Euler's
      ! Kelvin-Voigt, by coef(:, 1) a step); the square root of the larger
      ! of the two bounded the recurrence's largest eigenvalue in 200,000
      ! random rubbers of 1-7 arms (moduli 1-1e15, times 1e-12-1e3 s, steps
      ! 1e-9-1 s; a check by hand with NumPy, 2026-12-06). An arm that does
      ! not relax within a step to rounding (E_k = 1) is a spring over the
      ! run: it joins K_inf here, and its own mode changes nothing over a
      ! lap (lap_spinup)
      do j = 1, size(speeds)
         step%memory(j) = speeds(j) > 0.0_wp
         step%creep_decay(j) = 0.0_wp
         step%creep_weight(j) = 1.0_wp
         k_eff = self%stiffness
         do k = 1, n
            call arm_weights(speeds(j) * self%arm_times(k), advance, e, g, one_g, g_e, h)
            k_eff = k_eff + self%arm_stiffness(k) * g
            ke(k) = e
            kh(k) = self%arm_stiffness(k) * h
            kg(k) = self%arm_stiffness(k) * g
            step%coef(j, 1 + n + k) = one_g
            step%coef(j, 1 + 2 * n + k) = g_e
            step%coef(j, 1 + 3 * n + k) = e
         end do
         a = 0.0_wp
         do k = 1, n
            a = a + self%arm_stiffness(k) * step%coef(j, 1 + 2 * n + k)
            step%coef(j, 1 + k) = self%arm_stiffness(k) * ke(k) / k_eff
            step%coef(j, 2 + 4 * n + k) = kh(k) / k_eff
            step%coef(j, 2 + 5 * n + k) = kg(k) / k_eff
         end do
         step%coef(j, 2 + 4 * n) = self%stiffness / k_eff
         step%coef(j, 1) = a / k_eff
         ! the mean's slope against u1 (mx_mean): K_inf/2 + sum_k K_k H_k
         step%push_slope(j) = 0.5_wp * step%coef(j, 2 + 4 * n)
         do k = 1, n
            step%push_slope(j) = step%push_slope(j) + step%coef(j, 2 + 4 * n + k)
         end do
         if (step%memory(j)) then
            creep_time = maxval(self%arm_times, mask=self%arm_stiffness > 0.0_wp .and. &
               & ke < 1.0_wp) + sum(self%arm_stiffness * self%arm_times, mask=ke < 1.0_wp) / &
               & (self%stiffness + sum(self%arm_stiffness, mask=.not. ke < 1.0_wp))
            if (speeds(j) * creep_time > advance * 1.0e-300_wp) &
               & step%creep_decay(j) = exp(-advance / (speeds(j) * creep_time))
            step%creep_decay(j) = sqrt(max(step%coef(j, 1), step%creep_decay(j)))
            ! its size against the instant compression: k_eff / K_long - 1,
            ! K_long = K_inf and the arms that are springs over the run
            long = self%stiffness + sum(self%arm_stiffness, mask=.not. ke < 1.0_wp)
            step%creep_weight(j) = huge(1.0_wp)
            if (long > 0.0_wp) step%creep_weight(j) = max(1.0_wp, k_eff / long - 1.0_wp)
         end if
         step%k_eff(j) = k_eff
         ! the arms are the memory's modes: each decays by E_k a step
         do k = 1, n
            step%mode_decay(j, k) = ke(k)
            step%mode_weight(j, k) = self%arm_stiffness(k) / k_eff
         end do
      end do
      ! every lane's coefficients repeated for each element: the kernels then
      ! run over lanes and elements as one contiguous loop
      nl = size(speeds)
      allocate(step%per_element(nl * elements, n_coef(n)), stat=stat)
      if (stat /= 0) return
      do k = 1, n_coef(n)
         do i = 1, elements
            step%per_element((i - 1) * nl + 1 : i * nl, k) = step%coef(:, k)
         end do
      end do
   end subroutine mx_prepare

   !> u_free = sum_k K_k [(G_k - E_k) u + E_k v_k] / k_eff: where the element
   !> would carry no pressure at the step's end. The state is laid out
   !> (lanes x elements, 1 + arms): u, then each arm's v_k.
   pure subroutine mx_free(self, step, state, u_free)
      class(maxwell_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(out), contiguous :: u_free(:, :)
      call free_kernel(size(u_free), size(self%arm_stiffness), step%per_element, state, u_free)
   end subroutine mx_free

   !> u1 = u_free + push; v_k <- (1 - G_k) u1 + (G_k - E_k) u0 + E_k v_k.
   pure subroutine mx_update(self, step, state, u_free, push)
      class(maxwell_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(inout), contiguous :: state(:, :, :)
      real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
      call update_kernel(size(u_free), size(self%arm_stiffness), step%per_element, state, &
         & u_free, push)
   end subroutine mx_update

   !> The number of step coefficients of n arms (mx_prepare).
   pure integer function n_coef(n)
      integer, intent(in) :: n
      n_coef = 2 + 6 * n
   end function n_coef

   !> Along u linear from u0 to u1 over the step, arm k's spring stretch
   !> w = u - v_k obeys dw/dt = (u1 - u0)/dt - w/tau, whose mean over the
   !> step is H (u1 - u0) + G w0 (H = (1 - G)/r): the mean pressure is
   !>     K_inf (u0 + u1)/2 + sum_k K_k [H_k (u1 - u0) + G_k (u0 - v_k)],
   !> here over k_eff. Its work (u1 - u0) times that is the change of
   !> K_inf u^2/2 + sum_k K_k w_k^2/2 plus the dashpots' dissipation
   !> sum_k K_k int w_k^2/tau_k dt >= 0.
   pure subroutine mx_mean(self, step, state, u_free, push, mean)
      class(maxwell_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
      real(wp), intent(out), contiguous :: mean(:, :)
      call mean_kernel(size(u_free), size(self%arm_stiffness), step%per_element, state, &
         & u_free, push, mean)
   end subroutine mx_mean

   !> (K_inf u^2 + sum_k K_k (u - v_k)^2) / 2 per element, over k_eff.
   pure subroutine mx_stored_energy(self, step, state, energy, known)
      class(maxwell_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(out) :: energy(:)
      logical, intent(out) :: known
      integer :: nl, na
      nl = size(energy)
      na = size(self%arm_stiffness)
      call energy_kernel(nl, size(state) / (nl * (1 + na)), na, self%stiffness, &
         & self%arm_stiffness, step%k_eff, state, energy)
      known = .true.
   end subroutine mx_stored_energy

   !> mx_stored_energy on the state as the kernels lay it out: (lanes x
   !> elements, 1 + arms), lanes fastest.
   pure subroutine energy_kernel(nl, n, na, k_inf, k_arm, k_eff, state, energy)
      integer, intent(in) :: nl, n, na
      real(wp), intent(in) :: k_inf, k_arm(na), k_eff(nl), state(nl, n, 1 + na)
      real(wp), intent(out) :: energy(nl)
      real(wp) :: e, w
      integer :: i, j, k
      do j = 1, nl
         e = 0.0_wp
         do i = 1, n
            e = e + k_inf * state(j, i, 1)**2
            do k = 1, na
               w = state(j, i, 1) - state(j, i, 1 + k)
               e = e + k_arm(k) * w * w
            end do
         end do
         energy(j) = 0.5_wp * e / k_eff(j)
      end do
   end subroutine energy_kernel

   !> mx_mean over m = lanes x elements values, one loop per arm.
   pure subroutine mean_kernel(m, na, coef, state, u_free, push, mean)
      integer, intent(in) :: m, na
      real(wp), intent(in) :: coef(m, 2 + 6 * na), state(m, 1 + na), u_free(m), push(m)
      real(wp), intent(out) :: mean(m)
      integer :: p, k
      do p = 1, m
         mean(p) = 0.5_wp * coef(p, 2 + 4 * na) * (state(p, 1) + u_free(p) + push(p))
      end do
      do k = 1, na
         do p = 1, m
            mean(p) = mean(p) + coef(p, 2 + 4 * na + k) * (u_free(p) + push(p) - state(p, 1)) &
               & + coef(p, 2 + 5 * na + k) * (state(p, 1) - state(p, 1 + k))
         end do
      end do
   end subroutine mean_kernel

   !> mx_free over m = lanes x elements values as one loop per arm (long,
   !> contiguous vector loops); each value's sum in the arms' order.
   pure subroutine free_kernel(m, na, coef, state, u_free)
      integer, intent(in) :: m, na
      real(wp), intent(in) :: coef(m, 2 + 6 * na), state(m, 1 + na)
      real(wp), intent(out) :: u_free(m)
      integer :: p, k
      do p = 1, m
         u_free(p) = coef(p, 1) * state(p, 1)
      end do
      do k = 1, na
         do p = 1, m
            u_free(p) = u_free(p) + coef(p, 1 + k) * state(p, 1 + k)
         end do
      end do
   end subroutine free_kernel

   !> mx_update over m = lanes x elements values (u1 = u_free + push formed
   !> again for each arm: the same value).
   pure subroutine update_kernel(m, na, coef, state, u_free, push)
      integer, intent(in) :: m, na
      real(wp), intent(in) :: coef(m, 2 + 6 * na), u_free(m), push(m)
      real(wp), intent(inout) :: state(m, 1 + na)
      integer :: p, k
      do k = 1, na
         do p = 1, m
            state(p, 1 + k) = coef(p, 1 + na + k) * (u_free(p) + push(p)) &
               & + coef(p, 1 + 2 * na + k) * state(p, 1) &
               & + coef(p, 1 + 3 * na + k) * state(p, 1 + k)
         end do
      end do
      do p = 1, m
         state(p, 1) = u_free(p) + push(p)
      end do
   end subroutine update_kernel

   pure subroutine mx_memory_effect(self, name)
      class(maxwell_rubber), intent(in) :: self
      character(len=:), allocatable, intent(out) :: name
      name = "viscous_memory"
   end subroutine mx_memory_effect

   !> The exact weights of one arm over a step of length dt = advance / V,
   !> given vt = V tau: r = dt/tau, e = exp(-r), g = (1 - e)/r, one_g = 1 - g,
   !> g_e = g - e, each to a few ulps for every r >= 0 (see the module's
   !> comment), and h = (1 - g)/r (1/2 at r = 0, 0 at r = infinity).
   !> vt <= 0 (V = 0) is r = infinity.
   pure elemental subroutine arm_weights(vt, advance, e, g, one_g, g_e, h)
      real(wp), intent(in) :: vt, advance
      real(wp), intent(out) :: e, g, one_g, g_e, h
      real(wp) :: r, s
      integer :: n
      if (.not. (vt > advance * 1.0e-300_wp)) then
         ! r > 1e300: the arm relaxes completely within the step
         e = 0.0_wp
         g = 0.0_wp
         one_g = 1.0_wp
         g_e = 0.0_wp
         h = 0.0_wp
         return
      end if
      r = advance / vt
      if (r < 1.0_wp) then
         ! 1 - G = r/2! - r^2/3! + r^3/4! - ... (Horner), no cancellation
         s = 1.0_wp / real(factorial(n_series + 1), wp)
         do n = n_series - 1, 1, -1
            s = 1.0_wp / real(factorial(n + 1), wp) - r * s
         end do
         one_g = r * s
         h = s
         g = 1.0_wp - one_g
         e = exp(-r)
         ! G - E = (1 - E) - (1 - G), 1 - E = r G
         g_e = r * g - one_g
      else
         if (r < 745.0_wp) then
            e = exp(-r)
         else
            e = 0.0_wp                       ! below the smallest double
         end if
         g = (1.0_wp - e) / r
         one_g = 1.0_wp - g
         g_e = g - e
         h = one_g / r
      end if
   end subroutine arm_weights

   !> n! as a real (n <= 20).
   pure elemental function factorial(n) result(f)
      integer, intent(in) :: n
      real(wp) :: f
      integer :: k
      f = 1.0_wp
      do k = 2, n
         f = f * real(k, wp)
      end do
   end function factorial

   !> log10 a_T = -C1 (T - Tref) / (C2 + T - Tref) (Williams, Landel & Ferry
   !> 1955); exactly 0 at T = Tref. Call wlf_check first: outside its domain
   !> the value is clamped to +-max_log10_shift.
   pure function wlf_log10_shift(temperature, reference, c1, c2) result(log_at)
      real(wp), intent(in) :: temperature, reference, c1, c2
      real(wp) :: log_at, dt
      log_at = 0.0_wp
      if (temperature == reference) return
      dt = temperature - reference
      if (.not. (c2 + dt > 0.0_wp)) then
         log_at = max_log10_shift
         return
      end if
      log_at = max(-max_log10_shift, min(max_log10_shift, -c1 * dt / (c2 + dt)))
   end function wlf_log10_shift

   !> The WLF shift factor a_T = 10**log10 a_T (exactly 1 at T = Tref).
   pure function wlf_shift(temperature, reference, c1, c2) result(a_t)
      real(wp), intent(in) :: temperature, reference, c1, c2
      real(wp) :: a_t
      a_t = 1.0_wp
      if (temperature == reference) return
      a_t = 10.0_wp ** wlf_log10_shift(temperature, reference, c1, c2)
   end function wlf_shift

   !> Why the WLF shift cannot be used at these values ('' when it can): the
   !> equation diverges at T - Tref = -C2, and no fit holds beyond
   !> max_log10_shift decades.
   pure function wlf_check(temperature, reference, c1, c2) result(why)
      real(wp), intent(in) :: temperature, reference, c1, c2
      character(len=wlf_check_len(temperature, reference, c1, c2)) :: why
      character(len=:), allocatable :: deferred_text
      call wlf_check_text(temperature, reference, c1, c2, deferred_text)
      why = deferred_text
   end function wlf_check

   !> The length of wlf_check's text.
   pure integer function wlf_check_len(temperature, reference, c1, c2)
      real(wp), intent(in) :: temperature, reference, c1, c2
      character(len=:), allocatable :: deferred_text
      call wlf_check_text(temperature, reference, c1, c2, deferred_text)
      wlf_check_len = len(deferred_text)
   end function wlf_check_len

   !> The text of wlf_check, into a deferred-length argument.
   pure subroutine wlf_check_text(temperature, reference, c1, c2, why)
      real(wp), intent(in) :: temperature, reference, c1, c2
      character(len=:), allocatable, intent(out) :: why
      real(wp) :: dt, log_at
      why = ""
      if (temperature == reference) return
      dt = temperature - reference
      if (.not. (c2 + dt > 0.0_wp)) then
         why = "diverges"
         return
      end if
      log_at = -c1 * dt / (c2 + dt)
      if (.not. (abs(log_at) <= max_log10_shift)) why = "too far"
   end subroutine wlf_check_text

end module pavefric_maxwell
