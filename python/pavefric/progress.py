"""Progress of the long commands on stderr: done, elapsed, an estimate of
what is left.

``python -m pavefric accuracy``, ``validate`` and ``bench`` run for minutes.
On a terminal their progress is one line, rewritten in place; otherwise (a
log file, a batch job's output) a line at each tenth of the work done, so a
log holds about ten of them. ``-q``/``--quiet`` on each command drops them
(results still go to stdout, warnings and errors to stderr). The estimate
of the time left assumes that the rest of the work goes at the rate so far:
``elapsed * (total - done) / done``. A command uses it as::

    with Progress("accuracy", total=len(runs), unit="runs", quiet=args.quiet) as progress:
        for run in runs:
            ...                      # progress.clear() before printing to the terminal
            progress.advance(what=run.name)
"""
from __future__ import annotations

import sys
import time
from typing import Callable, TextIO


def remaining_seconds(elapsed: float, done: float, total: float) -> float | None:
    """The time left if the rest of the work goes at the rate so far.

    Parameters
    ----------
    elapsed : float
        Seconds since the work began.
    done : float
        Work done so far (any unit: runs, steps, estimated seconds).
    total : float
        All the work, in the same unit.

    Returns
    -------
    float or None
        ``elapsed * (total - done) / done`` seconds; 0 when all is done;
        None before anything is done (no rate to go by).

    Raises
    ------
    ValueError
        If ``total`` is not positive, or ``done`` or ``elapsed`` is negative.
    """
    if not total > 0:
        raise ValueError(f"total = {total}: must be > 0")
    if done < 0 or elapsed < 0:
        raise ValueError(f"done = {done}, elapsed = {elapsed}: must be >= 0")
    if done >= total:
        return 0.0
    if done == 0:
        return None
    return elapsed * (total - done) / done


def clock_text(seconds: float) -> str:
    """``seconds`` as ``M:SS``, or ``H:MM:SS`` from an hour on.

    Parameters
    ----------
    seconds : float
        A duration (rounded to whole seconds; negative counts as 0).

    Returns
    -------
    str
        The duration as a clock reads.
    """
    s = max(0, int(round(seconds)))
    h, rest = divmod(s, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class Progress:
    """Done, elapsed and remaining time of a long command, on stderr.

    Parameters
    ----------
    label : str
        What runs, at the start of each line (e.g. ``"accuracy"``).
    total : float
        All the work, in units of ``unit`` (> 0).
    unit : str, optional
        What is counted (``"runs"``, ``"sections"``).
    quiet : bool, optional
        Write nothing (``-q``/``--quiet``).
    stream : file, optional
        Where to write (default ``sys.stderr``).
    tty : bool, optional
        One line rewritten in place (True) or a line at each tenth of the
        work (False); default: whether ``stream`` is a terminal.
    clock : callable, optional
        Seconds from an arbitrary origin (default ``time.monotonic``; tests
        pass their own).

    Raises
    ------
    ValueError
        If ``total`` is not positive.
    """

    def __init__(self, label: str, total: float, unit: str = "steps", *, quiet: bool = False,
                 stream: TextIO | None = None, tty: bool | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        if not total > 0:
            raise ValueError(f"total = {total}: must be > 0")
        self.label = label
        self.total = total
        self.unit = unit
        self.quiet = quiet
        self.stream = sys.stderr if stream is None else stream
        if tty is None:
            isatty = getattr(self.stream, "isatty", None)
            tty = bool(isatty and isatty())
        self.tty = tty
        self.clock = clock
        self.start = clock()
        self.done = 0.0
        self._tenths = 0        # tenths of the work already reported (not a terminal)
        self._width = 0         # length of the line now on the terminal

    def line(self, what: str = "") -> str:
        """The progress line as it stands (without a line end).

        Parameters
        ----------
        what : str, optional
            The step just finished, shown at the end of the line.

        Returns
        -------
        str
            ``LABEL: DONE/TOTAL UNIT (P %), M:SS elapsed, about M:SS left[: WHAT]``.
        """
        elapsed = self.clock() - self.start
        left = remaining_seconds(elapsed, self.done, self.total)
        left_text = "?" if left is None else clock_text(left)
        text = (f"{self.label}: {self.done:g}/{self.total:g} {self.unit} "
                f"({100 * self.done / self.total:.0f} %), {clock_text(elapsed)} elapsed, "
                f"about {left_text} left")
        return f"{text}: {what}" if what else text

    def advance(self, amount: float = 1, what: str = "") -> None:
        """Count ``amount`` more work done, and show it.

        Parameters
        ----------
        amount : float, optional
            Work just finished, in units of ``unit`` (default 1).
        what : str, optional
            The step just finished, named on the line.
        """
        self.update(self.done + amount, what)

    def update(self, done: float, what: str = "") -> None:
        """Set the work done so far, and show it (on a terminal, every
        update; otherwise, a line each time a new tenth of the work is
        reached, and at the end).

        Parameters
        ----------
        done : float
            Work done so far, in units of ``unit`` (at most ``total``).
        what : str, optional
            The step just finished, named on the line.
        """
        self.done = min(float(done), float(self.total))
        if self.quiet:
            return
        if self.tty:
            text = self.line(what)
            pad = " " * max(0, self._width - len(text))
            self.stream.write(f"\r{text}{pad}")
            self._width = len(text)
        else:
            tenths = int(10 * self.done / self.total + 1e-9)
            if tenths <= self._tenths:
                return
            self._tenths = tenths
            self.stream.write(self.line(what) + "\n")
        self.stream.flush()

    def clear(self) -> None:
        """On a terminal, erase the progress line (before the command prints
        something else there); the next update draws it again."""
        if not self.quiet and self.tty and self._width:
            self.stream.write("\r" + " " * self._width + "\r")
            self.stream.flush()
            self._width = 0

    def close(self) -> None:
        """End the progress: on a terminal, the line is left as it is and a
        line end follows it."""
        if not self.quiet and self.tty and self._width:
            self.stream.write("\n")
            self.stream.flush()
            self._width = 0

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


__all__ = ["Progress", "remaining_seconds", "clock_text"]
