"""pavefric: tyre-rubber/pavement friction from a texture profile, dry and wet.

The friction model of Kane et al. (2017), computed by a Fortran core; this
package wraps it for pre- and post-processing.

>>> import pavefric
>>> ds = pavefric.simulate(heights_m, 0.87e-3, [20, 40, 60], mu_loc=0.6, depth=1e-3)
>>> ds["mu"].values
"""
from .core import (ANNOUNCE_SECONDS, CTM_DX, PavefricCostWarning, PavefricError,
                   PavefricKeywordError, PavefricMemoryError, PavefricWarning, Profile,
                   check_output, ProfilesFailedWarning, Scene, defaults, groups, layout,
                   load_scene, open_dataset, parameters, run, simulate)
from .profiles import ProfileEntry, element_profile, list_profiles, read_profile, write_profiles
from .plot import plot_mu_speed, plot_profile
from .texture import ifi, texture

open = open_dataset  # noqa: A001  - pavefric.open(path) reads an output file

from ._version import __version__  # meson.build project(version:), at build time

__all__ = ["ANNOUNCE_SECONDS", "CTM_DX", "PavefricCostWarning", "PavefricError",
           "PavefricKeywordError", "PavefricMemoryError", "PavefricWarning", "Profile",
           "ProfilesFailedWarning", "Scene", "load_scene", "defaults", "groups", "parameters",
           "layout", "open", "open_dataset", "ifi", "plot_mu_speed", "plot_profile",
           "read_profile", "texture", "run", "simulate", "__version__", "write_profiles",
           "list_profiles", "ProfileEntry", "check_output", "element_profile"]
