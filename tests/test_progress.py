"""Progress of the long commands (accuracy, validate, bench) on stderr:
pavefric.progress, and the commands' use of it. The clock is the test's own
(no timed assertions): the estimate is elapsed * (total - done) / done."""
from __future__ import annotations

import io
import re
import subprocess
import sys

import pytest

from conftest import ROOT
from pavefric.progress import Progress, clock_text, remaining_seconds

LINE = re.compile(r"^(?P<label>[\w-]+): (?P<done>[\d.]+)/(?P<total>[\d.]+) (?P<unit>\w+) "
                  r"\((?P<percent>\d+) %\), (?P<elapsed>[\d:]+) elapsed, "
                  r"about (?P<left>[\d:]+|\?) left(: (?P<what>.*))?$")


class FakeClock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def seconds(text: str) -> int:
    parts = [int(p) for p in text.split(":")]
    return sum(p * 60 ** i for i, p in enumerate(reversed(parts)))


def test_remaining_is_elapsed_times_left_over_done():
    assert remaining_seconds(10.0, 1, 4) == 30.0
    assert remaining_seconds(60.0, 3, 4) == 20.0
    assert remaining_seconds(5.0, 2.5, 10.0) == 15.0
    assert remaining_seconds(7.0, 4, 4) == 0.0
    assert remaining_seconds(0.0, 0, 4) is None          # no rate yet
    for bad in ((1.0, 1, 0), (1.0, -1, 4), (-1.0, 1, 4)):
        with pytest.raises(ValueError):
            remaining_seconds(*bad)


def test_clock_text():
    assert clock_text(0) == "0:00"
    assert clock_text(59.6) == "1:00"
    assert clock_text(754) == "12:34"
    assert clock_text(3 * 3600 + 62) == "3:01:02"
    assert clock_text(-3) == "0:00"


def test_not_a_terminal_a_line_at_each_tenth():
    """Forty steps of 3 s each: ten lines (at 4, 8, ..., 40), each with the
    estimate from its own elapsed time and fraction done."""
    clock, out = FakeClock(), io.StringIO()
    progress = Progress("accuracy", 40, "runs", stream=out, tty=False, clock=clock)
    for i in range(40):
        clock.now += 3.0
        progress.advance(what=f"run {i + 1}")
    progress.close()
    lines = out.getvalue().splitlines()
    assert len(lines) == 10, lines
    assert "\r" not in out.getvalue()
    for k, line in enumerate(lines, start=1):
        m = LINE.match(line)
        assert m, line
        done = 4 * k
        assert (m["label"], m["unit"], int(m["done"]), int(m["total"])) == \
            ("accuracy", "runs", done, 40)
        assert int(m["percent"]) == 10 * k
        assert seconds(m["elapsed"]) == 3 * done
        assert seconds(m["left"]) == round(3 * done * (40 - done) / done)
        assert m["what"] == f"run {done}"
    assert lines[-1].endswith("about 0:00 left: run 40")


def test_uneven_steps_still_sparse():
    """Steps of many sizes: never more than one line per tenth crossed, and
    the last line says all is done."""
    clock, out = FakeClock(), io.StringIO()
    progress = Progress("validate", 11, "sections", stream=out, tty=False, clock=clock)
    for amount in (0.5, 0.5, 3, 1, 1, 1, 1, 1, 1, 1):
        clock.now += 10
        progress.advance(amount)
    lines = out.getvalue().splitlines()
    percents = [int(LINE.match(line)["percent"]) for line in lines]
    assert len(lines) <= 10 and percents == sorted(percents) and len(set(percents)) == len(lines)
    assert lines[-1].startswith("validate: 11/11 sections (100 %), 1:40 elapsed, about 0:00 left")


def test_terminal_one_line_rewritten_in_place():
    clock, out = FakeClock(), io.StringIO()
    progress = Progress("bench", 4, "sections", stream=out, tty=True, clock=clock)
    for name in ("sweep", "program", "length", "estimate"):
        clock.now += 30
        progress.advance(what=name)
    assert "\n" not in out.getvalue()                      # one line, rewritten
    writes = out.getvalue().split("\r")[1:]
    assert len(writes) == 4
    assert writes[0].startswith("bench: 1/4 sections (25 %), 0:30 elapsed, about 1:30 left: "
                                "sweep")
    # a shorter line is padded over the longer one before it
    assert all(len(w) >= len(v.rstrip()) for v, w in zip(writes, writes[1:]))
    progress.clear()                                      # before other output
    assert out.getvalue().endswith("\r" + " " * len(writes[-1]) + "\r")
    clock.now += 1
    progress.update(4, what="estimate")
    progress.close()
    assert out.getvalue().endswith("about 0:00 left: estimate\n")


@pytest.mark.parametrize("tty", [True, False])
def test_quiet_writes_nothing(tty):
    out = io.StringIO()
    with Progress("accuracy", 5, stream=out, tty=tty, quiet=True) as progress:
        for _ in range(5):
            progress.advance()
        progress.clear()
    assert out.getvalue() == ""
    assert progress.done == 5


def test_the_stream_decides_terminal_or_not():
    class Tty(io.StringIO):
        def isatty(self):
            return True

    assert Progress("x", 1, stream=Tty()).tty
    assert not Progress("x", 1, stream=io.StringIO()).tty
    with pytest.raises(ValueError):
        Progress("x", 0)


def _progress_lines(stderr: str, label: str) -> list[re.Match]:
    return [m for m in map(LINE.match, stderr.splitlines()) if m and m["label"] == label]


def test_accuracy_command_progress_and_quiet(tmp_path):
    args = [sys.executable, "-m", "pavefric", "accuracy", str(ROOT / "inputs" / "ctm_dry.nml"),
            "--speeds", "40", "--repeats", "1", "--outdir", str(tmp_path / "out")]
    r = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    lines = _progress_lines(r.stderr, "accuracy")
    # a dry scene: 20 knob settings (no wet tolerance), the default, 5
    # tolerances for each of two time schemes, 10 passes of the order study
    # and its exact run
    assert 1 <= len(lines) <= 10 and all(int(m["total"]) == 42 for m in lines), r.stderr
    assert lines[-1]["done"] == "42" and lines[-1]["left"] == "0:00"
    assert lines[-1]["what"] == "ctm_dry, order, exact"
    assert "accuracy: 42/42" not in r.stdout                 # results only on stdout
    q = subprocess.run([*args, "-q"], capture_output=True, text=True, timeout=600)
    assert q.returncode == 0, q.stderr
    assert _progress_lines(q.stderr, "accuracy") == [] and " elapsed, " not in q.stderr
    assert q.stdout.count("accuracy: ") == r.stdout.count("accuracy: ")


@pytest.mark.parametrize("quiet", [False, True])
def test_bench_counts_its_sections(monkeypatch, capsys, quiet):
    """bench.run's progress counts SECTIONS, each named when done (the
    measurements replaced by stubs: this checks the progress, not them)."""
    from pavefric.studies import bench, bench_io, bench_mpi, rubber_report

    calls = []

    def stub(name):
        def f(*args, **kwargs):
            calls.append(name)
            return {}
        return f

    for name in ("sweep", "whole_program", "throughput", "scaling_elements", "scaling_length",
                 "threads", "api_threads", "mpi_batch", "estimate_accuracy", "accuracy_cost"):
        monkeypatch.setattr(bench, name, stub(name))
    monkeypatch.setattr(bench, "_reference", lambda path=None: None)
    monkeypatch.setattr(bench, "PlainLoop", lambda tmp: None)
    monkeypatch.setattr(bench_io, "reading", stub("reading"))
    monkeypatch.setattr(bench_mpi, "run", stub("batch"))
    monkeypatch.setattr(rubber_report, "cost", stub("rubber"))
    results = bench.run(quick=True, quiet=quiet)
    assert list(results) == list(bench.SECTIONS) and len(calls) == 13
    err = capsys.readouterr().err
    lines = _progress_lines(err, "bench")
    if quiet:
        assert lines == [] and err == ""
    else:
        assert 1 <= len(lines) <= 10 and lines[-1]["done"] == "13"
        assert lines[-1]["what"] == "accuracy" and lines[-1]["left"] == "0:00"
        named = [m["what"] for m in lines]
        assert named == [s for s in bench.SECTIONS if s in named]   # in order
