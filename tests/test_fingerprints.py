"""The 20 paper runs give bit-identical histories, step and Newton counts and energies to the
fingerprints stored before a refactor (``tests/data/fingerprints.json``, written by
``tests/fingerprints.py --write``).

A refactor of the solver that changes one floating-point operation's order shows up here; if
such a change is intended, regenerate the file in its own commit and say why.
"""

import pytest
from fingerprints import compute, load


@pytest.mark.parametrize("motion", ["full", "quick"])
def test_jit_runs_match_the_stored_fingerprints(motion):
    stored = load()[motion]
    current = compute(quick=motion == "quick")
    assert current.keys() == stored.keys()
    for name in stored:
        assert current[name] == stored[name], name


def test_dp5_runs_match_the_stored_fingerprints():
    # The default method's 20 full paper runs, stored before issue 16's refactor of the shared
    # machinery (limits, compile plumbing): a refactor must not change one of its operations.
    stored = load("dp5")["full"]
    current = compute(quick=False, method="dp5")
    assert current.keys() == stored.keys()
    for name in stored:
        assert current[name] == stored[name], name


def test_plan_runs_match_the_stored_fingerprints():
    # Three plan runs (square moat, every wall hit; with and without history; two laws),
    # stored from the commit before issue 24's compile work: the compiled loop's results for
    # a plan model may not change by one bit either (tests/plan_fingerprints.py).
    from plan_fingerprints import compute as compute_plan
    from plan_fingerprints import load as load_plan

    stored = load_plan()
    current = compute_plan()
    assert current.keys() == stored.keys()
    for name in stored:
        assert current[name] == stored[name], name


def test_a_72_run_suites_table_matches_its_stored_fingerprints():
    # Three records x two laws x two walls x six stripes, serial: every column of the run table
    # (timings and the code's identity left out) as stored from the commit before issue 24's
    # compile work (tests/suite_fingerprints.py): the suite machinery and the loop it runs
    # give the same table to the bit.
    from suite_fingerprints import compute as compute_suite
    from suite_fingerprints import load as load_suite_fingerprints

    stored = load_suite_fingerprints()
    current = compute_suite()
    assert stored["rows"] == 72
    for column, digest in stored.items():
        assert current.get(column) == digest, column
