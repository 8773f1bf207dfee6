"""Progress of a suite on stderr: a live bar on a terminal, plain lines otherwise."""

import sys
import time


class Progress:
    """Counts finished runs (or traces) and shows done/total, rate, ETA, collapses, failures.

    total : int  units of work (runs; traces for hunt-and-fill)
    unit : str  "runs" or "traces"
    """

    def __init__(self, total, unit="runs", stream=None, every=2.0):
        self.total, self.unit = total, unit
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.done = self.runs = self.collapses = self.failures = 0
        self.start = self._last = time.perf_counter()
        self.every = every

    def restart(self):
        """Start the clock now (after a cluster has started)."""
        self.start = self._last = time.perf_counter()

    def update(self, rows, units=None):
        """Record finished ``rows`` (units of work: ``len(rows)`` unless given)."""
        self.done += len(rows) if units is None else units
        self.runs += len(rows)
        self.collapses += sum(r["status"] == "collapsed" for r in rows)
        self.failures += sum(r["status"] in ("solver_failure", "error") for r in rows)
        now = time.perf_counter()
        if self.tty or now - self._last >= self.every or self.done >= self.total:
            self._last = now
            self._show(now)

    def line(self, now=None):
        elapsed = (now or time.perf_counter()) - self.start
        rate = self.runs / elapsed if elapsed > 0 else 0.0
        left = self.total - self.done
        eta = elapsed / self.done * left if self.done else float("nan")
        runs = f" ({self.runs} runs)" if self.unit != "runs" else ""
        eta_text = f"{int(eta // 60)}:{int(eta % 60):02d}" if eta == eta else "?"
        return (f"{self.done}/{self.total} {self.unit}{runs}  {rate:.1f} runs/s  ETA {eta_text}  "
                f"collapses {self.collapses}  failures {self.failures}")

    def _show(self, now):
        text = self.line(now)
        if self.tty:
            width = 24
            filled = int(width * self.done / self.total) if self.total else width
            self.stream.write(f"\r[{'#' * filled}{'-' * (width - filled)}] {text}\033[K")
        else:
            self.stream.write(f"femoat suite: {text}\n")
        self.stream.flush()

    def close(self):
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()
