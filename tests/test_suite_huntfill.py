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
    assert all(c == (im > x) for im, c in runs)


def test_hunt_steps_grow_by_the_increment():
    runs = hunt_fill(lambda im: im > 1.2, step0=0.1, step_increment=0.05, resolution=0.01,
                     max_runs=40)
    # im_1 = 0.1, then steps 0.15, 0.20, 0.25, 0.30: 0.25, 0.45, 0.70, 1.00; then 1.35 collapses
    assert [round(im, 12) for im, _ in runs[:6]] == [0.1, 0.25, 0.45, 0.7, 1.0, 1.35]
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
    assert [round(im, 12) for im, _ in runs] == [0.1, 0.2, 0.3, 0.4, 0.5]
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
