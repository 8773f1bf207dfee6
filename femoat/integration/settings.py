"""Integrator settings: the method of the open phase (Dormand-Prince 5(4) or Newmark/HHT-α; the
contact phase is always Newmark/HHT-α) and step control."""

import math
from dataclasses import dataclass

from femoat.integration import methods


METHODS = methods.NAMES
"""The integration methods of the open phase (see :class:`Integrator`), the registry of
:mod:`femoat.integration.methods`."""
MIN_RECORD_BUDGET = 1e6
"""The smallest ``Integrator.record_budget`` [bytes] (a few thousand samples)."""
DEFAULT_RTOL = {m.NAME: m.DEFAULT_RTOL for m in methods.MODULES}
"""Each method's default rtol: every peak within 1e-3 of a converged run
(``benchmarks/peak_accuracy.py`` measures it)."""


@dataclass(frozen=True)
class Integrator:
    """How to integrate (the *how* and *how big* of a run).

    ``Integrator()`` is the fifth-order open phase with Newmark in contact at rtol 1e-5;
    ``Integrator(method="newmark")`` the all-Newmark solver, bit for bit as before.

    Parameters
    ----------
    method : str
        "dp5" (default): while every gap is open, the building by the explicit Dormand-Prince
        5(4) pair and the walls exactly (:mod:`femoat.integration.methods.dp5`); while a contact
        is closed, Newmark/HHT-α as in "newmark". "newmark": implicit Newmark/HHT-α throughout
        (second order; the method of femoat before it had "dp5"). "ark5": "dp5" where no plan
        bearing's friction state moves (every 1D model: bit for bit), else the additive pair
        ARK5(4)8L[2]SA with each sliding plan bearing's friction state carried implicitly
        (:mod:`femoat.integration.methods.ark5`; the default of a plan run on a friction
        pendulum, :func:`femoat.run.plan_method`; "dp5" is refused on plan bearings).
        "tsit5": "dp5" with the Tsitouras 5(4) pair instead of Dormand-Prince's, on the same
        step (:mod:`femoat.integration.methods.tsit5`; why it is not the default:
        ``benchmarks/README.md``; refused on plan bearings as "dp5"). A triple pendulum with
        velocity-dependent friction takes "newmark" only in 1D (its friction a return over each
        step: :func:`femoat.bearings.registry.reads_duration`), "ark5" (its default) or
        "newmark" in plan (with μ_fast > μ on every surface; else "newmark" only). All
        locate contact events and land on element kinks the same way; "dp5", "tsit5" and
        "ark5" also land on the turning points of yielding elements (every stage of their step is
        evaluated from the committed state).
    alpha : float
        HHT-α parameter in [−1/3, 0]; 0 is Newmark's average acceleration (no numerical
        damping). β = (1−α)²/4 and γ = (1−2α)/2.
    rtol : float or None
        Accuracy knob [-]; None takes the method's default (:data:`DEFAULT_RTOL`). The local
        error of a step (Zienkiewicz-Xie estimate for Newmark, the embedded fourth-order
        solution's for "dp5") is kept below
        rtol × the DOF's scale: a story's drift against its yield drift, the base mat and the
        walls against the gap while all gaps are open and against δ_me while a contact is
        closed [in] ("dp5", "tsit5", "ark5": against half the largest indentation of the smallest
        episode under way, between 0.1·δ_me and δ_me, so that a small impact's peak force is
        held as a large one's), and the building's accelerations against 0.15 × the record's peak ground
        acceleration (at least 0.1 g) [in/s²] while all gaps are open
        (:func:`femoat.integration.solve.error_scales`). Smaller is more accurate and slower.
        Each method's default is chosen so that every peak (impact forces, displacements,
        drifts, floor accelerations) is within 1e-3 of a converged run
        (``benchmarks/peak_accuracy.py`` measures it).
    max_step : float or None
        Largest step [s]; ``None`` means the ground record's sample interval (steps never cross a
        sample anyway, so the excitation is exactly piecewise linear).
    min_step : float
        Smallest step [s]; a step that cannot converge at this size stops the run with an error.
    newton_tol : float
        Newton convergence: largest correction / DOF scale [-].
    max_newton : int
        Newton iterations per step attempt before the step is cut.
    contact_steps : float
        The first step after a gap closes is (local contact half-period)/contact_steps.
    record_every : int
        Keep every k-th step of the open phase in the output (contact steps are always kept).
    record_budget : float
        Largest memory the recorded histories may take [bytes] (default 2e9, 2 GB): a run whose
        record would grow beyond it ends with a ``RecordBudgetError`` naming the time reached,
        instead of exhausting the machine. (Growing the record briefly holds the old and the
        new buffers: up to 1.5 × this.)
    """

    method: str = "dp5"
    alpha: float = 0.0
    rtol: float | None = None
    max_step: float | None = None
    min_step: float = 1e-10
    newton_tol: float = 1e-10
    max_newton: int = 30
    contact_steps: float = 20.0
    record_every: int = 1
    record_budget: float = 2e9

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"method = {self.method!r}: choose one of {METHODS}.")
        if self.rtol is None:
            # a frozen dataclass fills its own default here (the only field resolved late)
            object.__setattr__(self, "rtol", DEFAULT_RTOL[self.method])
        if not (-1.0 / 3.0 - 1e-12 <= self.alpha <= 0.0):
            raise ValueError(f"alpha = {self.alpha!r} must be in [-1/3, 0] (HHT-α).")
        if not (math.isfinite(self.rtol) and 0 < self.rtol < 0.1):
            raise ValueError(f"rtol = {self.rtol!r} must be in (0, 0.1).")
        if self.max_step is not None and not (math.isfinite(self.max_step) and self.max_step > 0):
            raise ValueError(f"max_step = {self.max_step!r} must be a positive time [s] or None.")
        if not (math.isfinite(self.min_step) and self.min_step > 0):
            raise ValueError(f"min_step = {self.min_step!r} must be a positive time [s].")
        if not (0 < self.newton_tol < 1e-3):
            raise ValueError(f"newton_tol = {self.newton_tol!r} must be in (0, 1e-3).")
        if int(self.max_newton) < 2:
            raise ValueError(f"max_newton = {self.max_newton!r} must be at least 2.")
        if not self.contact_steps >= 2:
            raise ValueError(f"contact_steps = {self.contact_steps!r} must be >= 2.")
        if int(self.record_every) < 1:
            raise ValueError(f"record_every = {self.record_every!r} must be >= 1.")
        if not (isinstance(self.record_budget, (int, float)) and math.isfinite(self.record_budget)
                and self.record_budget >= MIN_RECORD_BUDGET):
            raise ValueError(f"record_budget = {self.record_budget!r} must be a memory of at "
                             f"least {MIN_RECORD_BUDGET:g} bytes (default 2e9, 2 GB).")

    @property
    def beta(self):
        return (1.0 - self.alpha) ** 2 / 4.0

    @property
    def gamma(self):
        return 0.5 - self.alpha

    @classmethod
    def hht(cls, alpha=-0.05, **kw):
        """HHT-α preset (numerical damping of high frequencies)."""
        return cls(alpha=alpha, **kw)
