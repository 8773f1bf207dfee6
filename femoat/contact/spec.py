"""What femoat knows about one kind of contact law, declared by the law's own module.

A law module (``linear.py``, ``kelvin_voigt.py``, ...) holds its compiled kernels, a frozen
dataclass of its kernel parameters (validated, units in brackets) and one :class:`LawSpec`
named ``LAW``: its letter and long name, the kernels it runs on, its damping parameter and the
paper's closed form from e, how it is calibrated and how it is drawn. :mod:`femoat.contact.laws`
builds every registry from these records; nothing else in femoat asks which letter a law has.
"""

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from femoat.compilation.jit import Kernel


@dataclass(frozen=True)
class KernelFamily:
    """Compiled kernels, shared by every law that packs its parameters the same way.

    Parameters
    ----------
    name : str
        The family's name in the generated dispatcher (:mod:`femoat.contact._dispatch`).
    force : Kernel
        ``(p, h, d, v) -> (f [kip], df/dδ [kip/in], df/dδ̇ [kip·s/in])`` at indentation d > 0
        [in] and rate v [in/s], from the committed history ``h`` (never modified).
    energy : Kernel
        ``(p, h, d) ->`` elastic energy [kip·in] the contact returns if unloaded from d > 0 [in].
    n_params : int
        Length of the params array ``p``.
    commit : Kernel or None
        ``(h, d)``: advance the history after a converged step ending at ``d`` [in]; None for a
        law without history.
    hertz_spring : bool
        The force holds the Hertz spring k_h·δ^1.5, k_h at ``p[femoat.contact.hertz.K_H]``: the
        time-stepping loop replaces it by its discrete gradient (:mod:`femoat.contact.hertz`).
    acts_at_zero : bool
        The force need not vanish as δ → 0⁺ (a dashpot c·δ̇): an episode still open at δ ≤ 0
        acts as at δ = 0⁺.
    """

    name: str
    force: Kernel
    energy: Kernel
    n_params: int
    commit: Kernel | None = None
    hertz_spring: bool = False
    acts_at_zero: bool = False

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise ValueError(f"name = {self.name!r}: a kernel family's name must be a Python "
                             "identifier (the generated dispatcher names it).")
        for role in ("force", "energy", "commit"):
            kernel = getattr(self, role)
            if not (isinstance(kernel, Kernel) or (role == "commit" and kernel is None)):
                raise ValueError(f"{role} = {kernel!r}: must be a kernel decorated with "
                                 "femoat.compilation.jit.njit" + (" or None." if role == "commit" else "."))
        if not (isinstance(self.n_params, int) and self.n_params >= 1):
            raise ValueError(f"n_params = {self.n_params!r}: must be an integer >= 1.")


@dataclass(frozen=True)
class Bracket:
    """Calibration by a root search of the damping parameter over [lo, hi] [-] (the achieved
    restitution must cross the target inside it)."""

    lo: float
    hi: float

    def __post_init__(self):
        if not (math.isfinite(self.lo) and math.isfinite(self.hi) and self.lo < self.hi):
            raise ValueError(f"Bracket({self.lo!r}, {self.hi!r}): need finite lo < hi.")

    def __call__(self, law, search):
        return search.solve(law, self.lo, self.hi)


@dataclass(frozen=True)
class LawSpec:
    """One kind of contact law: what femoat reads about it besides its kernels.

    Parameters
    ----------
    letter : str
        One capital letter, the law's key everywhere (scenario files, the CLI, results).
    name : str
        Long name, e.g. "Kelvin-Voigt" (:func:`femoat.contact.make_law` accepts it too).
    kernels : KernelFamily
        The compiled kernels the law runs on.
    parameters : type
        Frozen dataclass of the kernel parameters, validated on construction, with
        ``from_law(law)`` (from a :class:`~femoat.contact.ContactLaw`), ``params()`` (the
        family's float array ``p``), ``separation_indicator(d, v, v0)`` (its zero crossing ends a
        contact before δ = 0; constant 1.0 if it never does) and, for a law with an OpenSees twin,
        ``opensees_material(gap)``.
    style : dict
        matplotlib colour and line style of the law's curves.
    damping : str or None
        Name of the damping parameter (e.g. "xi_KV"); None for an undamped law.
    damping_from_e : callable or None
        The paper's closed form, restitution e [-] → damping parameter [-].
    calibration : callable or None
        ``(law, search) -> law`` reaching a target restitution exactly (see
        :mod:`femoat.impact.calibration`; a :class:`Bracket` for a plain root search). None:
        the law cannot be calibrated.
    options : tuple of str
        The :class:`~femoat.contact.ContactLaw` options the law reads beyond its parameters
        and damping (``"allow_tension"``).
    paper : bool
        One of the paper's five laws: the paper study and Fig. 1 run it.
    """

    letter: str
    name: str
    kernels: KernelFamily
    parameters: type
    style: dict = field(default_factory=dict)
    damping: str | None = None
    damping_from_e: Callable[[float], float] | None = None
    calibration: Callable | None = None
    options: tuple = ()
    paper: bool = False

    def __post_init__(self):
        if not (isinstance(self.letter, str) and len(self.letter) == 1 and self.letter.isupper()):
            raise ValueError(f"letter = {self.letter!r}: a law's key is one capital letter.")
        if not (isinstance(self.name, str) and self.name.strip()):
            raise ValueError(f"name = {self.name!r}: give the law a long name.")
        if not isinstance(self.kernels, KernelFamily):
            raise ValueError(f"kernels = {self.kernels!r}: must be a KernelFamily.")
        missing = [m for m in ("from_law", "params", "separation_indicator")
                   if not hasattr(self.parameters, m)]
        if missing:
            raise ValueError(f"parameters = {self.parameters!r}: a law's parameter class needs "
                             f"{', '.join(missing)}.")
        if (self.damping is None) != (self.damping_from_e is None):
            raise ValueError(f"law {self.letter}: damping (its name) and damping_from_e (the "
                             "closed form from e) go together; give both or neither.")
        if self.calibration is not None and self.damping is None:
            raise ValueError(f"law {self.letter}: only a law with a damping parameter can be "
                             "calibrated; drop calibration or name the damping.")
        unknown = set(self.options) - {"allow_tension"}
        if unknown:
            raise ValueError(f"options = {self.options!r}: unknown option(s) "
                             f"{sorted(unknown)}; the ContactLaw options are: allow_tension.")

    @property
    def calibratable(self):
        """Can :func:`femoat.impact.calibration.calibrate` tune this law's damping to reach e?"""
        return self.calibration is not None
