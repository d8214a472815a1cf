"""Moved to :mod:`pavefric.studies.validation` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import validation as _moved

_warnings.warn("pavefric.validation is now pavefric.studies.validation", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
