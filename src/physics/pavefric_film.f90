!> Film components: what the water between the pad and the road does.
!>
!> A film sees the whole gap field under the pad (gap_i >= 0 under element
!> i, 0 where the element touches) and may return a load that lifts the pad
!> (it then takes part in the load balance), a change of local friction on
!> each element (a share of mu_loc), or both. Films that evolve in time keep
!> a state per road sample (the water on the road), advanced with the pad.
!> The driver and the load balance see only this interface (`film_model`).
module pavefric_film
   use pavefric_kinds, only: wp, lanes
   use pavefric_bearing, only: bearing_prefactor, hydro_load, hydro_loads
   use pavefric_params, only: param_spec_type, param_value_type, real_param, real_value
   use pavefric_output_spec, only: output_var_type, output_var, out_int64, out_flag, &
      & dim_position_speed, when_series
   implicit none
   private

   public :: film_model, film_step_type, pseudo_bearing_film
   public :: film_context_type, film_entry_type, film_builder
   public :: pseudo_bearing_entry, pseudo_bearing_n_parameters
   public :: film_outputs, n_film_outputs

   !> The result variables of a film that carries load (film_outputs).
   integer, parameter :: n_film_outputs = 9

   !> What every film is built with, from the scene: the water depth H_in
   !> (m) and viscosity eta (Pa s), the pad's width and length (m) and the
   !> road's microtexture RMS height (m). A film's own variables come from
   !> its declarations (film_entry_type).
   type :: film_context_type
      real(wp) :: depth = 0.0_wp, eta = 0.0_wp, width = 0.0_wp, length = 0.0_wp
      real(wp) :: microtexture_rms = 0.0_wp
   end type film_context_type

   !> What one speed makes of the film.
   type :: film_step_type
      !> Whether the film takes part at this speed (water and motion).
      logical :: active = .false.
      !> Time step (s) and model coefficients (meaning is the model's).
      real(wp) :: dt = 0.0_wp
      real(wp), allocatable :: coef(:)
   end type film_step_type

   !> A water film model.
   type, abstract :: film_model
   contains
      !> Step coefficients at speed V when the pad advances `advance` per step.
      procedure(prepare_interface), deferred :: prepare
      !> Whether it carries load (and then takes part in the load balance).
      procedure(flag_interface), deferred :: carries_load
      !> Whether it changes the local friction of the elements.
      procedure(flag_interface), deferred :: changes_friction
      !> The output's name of the effect ('hydrodynamic_bearing', ...).
      procedure(name_interface), deferred :: effect
      !> Values of state per road sample (0: stateless).
      procedure :: state_size => film_no_state
      !> Whether the film takes part in the balance at this position, from
      !> the gap field at the dry balance (load films).
      procedure :: engages => film_never
      !> Load (N) on the pad for a gap field, and its derivative with
      !> respect to the pad's penetration (gap_i = max(0, d_i - x)).
      procedure :: load => film_no_load
      !> `load` for several lanes (speeds) at once: gap(lane, element), the
      !> lanes where `active`; each lane's numbers are `load`'s to the bit.
      !> The default: for a film whose `sums_suffice`, the lanes' sums in
      !> one pass (interleaved, each in element order) and `loads_of_sums`;
      !> otherwise `load` lane by lane. `work(:, lane)` is the lane's
      !> workspace (work_size values), kept by the caller between calls.
      procedure :: loads => film_loads_by_lane
      !> Values of workspace per lane for `loads` and `report` on a pad of n
      !> elements (0: none). The caller keeps it between the calls of one
      !> speed's run and zeroes it when the run (re)starts; a film may keep
      !> a warm start there, provided its numbers do not depend on it.
      procedure :: work_size => film_no_work
      !> Whether the load depends on the gap field only through its sum and
      !> the number of open gaps (gap_i > 0). The balance then sums both in
      !> its own pass over the elements and calls `loads_of_sums` (one pass
      !> over the pad fewer per evaluation, no gap field stored).
      procedure :: sums_suffice => film_flag_false
      !> Whether the load may jump where an element touches (x = d_i: its
      !> gap closes), and only there. The wet balance then bisects at those
      !> points first, so that a root at a jump is found in a few
      !> evaluations, not by halving the bracket to adjacent doubles.
      procedure :: jumps_at_contact => film_flag_false
      !> Whether the load is monotone in the penetration and in each gap (a
      !> wider gap never carries more). The balance then has one root, and
      !> from one position to the next it moves within the range of the
      !> clearances' moves. Where it may not be (the Reynolds film), the
      !> driver counts the positions where the root left that range
      !> (film_root_jumps).
      procedure :: load_monotone => film_flag_true
      !> `loads` from each lane's gap sum (in element order) and count of
      !> open gaps, for films whose `sums_suffice`: each lane's numbers are
      !> `loads`'s to the bit. (Not called for the others; the default
      !> returns no load.)
      procedure :: loads_of_sums => film_no_loads_of_sums
      !> `engages` from the gap field's sum (in element order) and count of
      !> open gaps, for films whose `sums_suffice`: `engages`'s answer for
      !> every field with these sums. (Not called for the others; the
      !> default, as `engages`' default, never engages.)
      procedure :: engages_of_sums => film_never_of_sums
      !> For films whose `sums_suffice`: the penetration x_e such that,
      !> where x_dry is the dry root (sum_i max(0, x_dry - d_i) = s), the
      !> film engages at it (`engages_of_sums` there) iff x_dry > x_e; from
      !> the sum of d in element order, the element count and s. The
      !> balance then decides without the dry root. The default, as
      !> `engages_of_sums`', never engages.
      procedure :: engage_level => film_never_level
      !> Penetration below which the film carries nothing and no element
      !> touches, given the shifted clearances d (min d = 0): the wet
      !> balance's lower bracket is min(0, this).
      procedure :: lower_bound => film_lower_zero
      !> `lower_bound` from the sum of d (in element order), for films whose
      !> `sums_suffice`: `lower_bound`'s value to the bit. (Not called for
      !> the others; the default, as `lower_bound`'s, is 0.)
      procedure :: lower_bound_of_sum => film_lower_zero_of_sum
      !> The state of every road sample before the pad arrives.
      procedure :: reset => film_reset_nothing
      !> A road sample passes under the pad's leading edge.
      procedure :: enter => film_enter_nothing
      !> Advance the film under the elements by one step and return each
      !> element's share of mu_loc and, under each element in contact, the
      !> film's thickness after the step (on its first road
      !> sample; 0 out of contact) (friction films).
      procedure :: friction => film_friction_unchanged
      !> What the film's solution at a gap field is, for the outputs (load
      !> films, once per averaged position at the balance's root): whether
      !> it settled, its water between the pad and the road per unit of pad
      !> area (m) and its largest pressure (Pa). The default: settled, no
      !> water or pressure resolved. `work` is the lane's workspace, as
      !> `loads` left it.
      procedure :: report => film_no_report
      !> Whether `report` has anything to say (else the driver skips it).
      procedure :: reports => film_flag_false
   end type film_model

   !> A wet model as the registry (pavefric_wet_models) holds it: its name
   !> (&water wet_model), the variables it declares (its own, in the
   !> scene's table and docs/inputs.md) and how it builds itself from the
   !> scene's context and values.
   type :: film_entry_type
      character(len=:), allocatable :: name
      type(param_spec_type), allocatable :: parameters(:)
      procedure(film_builder), pointer, nopass :: build => null()
      !> The result variables only this wet model produces (beside every
      !> load-carrying film's, film_outputs); none for most.
      type(output_var_type), allocatable :: outputs(:)
   end type film_entry_type

   abstract interface
      !> Build a film from the scene's context and its values (`specs` and
      !> `values`: the whole table, a film reads its own by group and name).
      subroutine film_builder(context, specs, values, film)
         import :: film_context_type, param_spec_type, param_value_type, film_model
         type(film_context_type), intent(in) :: context
         type(param_spec_type), intent(in) :: specs(:)
         type(param_value_type), intent(in) :: values(:)
         class(film_model), allocatable, intent(out) :: film
      end subroutine film_builder

      pure subroutine prepare_interface(self, speed, advance, step)
         import :: film_model, film_step_type, wp
         class(film_model), intent(in) :: self
         real(wp), intent(in) :: speed, advance
         type(film_step_type), intent(out) :: step
      end subroutine prepare_interface

      pure logical function flag_interface(self)
         import :: film_model
         class(film_model), intent(in) :: self
      end function flag_interface

      !> A name, into a deferred-length argument (not a function result:
      !> gfortran keeps such a result's length in a static variable).
      pure subroutine name_interface(self, name)
         import :: film_model
         class(film_model), intent(in) :: self
         character(len=:), allocatable, intent(out) :: name
      end subroutine name_interface
   end interface

   !> The paper's hydrodynamic pseudo-bearing (Eqs. 13-15): an inclined-pad
   !> film of inlet H_in (the water depth) and outlet the mean gap under the
   !> pad; it carries load while the water fills the valleys (mean gap < H_in).
   type, extends(film_model) :: pseudo_bearing_film
      !> Water depth H_in (m), viscosity eta (Pa s), alpha, beta, pad width l
      !> and length L (m).
      real(wp) :: depth = 0.0_wp, eta = 0.0_wp, alpha = 0.0_wp, beta = 0.0_wp
      real(wp) :: width = 0.0_wp, length = 0.0_wp
   contains
      procedure :: prepare => bearing_prepare
      procedure :: carries_load => bearing_carries_load
      procedure :: changes_friction => bearing_changes_friction
      procedure :: effect => bearing_effect
      procedure :: engages => bearing_engages
      procedure :: load => bearing_load
      procedure :: sums_suffice => bearing_sums_suffice
      procedure :: loads_of_sums => bearing_loads_of_sums
      procedure :: lower_bound => bearing_lower_bound
      procedure :: engages_of_sums => bearing_engages_of_sums
      procedure :: engage_level => bearing_engage_level
      procedure :: lower_bound_of_sum => bearing_lower_bound_of_sum
   end type pseudo_bearing_film

   !> Variables the pseudo-bearing declares (pseudo_bearing_entry).
   integer, parameter :: pseudo_bearing_n_parameters = 2

contains

   ! --- the paper's pseudo-bearing as a wet model: its variables and builder ---

   !> &water wet_model = 'kane2017': the paper's Eq. 15 with its coefficients
   !> &water alpha and beta.
   !> What the load balance reports of any film that carries load (written
   !> for every run: zero where no film took part).
   pure function film_outputs() result(t)
      type(output_var_type) :: t(n_film_outputs)
      t(1) = output_var("film", "wet_fraction", "1", "share of averaged positions where " // &
         & "the water film carried load")
      t(2) = output_var("film", "mean_hydro_load", "N", "load carried by the water film, " // &
         & "averaged over positions")
      t(3) = output_var("film", "bearing_evaluations", "1", "evaluations of the wet " // &
         & "balance over the pad's elements, each with the film's load (0: no film took " // &
         & "part in the balance; with wet_model = 'kane2017' Newton's steps between them " // &
         & "run on the formula of the contacts' piece and are not counted)", out_int64)
      t(4) = output_var("film", "bearing_ran", "", "whether a load-carrying water film took " // &
         & "part in the load balance", out_flag)
      t(5) = output_var("film", "hydro_load", "N", "load carried by the water film (Eq. 15)", &
         & dims=dim_position_speed, when=when_series)
      t(6) = output_var("film", "film_load_share", "1", "share of the pad's load carried " // &
         & "by the water film, averaged over positions (mean_hydro_load / &pad load)")
      t(7) = output_var("film", "mean_water_thickness", "m", "water between the pad and " // &
         & "the road per unit of pad area, averaged over positions: with wet_model = " // &
         & "'reynolds' each element's mean gap h_T times its fill theta, over the pad (up " // &
         & "to about twice the water depth: under the pad the water moves at V/2, half the " // &
         & "road's speed, so the same flow is twice as thick); 0 for " // &
         & "the models that do not resolve the water under the pad (kane2017; squeeze's " // &
         & "film on the contacts is mean_film_thickness)")
      t(8) = output_var("film", "film_unsettled", "1", "averaged positions where the " // &
         & "film's solution at the balance did not settle (wet_model = 'reynolds': its " // &
         & "active set; the last iterate is used, and a warning says so)", out_int64)
      t(9) = output_var("film", "film_root_jumps", "1", "averaged positions where the " // &
         & "wet balance's root moved from the position before outside the range of the " // &
         & "elements' clearances' moves, which a load monotone in the penetration and in " // &
         & "each gap never does: there the film's load is not monotone, and the pad may " // &
         & "have jumped to another root (wet_model = 'reynolds'; counted only for films " // &
         & "whose load may not be monotone, 0 for the others). Where it is not 0, mu " // &
         & "depends on the time step and may have no converged value; a warning says so " // &
         & "(docs/model.md)", out_int64, &
         & short="averaged positions where the wet balance's root may have jumped")
   end function film_outputs

   pure function pseudo_bearing_entry() result(e)
      type(film_entry_type) :: e
      e%name = "kane2017"
      allocate(e%outputs(0))
      allocate(e%parameters(pseudo_bearing_n_parameters))
      e%parameters(1) = real_param("water", "alpha", "12.0", "1", "model", &
         & "empirical bearing coefficient of Eq. 15, a calibration parameter. The default " // &
         & "is the value fitted on the paper's six 20 km/h DFT measurements with the " // &
         & "reference surfaces (python -m pavefric validate, docs/validation.md); the " // &
         & "paper's 105 (units unstated) lifts the pad off every CTM-like surface by " // &
         & "10-20 km/h with SI units.", lower=0.0_wp, upper=1.0e12_wp)
      e%parameters(2) = real_param("water", "beta", "1.75", "1", "model", &
         & "empirical speed exponent of Eq. 15 (speed in m/s)", lower=0.0_wp, upper=10.0_wp, &
         & plausible_lower=0.0_wp, plausible_upper=4.0_wp, &
         & plausible_note="the paper's value is 1.75")
      e%build => pseudo_bearing_build
   end function pseudo_bearing_entry

   subroutine pseudo_bearing_build(context, specs, values, film)
      type(film_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(film_model), allocatable, intent(out) :: film
      allocate(film, source=pseudo_bearing_film(depth=context%depth, eta=context%eta, &
         & alpha=real_value(specs, values, "water", "alpha"), &
         & beta=real_value(specs, values, "water", "beta"), width=context%width, &
         & length=context%length))
   end subroutine pseudo_bearing_build

   ! --- defaults of the interface ---------------------------------------------

   pure integer function film_no_state(self)
      class(film_model), intent(in) :: self
      film_no_state = 0
   end function film_no_state


   pure integer function film_no_work(self, n)
      class(film_model), intent(in) :: self
      integer, intent(in) :: n
      film_no_work = 0
   end function film_no_work

   pure logical function film_flag_false(self)
      class(film_model), intent(in) :: self
      film_flag_false = .false.
   end function film_flag_false

   pure logical function film_flag_true(self)
      class(film_model), intent(in) :: self
      film_flag_true = .true.
   end function film_flag_true

   pure subroutine film_no_report(self, step, gap, settled, water, pressure_max, work)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      !> The lane's workspace (work_size values).
      real(wp), intent(inout) :: work(:)
      logical, intent(out) :: settled
      real(wp), intent(out) :: water, pressure_max
      settled = .true.
      water = 0.0_wp
      pressure_max = 0.0_wp
   end subroutine film_no_report

   pure logical function film_never(self, step, gap)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      film_never = .false.
   end function film_never

   pure logical function film_never_of_sums(self, step, n, total, n_open)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: total, n_open
      film_never_of_sums = .false.
   end function film_never_of_sums

   pure real(wp) function film_never_level(self, step, n, sum_d, s)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: sum_d, s
      film_never_level = huge(1.0_wp)
   end function film_never_level

   pure subroutine film_no_load(self, step, gap, wh, dwh_dx)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      real(wp), intent(out) :: wh, dwh_dx
      wh = 0.0_wp
      dwh_dx = 0.0_wp
   end subroutine film_no_load

   pure subroutine film_loads_by_lane(self, nl, n, steps, gap, active, wh, dwh_dx, work)
      class(film_model), intent(in) :: self
      integer, intent(in) :: nl, n
      type(film_step_type), intent(in) :: steps(nl)
      real(wp), intent(in) :: gap(nl, n)
      logical, intent(in) :: active(nl)
      real(wp), intent(inout) :: wh(nl), dwh_dx(nl)
      !> The lanes' workspaces (work_size, nl); not used here.
      real(wp), intent(inout) :: work(:, :)
      real(wp) :: row(n), total(lanes), n_open(lanes)
      integer :: j
      if (self%sums_suffice()) then
         call gap_sums(nl, n, gap, total, n_open)
         call self%loads_of_sums(nl, n, steps, total, n_open, active, wh, dwh_dx)
         return
      end if
      do j = 1, nl
         if (.not. active(j)) cycle
         row = gap(j, :)
         call self%load(steps(j), row, wh(j), dwh_dx(j))
      end do
   end subroutine film_loads_by_lane

   pure subroutine film_no_loads_of_sums(self, nl, n, steps, total, n_open, active, wh, &
      & dwh_dx)
      class(film_model), intent(in) :: self
      integer, intent(in) :: nl, n
      type(film_step_type), intent(in) :: steps(nl)
      real(wp), intent(in) :: total(nl), n_open(nl)
      logical, intent(in) :: active(nl)
      real(wp), intent(inout) :: wh(nl), dwh_dx(nl)
      where (active)
         wh = 0.0_wp
         dwh_dx = 0.0_wp
      end where
   end subroutine film_no_loads_of_sums

   pure real(wp) function film_lower_zero(self, step, d)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: d(:)
      film_lower_zero = 0.0_wp
   end function film_lower_zero

   pure real(wp) function film_lower_zero_of_sum(self, step, n, sum_d)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: sum_d
      film_lower_zero_of_sum = 0.0_wp
   end function film_lower_zero_of_sum

   pure subroutine film_reset_nothing(self, step, state)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(inout) :: state(:, :)
   end subroutine film_reset_nothing

   pure subroutine film_enter_nothing(self, step, state, sample)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(inout) :: state(:, :)
      integer, intent(in) :: sample
   end subroutine film_enter_nothing

   pure subroutine film_friction_unchanged(self, step, state, first, footprint, closed, &
         & pressure, element_length, share, thickness)
      class(film_model), intent(in) :: self
      type(film_step_type), intent(in) :: step
      !> Per road sample (its second index, the profile's refined samples).
      real(wp), intent(inout) :: state(:, :)
      !> The road sample under each element's start; the element stands on
      !> `footprint` samples from it, in order (a closed profile's wrap
      !> round its end; an open profile's beyond its last sample are that
      !> sample).
      integer, intent(in) :: first(:), footprint
      logical, intent(in) :: closed
      !> Contact pressure of each element (Pa; 0 out of contact), element length (m).
      real(wp), intent(in) :: pressure(:), element_length
      !> Each element's share of mu_loc, and the film's thickness (m) under
      !> each element in contact after the step (0 out of contact).
      real(wp), intent(out) :: share(:), thickness(:)
      share = 1.0_wp
      thickness = 0.0_wp
   end subroutine film_friction_unchanged


   ! --- the paper's pseudo-bearing ----------------------------------------------

   !> Active with water and motion (Sect. 3); coef(1) is Eq. 15's prefactor
   !> P = alpha 6 eta V**beta l L**2, coef(2:3) its scales P / H_in**2 and
   !> P / H_in**3.
   pure subroutine bearing_prepare(self, speed, advance, step)
      class(pseudo_bearing_film), intent(in) :: self
      real(wp), intent(in) :: speed, advance
      type(film_step_type), intent(out) :: step
      allocate(step%coef(3))
      step%coef = 0.0_wp
      step%active = self%depth > 0.0_wp .and. speed > 0.0_wp
      if (step%active) then
         step%coef(1) = bearing_prefactor(self%alpha, self%beta, self%eta, speed, self%width, &
            & self%length)
         ! Eq. 15's scales P / H_in**2 and P / H_in**3 (hydro_loads)
         step%coef(2) = step%coef(1) / self%depth**2
         step%coef(3) = step%coef(1) / self%depth**3
      end if
      if (speed > 0.0_wp) step%dt = advance / speed
   end subroutine bearing_prepare

   pure logical function bearing_carries_load(self)
      class(pseudo_bearing_film), intent(in) :: self
      bearing_carries_load = .true.
   end function bearing_carries_load

   pure logical function bearing_changes_friction(self)
      class(pseudo_bearing_film), intent(in) :: self
      bearing_changes_friction = .false.
   end function bearing_changes_friction

   pure subroutine bearing_effect(self, name)
      class(pseudo_bearing_film), intent(in) :: self
      character(len=:), allocatable, intent(out) :: name
      name = "hydrodynamic_bearing"
   end subroutine bearing_effect

   !> Wet iff the water fills the valleys under the pad: the mean gap (the
   !> trapped water's volume per unit width over L) is below H_in (Sect. 3).
   pure logical function bearing_engages(self, step, gap)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      bearing_engages = mean(gap) < self%depth
   end function bearing_engages

   !> bearing_engages from the gaps' sum: mean(gap) is that sum (in element
   !> order) over n.
   pure logical function bearing_engages_of_sums(self, step, n, total, n_open)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: total, n_open
      bearing_engages_of_sums = total / real(n, wp) < self%depth
   end function bearing_engages_of_sums

   !> At the dry root the gaps sum to sum(d) - n x_dry + s (the pushes sum
   !> to s), so the mean gap is below H_in iff x_dry > (sum(d) + s) / n - H_in.
   pure real(wp) function bearing_engage_level(self, step, n, sum_d, s)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: sum_d, s
      bearing_engage_level = (sum_d + s) / real(n, wp) - self%depth
   end function bearing_engage_level

   !> Eq. 15 with H_out = the mean gap; d(mean gap)/dx = -(elements with a gap)/N.
   pure subroutine bearing_load(self, step, gap, wh, dwh_dx)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: gap(:)
      real(wp), intent(out) :: wh, dwh_dx
      real(wp) :: dwh, total, n_gap
      integer :: i
      ! one pass: the sum in element order (the mean's bits), the open gaps
      ! counted in a real (exact)
      total = 0.0_wp
      n_gap = 0.0_wp
      do i = 1, size(gap)
         total = total + gap(i)
         n_gap = n_gap + merge(1.0_wp, 0.0_wp, gap(i) > 0.0_wp)
      end do
      call hydro_load(step%coef(1), self%depth, total / real(size(gap), wp), wh, dwh)
      dwh_dx = -(dwh * n_gap / real(size(gap), wp))
   end subroutine bearing_load

   !> Eq. 15 needs only the mean gap (H_out) and, for its derivative, the
   !> share of open gaps.
   pure logical function bearing_sums_suffice(self)
      class(pseudo_bearing_film), intent(in) :: self
      bearing_sums_suffice = .true.
   end function bearing_sums_suffice

   pure subroutine bearing_loads_of_sums(self, nl, n, steps, total, n_open, active, wh, dwh_dx)
      class(pseudo_bearing_film), intent(in) :: self
      integer, intent(in) :: nl, n
      type(film_step_type), intent(in) :: steps(nl)
      real(wp), intent(in) :: total(nl), n_open(nl)
      logical, intent(in) :: active(nl)
      real(wp), intent(inout) :: wh(nl), dwh_dx(nl)
      ! fixed-size locals (run-time sizes would be heap allocations); the
      ! steps of inactive lanes are not read (nor are these by hydro_loads)
      real(wp), dimension(lanes) :: prefactor, scale2, scale3, h_out, dwh
      real(wp) :: dw
      integer :: j
      if (nl > lanes) then
         ! more films than the balance's lanes: one at a time
         do j = 1, nl
            if (.not. active(j)) cycle
            call hydro_load(steps(j)%coef(1), self%depth, total(j) / real(n, wp), wh(j), dw)
            dwh_dx(j) = -(dw * n_open(j) / real(n, wp))
         end do
         return
      end if
      do j = 1, nl
         if (.not. active(j)) cycle
         prefactor(j) = steps(j)%coef(1)
         scale2(j) = steps(j)%coef(2)
         scale3(j) = steps(j)%coef(3)
         h_out(j) = total(j) / real(n, wp)
      end do
      call hydro_loads(nl, prefactor, scale2, scale3, self%depth, h_out, active, wh, dwh)
      do j = 1, nl
         if (active(j)) dwh_dx(j) = -(dwh(j) * n_open(j) / real(n, wp))
      end do
   end subroutine bearing_loads_of_sums

   !> Per lane, the sum of the gaps in element order and the open gaps
   !> (counted in a real): lanes innermost on explicit run-time shapes, a
   !> vector loop.
   pure subroutine gap_sums(nl, n, gap, total, n_gap)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: gap(nl, n)
      real(wp), intent(out) :: total(nl), n_gap(nl)
      integer :: i, j
      real(wp) :: t1, c1
      if (nl == 1) then
         t1 = 0.0_wp                             ! one lane: a plain loop
         c1 = 0.0_wp
         do i = 1, n
            t1 = t1 + gap(1, i)
            c1 = c1 + merge(1.0_wp, 0.0_wp, gap(1, i) > 0.0_wp)
         end do
         total(1) = t1
         n_gap(1) = c1
         return
      end if
      total = 0.0_wp
      n_gap = 0.0_wp
      do i = 1, n
         do j = 1, nl
            total(j) = total(j) + gap(j, i)
            n_gap(j) = n_gap(j) + merge(1.0_wp, 0.0_wp, gap(j, i) > 0.0_wp)
         end do
      end do
   end subroutine gap_sums

   !> Below mean(d) - H_in the mean gap exceeds H_in (no wedge, no load).
   pure real(wp) function bearing_lower_bound(self, step, d)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      real(wp), intent(in) :: d(:)
      bearing_lower_bound = sum(d) / real(size(d), wp) - self%depth
   end function bearing_lower_bound

   !> bearing_lower_bound from sum(d) (in element order).
   pure real(wp) function bearing_lower_bound_of_sum(self, step, n, sum_d)
      class(pseudo_bearing_film), intent(in) :: self
      type(film_step_type), intent(in) :: step
      integer, intent(in) :: n
      real(wp), intent(in) :: sum_d
      bearing_lower_bound_of_sum = sum_d / real(n, wp) - self%depth
   end function bearing_lower_bound_of_sum

   !> Mean of a gap field, summed in element order.
   pure real(wp) function mean(gap)
      real(wp), intent(in) :: gap(:)
      integer :: i
      mean = 0.0_wp
      do i = 1, size(gap)
         mean = mean + gap(i)
      end do
      mean = mean / real(size(gap), wp)
   end function mean

end module pavefric_film
