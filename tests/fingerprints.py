"""Fingerprints of the 20 paper runs: the solver's exact output, to hold a refactor to bit-identity.

For each wall (concrete, steel), contact law (E, V, J, H, M) and impact damping (published,
consistent) under :func:`femoat.paper.paper_motion`, a sha256 of every recorded history's bytes
(time, displacement, contact force, and all the other channels together), the step, rejection and
Newton counts and the energy terms (as ``float.hex``, exact). Two sets: the full motion (as in
the paper) and the quick one (its first 4 s).

    PYTHONPATH=. python tests/fingerprints.py            # print the current fingerprints' diff
    PYTHONPATH=. python tests/fingerprints.py --write    # store them (both files)
    PYTHONPATH=. python tests/fingerprints.py --write dp5   # store only the dp5 file

Store them only from a commit whose results are the reference (the one before a refactor).

``data/fingerprints.json`` holds the Newmark runs (issue 15's contract: unchanged since before
the higher-order method); ``data/fingerprints_dp5.json`` the default method's full-motion runs,
so that a refactor of the shared machinery (issue 16) is held to bit-identity for dp5 too.
"""

import hashlib
import json
import sys
from pathlib import Path

import numpy as np

PATH = Path(__file__).resolve().parent / "data" / "fingerprints.json"
PATH_DP5 = PATH.with_name("fingerprints_dp5.json")
ARRAYS = ("time", "displacement", "velocity", "acceleration", "ground_acceleration",
          "element_force", "element_deformation", "contact_force", "indentation",
          "indentation_rate", "contact_closed")
STATS = ("steps", "rejected_error", "rejected_newton", "newton_iterations", "events", "recorded")


def _sha(*arrays):
    h = hashlib.sha256()
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def fingerprint(result):
    """The exact fingerprint of a :class:`~femoat.results.RunResult`."""
    st = result.meta["stats"]
    return dict(
        time=_sha(result.time), displacement=_sha(result.displacement),
        contact_force=_sha(result.contact_force),
        all_histories=_sha(*(getattr(result, k) for k in ARRAYS)),
        **{k: int(st[k]) for k in STATS},
        energy={k: float(v).hex() for k, v in sorted(result.energy.items())},
    )


def keys():
    from femoat.paper import LAWS, WALLS

    return [(w, law, d) for d in ("published", "consistent") for w in WALLS for law in LAWS]


def compute(quick, only=None, method="newmark"):
    """{"wall/law/damping": fingerprint} of the paper runs (all 20, or the keys in ``only``)."""
    from femoat.integration.settings import Integrator
    from femoat.paper import paper_model, paper_motion
    from femoat.run import run

    motion = paper_motion(quick=quick)
    out = {}
    for wall, law, damping in keys():
        name = f"{wall}/{law}/{damping}"
        if only is not None and name not in only:
            continue
        r = run(paper_model(wall, law, damping), motion, Integrator(method=method),
                extra_time=1.0 if quick else 2.0)
        out[name] = fingerprint(r)
    return out


def write_or_compare(path, current, argv):
    """``--write`` in argv: store ``current`` ({key: fingerprint}) at ``path``; else print the
    keys whose stored fingerprint differs. Exit status 0 when stored or all equal."""
    if "--write" in argv:
        path.write_text(json.dumps(current, indent=1, sort_keys=True) + "\n")
        print(f"wrote {path}")
        return 0
    stored = json.loads(path.read_text())
    bad = [k for k in stored if current.get(k) != stored[k]]
    print("bit-identical" if not bad else f"these differ: {bad}")
    return 0 if not bad else 1


def load(method="newmark"):
    return json.loads((PATH if method == "newmark" else PATH_DP5).read_text())


def main(argv):
    ok = True
    named = [m for m in ("newmark", "dp5") if m in argv]
    for method, path in (("newmark", PATH), ("dp5", PATH_DP5)):
        if named and method not in named:
            continue
        current = {"full": compute(False, method=method)}
        if method == "newmark":
            current["quick"] = compute(True, method=method)
        if "--write" in argv:
            path.write_text(json.dumps(current, indent=1, sort_keys=True) + "\n")
            print(f"wrote {path}")
            continue
        print(method, end=": ")
        ok &= _compare(current, load(method))
    return 0 if ok else 1


def _compare(current, stored):
    bad = [(s, k) for s in current for k in current[s] if current[s][k] != stored[s].get(k)]
    for s, k in bad:
        print(f"{s} {k}: differs", {f: (stored[s][k][f], current[s][k][f])
                                    for f in current[s][k] if stored[s][k][f] != current[s][k][f]})
    print("bit-identical" if not bad else f"{len(bad)} runs differ")
    return not bad


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    raise SystemExit(main(sys.argv[1:]))
