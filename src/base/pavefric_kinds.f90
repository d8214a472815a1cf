!> Kinds, physical constants and the version string of pavefric.
module pavefric_kinds
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private

   public :: wp, i8, pi, kmh_to_ms, pavefric_version, lanes

   !> Working precision: IEEE double.
   integer, parameter :: wp = selected_real_kind(15)
   !> 64-bit integer for counters that may exceed 2**31 on huge batches.
   integer, parameter :: i8 = int64
   !> Archimedes' constant.
   real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
   !> Conversion factor from km/h to m/s.
   real(wp), parameter :: kmh_to_ms = 1.0_wp / 3.6_wp
   !> Speeds advanced together (lanes): a fixed width, so that the element
   !> loops over the lanes compile to whole vectors (two AVX2 vectors, four
   !> SSE2 ones) and the lanes' work arrays live on the stack.
   integer, parameter :: lanes = 8
   !> Version of the code, written into every output file: meson.build's
   !> project(version:), through the generated pavefric_version.inc.
   include "pavefric_version.inc"

end module pavefric_kinds
