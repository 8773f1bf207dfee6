"""Hunt-and-fill (Vamvatsikos & Cornell 2002) as a pure function of a collapse oracle."""

import pytest

from femoat.suite.huntfill import collapse_bracket, hunt_fill


@pytest.mark.parametrize("x", [0.03, 0.5, 1.234, 2.9999])
def test_brackets_a_monotone_oracle_within_the_resolution(x):
    runs = hunt_fill(lambda im: im > x, step0=0.1, step_increment=0.05, resolution=0.01,
                     max_runs=40)
    low, high = collapse_bracket(runs)
    # a monotone oracle "collapse iff im > x": the bracket holds x and is at most 0.01 wide
    assert low <= x < high
    assert high - low <= 0.01
    assert len(runs) <= 40
    assert all(c == (im > x) for im, c, _ in runs)


def test_hunt_steps_grow_by_the_increment():
    runs = hunt_fill(lambda im: im > 1.2, step0=0.1, step_increment=0.05, resolution=0.01,
                     max_runs=40)
    # im_1 = 0.1, then steps 0.15, 0.20, 0.25, 0.30: 0.25, 0.45, 0.70, 1.00; then 1.35 collapses
    assert [round(im, 12) for im, _, _ in runs[:6]] == [0.1, 0.25, 0.45, 0.7, 1.0, 1.35]
    # bracket [1.00, 1.35]: the first bisection is at 1.175 (survives), the next at 1.2625
    assert runs[6][0] == pytest.approx(1.175) and runs[7][0] == pytest.approx(1.2625)


def test_fill_halves_gaps_and_runs_are_capped():
    runs = hunt_fill(lambda im: im > 1.2, step0=0.1, step_increment=0.05, resolution=0.01,
                     max_runs=20)
    assert len(runs) == 20
    # after the hunt (6 runs) and bracket (6 bisections: 0.35/2^6 = 0.0055 <= 0.01) come fills:
    # the largest non-collapse gap is then 0.30 (0.70 -> 1.00), halved at 0.85
    assert runs[12][0] == pytest.approx(0.85)


def test_never_collapsing_trace_ends_after_max_runs():
    runs = hunt_fill(lambda im: False, step0=0.1, step_increment=0.0, resolution=0.01, max_runs=5)
    assert [round(im, 12) for im, _, _ in runs] == [0.1, 0.2, 0.3, 0.4, 0.5]
    assert collapse_bracket(runs) == (pytest.approx(0.5), None)


def test_bad_parameters_name_themselves():
    with pytest.raises(ValueError, match="step0"):
        hunt_fill(lambda im: True, step0=-1, step_increment=0, resolution=0.1, max_runs=3)


def test_a_collapse_found_by_the_fill_is_bracketed_again():
    # a non-monotone IDA curve: collapse on [0.425, 0.45) and from 0.456 on ("resurrection" in
    # between). Hunt (step0 = increment = 0.05): 0.05, 0.15, 0.30, 0.50 (collapse); the bracket
    # then closes on 0.456; fill runs halve the gaps below 0.45 and one of them lands in
    # [0.425, 0.45); the lowest collapse moves down and must be bracketed to the resolution
    def collapsed(im):
        return 0.425 <= im < 0.45 or im >= 0.456

    runs = hunt_fill(collapsed, 0.05, 0.05, 0.01, 40)
    low, high = collapse_bracket(runs)
    assert 0.425 <= high <= 0.435 and high - low <= 0.01 and low < 0.425


# ---- the onsets of pounding (step 3) ----------------------------------------------------------
from femoat.suite.huntfill import ANY, Outcome, onset_bracket  # noqa: E402


def _oracle(collapse, onsets):
    """A monotone record: it collapses at and above ``collapse`` and pounds on wall w at and
    above ``onsets[w]`` [g]."""
    def run(im):
        return Outcome(im >= collapse, frozenset(w for w, x in onsets.items() if im >= x))
    return run


@pytest.mark.parametrize("onsets", [{"pos": 0.437, "neg": 0.913},
                                    {"px": 0.437, "mx": 0.913, "py": 1.05, "my": 0.2}])
def test_each_walls_onset_is_bracketed_to_the_resolution(onsets):
    walls = tuple(onsets)
    runs = hunt_fill(_oracle(1.2, onsets), 0.1, 0.05, 0.01, 60, walls)
    # hunt 0.1, 0.25, 0.45, 0.70, 1.00, 1.35 (collapse); the first runs that pound on a wall
    # bracket its onset, e.g. pos (0.25, 0.45]: bisected until at most 0.01 wide, it still
    # holds the true onset x (clear < x <= onset: a monotone record pounds iff im >= x)
    for w, x in [*onsets.items(), (ANY, min(onsets.values()))]:
        clear, onset = onset_bracket(runs, w)
        assert clear < x <= onset and onset - clear <= 0.01
    low, high = collapse_bracket(runs)
    assert low < 1.2 <= high and high - low <= 0.01
    # the collapse comes first: hunt (6) and bracket (0.35 / 2^6 <= 0.01: 6) as without onsets
    plain = hunt_fill(_oracle(1.2, onsets), 0.1, 0.05, 0.01, 60)
    assert runs[:12] == plain[:12]
    # then onset runs, 10 in the 1D case (pos 0.437 in (0.25, 0.45]: 0.20 / 2^5 <= 0.01, 5
    # bisections, any wall's the same bracket; neg in (0.70, 1.00]: 0.30 / 2^5, 5 more), then
    # the fill (every gap below the collapse down to 0.01 would take more than the 60 runs)
    if walls == ("pos", "neg"):
        assert all(0.25 < r.im < 0.45 or 0.70 < r.im < 1.00 for r in runs[12:22])
        for w in (ANY, *walls):
            clear, onset = onset_bracket(runs[:22], w)
            assert onset - clear <= 0.01


def test_a_wall_hit_only_after_the_collapse_gets_no_onset_runs():
    # collapse at 0.8 g, neg only at 0.913 g: the collapse run (0.8 <= 1.00) did not pound neg,
    # so neg has no onset (collapsed first) and no run of its own: the trace bracketing pos
    # and neg is the trace bracketing pos alone
    onsets = {"pos": 0.437, "neg": 0.913}
    both = hunt_fill(_oracle(0.8, onsets), 0.1, 0.05, 0.01, 60, ("pos", "neg"))
    pos_only = hunt_fill(_oracle(0.8, onsets), 0.1, 0.05, 0.01, 60, ("pos",))
    assert onset_bracket(both, "neg") is None
    assert both == pos_only
    # and a record that never pounds runs as the collapse-only trace
    never = hunt_fill(_oracle(0.8, {}), 0.1, 0.05, 0.01, 60, ("pos", "neg"))
    assert never == hunt_fill(_oracle(0.8, {}), 0.1, 0.05, 0.01, 60)


@pytest.mark.parametrize("max_runs", [8, 12, 14])
def test_the_budget_caps_the_onset_runs_and_the_brackets_stay_true(max_runs):
    onsets = {"pos": 0.437, "neg": 0.913}
    runs = hunt_fill(_oracle(1.2, onsets), 0.1, 0.05, 0.01, max_runs, ("pos", "neg"))
    # hunt 6 + collapse bracket 6 = 12 runs: 8 leaves the collapse bracket wider than the
    # resolution and no onset run; 14 gives the onsets two runs, to the widest bracket first:
    # neg's (0.70, 1.00] (0.30 wide) then pos's (0.25, 0.45] (0.20 wide)
    assert len(runs) == max_runs
    for w, x in onsets.items():
        clear, onset = onset_bracket(runs, w)
        assert clear < x <= onset  # wider than the resolution, still true
    if max_runs == 14:
        assert [r.im for r in runs[12:]] == pytest.approx([0.85, 0.35])


def test_an_onset_found_below_by_the_fill_is_bracketed_again():
    # pos pounds on [0.30, 0.32) and from 0.60 on (a gap that stops pounding in between): the
    # hunt brackets 0.60; the fill, halving the gaps below 1.2 to 0.01, lands in [0.30, 0.32)
    # (0.02 wide) and the onset moves down to 0.30, bisected again to the resolution
    def run(im):
        return Outcome(im >= 1.2, frozenset({"pos"}) if 0.3 <= im < 0.32 or im >= 0.6 else
                       frozenset())

    runs = hunt_fill(run, 0.1, 0.05, 0.01, 200, ("pos",))
    clear, onset = onset_bracket(runs, "pos")
    assert clear < 0.3 <= onset and onset - clear <= 0.01
