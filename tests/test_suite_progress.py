"""Progress on stderr: plain lines when the stream is not a terminal."""

import io

from femoat.suite.progress import Progress


def test_plain_lines_count_runs_collapses_and_failures():
    out = io.StringIO()  # not a TTY: one plain line per update once `every` seconds passed
    p = Progress(4, "runs", stream=out, every=0.0)
    p.update([{"status": "ok"}, {"status": "collapsed"}])
    p.update([{"status": "solver_failure"}, {"status": "error"}])
    lines = out.getvalue().splitlines()
    assert len(lines) == 2 and "\r" not in out.getvalue()
    assert lines[0].startswith("femoat suite: 2/4 runs")
    # 4 runs: 1 collapse; a solver failure and an error are both failures
    assert "4/4 runs" in lines[1] and "collapses 1" in lines[1] and "failures 2" in lines[1]


def test_traces_show_their_runs():
    out = io.StringIO()
    p = Progress(3, "traces", stream=out, every=0.0)
    p.update([{"status": "ok"}] * 5, units=1)
    assert "1/3 traces (5 runs)" in out.getvalue()
