"""Moved to :mod:`pavefric.studies.energy_report` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import energy_report as _moved

if __name__ == "__main__":
    import runpy as _runpy
    _runpy.run_module("pavefric.studies.energy_report", run_name="__main__")
    _sys.exit(0)
_warnings.warn("pavefric.energy_report is now pavefric.studies.energy_report", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
