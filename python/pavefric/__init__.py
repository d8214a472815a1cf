"""pavefric: tyre-rubber/pavement friction from a texture profile, dry and wet.

The friction model of Kane et al. (2017), computed by a Fortran core; this
package wraps it for pre- and post-processing.

>>> import pavefric
>>> ds = pavefric.simulate(heights_m, 0.87e-3, [20, 40, 60], mu_loc=0.6, depth=1e-3)
>>> ds["mu"].values
"""
from .core import (PavefricError, Profile, ProfilesFailedWarning, Scene, defaults, layout,
                   load_scene, open_dataset, read_profile, run, simulate)
from .plot import plot_mu_speed, plot_profile
from .texture import ifi, texture

open = open_dataset  # noqa: A001  - pavefric.open(path) reads an output file

__version__ = "0.1.0"

__all__ = ["PavefricError", "ProfilesFailedWarning", "Profile", "Scene", "load_scene", "defaults",
           "layout", "open", "open_dataset",
           "ifi", "plot_mu_speed", "plot_profile", "read_profile", "texture", "run", "simulate", "__version__"]
