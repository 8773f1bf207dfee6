"""The drift panel of the global-response figure: whole-number story ticks, drift in inches, and
the drift ratio on a second axis once the peaks carry ``peak_drift_ratio``."""

import numpy as np
import pytest

from femoat.plotting.paper_figures import drift_panel
from femoat.plotting.style import pyplot

DRIFT = [0.30, 0.22, 0.11]  # [in], stories 1-3


@pytest.fixture
def ax():
    plt = pyplot()
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def _story_ticks(ax):
    ax.figure.canvas.draw()
    return list(ax.get_yticks())


def test_stories_are_whole_numbers_and_drift_is_in_inches(ax):
    # before: matplotlib's automatic ticks showed 1.25, 1.5, ... between the 3 stories
    assert drift_panel(ax, {"H": {"peak_drift": DRIFT}, "E": {"peak_drift": DRIFT}}) is None
    assert _story_ticks(ax) == [1, 2, 3]
    assert ax.get_xlabel() == "drift [in]"


def test_equal_story_heights_give_a_ratio_scale(ax):
    # every story 36 in high: ratio = drift / 36, so 0.36 in reads as 1 % on the top axis
    peaks = {"H": {"peak_drift": DRIFT, "peak_drift_ratio": [d / 36.0 for d in DRIFT]}}
    top = drift_panel(ax, peaks)
    assert top is not None and "ratio" in top.get_xlabel()
    ax.set_xlim(0.0, 0.72)
    assert _story_ticks(ax) == [1, 2, 3]  # (draws the figure, which sets the top axis' limits)
    np.testing.assert_allclose(top.get_xlim(), (0.0, 2.0), atol=1e-12)


def test_unequal_story_heights_draw_ratio_curves(ax):
    heights = [48.0, 36.0, 36.0]  # [in]: no single scale maps drift to ratio
    ratio = [d / h for d, h in zip(DRIFT, heights)]
    top = drift_panel(ax, {"J": {"peak_drift": DRIFT, "peak_drift_ratio": ratio}})
    (line,) = top.get_lines()
    np.testing.assert_allclose(line.get_xdata(), 100.0 * np.array(ratio))
    np.testing.assert_array_equal(line.get_ydata(), [1, 2, 3])
    assert _story_ticks(ax) == [1, 2, 3]


def test_the_ratio_axis_names_the_story_height_and_says_when_it_is_assumed(ax):
    # 39 in is femoat's default story height (13 ft at quarter scale), an assumption
    peaks = {"H": {"peak_drift": DRIFT, "peak_drift_ratio": [d / 39.0 for d in DRIFT]}}
    assert drift_panel(ax, peaks).get_xlabel() == (
        "drift ratio [%] = drift / 39 in (the default story height, an assumption)")


def test_a_logarithmic_acceleration_axis_has_one_set_of_labels(ax):
    from femoat.plotting.paper_figures import _plain_log_ticks

    # 0.35-0.9 g: on less than a decade matplotlib labels the minor ticks (2x10^-1, 3x10^-1,
    # ..., 6x10^-1) beside the majors' 10^-1, 10^0: two sets of labels. Here: plain numbers on
    # the major ticks only, one each
    ax.set_xscale("log")
    ax.plot([0.35, 0.9], [0, 3])
    ax.set_xlim(0.35, 0.9)
    _plain_log_ticks(ax.xaxis)
    ax.figure.canvas.draw()
    major = [t.get_text() for t in ax.xaxis.get_ticklabels() if t.get_text()]
    minor = [t.get_text() for t in ax.xaxis.get_ticklabels(minor=True) if t.get_text()]
    assert minor == [] and "0.5" in major and len(set(major)) == len(major)
    assert not any("times" in t or "^" in t for t in major)
