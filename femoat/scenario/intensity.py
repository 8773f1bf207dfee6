"""``[motion] sa`` and ``period``: a scenario's record scaled to a target Sa(T), the way a
suite's ``[scaling] im = "sa"`` scales its records (the same code,
:mod:`femoat.ground_motions.intensity`).

``sa`` [g] is the target 5 %-damped pseudo-spectral acceleration at ``period`` [s], the
prototype's period T: as in a suite, Sa is the record's **as applied in time** at
T·time_scale, which with time similitude is the record's as read at T. One record (1D): its
component's Sa(T). A pair (plan): the **geometric mean** of its two components' Sa(T), as
recorded before the pair is turned (angle), so that the factor does not depend on the angle and
a pair scaled once is applied at any orientation (FEMA P695 practice, docs/plan.md §2). The one
factor, target / Sa(T) of the record, multiplies the record (a pair: both components); it
replaces every other amplitude key (``pga``; a pair's ``scale`` and ``normalized``) and is
echoed by ``femoat run`` (:meth:`SaScaling.describe`).
"""

from typing import NamedTuple

from femoat.scenario.reading import number

KEYS = ("sa", "period")


class SaScaling(NamedTuple):
    """How a scenario's record was scaled to ``[motion] sa``."""

    target: float  # the Sa(T) asked for, sa [g]
    period: float  # T [s], the prototype's period
    record: float  # the record's own Sa(T) [g] (a pair: the geometric mean of its components')
    factor: float  # amplitude factor on the record, target / record [-]
    time_scale: float  # [-]: Sa is the applied record's at T·time_scale
    components: int  # 1 (a record) or 2 (a pair)

    def describe(self):
        """One sentence for the terminal and README.txt: the target, the record's own Sa(T) and
        the factor."""
        own = (f"the pair's own {self.record:.4g} g (the geometric mean of its two components', "
               "as recorded)" if self.components == 2 else f"the record's own {self.record:.4g} g")
        when = ("" if self.time_scale == 1.0 else
                f", the applied record's at T*time_scale = {self.period * self.time_scale:g} s")
        return (f"scaled to Sa({self.period:g} s) = {self.target:g} g ([motion] sa, 5 % "
                f"damped{when}): {own}, factor {self.factor:.6g} [-]"
                + (" on both components" if self.components == 2 else ""))


def sa_scaling(d, applied, time_scale, where, replaces):
    """The :class:`SaScaling` of a ``[motion]`` table (None without ``sa``).

    d : dict  the table
    applied : tuple of GroundMotion  the record's components as applied in time (time-scaled),
        unscaled in amplitude: one (a record) or two (a pair, before its turn)
    time_scale : float  [-] the table's time_scale (Sa is read at period·time_scale)
    where : str  the table's name in messages
    replaces : tuple of str  the table's other amplitude keys, refused beside ``sa``
    """
    from femoat.ground_motions.intensity import geometric_mean, spectral_acceleration

    if "sa" not in d:
        if "period" in d:
            raise ValueError(f"{where} period = {d['period']!r}: the period of sa, the target "
                             "Sa(T) [g]; add sa = ... (e.g. sa = 0.5) or remove period.")
        return None
    given = [key for key in replaces if key in d]
    if given:
        raise ValueError(f"{where} sa and {', '.join(given)}: sa sets the record's amplitude "
                         "alone (the factor that brings its Sa(T) to sa); give sa with period, "
                         f"or {' / '.join(replaces)}, not both.")
    if "period" not in d:
        raise ValueError(f"{where} sa = {d['sa']!r} needs period = T [s], the period of the "
                         "target Sa(T), e.g. period = 2.0.")
    target = _positive(d, "sa", where, "g", "the target Sa(T), e.g. sa = 0.5")
    period = _positive(d, "period", where, "s", "the prototype's period T, e.g. period = 2.0")
    own = geometric_mean([spectral_acceleration(c, period * time_scale) for c in applied])
    if own == 0.0:
        raise ValueError(f"{where} sa = {target:g}: the record's Sa({period:g} s) is 0 g, so it "
                         "cannot be scaled to it; use another record or period.")
    return SaScaling(target, period, own, target / own, time_scale, len(applied))


def _positive(d, key, where, unit, what):
    value = number(d, key, None, where, unit)
    if value <= 0.0:
        raise ValueError(f"{where} {key} = {d[key]!r}: expected a positive number [{unit}], "
                         f"{what}.")
    return value
