"""The plan figures (femoat.plotting.plan_figures) read back from their artists, and the plain
input they draw (femoat.plotting.plan_history.PlanHistory).

The synthetic orbit used throughout: the base mat driven once around a circle of radius 5 in,
one sample per degree (θ_k = k°, k = 0..359, x = 5 cos θ, y = 5 sin θ), in a square moat with
4 in gaps; a wall's force is 100 kip/in times the base mat's overshoot past its gap, so a wall
is in contact exactly where the mat is beyond its line: the +x wall where 5 cos θ > 4, i.e.
|θ| < acos(0.8) = 36.87°.
"""

import math

import numpy as np
import pytest
from conftest import opensees_or_skip

from femoat.plotting.plan_figures import plot_plan_impact_forces, plot_plan_orbit
from femoat.plotting.plan_history import PlanHistory

RADIUS, GAP, STIFFNESS = 5.0, 4.0, 100.0  # [in], [in], [kip/in]


def circle_history(gaps=(GAP, GAP, GAP, GAP)):
    theta = np.radians(np.arange(360.0))
    base = RADIUS * np.column_stack([np.cos(theta), np.sin(theta)])
    over = np.column_stack([base[:, 0] - gaps[0], -base[:, 0] - gaps[1],
                            base[:, 1] - gaps[2], -base[:, 1] - gaps[3]])
    return PlanHistory(time=np.arange(360) * 0.01, base=base,
                       wall_force=STIFFNESS * np.maximum(over, 0.0), gaps=gaps, title="circle")


def lines_by_gid(fig):
    return {line.get_gid(): line for ax in fig.axes for line in ax.lines if line.get_gid()}


def test_the_outline_is_the_rectangle_at_the_gaps(tmp_path):
    # Gaps +x 3, −x 5, +y 2, −y 6 [in]: the +x wall is the line x = 3 from y = −6 to y = 2, the
    # −x wall x = −5 over the same span, the +y wall y = 2 from x = −5 to x = 3, the −y wall
    # y = −6 likewise; the four corners are (3, 2), (−5, 2), (−5, −6), (3, −6).
    h = circle_history(gaps=(3.0, 5.0, 2.0, 6.0))
    fig = plot_plan_orbit(h, tmp_path / "orbit.png")
    assert (tmp_path / "orbit.png").stat().st_size > 10_000
    lines = lines_by_gid(fig)
    expected = {"+x": [(3, -6), (3, 2)], "-x": [(-5, -6), (-5, 2)],
                "+y": [(-5, 2), (3, 2)], "-y": [(-5, -6), (3, -6)]}
    for side, ends in expected.items():
        np.testing.assert_array_equal(lines[f"wall {side}"].get_xydata(), ends)
    ax = fig.axes[0]
    assert ax.get_aspect() == 1.0  # equal axes: a circle stays a circle
    assert "[in]" in ax.get_xlabel() and "[in]" in ax.get_ylabel()
    # The orbit is the base mat's (x, y), every sample.
    np.testing.assert_array_equal(lines["orbit"].get_xydata(), h.base)


def test_a_circular_orbit_hits_the_four_walls_at_the_expected_angles(tmp_path):
    fig = plot_plan_orbit(circle_history(), tmp_path / "orbit.png")
    lines = lines_by_gid(fig)
    half = math.degrees(math.acos(GAP / RADIUS))  # 36.87°: 5 cos θ > 4 for |θ| < 36.87°
    # One sample per degree: cos 36° = 0.809 > 0.8 > cos 37° = 0.799, so each wall is in
    # contact at the 73 whole degrees within ±36° of its normal, and at no corner (|x| > 4 and
    # |y| > 4 would need r² > 32 > 25).
    for side, normal in (("+x", 0.0), ("-x", 180.0), ("+y", 90.0), ("-y", 270.0)):
        xy = lines[f"impacts {side}"].get_xydata()
        assert len(xy) == 73
        angle = np.degrees(np.arctan2(xy[:, 1], xy[:, 0]))
        off = (angle - normal + 180.0) % 360.0 - 180.0  # signed angle from the wall's normal
        assert np.abs(off).max() == pytest.approx(36.0) and np.abs(off).max() < half
        assert off.mean() == pytest.approx(0.0, abs=1e-9)  # centred on the normal
        np.testing.assert_allclose(np.hypot(*xy.T), RADIUS)  # at the mat's positions
    # The largest plan displacement is the radius.
    assert np.hypot(*lines["peak"].get_xydata()[0]) == pytest.approx(RADIUS)


def test_markers_count_the_samples_in_contact_including_corners(tmp_path):
    # A square orbit's corner (6, 6) is beyond the +x and the +y lines at once: a corner impact,
    # a marker for each wall. Samples: (0, 0), (6, 0), (6, 6), (0, 6), (−6, 6), (0, 0); forces
    # are given directly (not derived from the orbit): the figure marks where force > 0.
    base = [(0, 0), (6, 0), (6, 6), (0, 6), (-6, 6), (0, 0)]
    force = np.array([[0, 0, 0, 0], [9, 0, 0, 0], [7, 0, 8, 0], [0, 0, 9, 0],
                      [0, 3, 4, 0], [0, 0, 0, 0.0]])
    h = PlanHistory(np.arange(6.0), base, force, (4, 4, 4, 4))
    lines = lines_by_gid(plot_plan_orbit(h, tmp_path / "orbit.png"))
    np.testing.assert_array_equal(lines["impacts +x"].get_xydata(), [(6, 0), (6, 6)])
    np.testing.assert_array_equal(lines["impacts -x"].get_xydata(), [(-6, 6)])
    np.testing.assert_array_equal(lines["impacts +y"].get_xydata(), [(6, 6), (0, 6), (-6, 6)])
    assert len(lines["impacts -y"].get_xydata()) == 0
    # Closures: +x one (samples 1-2), −x one, +y one (samples 2-4), −y none.
    np.testing.assert_array_equal(h.impacts(), [1, 1, 1, 0])


def test_impact_force_panels_per_wall(tmp_path):
    h = circle_history()
    fig = plot_plan_impact_forces(h, tmp_path / "forces.png")
    assert (tmp_path / "forces.png").stat().st_size > 10_000
    assert len(fig.axes) == 4
    lines = lines_by_gid(fig)
    for c, side in enumerate(h.sides):
        np.testing.assert_array_equal(lines[f"force {side}"].get_xydata(),
                                      np.column_stack([h.time, h.wall_force[:, c]]))
    # Peak force: 100 kip/in × (5 − 4) in = 100 kip on every wall (each touches the circle's
    # extreme at its normal). Closures: the orbit starts at θ = 0 in contact with +x, leaves it
    # at 37° and closes on it again at 324°: 2 impacts; the other walls 1 each.
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0].startswith("+x wall") and "2 impacts, peak 100.0 kip" in titles[0]
    for title in titles[1:]:
        assert "1 impact, peak 100.0 kip" in title
    assert all(ax.get_ylabel() == "impact force [kip]" for ax in fig.axes)
    assert fig.axes[-1].get_xlabel() == "time [s]"


def test_a_moat_with_missing_walls_closes_the_outline_around_the_orbit(tmp_path):
    # Walls only at ±x (gaps 4 in): the ±x lines span y over the orbit's reach, ±5 in.
    h = circle_history()
    two = PlanHistory(h.time, h.base, h.wall_force[:, :2], (4.0, 4.0), sides=("+x", "-x"))
    lines = lines_by_gid(plot_plan_orbit(two, tmp_path / "orbit.png"))
    np.testing.assert_allclose(lines["wall +x"].get_xydata(), [(4, -5), (4, 5)], atol=1e-12)
    assert "wall +y" not in lines
    assert two.gap("+y") is None and two.gap("-x") == 4.0


@pytest.mark.parametrize("change, message", [
    (dict(base=np.zeros((360, 3))),
     r"PlanHistory.base has shape \(360, 3\); it must be \(360, 2\)"),
    (dict(wall_force=np.full((360, 4), np.nan)),
     r"PlanHistory.wall_force\[0, 0\] = nan is not finite"),
    (dict(gaps=(4, -1, 4, 4)), r"wall -x has gap = -1.0; a gap is a clearance >= 0 \[in\]"),
    (dict(gaps=(4, 4, 4)), r"PlanHistory.gaps has shape \(3,\); it must be \(4,\)"),
    (dict(time=np.zeros(360)), "at least two increasing times"),
    (dict(sides=("-x", "+x", "+y", "-y")), "in the order '\\+x', '-x', '\\+y', '-y'"),
    (dict(sides=("+x", "-x", "+y", "up")), "side = 'up' is not a moat wall"),
    (dict(base="orbit"), "PlanHistory.base must be an array of numbers"),
])
def test_bad_input_names_the_field(change, message):
    h = circle_history()
    fields = dict(time=h.time, base=h.base, wall_force=h.wall_force, gaps=h.gaps, sides=h.sides)
    with pytest.raises(ValueError, match=message):
        PlanHistory(**{**fields, **change})


def test_arrays_are_read_only_and_the_plots_refuse_other_input(tmp_path):
    h = circle_history()
    with pytest.raises(ValueError, match="read-only"):
        h.base[0, 0] = 1.0
    with pytest.raises(ValueError, match="history must be a PlanHistory"):
        plot_plan_orbit({"base": h.base}, tmp_path / "x.png")


@pytest.mark.opensees
def test_figures_of_an_opensees_twin_run(tmp_path):
    opensees_or_skip()
    from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
    from femoat.opensees.plan import opensees_plan_run
    from femoat.plan import PlanModel, rectangular_moat

    # The real path: the first 3 s of FEMA P695 far-field record 1 (Northridge, Beverly Hills)
    # as a pair scaled by 2, the paper's building in a square moat of steel walls (Jankowski
    # law) at 0.2 in, small enough for the opening seconds to reach a wall.
    pair = fema_p695_pair("farfield", 1)
    n = round(3.0 / pair.dt) + 1
    pair = RecordPair(GroundMotion(pair.x.accel_g[:n], pair.dt),
                      GroundMotion(pair.y.accel_g[:n], pair.dt), scale=2.0)
    model = PlanModel(walls=rectangular_moat("steel", "J", gap=0.2))
    run = opensees_plan_run(model, pair, 1e-3, duration=3.0)
    h = PlanHistory.from_opensees(run, model, title="FEMA P695 FF1 x2, first 3 s")
    assert run["peaks"]["impacts"].sum() >= 1  # the figure has impacts to show
    # PlanHistory's closures and peaks are the twin's own (counted there independently).
    np.testing.assert_array_equal(h.impacts(), run["peaks"]["impacts"])
    assert h.peak_plan_displacement() == run["peaks"]["plan_base_displacement"]
    orbit = lines_by_gid(plot_plan_orbit(h, tmp_path / "orbit.png"))
    for c, side in enumerate(run["walls"]):
        hit = run["contact_force"][:, c] > 0
        np.testing.assert_array_equal(orbit[f"impacts {side}"].get_xydata(),
                                      run["base_displacement"][hit])
        np.testing.assert_array_equal(orbit[f"wall {side}"].get_xydata()[0] @ model.walls[c].normal,
                                      0.2)  # the wall's line at its gap along its normal
    fig = plot_plan_impact_forces(h, tmp_path / "forces.png")
    for ax, side, peak in zip(fig.axes, run["walls"], run["peaks"]["impact_force"]):
        assert f"peak {peak:.1f} kip" in ax.get_title()
    with pytest.raises(ValueError, match="not the model's"):
        PlanHistory.from_opensees(run, PlanModel(walls=rectangular_moat(sides=("+x", "-x"))))
