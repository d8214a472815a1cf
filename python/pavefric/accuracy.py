"""Moved to :mod:`pavefric.studies.accuracy` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import accuracy as _moved

_warnings.warn("pavefric.accuracy is now pavefric.studies.accuracy", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
