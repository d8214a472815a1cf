"""Moved to :mod:`pavefric.studies.reference_surfaces` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import reference_surfaces as _moved

_warnings.warn("pavefric.reference_surfaces is now pavefric.studies.reference_surfaces", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
