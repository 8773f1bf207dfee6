"""Fingerprints of plan runs: the plan solver's exact output, to hold a refactor to bit-identity
(the plan twin of :mod:`fingerprints`, stored before issue 24's compile work and issue 25's
model family).

Three runs of the paper building in a square moat of four concrete walls (law H, 2 in gaps)
under FEMA P695 far-field pair 1, its first 8 s x 2.5, turned by 30° (every wall is hit):
Newmark with the whole history, the same run without history (the loop's running peaks and
impact table), and the steel moat with law E. Each fingerprint: sha256 of every history's bytes,
the step counts, the energy terms and every named peak (``float.hex``, exact).

    PYTHONPATH=. python tests/plan_fingerprints.py            # compare with the stored ones
    PYTHONPATH=. python tests/plan_fingerprints.py --write    # store them
"""

import json
import sys
from pathlib import Path

import numpy as np
from fingerprints import _sha, write_or_compare

PATH = Path(__file__).resolve().parent / "data" / "fingerprints_plan.json"
ARRAYS = ("time", "displacement", "velocity", "acceleration", "ground_acceleration",
          "element_force", "element_deformation", "bearing_force", "contact_force",
          "indentation", "indentation_rate", "contact_closed")
STATS = ("steps", "rejected_error", "rejected_newton", "newton_iterations", "events", "recorded")
CASES = ("concrete/H/history", "concrete/H/peaks", "steel/E/history")
TIMINGS = ("cpu_seconds", "compile_seconds")
"""Peaks that are timings, not results (left out)."""


def _exact(value):
    if isinstance(value, (bool, np.bool_)) or value is None:
        return value
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value).hex()
    if isinstance(value, dict):
        return {str(k): _exact(v) for k, v in sorted(value.items())}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_exact(v) for v in value]
    return str(value)


def fingerprint(result):
    """The exact fingerprint of a :class:`~femoat.results.plan.PlanRunResult`."""
    st = result.meta["stats"]
    return dict(all_histories=_sha(*(getattr(result, k) for k in ARRAYS)),
                **{k: int(st[k]) for k in STATS},
                energy=_exact(result.energy),
                peaks=_exact({k: v for k, v in result.peaks.items() if k not in TIMINGS}))


def compute():
    """{case: fingerprint} of :data:`CASES`."""
    from femoat.ground_motions.pair import RecordPair, fema_p695_pair
    from femoat.ground_motions.record import GroundMotion
    from femoat.integration.settings import Integrator
    from femoat.plan import PlanModel
    from femoat.plan.moat import rectangular_moat
    from femoat.run import run

    p = fema_p695_pair("farfield", 1)

    def first(gm):
        n = int(round(8.0 / gm.dt)) + 1
        return GroundMotion(2.5 * gm.accel_g[:n], gm.dt, name=gm.name)

    pair = RecordPair(first(p.x), first(p.y), angle=30.0)
    out = {}
    for case in CASES:
        wall, law, kind = case.split("/")
        model = PlanModel(walls=rectangular_moat(wall, law, gap=2.0))
        r = run(model, pair, Integrator(method="newmark"), history=kind == "history")
        out[case] = fingerprint(r)
    return out


def load():
    return json.loads(PATH.read_text())


def main(argv):
    return write_or_compare(PATH, compute(), argv)


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    raise SystemExit(main(sys.argv[1:]))
