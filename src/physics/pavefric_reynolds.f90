!> A mixed-lubrication film from the water's own flow (`&water wet_model =
!> 'reynolds'`; MODEL.md section 11, docs/model.md "The Reynolds film").
!>
!> Along the pad, 1-D in the sliding direction, the average Reynolds
!> equation of Patir & Cheng (1978, 1979) for the road moving at V under the
!> pad, in the pad's frame, quasi-steady in the road's frame (the pad's face
!> out of contact is taken as flat; its own recovery and its vertical motion
!> are not squeeze sources here):
!>     d/ds(k dp/ds) - 12 k p / b**2 = (V/2) d(theta c)/ds,
!>     k = phi_x(h/sigma) h_T**3 / (12 eta),   c = h_T + sigma phi_s(h/sigma),
!> s from the leading edge, h the nominal gap under an element (0 in
!> contact), h_T the mean gap over the microtexture's Gaussian heights (RMS
!> sigma), phi_x and phi_s the pressure and shear flow factors (isotropic
!> roughness, gamma = 1), and the side leakage from a parabolic pressure
!> across a drainage length b: the run of open (or closed) elements holding
!> the place, capped at the pad width l (the texture drains sideways through
!> its own channels).
!> Discretisation: vertex-centred finite volumes, the gap per element, the
!> pressure p and fill theta at the nodes between elements (a step from a
!> valley onto a contact land has its node at the step, drained back through
!> the valley; a cell-centred scheme put the land's pressure inside the land
!> and locked it), the transport upwind.
!> Cavitation: the mass-conserving Jakobsson-Floberg-Olsson condition in
!> Elrod-Adams form: at each node either the film is full (theta = 1,
!> p >= 0) or partial (p = 0, 0 <= theta <= 1), solved as a complementarity
!> problem by a primal-dual active-set iteration, one tridiagonal solve
!> (pavefric_tridiagonal: elimination without pivoting, which the system's
!> column diagonal dominance allows (assemble_and_solve); its factors kept
!> for the load's derivative) per iteration, started from the set of
!> the lane's last
!> solve (its workspace; the complementarity solution does not depend on
!> where the iteration starts, so neither do the numbers).
!> Inlet: the water on the road (depth H_in, moving at V) brings V H_in per
!> unit width; the gap under the leading element takes (V/2) c_1. A starved
!> inlet (2 H_in < c_1) lets it all in at ambient pressure; a flooded one
!> stops the share f = 1 - c_1 / (2 H_in) of the water at the leading edge,
!> whose dynamic pressure f rho V**2 / 2 is the inlet node's pressure (the
!> inertia that lets a smooth surface hydroplane). Outlet: ambient pressure.
!> The film's load, l ds (p_in / 2 + sum of the interior nodes' p), takes
!> part in the pad's load balance; the elements in contact carry the rest
!> with the full mu_loc (the microtexture pierces the film where the rubber
!> touches: the Greenwood-Williamson share erfc(h / (sqrt(2) sigma)) is 1
!> at h = 0).
module pavefric_reynolds
   use pavefric_kinds, only: wp
   use pavefric_film, only: film_model, film_step_type, film_context_type, film_entry_type
   use pavefric_params, only: param_spec_type, param_value_type, real_param, real_value
   use pavefric_tridiagonal, only: tridiagonal_factor, tridiagonal_solve
   use pavefric_output_spec, only: output_var, dim_position_speed, when_film_report_series
   implicit none
   private

   public :: reynolds_film, reynolds_entry, reynolds_n_parameters
   public :: reynolds_solve, reynolds_cell_terms, sigma_floor

   !> Variables the Reynolds film declares (reynolds_entry); it takes the
   !> water, the pad and &surface microtexture_rms from the scene.
   integer, parameter :: reynolds_n_parameters = 1

   !> The microtexture height below which a contact land would seal (m): the
   !> film uses max(microtexture_rms, this), so that water always drains
   !> through a contact (docs/model.md).
   real(wp), parameter :: sigma_floor = 1.0e-6_wp

   !> Active-set iterations before giving up (the set of full nodes changes
   !> at each; tests/test_reynolds.py allows 40 on random gap fields).
   integer, parameter :: max_active_set = 200

   !> Active-set iterations from a warm start before it starts again cold.
   integer, parameter :: max_warm = 20

   !> A lane's workspace (reynolds_work_size): the warm-start flag, the set
   !> (n values), then arrays of n values: the gap's terms h_T, c, k / ds and
   !> 6 (ds / run)**2 (film_terms), the derivatives of c and k / ds with
   !> respect to the penetration, the derivative's right side, the nodes'
   !> pressure and fill, the solver's right side and three diagonals (its
   !> factors after a solve), and the gap field of the last load
   !> (load_in_work); then three values: whether that
   !> load's solution is kept (0 no, 1 settled, 2 not settled) and its
   !> inlet's tc0 and p0, so that the report at the balance's root, which
   !> is where the balance evaluated the load last, reads it instead of
   !> solving the film once more.
   integer, parameter :: w_ht = 1, w_c = 2, w_k = 3, w_run = 4, w_dc = 5, w_dk = 6, &
      & w_rhs = 7, w_p = 8, w_theta = 9, w_y = 10, w_dl = 11, w_dd = 12, w_du = 13, &
      & w_gap = 14
   !> Arrays of n values in a lane's workspace, the set's included.
   integer, parameter :: n_work_arrays = 15
   !> Values after the arrays: the kept solution's flag, tc0 and p0.
   integer, parameter :: n_work_values = 3

   !> The Reynolds film.
   type, extends(film_model) :: reynolds_film
      !> Water depth H_in (m), viscosity eta (Pa s), microtexture RMS height
      !> sigma (m, floored at sigma_floor), pad width l and length L (m),
      !> water density rho (kg m-3).
      real(wp) :: depth = 0.0_wp, eta = 0.0_wp, sigma = sigma_floor, width = 0.0_wp
      real(wp) :: length = 0.0_wp, density = 0.0_wp
   contains
      procedure :: prepare => reynolds_prepare
      procedure :: carries_load => reynolds_carries_load
      procedure :: changes_friction => reynolds_changes_friction
      procedure :: effect => reynolds_effect
      procedure :: engages => reynolds_engages
      procedure :: load => reynolds_load
      procedure :: loads => reynolds_loads
      procedure :: work_size => reynolds_work_size
      procedure :: lower_bound => reynolds_lower_bound
      procedure :: report => reynolds_report
      procedure :: reports => reynolds_carries_load
      !> Its drainage lengths (the runs of open and of touching elements)
      !> change where an element touches: the load jumps there.
      procedure :: jumps_at_contact => reynolds_carries_load
      !> Its load is not monotone in the penetration: where the inlet's
      !> pressure reaches further under a rising pad, a lifted and a seated
      !> pad both balance (docs/model.md).
      procedure :: load_monotone => reynolds_not_monotone
   end type reynolds_film

contains

   !> &water wet_model = 'reynolds'.
   pure function reynolds_entry() result(e)
      type(film_entry_type) :: e
      e%name = "reynolds"
      allocate(e%outputs(2))
      e%outputs(1) = output_var("reynolds", "film_pressure_max", "Pa", "largest pressure " // &
         & "of the Reynolds film under the pad (the inlet's dynamic pressure included) at " // &
         & "the balance's root", dims=dim_position_speed, when=when_film_report_series)
      e%outputs(2) = output_var("reynolds", "water_thickness", "m", "water between the " // &
         & "pad and the road per unit of pad area (each element's mean gap h_T times its " // &
         & "fill theta) at the balance's root. At one position it may reach several " // &
         & "times the water depth (6.2 times on a closed white-noise profile of RMS 2 mm at " // &
         & "300 km/h, " // &
         & "tests/test_reynolds.py): the film is solved quasi-steady at each position, " // &
         & "without the storage term, so nothing holds the water in the valleys under " // &
         & "the pad to what entered at its leading edge; its mean over the positions, " // &
         & "mean_water_thickness, stays within about twice the depth", dims=dim_position_speed, &
         & when=when_film_report_series)
      allocate(e%parameters(reynolds_n_parameters))
      e%parameters(1) = real_param("water", "density", "998.2", "kg m-3", "model", &
         & "density of the water, for the dynamic pressure rho V**2 / 2 that the water " // &
         & "stopped at the pad's leading edge exerts with wet_model = 'reynolds' (the " // &
         & "default: water at 20 C)", lower=0.0_wp, upper=1.0e5_wp, &
         & plausible_lower=900.0_wp, plausible_upper=1100.0_wp, &
         & plausible_note="water is about 1000 kg m-3")
      e%build => reynolds_build
   end function reynolds_entry

   subroutine reynolds_build(context, specs, values, film)
      type(film_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(film_model), allocatable, intent(out) :: film
      allocate(film, source=reynolds_film(depth=context%depth, eta=context%eta, &
         & sigma=max(context%microtexture_rms, sigma_floor), width=context%width, &
         & length=context%length, density=real_value(specs, values, "water", "density")))
   end subroutine reynolds_build

   !> Active with water and motion; coef(1) = V (m/s).
   pure subroutine reynolds_prepare(self, speed, advance, step)
      class(reynolds_film), intent(in) :: self
      real(wp), intent(in) :: speed, advance
      type(film_step_type), intent(out) :: step
      allocate(step%coef(1))
      step%coef(1) = speed
      step%active = self%depth > 0.0_wp .and. speed > 0.0_wp .and. self%eta > 0.0_wp
      if (speed > 0.0_wp) step%dt = advance / speed
   end subroutine reynolds_prepare

   pure logical function reynolds_carries_load(self)
      class(reynolds_film), intent(in) :: self
      reynolds_carries_load = .true.
   end function reynolds_carries_load

   pure logical function reynolds_not_monotone(self)
      class(reynolds_film), intent(in) :: self
      reynolds_not_monotone = .false.
   end function reynolds_not_monotone

   pure logical function reynolds_changes_friction(self)
      class(reynolds_film), intent(in) :: self
      reynolds_changes_friction = .false.
   end function reynolds_changes_friction

   pure subroutine reynolds_effect(self, name)
      class(reynolds_film), intent(in) :: self
      character(len=:), allocatable, intent(out) :: name
      name = "reynolds_film"
   end subroutine reynolds_effect

   !> A film is full somewhere only where the water brought, V H_in, fills
   !> the gap's Couette flux (V/2) c: where c <= 2 H_in. c grows with the gap,
   !> so the narrowest gap decides. Otherwise every cell is partial at
   !> ambient pressure and the film carries nothing.
   pure logical function reynolds_engages(self, step, gap)
      class(reynolds_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      real(wp) :: h_t, c, k
      reynolds_engages = .false.
      if (.not. step%active .or. size(gap) == 0) return
      call reynolds_cell_terms(minval(gap), self%sigma, self%eta, h_t, c, k)
      reynolds_engages = c <= 2.0_wp * self%depth
   end function reynolds_engages

   !> Below x = -2 H_in every gap is at least 2 H_in (min d = 0): no cell is
   !> full, no load, and no element touches.
   pure real(wp) function reynolds_lower_bound(self, step, d)
      class(reynolds_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: d(:)
      reynolds_lower_bound = -2.0_wp * self%depth
   end function reynolds_lower_bound

   !> Per lane: the warm-start flag (1: the set below is the last solve's,
   !> settled), the set of full nodes (1 full, 0 partial), and the scratch
   !> arrays w_ht .. w_gap, then the kept solution's values.
   pure integer function reynolds_work_size(self, n)
      class(reynolds_film), intent(in) :: self
      integer, intent(in) :: n
      reynolds_work_size = work_size(n)
   end function reynolds_work_size

   pure integer function work_size(n)
      integer, intent(in) :: n
      work_size = 1 + n_work_arrays * max(n, 1) + n_work_values
   end function work_size

   !> Where the kept solution's values start in a lane's workspace.
   pure integer function kept(n)
      integer, intent(in) :: n
      kept = 2 + n_work_arrays * max(n, 1)
   end function kept

   !> The film's load (N) on the gap field, and its derivative with respect
   !> to the penetration by a difference at the same full and partial nodes
   !> (one more tridiagonal solve). One lane, cold (the compiled tests').
   pure subroutine reynolds_load(self, step, gap, wh, dwh_dx)
      class(reynolds_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      real(wp), intent(out) :: wh, dwh_dx
      real(wp) :: work(work_size(size(gap)))
      wh = 0.0_wp
      dwh_dx = 0.0_wp
      if (.not. step%active .or. size(gap) == 0) return
      work = 0.0_wp
      call load_in_work(self, step%coef(1), gap, work, wh, dwh_dx)
   end subroutine reynolds_load

   !> reynolds_load for the lanes where `active`, each in its own workspace
   !> (work(:, lane), warm from its last solve): no allocation.
   pure subroutine reynolds_loads(self, nl, n, steps, gap, active, wh, dwh_dx, work)
      class(reynolds_film), intent(in) :: self
      integer, intent(in) :: nl, n
      type(film_step_type), intent(in) :: steps(nl)
      real(wp), intent(in) :: gap(nl, n)
      logical, intent(in) :: active(nl)
      real(wp), intent(inout) :: wh(nl), dwh_dx(nl)
      real(wp), intent(inout) :: work(:, :)
      integer :: j
      do j = 1, nl
         if (.not. active(j)) cycle
         wh(j) = 0.0_wp
         dwh_dx(j) = 0.0_wp
         if (.not. steps(j)%active .or. n == 0) cycle
         call load_in_work(self, steps(j)%coef(1), gap(j, :), work(:, j), wh(j), dwh_dx(j))
      end do
   end subroutine reynolds_loads

   !> The load and its derivative in a lane's workspace w (reynolds_work_size).
   !> The derivative is the solution's at the settled set, differentiated:
   !> with A y = b the settled system, dy/dx = A**-1 (db/dx - dA/dx y), from
   !> the cell terms' analytic derivatives (an open gap narrows as x grows; a
   !> contact's stays shut; the drainage lengths held), one more tridiagonal
   !> solve with the settled system's factors (A refactored only where the
   !> set did not settle) and no more transcendental functions. Where the load jumps (an
   !> element touching) or kinks (a node leaving the set), this is the
   !> slope of the side the settled set holds; the balance is bracketed.
   pure subroutine load_in_work(self, speed, gap, w, wh, dwh_dx)
      class(reynolds_film), intent(in) :: self
      real(wp), intent(in) :: speed, gap(:)
      real(wp), intent(inout) :: w(:)
      real(wp), intent(out) :: wh, dwh_dx
      real(wp) :: tc0, p0, dtc0, dp0, total
      integer :: n, info, m
      logical :: converged
      n = size(gap)
      call solve_in_work(self, speed, gap, w, wh, converged, tc0, p0, dtc0, dp0, info)
      ! kept for the report (the derivative below leaves p and theta as the
      ! solve made them)
      w(at(w_gap, n) : at(w_gap, n) + n - 1) = gap
      w(kept(n)) = merge(merge(1.0_wp, 2.0_wp, converged), 0.0_wp, info == 0)
      w(kept(n) + 1) = tc0
      w(kept(n) + 2) = p0
      dwh_dx = 0.0_wp
      if (n < 2) then
         dwh_dx = max(0.0_wp, self%width * self%length * 0.5_wp * dp0)
         return
      end if
      associate (set => w(2 : n + 1), &
         & c => w(at(w_c, n) : at(w_c, n) + n - 1), &
         & k => w(at(w_k, n) : at(w_k, n) + n - 1), &
         & run => w(at(w_run, n) : at(w_run, n) + n - 1), &
         & dc => w(at(w_dc, n) : at(w_dc, n) + n - 1), &
         & dk => w(at(w_dk, n) : at(w_dk, n) + n - 1), &
         & rhs => w(at(w_rhs, n) : at(w_rhs, n) + n - 1), &
         & p => w(at(w_p, n) : at(w_p, n) + n - 1), &
         & y => w(at(w_y, n) : at(w_y, n) + n - 1), &
         & dl => w(at(w_dl, n) : at(w_dl, n) + n - 1), &
         & dd => w(at(w_dd, n) : at(w_dd, n) + n - 1), &
         & du => w(at(w_du, n) : at(w_du, n) + n - 1))
         if (info /= 0) return
         call derivative_rhs(speed, k, run, dc, dk, p0, dtc0, dp0, set, y, rhs)
         if (converged) then
            ! the last iteration's system is the settled set's: its factors
            y(1:n - 1) = rhs(1:n - 1)
            call tridiagonal_solve(n - 1, dl, dd, du, y)
         else
            ! (the set was flipped after the last solve)
            call assemble_and_solve(speed, c, k, run, tc0, p0, set, y, dl, dd, du, info, rhs)
            if (info /= 0) return
         end if
         ! the load's nodes: the full ones at a positive pressure (p, as the
         ! solve left it, is 0 at the others)
         total = 0.0_wp
         do m = 1, n - 1
            if (p(m) > 0.0_wp) total = total + y(m)
         end do
         dwh_dx = max(0.0_wp, self%width * (self%length / real(n, wp)) * (total + 0.5_wp * dp0))
      end associate
   end subroutine load_in_work

   !> The film on a gap field in a lane's workspace w, warm from its set:
   !> the gap's terms (w_ht .. w_run), the nodes' pressure and fill (w_p,
   !> w_theta), the load (N), whether the set settled, and the inlet's flux
   !> coefficient tc0 and pressure p0.
   pure subroutine solve_in_work(self, speed, gap, w, load, settled, tc0, p0, dtc0, dp0, info)
      class(reynolds_film), intent(in) :: self
      real(wp), intent(in) :: speed, gap(:)
      real(wp), intent(inout) :: w(:)
      real(wp), intent(out) :: load, tc0, p0
      logical, intent(out) :: settled
      !> If present: the derivatives of tc0 and p0 with respect to the
      !> penetration, and those of c and k in the workspace (w_dc, w_dk).
      real(wp), intent(out), optional :: dtc0, dp0
      !> If present: 0, or the solver's (a singular system: no solution).
      integer, intent(out), optional :: info
      integer :: iterations, n, solver_info
      n = size(gap)
      associate (c => w(at(w_c, n) : at(w_c, n) + n - 1), &
         & k => w(at(w_k, n) : at(w_k, n) + n - 1), &
         & run => w(at(w_run, n) : at(w_run, n) + n - 1))
         if (present(dtc0)) then
            call film_terms(self%depth, self%eta, self%sigma, self%width, self%length, &
               & self%density, speed, gap, w(at(w_ht, n) : at(w_ht, n) + n - 1), c, k, run, &
               & tc0, p0, w(at(w_dc, n) : at(w_dc, n) + n - 1), &
               & w(at(w_dk, n) : at(w_dk, n) + n - 1), dtc0, dp0)
         else
            call film_terms(self%depth, self%eta, self%sigma, self%width, self%length, &
               & self%density, speed, gap, w(at(w_ht, n) : at(w_ht, n) + n - 1), c, k, run, &
               & tc0, p0)
         end if
         call solve_terms(self%width, self%length, speed, c, k, run, tc0, p0, &
            & w(at(w_p, n) : at(w_p, n) + n - 1), w(at(w_theta, n) : at(w_theta, n) + n - 1), &
            & w(2 : n + 1), w(1), load, iterations, settled, &
            & w(at(w_y, n) : at(w_y, n) + n - 1), w(at(w_dl, n) : at(w_dl, n) + n - 1), &
            & w(at(w_dd, n) : at(w_dd, n) + n - 1), w(at(w_du, n) : at(w_du, n) + n - 1), &
            & solver_info)
      end associate
      if (present(info)) info = solver_info
   end subroutine solve_in_work

   !> Where the workspace's array i (w_ht .. w_gap) of a pad of n elements
   !> starts: after the warm-start flag and the set.
   pure integer function at(i, n)
      integer, intent(in) :: i, n
      at = 2 + i * max(n, 1)
   end function at

   !> The film's solution at a gap field, for the outputs: whether its active
   !> set settled, its largest pressure (Pa, the inlet's included), and its
   !> water per unit of pad area (m): each element's
   !> mean gap h_T filled to the share the transport upwind gives it (the
   !> fill theta of the node ahead of it; the leading element's, the inlet's
   !> tc0 / c_1), averaged over the elements. In the lane's workspace, warm
   !> from the balance's last solve.
   pure subroutine reynolds_report(self, step, gap, settled, water, pressure_max, work)
      class(reynolds_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      real(wp), intent(inout) :: work(:)
      logical, intent(out) :: settled
      real(wp), intent(out) :: water, pressure_max
      real(wp) :: load, tc0, p0
      integer :: j, n
      settled = .true.
      water = 0.0_wp
      pressure_max = 0.0_wp
      n = size(gap)
      if (.not. step%active .or. n == 0) return
      if (work(kept(n)) > 0.0_wp .and. &
         & all(work(at(w_gap, n) : at(w_gap, n) + n - 1) == gap)) then
         ! the balance's last load was on this gap field: its solution
         ! (the same numbers a solve from its settled set gives)
         settled = work(kept(n)) == 1.0_wp
         tc0 = work(kept(n) + 1)
         p0 = work(kept(n) + 2)
      else
         call solve_in_work(self, step%coef(1), gap, work, load, settled, tc0, p0)
      end if
      associate (h_t => work(at(w_ht, n) : at(w_ht, n) + n - 1), &
         & c => work(at(w_c, n) : at(w_c, n) + n - 1), &
         & p => work(at(w_p, n) : at(w_p, n) + n - 1), &
         & theta => work(at(w_theta, n) : at(w_theta, n) + n - 1))
         water = min(1.0_wp, tc0 / c(1)) * h_t(1)
         do j = 2, n
            water = water + theta(j - 1) * h_t(j)
         end do
         water = water / real(n, wp)
         ! the nodes' pressures and the inlet's (p0 where the film is flooded)
         pressure_max = p0
         if (n > 1) pressure_max = max(maxval(p(1:n - 1)), p0)
      end associate
   end subroutine reynolds_report

   !> Per cell: the mean gap h_T over Gaussian heights of RMS sigma at nominal
   !> gap h (E[max(0, h - z)] = h Phi(h/sigma) + sigma phi(h/sigma)), the
   !> transport c = h_T + sigma phi_s, and the flow coefficient
   !> k = phi_x h_T**3 / (12 eta). Flow factors of Patir & Cheng (1978, 1979)
   !> for isotropic roughness (gamma = 1): phi_x = 1 - 0.90 exp(-0.56 H),
   !> phi_s = 1.899 H**0.98 exp(-0.92 H + 0.05 H**2) (H <= 5),
   !> 1.126 exp(-0.25 H) (H > 5), H = h / sigma.
   !> With dc and dk present, also their derivatives with respect to h
   !> (dh_T/dh = Phi(h/sigma); 0 at h <= 0, a contact, which stays shut).
   pure subroutine reynolds_cell_terms(h, sigma, eta, h_t, c, k, dc, dk)
      real(wp), intent(in) :: h, sigma, eta
      real(wp), intent(out) :: h_t, c, k
      real(wp), intent(out), optional :: dc, dk
      real(wp), parameter :: inv_sqrt2 = 0.70710678118654752_wp
      real(wp), parameter :: inv_sqrt2pi = 0.39894228040143268_wp
      !> h / sigma from which Phi = 1 and h_t = h in double precision:
      !> erfc(-8.5 / sqrt(2)) = 2 - 2e-17 rounds to 2, and
      !> phi(8.5) / 8.5 = 1e-17 is below half an ulp of 1 (and both fall
      !> as h / sigma grows).
      real(wp), parameter :: far_gap = 8.5_wp
      real(wp) :: hs, phi_x, phi_s, big_phi, e_x, dphi_s, e_g
      if (h <= 0.0_wp) then
         ! an element in contact (most of them, often): the same numbers as
         ! below at hs = 0, without the transcendental functions (erfc(0)
         ! and exp(0) are 1, hs**0.98 is 0)
         h_t = sigma * inv_sqrt2pi
         c = h_t
         k = (1.0_wp - 0.90_wp) * h_t**3 / (12.0_wp * eta)
         if (present(dc)) dc = 0.0_wp
         if (present(dk)) dk = 0.0_wp
         return
      end if
      hs = h / sigma
      if (hs >= far_gap) then
         ! far above the microtexture: Phi(hs) rounds to 1 and sigma phi(hs)
         ! to nothing beside h (below half an ulp of it), so these are the
         ! numbers the formulas give, to the bit, without erfc and an exp
         big_phi = 1.0_wp
         h_t = h
      else
         ! Phi(hs) = erfc(-hs / sqrt(2)) / 2 = 1 - erfc_scaled(y) exp(-y**2) / 2,
         ! y = hs / sqrt(2): the exponential is the one h_T needs (one
         ! evaluation for both)
         e_g = exp(-0.5_wp * hs * hs)
         big_phi = 1.0_wp - 0.5_wp * erfc_scaled(hs * inv_sqrt2) * e_g
         h_t = h * big_phi + sigma * inv_sqrt2pi * e_g
      end if
      e_x = exp(-0.56_wp * hs)
      phi_x = 1.0_wp - 0.90_wp * e_x
      if (hs <= 5.0_wp) then
         ! (hs**0.98 inside the exponential: one exp and a log for the two
         ! exps of a power and the product)
         phi_s = 1.899_wp * exp(0.98_wp * log(hs) - 0.92_wp * hs + 0.05_wp * hs * hs)
         ! d phi_s / d hs; phi_s / hs bounded below hs = 1e-100 (Newton's
         ! slope only)
         dphi_s = phi_s * (0.1_wp * hs - 0.92_wp) + 0.98_wp * phi_s / max(hs, 1.0e-100_wp)
      else
         phi_s = 1.126_wp * exp(-0.25_wp * hs)
         dphi_s = -0.25_wp * phi_s
      end if
      c = h_t + sigma * phi_s
      k = phi_x * h_t**3 / (12.0_wp * eta)
      if (present(dc)) dc = big_phi + dphi_s
      if (present(dk)) dk = (0.90_wp * 0.56_wp * e_x / sigma * h_t**3 &
         & + 3.0_wp * phi_x * h_t**2 * big_phi) / (12.0_wp * eta)
   end subroutine reynolds_cell_terms

   !> The film on a gap field (element order, the leading element last): at
   !> the nodes between elements, numbered from the leading edge (node j
   !> behind the j-th element from it; entry n unused), the pressure p (Pa,
   !> width-averaged), the fill theta and which are full; the load (N), the
   !> active-set iterations and whether they settled (if not, the last
   !> iterate with p clipped at 0). Cold: every node full at the start.
   pure subroutine reynolds_solve(depth, eta, sigma, width, length, density, speed, gap, p, &
         & theta, full, load, iterations, converged)
      real(wp), intent(in) :: depth, eta, sigma, width, length, density, speed, gap(:)
      real(wp), intent(out) :: p(size(gap)), theta(size(gap)), load
      logical, intent(out) :: full(size(gap))
      integer, intent(out) :: iterations
      logical, intent(out) :: converged
      real(wp) :: p0, tc0, warm
      real(wp) :: h_t(size(gap)), c(size(gap)), k(size(gap)), run(size(gap)), set(size(gap))
      real(wp), dimension(max(1, size(gap))) :: y, dl, dd, du
      integer :: info
      call film_terms(depth, eta, sigma, width, length, density, speed, gap, h_t, c, k, run, &
         & tc0, p0)
      warm = 0.0_wp
      call solve_terms(width, length, speed, c, k, run, tc0, p0, p, theta, set, warm, load, &
         & iterations, converged, y, dl, dd, du, info)
      full = set > 0.5_wp
   end subroutine reynolds_solve

   !> The active-set iteration on the gap's terms (film_terms: k / ds and
   !> 6 (ds / run)**2 in the places of k and run): the nodes'
   !> pressure and fill, the load. `set` (1 full, 0 partial per node) is
   !> where it starts when warm > 0 (else every node full) and the settled
   !> set on return; warm is 1 on return when it settled (else 0). A warm
   !> start that does not settle in max_warm iterations starts again cold.
   !> y, dl, dd, du: scratch of at least size(c); on return where it
   !> settled, y the last solution and dl .. du the factors of its system
   !> (the settled set's). info: 0, or the solver's (a singular system: not
   !> settled, no load).
   pure subroutine solve_terms(width, length, speed, c, k, run, tc0, p0, p, theta, set, warm, &
         & load, iterations, converged, y, dl, dd, du, info)
      real(wp), intent(in) :: width, length, speed, c(:), k(:), run(:), tc0, p0
      real(wp), intent(out) :: p(:), theta(:), load
      real(wp), intent(inout) :: set(:), warm
      integer, intent(out) :: iterations
      logical, intent(out) :: converged
      real(wp), intent(inout) :: y(:), dl(:), dd(:), du(:)
      integer, intent(out) :: info
      logical :: changed
      integer :: j, n, attempt, budget, it
      ! nodes 1 .. n-1 between the elements (node j behind element j from the
      ! leading edge); p(j), theta(j), set(j) are node j's; p(n) = 0 (outlet)
      n = size(c)
      converged = .false.
      p(1:n) = 0.0_wp
      theta(1:n) = 1.0_wp
      load = 0.0_wp
      info = 0
      iterations = 0
      do attempt = merge(1, 2, warm > 0.5_wp), 2
         if (attempt == 2) set(1:n) = 1.0_wp
         budget = merge(max_warm, max_active_set, attempt == 1)
         do it = 1, budget
            iterations = iterations + 1
            call assemble_and_solve(speed, c, k, run, tc0, p0, set, y, dl, dd, du, info)
            if (info /= 0) exit
            changed = .false.
            do j = 1, n - 1
               if (y(j) < 0.0_wp) then
                  set(j) = 1.0_wp - set(j)
                  changed = .true.
               end if
            end do
            if (.not. changed) then
               converged = .true.
               exit
            end if
         end do
         if (converged .or. info /= 0) exit
      end do
      warm = merge(1.0_wp, 0.0_wp, converged)
      if (info /= 0) return
      do j = 1, n - 1
         if (set(j) > 0.5_wp) then
            p(j) = max(0.0_wp, y(j))
            theta(j) = 1.0_wp
         else
            p(j) = 0.0_wp
            theta(j) = min(1.0_wp, max(0.0_wp, 1.0_wp - y(j)))
         end if
      end do
      load = nodes_load(width, length, p(1:n), p0)
   end subroutine solve_terms

   !> The film's load (N) from the nodes' pressures p(1:n-1) (p(n) is not a
   !> node) and the inlet's p0 (half an element's area: the leading edge).
   pure real(wp) function nodes_load(width, length, p, p0) result(load)
      real(wp), intent(in) :: width, length, p(:), p0
      integer :: n
      n = size(p)
      load = width * (length / real(n, wp)) * (sum(p(1:n - 1)) + 0.5_wp * p0)
   end function nodes_load

   !> The gap's terms, in order from the leading edge (element n first): the
   !> mean gap h_T, transport c and flow coefficient k per element (as
   !> kd = k / ds, the conductance between two nodes), its drainage length
   !> run (the run of open, or of touching, elements holding it, capped at
   !> the pad width; as runf = 6 (ds / run)**2, so that the side leakage
   !> 12 k / run**2 over a cell of length ds is kd runf: no division in the
   !> systems built from them), and the inlet: the flux coefficient tc0 (the
   !> leading gap's c, or 2 H_in if starved) and the dynamic pressure p0
   !> (Pa) of the water the leading edge stops. They do not depend on the
   !> active set.
   !> With dc, dk, dtc0 and dp0 present (all or none), also the derivatives
   !> of c, kd, tc0 and p0 with respect to the penetration x (gap = d - x
   !> where open).
   pure subroutine film_terms(depth, eta, sigma, width, length, density, speed, gap, h_t, c, &
         & kd, runf, tc0, p0, dc, dk, dtc0, dp0)
      real(wp), intent(in) :: depth, eta, sigma, width, length, density, speed, gap(:)
      real(wp), intent(out) :: h_t(size(gap)), c(size(gap)), kd(size(gap)), runf(size(gap))
      real(wp), intent(out) :: tc0, p0
      real(wp), intent(out), optional :: dc(size(gap)), dk(size(gap)), dtc0, dp0
      real(wp) :: ds, inv_ds, run
      integer :: j, n, i1
      logical :: slopes
      n = size(gap)
      ds = length / real(n, wp)
      inv_ds = real(n, wp) / length
      slopes = present(dc)
      if (slopes) then
         do j = 1, n
            call reynolds_cell_terms(gap(n + 1 - j), sigma, eta, h_t(j), c(j), kd(j), dc(j), &
               & dk(j))
            dc(j) = -dc(j)
            dk(j) = -dk(j) * inv_ds
            kd(j) = kd(j) * inv_ds
         end do
         dtc0 = 0.0_wp
         dp0 = 0.0_wp
      else
         do j = 1, n
            call reynolds_cell_terms(gap(n + 1 - j), sigma, eta, h_t(j), c(j), kd(j))
            kd(j) = kd(j) * inv_ds
         end do
      end if
      ! each run of open (or of touching) elements in one pass: its length,
      ! capped at the pad width, is the drainage length of its elements
      j = 1
      do while (j <= n)
         i1 = j
         do while (i1 < n)
            if ((gap(n - i1) > 0.0_wp) .neqv. (gap(n + 1 - j) > 0.0_wp)) exit
            i1 = i1 + 1
         end do
         run = min(width, real(i1 - j + 1, wp) * ds)
         runf(j:i1) = 6.0_wp * (ds / run)**2
         j = i1 + 1
      end do
      tc0 = 0.0_wp
      p0 = 0.0_wp
      if (n == 0) return
      if (2.0_wp * depth >= c(1)) then
         tc0 = c(1)
         p0 = (1.0_wp - c(1) / (2.0_wp * depth)) * 0.5_wp * density * speed * speed
         if (slopes) then
            dtc0 = dc(1)
            dp0 = -dc(1) / (2.0_wp * depth) * 0.5_wp * density * speed * speed
         end if
      else
         tc0 = 2.0_wp * depth
      end if
   end subroutine film_terms

   !> Vertex-centred: the gap per element, the pressure and fill at the nodes
   !> between elements; element j carries q_j = (V/2) theta_(j-1) c_j +
   !> kd_j (p_(j-1) - p_j) (kd = k / ds); node m balances q_(m+1) - q_m +
   !> leak = 0, the leak from the parabolic pressure across the drainage
   !> length, (kd_m runf_m + kd_(m+1) runf_(m+1)) p_m (film_terms).
   !> y: the full nodes' pressure, the partial nodes' 1 - theta (set: 1
   !> full, 0 partial). dl, dd, du: scratch of at least size(c), the
   !> system's factors on return (tridiagonal_factor's; info its status).
   !> With rhs present, the system's matrix solved for rhs(1:n-1) instead.
   !> The matrix is column diagonally dominant, so it needs no pivoting
   !> (pavefric_tridiagonal): a full node's column holds kd_m + kd_(m+1) +
   !> leak on the diagonal and -kd_m, -kd_(m+1) beside it (the leak > 0);
   !> a partial node's, -(V/2) c_(m+1) on the diagonal, (V/2) c_(m+1) below
   !> and 0 above (the transport is upwind).
   pure subroutine assemble_and_solve(speed, c, kd, runf, tc0, p0, set, y, dl, dd, du, &
         & info, rhs)
      real(wp), intent(in) :: speed, c(:), kd(:), runf(:), tc0, p0, set(:)
      real(wp), intent(inout) :: y(:), dl(:), dd(:), du(:)
      integer, intent(out) :: info
      real(wp), intent(in), optional :: rhs(:)
      real(wp) :: half_v
      integer :: n, m
      n = size(c)
      half_v = 0.5_wp * speed
      info = 0
      y(1:n) = 0.0_wp
      if (n < 2) return
      do m = 1, n - 1
         if (set(m) > 0.5_wp) then
            dd(m) = kd(m) + kd(m + 1) + (kd(m) * runf(m) + kd(m + 1) * runf(m + 1))
         else
            dd(m) = -half_v * c(m + 1)
         end if
         y(m) = -half_v * c(m + 1)
         if (m == 1) then
            y(m) = y(m) + half_v * tc0 + kd(1) * p0
         else
            y(m) = y(m) + half_v * c(m)
            dl(m - 1) = merge(-kd(m), half_v * c(m), set(m - 1) > 0.5_wp)
         end if
         if (m < n - 1) du(m) = merge(-kd(m + 1), 0.0_wp, set(m + 1) > 0.5_wp)
      end do
      if (present(rhs)) y(1:n - 1) = rhs(1:n - 1)
      call tridiagonal_factor(n - 1, dl, dd, du, info)
      if (info == 0) call tridiagonal_solve(n - 1, dl, dd, du, y)
   end subroutine assemble_and_solve

   !> The derivative's right side db/dx - (dA/dx) y of the system
   !> assemble_and_solve builds at a set (y its solution there), from the
   !> derivatives dc, dkd, dtc0, dp0 of its terms (the drainage lengths
   !> held): row m of A y = b differentiated, y fixed. Its terms are those
   !> of assemble_and_solve differentiated one by one: change both together
   !> (tests/test_reynolds.py, "the load slope", compares the result with
   !> differences of the load).
   pure subroutine derivative_rhs(speed, kd, runf, dc, dkd, p0, dtc0, dp0, set, y, rhs)
      real(wp), intent(in) :: speed, kd(:), runf(:), dc(:), dkd(:), p0, dtc0, dp0
      real(wp), intent(in) :: set(:), y(:)
      real(wp), intent(out) :: rhs(:)
      real(wp) :: half_v, r
      integer :: n, m
      n = size(kd)
      half_v = 0.5_wp * speed
      do m = 1, n - 1
         ! db/dx
         r = -half_v * dc(m + 1)
         if (m == 1) then
            r = r + half_v * dtc0 + dkd(1) * p0 + kd(1) * dp0
         else
            r = r + half_v * dc(m)
         end if
         ! - (dA/dx) y: the diagonal, then the neighbours
         if (set(m) > 0.5_wp) then
            r = r - (dkd(m) + dkd(m + 1) + (dkd(m) * runf(m) + dkd(m + 1) * runf(m + 1))) &
               & * y(m)
         else
            r = r + half_v * dc(m + 1) * y(m)
         end if
         if (m > 1) r = r - merge(-dkd(m), half_v * dc(m), set(m - 1) > 0.5_wp) * y(m - 1)
         if (m < n - 1) then
            if (set(m + 1) > 0.5_wp) r = r + dkd(m + 1) * y(m + 1)
         end if
         rhs(m) = r
      end do
   end subroutine derivative_rhs

end module pavefric_reynolds
