"""The benchmark's own measurements: a run's peak memory is that run's,
not the largest of every process the benchmark started before it (the
survey plan reported 587 MB a rank inside `python -m pavefric bench`, where
the 10,000,000-point run came first; 76 MB alone)."""
import sys

from pavefric.studies.bench_mpi import _timed


def test_peak_memory_is_the_runs_own(tmp_path):
    big = [sys.executable, "-c", "b = bytearray(300 * 2**20); b[::4096] = b'x' * len(b[::4096])"]
    small = [sys.executable, "-c", "pass"]
    _, rss_big = _timed(big, None, tmp_path, 1)
    _, rss_small = _timed(small, None, tmp_path, 1)
    assert rss_big > 300 * 1024                    # kB: the 300 MiB were touched
    assert rss_small < 100 * 1024, rss_small       # the interpreter alone, not the big run


def test_peak_memory_is_not_the_benchmarks_own(tmp_path):
    """Linux counts what a child had before exec (the benchmark's own
    resident pages, shared after fork) in its peak: the benchmark holding
    300 MiB must not make a small run look large."""
    held = bytearray(300 * 2**20)
    held[::4096] = b"x" * len(held[::4096])
    seconds, rss = _timed([sys.executable, "-c", "pass"], None, tmp_path, 1)
    assert rss < 100 * 1024, rss
    assert 0.0 < seconds < 30.0
    del held


def test_a_failing_command_is_reported(tmp_path):
    import pytest
    with pytest.raises(RuntimeError, match="went wrong"):
        _timed([sys.executable, "-c", "import sys; sys.exit('went wrong')"], None, tmp_path, 1)
