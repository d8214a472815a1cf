!> Facet angles of the profile and the local friction on them (Eqs. 5, 6, 10).
module pavefric_facet
   use pavefric_kinds, only: wp, pi
   use pavefric_params, only: param_spec_type, real_param
   use pavefric_output_spec, only: output_var_type, output_var, out_int64
   implicit none
   private

   public :: facet_friction, facet_tangent
   public :: facet_parameters, facet_n_parameters, facet_outputs, n_facet_outputs

   !> The result variables of the facets' friction (facet_outputs).
   integer, parameter :: n_facet_outputs = 2

   !> The variables the facets' friction declares: &surface mu_loc and
   !> &numerics theta_max_deg.
   integer, parameter :: facet_n_parameters = 2

contains

   !> What the time loop reports of the facets.
   pure function facet_outputs() result(t)
      type(output_var_type) :: t(n_facet_outputs)
      t(1) = output_var("facets", "n_clamped", "1", "contacts on facets clamped at " // &
         & "theta_max, summed over averaged positions", out_int64)
      t(2) = output_var("facets", "mu_adhesion", "1", "the local friction's part of mu: the " // &
         & "work of mu_loc on the facets per unit load and distance slid (0 with mu_loc = " // &
         & "0); mu = mu_hysteresis + mu_adhesion")
   end function facet_outputs

   !> The facets' variables: the local friction of the texture finer than
   !> the pad's elements, and the clamp on the steepest facet.
   pure function facet_parameters() result(s)
      type(param_spec_type) :: s(facet_n_parameters)
      s(1) = real_param("surface", "mu_loc", "0.5", "1", "model", &
         & "local friction of the facets: all texture scales finer than dx (British " // &
         & "Pendulum SRT in the paper: 0.30-0.75). Set it for your surface.", &
         & lower=0.0_wp, upper=100.0_wp, plausible_lower=0.0_wp, plausible_upper=2.0_wp, &
         & plausible_note="pendulum values of roads lie between 0.2 and 1.2")
      s(2) = real_param("numerics", "theta_max_deg", "85", "degree", "model", &
         & "steepest facet angle plus friction angle; steeper facets are clamped to " // &
         & "+-theta_max_deg and counted in n_clamped", lower=0.0_wp, lower_strict=.true., &
         & upper=90.0_wp, upper_strict=.true.)
   end function facet_parameters

   !> For each sample k: tan(theta_k), theta_k = alpha_k + atan(mu_loc), with
   !> alpha_k = atan((z(k+1) - z(k-1)) / (2 dx)) (central difference; wraps on a
   !> closed profile, one-sided at the ends of an open one), theta clamped to
   !> [-theta_max, theta_max]; `clamped(k)` says whether the clamp acted.
   !> FF = F tan(theta) equals F (sin a + mu cos a)/(cos a - mu sin a) (Eq. 10).
   !> The tangent is formed by facet_tangent's addition formula (no atan and
   !> tan per sample: they were 6 % of a 10-million-point run).
   pure subroutine facet_friction(z, dx, closed, mu_loc, theta_max_deg, tan_theta, clamped, &
         & slopes)
      real(wp), intent(in) :: z(:), dx, mu_loc, theta_max_deg
      logical, intent(in) :: closed
      real(wp), intent(out) :: tan_theta(:)
      logical, intent(out) :: clamped(:)
      !> Optional: the facet slopes tan(alpha_k) themselves.
      real(wp), intent(out), optional :: slopes(:)
      real(wp) :: slope, tan_max
      integer :: k, n
      n = size(z)
      tan_max = tan(theta_max_deg * pi / 180.0_wp)
      do k = 1, n
         if (n == 1) then
            slope = 0.0_wp
         else if (k == 1) then
            if (closed) then
               slope = (z(2) - z(n)) / (2.0_wp * dx)
            else
               slope = (z(2) - z(1)) / dx
            end if
         else if (k == n) then
            if (closed) then
               slope = (z(1) - z(n-1)) / (2.0_wp * dx)
            else
               slope = (z(n) - z(n-1)) / dx
            end if
         else
            slope = (z(k+1) - z(k-1)) / (2.0_wp * dx)
         end if
         if (present(slopes)) slopes(k) = slope
         call facet_tangent(slope, mu_loc, tan_max, tan_theta(k), clamped(k))
      end do
   end subroutine facet_friction

   !> tan(alpha + atan(mu)) for a facet of slope s = tan(alpha) and a local
   !> friction mu >= 0, with theta = alpha + atan(mu) clamped to
   !> [-theta_max, theta_max] (tan_max = tan(theta_max)): the addition formula
   !> (s + mu) / (1 - s mu), no trigonometric call. 1 - s mu <= 0 means theta
   !> >= 90 degrees (clamped); otherwise the tangent is monotone in theta.
   elemental subroutine facet_tangent(s, mu, tan_max, t, clamped)
      real(wp), intent(in) :: s, mu, tan_max
      real(wp), intent(out) :: t
      logical, intent(out) :: clamped
      real(wp) :: den
      den = 1.0_wp - s * mu
      if (den <= 0.0_wp) then
         t = tan_max
         clamped = .true.
         return
      end if
      t = (s + mu) / den
      clamped = abs(t) > tan_max
      t = max(-tan_max, min(tan_max, t))
   end subroutine facet_tangent

end module pavefric_facet
