!> Rubber components: how one pad element's pressure answers its
!> compression over a time step (paper Eqs. 3, 8).
!>
!> Any linear viscoelastic element integrated implicitly over a step gives,
!> at the step's end, a pressure linear in the new compression u:
!>     p = k_eff (u - u_free),
!> where k_eff is the same for every element and u_free, the compression at
!> which the element would carry no pressure, depends on the element's own
!> history (its internal state). The element touches the road iff its
!> geometric compression g exceeds u_free; then u = g, else it recovers
!> freely to u = u_free. The driver and the load balance see only this
!> form (`rubber_model`), so Kelvin-Voigt, a generalised Maxwell element or
!> any other linear model sit side by side behind one interface.
module pavefric_rubber
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type
   use pavefric_params, only: param_spec_type, param_value_type, real_param, real_value
   use pavefric_output_spec, only: output_var_type, output_var, out_int64, out_flag
   implicit none
   private

   public :: rubber_model, rubber_step_type, kelvin_voigt_rubber
   public :: rubber_context_type, rubber_entry_type, rubber_builder, rubber_checker
   public :: kelvin_voigt_entry, kelvin_voigt_n_parameters
   public :: rubber_outputs, n_rubber_outputs

   !> The result variables of every rubber law (rubber_outputs).
   integer, parameter :: n_rubber_outputs = 4

   !> The variables the Kelvin-Voigt law declares (kelvin_voigt_entry).
   integer, parameter :: kelvin_voigt_n_parameters = 1

   !> What every rubber law is built with, from the &rubber group's shared
   !> variables (pavefric_rubber_models): the spring K (a Maxwell element's
   !> equilibrium spring K_inf, N m-3) and the WLF shift a_T of the scene's
   !> temperature, by which every relaxation time is multiplied. A law's own
   !> variables come from its declarations (rubber_entry_type).
   type :: rubber_context_type
      real(wp) :: stiffness = 0.0_wp, shift = 1.0_wp
   end type rubber_context_type

   !> A rubber law as the registry (pavefric_rubber_models) sees it: its
   !> name (&rubber model), the variables it declares, how it is built from
   !> them and, optionally, the checks that involve several of them.
   type :: rubber_entry_type
      character(len=:), allocatable :: name
      type(param_spec_type), allocatable :: parameters(:)
      procedure(rubber_builder), pointer, nopass :: build => null()
      procedure(rubber_checker), pointer, nopass :: check => null()
   end type rubber_entry_type

   !> What the time step makes of the rubber at each of a set of speeds
   !> (lanes): the same for every element. The driver advances all the
   !> speeds of a scene together, so every array has the lanes first.
   type :: rubber_step_type
      !> Slope of p(u) over a step (N m-3), the effective stiffness, per lane.
      real(wp), allocatable :: k_eff(:)
      !> Whether the elements carry memory from step to step, per lane.
      logical, allocatable :: memory(:)
      !> Coefficients of the model's state update (lanes, model's count).
      real(wp), allocatable :: coef(:, :)
      !> The same repeated for every element, (lanes x elements, model's
      !> count), for models whose loops run over lanes and elements as one
      !> (not allocated by models that do not need it).
      real(wp), allocatable :: per_element(:, :)
      !> The memory's modes (lanes, modes): the factor by which each decays
      !> over a step (in [0, 1)) and its share of the effective stiffness.
      !> The driver spins a closed profile up until what is left of the
      !> start can no longer change the state from one lap to the next.
      real(wp), allocatable :: mode_decay(:, :), mode_weight(:, :)
      !> Per lane, a bound on the factor by which the pad's creep under its
      !> constant load decays over a step (its longest retardation; [0, 1]).
      !> A memory mode's relaxation at a fixed compression is not the pad's
      !> creep at a fixed load: a soft equilibrium spring beside stiff arms
      !> creeps far longer than the arms relax. The driver takes a closed
      !> profile's mean as the dissipation only where this, too, has died
      !> out in the spin-up (not allocated: never).
      real(wp), allocatable :: creep_decay(:)
      !> Per lane, the size of that creep against the instant compression
      !> under the same load: k_eff / K_long - 1, K_long the stiffness that
      !> holds the load in the long run (at least 1; huge where nothing
      !> does). A soft equilibrium spring beside stiff dashpots or arms creeps
      !> far beyond the pad's instant compression (an attack's flat road:
      !> K_long 1e5 N m-3 against k_eff 3e11). Not allocated: 1.
      real(wp), allocatable :: creep_weight(:)
      !> A law whose step-mean pressure (mean_push) is linear in the step's
      !> two compressions alone, mean = c0 u0 + c1 u1 (in units of k_eff),
      !> gives (c0, c1) per lane here: the driver then forms it within its
      !> own pass (not allocated by laws with other internal state). A third
      !> column c2: the slope of the free path's mean against the push
      !> (the free path from u0 to u_free has mean c2 (u0 - u_free); the
      !> driver's contact ramp, docs/model.md, "The step's force where a
      !> contact starts or ends").
      real(wp), allocatable :: mean_weights(:, :)
      !> Per lane, the slope of the step-mean pressure (mean_push, in units
      !> of k_eff) against the element's push at the step's end, all else
      !> fixed: the free path's mean is then mean - slope push (the driver's
      !> contact ramp), for a law without mean_weights (whose third column
      !> serves instead; the Kelvin-Voigt law leaves this unallocated). Not
      !> allocated: taken as 0 (the ramp then starts from the step's own
      !> mean, still continuous where the pushes vanish).
      real(wp), allocatable :: push_slope(:)
   end type rubber_step_type

   !> A rubber element model.
   type, abstract :: rubber_model
   contains
      !> Internal state values per element (>= 1; the first is the compression).
      procedure(state_size_interface), deferred :: state_size
      !> Step coefficients at speeds V(:) when the pad of `elements` advances
      !> `advance` per step.
      procedure(prepare_interface), deferred :: prepare
      !> u_free(lane, element) of every element from its state.
      procedure(free_interface), deferred :: free_compression
      !> New state after a step whose compression ends at u_free + push.
      procedure(update_interface), deferred :: update
      !> The element's pressure averaged over the step, exactly for the
      !> step's own path (before update: the state is the step's start).
      procedure(mean_interface), deferred :: mean_push
      !> The effect the element's memory stands for, for the output ('viscous_memory').
      procedure(name_interface), deferred :: memory_effect
      !> Each lane's stored elastic energy, summed over the elements, in
      !> units of k_eff (as push x compression: the energy over l dx k_eff),
      !> from the state after an update; `known` false for a law that does
      !> not say (the default). An open profile's mean then takes out the
      !> energy stored at the ends of the stretch averaged.
      procedure :: stored_energy => no_stored_energy
   end type rubber_model

   abstract interface
      !> Build the law from the scene's context and its values (`specs`
      !> and `values`: the whole table, a law reads its own by group and
      !> name). Not pure: a polymorphic result.
      subroutine rubber_builder(context, specs, values, rubber)
         import :: rubber_context_type, param_spec_type, param_value_type, rubber_model
         type(rubber_context_type), intent(in) :: context
         type(param_spec_type), intent(in) :: specs(:)
         type(param_value_type), intent(in) :: values(:)
         class(rubber_model), allocatable, intent(out) :: rubber
      end subroutine rubber_builder

      !> Checks of the law's variables that involve several values (each
      !> value's own range is checked by the table already). `chosen`: the
      !> scene's &rubber model is this law (some checks apply only then).
      pure subroutine rubber_checker(specs, values, chosen, error)
         import :: param_spec_type, param_value_type, error_type
         type(param_spec_type), intent(in) :: specs(:)
         type(param_value_type), intent(in) :: values(:)
         logical, intent(in) :: chosen
         type(error_type), allocatable, intent(out) :: error
      end subroutine rubber_checker

      pure integer function state_size_interface(self)
         import :: rubber_model
         class(rubber_model), intent(in) :: self
      end function state_size_interface

      pure subroutine prepare_interface(self, speeds, advance, elements, step, stat)
         import :: rubber_model, rubber_step_type, wp
         class(rubber_model), intent(in) :: self
         real(wp), intent(in) :: speeds(:), advance
         integer, intent(in) :: elements
         type(rubber_step_type), intent(out) :: step
         !> 0, or the allocation's status (not enough memory)
         integer, intent(out) :: stat
      end subroutine prepare_interface

      pure subroutine free_interface(self, step, state, u_free)
         import :: rubber_model, rubber_step_type, wp
         class(rubber_model), intent(in) :: self
         type(rubber_step_type), intent(in) :: step
         !> The elements' state: lanes x state_size x elements values, laid
         !> out as the model chooses (the driver only zeroes it)
         real(wp), intent(in), contiguous :: state(:, :, :)
         !> (lanes, elements)
         real(wp), intent(out), contiguous :: u_free(:, :)
      end subroutine free_interface

      pure subroutine update_interface(self, step, state, u_free, push)
         import :: rubber_model, rubber_step_type, wp
         class(rubber_model), intent(in) :: self
         type(rubber_step_type), intent(in) :: step
         real(wp), intent(inout), contiguous :: state(:, :, :)
         !> The free compression of the step and how far beyond it each
         !> element was pushed (0 out of contact): u = u_free + push.
         real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
      end subroutine update_interface

      !> The mean over the step of each element's pressure, in units of
      !> k_eff (as push): (1/dt) int p dt / k_eff along the path the update
      !> integrates exactly (u linear in time from the state's u0 to
      !> u_free + push). Its product with u1 - u0 is then the step's work on
      !> the element, exactly its stored-energy change plus a non-negative
      !> dissipation (docs/model.md, "Energy"). Called before update.
      pure subroutine mean_interface(self, step, state, u_free, push, mean)
         import :: rubber_model, rubber_step_type, wp
         class(rubber_model), intent(in) :: self
         type(rubber_step_type), intent(in) :: step
         real(wp), intent(in), contiguous :: state(:, :, :)
         real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
         !> (lanes, elements)
         real(wp), intent(out), contiguous :: mean(:, :)
      end subroutine mean_interface

      !> A name, into a deferred-length argument (not a function result:
      !> gfortran keeps such a result's length in a static variable).
      pure subroutine name_interface(self, name)
         import :: rubber_model
         class(rubber_model), intent(in) :: self
         character(len=:), allocatable, intent(out) :: name
      end subroutine name_interface
   end interface

   !> The paper's Kelvin-Voigt element p = K u + C du/dt, backward Euler.
   type, extends(rubber_model) :: kelvin_voigt_rubber
      !> Spring modulus K (N m-3) and dashpot viscosity C (N s m-3), per unit length.
      real(wp) :: stiffness = 0.0_wp, viscosity = 0.0_wp
   contains
      procedure :: state_size => kv_state_size
      procedure :: prepare => kv_prepare
      procedure :: free_compression => kv_free
      procedure :: update => kv_update
      procedure :: mean_push => kv_mean
      procedure :: memory_effect => kv_memory_effect
      procedure :: stored_energy => kv_stored_energy
   end type kelvin_voigt_rubber

contains

   !> What the time loop reports of the rubber, whichever its law.
   pure function rubber_outputs() result(t)
      type(output_var_type) :: t(n_rubber_outputs)
      t(1) = output_var("rubber", "max_compression", "m", "largest compression of a " // &
         & "rubber element (compare with the pad thickness)")
      t(2) = output_var("rubber", "memory_updates", "1", "element-steps that updated the " // &
         & "rubber's memory (0: no memory kept)", out_int64)
      t(3) = output_var("rubber", "viscous_memory_ran", "", "whether the rubber elements " // &
         & "carried memory", out_flag)
      t(4) = output_var("rubber", "mu_hysteresis", "1", "the rubber's part of mu: the work " // &
         & "of the facet forces on the rubber (its stored energy returned over a closed " // &
         & "profile, its dissipation kept) per unit load and distance slid; 0 for an " // &
         & "elastic pad on a closed profile (docs/model.md)")
   end function rubber_outputs

   !> The paper's Kelvin-Voigt law (Eq. 3): the spring K of the context and
   !> a dashpot C in parallel, C shifted to the temperature (C -> a_T C).
   pure function kelvin_voigt_entry() result(e)
      type(rubber_entry_type) :: e
      e%name = "kelvin_voigt"
      allocate(e%parameters(kelvin_voigt_n_parameters))
      e%parameters(1) = real_param("rubber", "viscosity", "1.0e2", "N s m-3", "model", &
         & "dashpot viscosity per unit length C (paper: fitted on GSSB at 20 km/h), at " // &
         & "the reference temperature; 0 = elastic rubber: no viscous memory is kept. " // &
         & "model = 'kelvin_voigt' only.", lower=0.0_wp, upper=1.0e12_wp)
      e%build => kelvin_voigt_build
   end function kelvin_voigt_entry

   subroutine kelvin_voigt_build(context, specs, values, rubber)
      type(rubber_context_type), intent(in) :: context
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      class(rubber_model), allocatable, intent(out) :: rubber
      allocate(rubber, source=kelvin_voigt_rubber(stiffness=context%stiffness, &
         & viscosity=context%shift * real_value(specs, values, "rubber", "viscosity")))
   end subroutine kelvin_voigt_build

   pure integer function kv_state_size(self)
      class(kelvin_voigt_rubber), intent(in) :: self
      kv_state_size = 1
   end function kv_state_size

   !> Backward Euler of K u + C du/dt = p over dt = advance / V:
   !> k_eff = K + C/dt, and with p = 0 (Eq. 8) u_free = u_prev / (1 + K dt/C)
   !> = u_prev C V / (C V + K advance), 0 for C = 0 or V = 0 (no division by
   !> zero in either limit). coef(:, 1) is that relaxation factor.
   pure subroutine kv_prepare(self, speeds, advance, elements, step, stat)
      class(kelvin_voigt_rubber), intent(in) :: self
      real(wp), intent(in) :: speeds(:), advance
      integer, intent(in) :: elements
      type(rubber_step_type), intent(out) :: step
      integer, intent(out) :: stat
      real(wp) :: cv
      integer :: i, j, nl
      nl = size(speeds)
      allocate(step%k_eff(nl), step%memory(nl), step%coef(nl, 1), &
         & step%per_element(nl * elements, 1), step%mode_decay(nl, 1), step%mode_weight(nl, 1), &
         & step%mean_weights(nl, 3), step%creep_decay(nl), &
         & step%creep_weight(nl), stat=stat)
      if (stat /= 0) return
      do j = 1, nl
         cv = self%viscosity * speeds(j)
         step%k_eff(j) = self%stiffness + cv / advance            ! K + C/dt
         step%memory(j) = cv > 0.0_wp
         if (step%memory(j)) then
            step%coef(j, 1) = cv / (cv + self%stiffness * advance)
         else
            step%coef(j, 1) = 0.0_wp
         end if
         ! one mode: the compression's relaxation, all of the element
         step%mode_decay(j, 1) = step%coef(j, 1)
         step%mode_weight(j, 1) = 1.0_wp
         ! under a constant load the element creeps by the same factor
         ! (K u + C (u - u') / dt = F: u - F/K = b (u' - F/K))
         step%creep_decay(j) = step%coef(j, 1)
         ! k_eff / K - 1 = C V / (K advance)
         step%creep_weight(j) = huge(1.0_wp)
         if (self%stiffness > 0.0_wp) step%creep_weight(j) = &
            & max(1.0_wp, min(huge(1.0_wp), cv / advance / self%stiffness))
         ! the mean (1 - b)(u0 + u1)/2 + b (u1 - u0) (kv_mean) as weights
         ! of u0 and u1
         step%mean_weights(j, 1) = 0.5_wp * (1.0_wp - step%coef(j, 1)) - step%coef(j, 1)
         step%mean_weights(j, 2) = 0.5_wp * (1.0_wp - step%coef(j, 1)) + step%coef(j, 1)
         ! on the free path (u1 = b u0) the mean is (1 - b)^2 u0 / 2, that is
         ! (1 - b)/2 times the free path's change u0 - b u0
         step%mean_weights(j, 3) = 0.5_wp * (1.0_wp - step%coef(j, 1))
      end do
      do i = 1, elements
         step%per_element((i - 1) * nl + 1 : i * nl, 1) = step%coef(:, 1)
      end do
   end subroutine kv_prepare

   pure subroutine kv_free(self, step, state, u_free)
      class(kelvin_voigt_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(out), contiguous :: u_free(:, :)
      call kv_free_kernel(size(u_free), step%per_element, state, u_free)
   end subroutine kv_free

   !> The compression is the whole state: u = max(g, u_free) = u_free + push.
   pure subroutine kv_update(self, step, state, u_free, push)
      class(kelvin_voigt_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(inout), contiguous :: state(:, :, :)
      real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
      call kv_update_kernel(size(u_free), state, u_free, push)
   end subroutine kv_update

   !> Along u linear from u0 to u1 = u_free + push, p = K u + C (u1 - u0)/dt
   !> averages K (u0 + u1)/2 + C (u1 - u0)/dt; over k_eff = K + C/dt, with
   !> b = (C/dt)/k_eff (coef 1): (1 - b)(u0 + u1)/2 + b (u1 - u0). The work
   !> is K (u1^2 - u0^2)/2 + C (u1 - u0)^2/dt: stored plus dissipated.
   pure subroutine kv_mean(self, step, state, u_free, push, mean)
      class(kelvin_voigt_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(in), contiguous :: u_free(:, :), push(:, :)
      real(wp), intent(out), contiguous :: mean(:, :)
      call kv_mean_kernel(size(u_free, 1), size(u_free, 2), step%mean_weights(:, 1:2), state, &
         & u_free, &
         & push, mean)
   end subroutine kv_mean

   !> kv_mean from the lanes' mean_weights (kv_prepare), the one form of it
   !> the driver also uses; the state is (lanes, elements), u0 per element.
   pure subroutine kv_mean_kernel(nl, n, weights, state, u_free, push, mean)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: weights(nl, 2), state(nl, n), u_free(nl, n), push(nl, n)
      real(wp), intent(out) :: mean(nl, n)
      integer :: i, j
      do i = 1, n
         do j = 1, nl
            mean(j, i) = weights(j, 1) * state(j, i) + weights(j, 2) * (u_free(j, i) + push(j, i))
         end do
      end do
   end subroutine kv_mean_kernel

   !> Over m = lanes x elements values as one contiguous loop.
   pure subroutine kv_free_kernel(m, relax, state, u_free)
      integer, intent(in) :: m
      real(wp), intent(in) :: relax(m), state(m)
      real(wp), intent(out) :: u_free(m)
      integer :: p
      do p = 1, m
         u_free(p) = relax(p) * state(p)
      end do
   end subroutine kv_free_kernel

   pure subroutine kv_update_kernel(m, state, u_free, push)
      integer, intent(in) :: m
      real(wp), intent(inout) :: state(m)
      real(wp), intent(in) :: u_free(m), push(m)
      integer :: p
      do p = 1, m
         state(p) = u_free(p) + push(p)
      end do
   end subroutine kv_update_kernel

   !> A law that does not say what it stores.
   pure subroutine no_stored_energy(self, step, state, energy, known)
      class(rubber_model), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      !> (lanes)
      real(wp), intent(out) :: energy(:)
      logical, intent(out) :: known
      energy = 0.0_wp
      known = .false.
   end subroutine no_stored_energy

   !> K u^2 / 2 per element, over k_eff: (1 - b) u^2 / 2, b = coef 1.
   pure subroutine kv_stored_energy(self, step, state, energy, known)
      class(kelvin_voigt_rubber), intent(in) :: self
      type(rubber_step_type), intent(in) :: step
      real(wp), intent(in), contiguous :: state(:, :, :)
      real(wp), intent(out) :: energy(:)
      logical, intent(out) :: known
      call kv_energy_kernel(size(energy), size(state) / size(energy), step%coef(:, 1), state, &
         & energy)
      known = .true.
   end subroutine kv_stored_energy

   pure subroutine kv_energy_kernel(nl, n, b, state, energy)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: b(nl), state(nl, n)
      real(wp), intent(out) :: energy(nl)
      integer :: i, j
      energy = 0.0_wp
      do i = 1, n
         do j = 1, nl
            energy(j) = energy(j) + state(j, i) * state(j, i)
         end do
      end do
      do j = 1, nl
         energy(j) = 0.5_wp * (1.0_wp - b(j)) * energy(j)
      end do
   end subroutine kv_energy_kernel

   pure subroutine kv_memory_effect(self, name)
      class(kelvin_voigt_rubber), intent(in) :: self
      character(len=:), allocatable, intent(out) :: name
      name = "viscous_memory"
   end subroutine kv_memory_effect

end module pavefric_rubber
