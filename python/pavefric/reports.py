"""Moved to :mod:`pavefric.studies.reports` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import reports as _moved

_warnings.warn("pavefric.reports is now pavefric.studies.reports", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
