"""Moved to :mod:`pavefric.studies.rubber_report` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import rubber_report as _moved

_warnings.warn("pavefric.rubber_report is now pavefric.studies.rubber_report", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
