"""Moved to :mod:`pavefric.studies.bench_io` (the studies and reports are apart
from the library, docs/architecture.md). This name stays for a deprecation
period: importing it warns and gives the moved module itself."""
import sys as _sys
import warnings as _warnings

from .studies import bench_io as _moved

if __name__ == "__main__":
    import runpy as _runpy
    _runpy.run_module("pavefric.studies.bench_io", run_name="__main__")
    _sys.exit(0)
_warnings.warn("pavefric.bench_io is now pavefric.studies.bench_io", DeprecationWarning, stacklevel=2)
_sys.modules[__name__] = _moved
