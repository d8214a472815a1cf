!> The declaration of an input variable and its value: what every
!> component and the scene's own table declare (name, group, unit, default,
!> valid and plausible ranges, meaning), with the helpers that build a
!> declaration and find a value by group and name. Types and pure helpers
!> only; the table itself and the namelist reading are the model's
!> (pavefric_model), which re-exports all of this.
module pavefric_params
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: param_spec_type, param_value_type
   public :: kind_real, kind_integer, kind_logical, kind_text, kind_real_list
   public :: param_base, text_param, logical_param, int_param, real_param, list_param
   public :: find_parameter, real_value, list_value, logical_value, integer_value, text_value

   !> Kinds of value.
   integer, parameter :: kind_real = 1, kind_integer = 2, kind_logical = 3, kind_text = 4, &
      & kind_real_list = 5

   !> The declaration of one namelist variable.
   type :: param_spec_type
      !> Namelist group and variable name.
      character(len=:), allocatable :: group, name
      !> Keyword of pavefric.simulate() / read_profile() ('' when the variable
      !> is not one: file names, batch settings).
      character(len=:), allocatable :: keyword
      !> 'model' (simulate keywords), 'profile' (read_profile keywords),
      !> 'scene', 'output' or 'batch'.
      character(len=:), allocatable :: scope
      integer :: kind = kind_real
      !> Unit (SI unless the name says otherwise); '' for none.
      character(len=:), allocatable :: unit
      !> The default as namelist text ('' when the variable has none).
      character(len=:), allocatable :: default
      !> Text values allowed (space-separated; '' = any text).
      character(len=:), allocatable :: choices
      !> Hard range: outside is an error.
      real(wp) :: lower = -huge(1.0_wp), upper = huge(1.0_wp)
      logical :: lower_strict = .false., upper_strict = .false.
      !> Plausible range: outside is a warning (what a road or a DFT can be).
      real(wp) :: plausible_lower = -huge(1.0_wp), plausible_upper = huge(1.0_wp)
      character(len=:), allocatable :: plausible_note
      !> Largest number of values of a list.
      integer :: max_values = 1
      !> Whether a single scene must give it.
      logical :: required = .false.
      !> One-line meaning (and notes) for the docs.
      character(len=:), allocatable :: meaning
   end type param_spec_type

   !> The value of one variable.
   type :: param_value_type
      real(wp) :: r = 0.0_wp
      integer :: i = 0
      logical :: b = .false.
      character(len=:), allocatable :: t
      real(wp), allocatable :: list(:)
      !> Whether the input gave it (else the default, or unset).
      logical :: given = .false.
      !> Whether it has a value (false for an optional variable not given).
      logical :: set = .false.
      !> The scene file's line that gave it (0: not from a file's line).
      integer :: line = 0
   end type param_value_type

contains

   ! --- declaration helpers ------------------------------------------------


   pure function param_base(group, name, default, unit, scope, meaning, kind) result(s)
      character(len=*), intent(in) :: group, name, default, unit, scope, meaning
      integer, intent(in) :: kind
      type(param_spec_type) :: s
      s%group = group
      s%name = name
      s%default = default
      s%unit = unit
      s%scope = scope
      s%meaning = meaning
      s%kind = kind
      s%choices = ""
      s%plausible_note = ""
      s%keyword = ""
      if (scope == "model" .or. scope == "profile") s%keyword = name
   end function param_base

   pure function text_param(group, name, default, unit, scope, meaning, choices) result(s)
      character(len=*), intent(in) :: group, name, default, unit, scope, meaning
      character(len=*), intent(in), optional :: choices
      type(param_spec_type) :: s
      s = param_base(group, name, "'" // default // "'", unit, scope, meaning, kind_text)
      if (present(choices)) s%choices = choices
   end function text_param

   pure function logical_param(group, name, default, scope, meaning) result(s)
      character(len=*), intent(in) :: group, name, default, scope, meaning
      type(param_spec_type) :: s
      s = param_base(group, name, default, "", scope, meaning, kind_logical)
   end function logical_param

   pure function int_param(group, name, default, scope, meaning, lower, upper) result(s)
      character(len=*), intent(in) :: group, name, default, scope, meaning
      integer, intent(in) :: lower, upper
      type(param_spec_type) :: s
      s = param_base(group, name, default, "", scope, meaning, kind_integer)
      s%lower = real(lower, wp)
      s%upper = real(upper, wp)
   end function int_param

   pure function real_param(group, name, default, unit, scope, meaning, lower, upper, &
         & lower_strict, upper_strict, plausible_lower, plausible_upper, plausible_note) &
         & result(s)
      character(len=*), intent(in) :: group, name, default, unit, scope, meaning
      real(wp), intent(in) :: lower, upper
      logical, intent(in), optional :: lower_strict, upper_strict
      real(wp), intent(in), optional :: plausible_lower, plausible_upper
      character(len=*), intent(in), optional :: plausible_note
      type(param_spec_type) :: s
      s = param_base(group, name, default, unit, scope, meaning, kind_real)
      s%lower = lower
      s%upper = upper
      if (present(lower_strict)) s%lower_strict = lower_strict
      if (present(upper_strict)) s%upper_strict = upper_strict
      if (present(plausible_lower)) s%plausible_lower = plausible_lower
      if (present(plausible_upper)) s%plausible_upper = plausible_upper
      if (present(plausible_note)) s%plausible_note = plausible_note
   end function real_param

   pure function list_param(group, name, default, unit, scope, meaning, lower, upper, &
         & max_values, plausible_lower, plausible_upper, plausible_note) result(s)
      character(len=*), intent(in) :: group, name, default, unit, scope, meaning
      real(wp), intent(in) :: lower, upper
      integer, intent(in) :: max_values
      real(wp), intent(in), optional :: plausible_lower, plausible_upper
      character(len=*), intent(in), optional :: plausible_note
      type(param_spec_type) :: s
      s = real_param(group, name, default, unit, scope, meaning, lower, upper, &
         & plausible_lower=plausible_lower, plausible_upper=plausible_upper, &
         & plausible_note=plausible_note)
      s%kind = kind_real_list
      s%max_values = max_values
   end function list_param

   ! --- values by name --------------------------------------------------------

   !> The id of &group name: its index in `specs` (0 when there is none).
   pure integer function find_parameter(specs, group, name)
      type(param_spec_type), intent(in) :: specs(:)
      character(len=*), intent(in) :: group, name
      integer :: k
      find_parameter = 0
      do k = 1, size(specs)
         if (specs(k)%group == group .and. specs(k)%name == name) then
            find_parameter = k
            return
         end if
      end do
   end function find_parameter

   !> The value of the real variable &group name (0 when `specs` has none:
   !> a component asks only for what it or the scene declares).
   pure real(wp) function real_value(specs, values, group, name)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      character(len=*), intent(in) :: group, name
      integer :: k
      real_value = 0.0_wp
      k = find_parameter(specs, group, name)
      if (k > 0) real_value = values(k)%r
   end function real_value

   !> The value of the logical variable &group name (.false. when `specs`
   !> has none).
   pure logical function logical_value(specs, values, group, name)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      character(len=*), intent(in) :: group, name
      integer :: k
      logical_value = .false.
      k = find_parameter(specs, group, name)
      if (k > 0) logical_value = values(k)%b
   end function logical_value

   !> The value of the integer variable &group name (0 when `specs` has none).
   pure integer function integer_value(specs, values, group, name)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      character(len=*), intent(in) :: group, name
      integer :: k
      integer_value = 0
      k = find_parameter(specs, group, name)
      if (k > 0) integer_value = values(k)%i
   end function integer_value

   !> The value of the text variable &group name ("" when `specs` has none
   !> or it has no value). A subroutine: gfortran keeps a deferred-length
   !> function result's length in a static variable, which threads share.
   pure subroutine text_value(specs, values, group, name, text)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      character(len=*), intent(in) :: group, name
      character(len=:), allocatable, intent(out) :: text
      integer :: k
      text = ""
      k = find_parameter(specs, group, name)
      if (k > 0) then
         if (allocated(values(k)%t)) text = values(k)%t
      end if
   end subroutine text_value

   !> The values of the list variable &group name (none when it has no
   !> value or `specs` has no such variable).
   pure function list_value(specs, values, group, name) result(list)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      character(len=*), intent(in) :: group, name
      real(wp), allocatable :: list(:)
      integer :: k
      k = find_parameter(specs, group, name)
      if (k > 0) then
         if (allocated(values(k)%list)) then
            list = values(k)%list
            return
         end if
      end if
      allocate(list(0))
   end function list_value

end module pavefric_params
