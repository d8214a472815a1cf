"""Moved to :mod:`pavefric.studies.speed_gradient` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import speed_gradient as _moved

_warnings.warn("pavefric.speed_gradient is now pavefric.studies.speed_gradient", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
