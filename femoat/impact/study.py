"""One impact per contact law: the data behind the paper's Fig. 1."""

from femoat.contact.laws import LAW_CODES, PAPER_LAWS, make_law
from femoat.impact.calibration import calibrate as _calibrate
from femoat.impact.single import simulate_impact
from femoat.walls.presets import wall_preset


def impact_all_laws(wall="concrete", v0=10.0, rigid=True, calibrate=False, damping="published",
                    laws=PAPER_LAWS):
    """Simulate one impact of m_eff at ``v0`` [in/s] through each law.

    Parameters
    ----------
    wall : str
        Preset giving the contact parameters (and the SDOF wall when ``rigid`` is False).
    v0 : float
        Impact speed [in/s].
    rigid : bool
        Hit a rigid stop (the setting of Fig. 1) instead of the preset's SDOF wall.
    calibrate : bool
        Calibrate each law that can be (``law.calibratable``) to reach the preset's e exactly
        at ``v0``.
    damping : str
        The preset's C_imp choice, "published" or "consistent" (used when ``rigid`` is False).
    laws : str
        Which laws, by letter (default: the paper's five).

    Returns a dict letter -> :class:`~femoat.impact.single.ImpactResult`.
    """
    preset = wall_preset(wall, damping=damping)
    target = None if rigid else preset.wall
    results = {}
    for kind in laws:
        if kind not in LAW_CODES:
            raise ValueError(f"laws: {kind!r} is not a law letter; use letters of "
                             f"{''.join(LAW_CODES)}.")
        law = make_law(kind, preset.contact)
        if calibrate and law.calibratable:
            law = _calibrate(law, v0)
        results[kind] = simulate_impact(law, v0, wall=target)
    return results
