"""The contact laws femoat knows, every registry built from one tuple of modules, and
:class:`ContactLaw`, one law with its parameters (docs/paper.md §2).

Each law is one module (:mod:`~femoat.contact.linear` E, :mod:`~femoat.contact.kelvin_voigt`
V, :mod:`~femoat.contact.jankowski` J, :mod:`~femoat.contact.hertzdamp` H,
:mod:`~femoat.contact.muthukumar` M) holding its compiled kernels, the validated frozen dataclass
of its kernel parameters (with its OpenSees twin) and its :class:`~femoat.contact.spec.LawSpec`
``LAW``: letter, name, damping parameter and the paper's closed form from e, calibration,
plotting style. :data:`MODULES` lists them; :data:`LAW_SPECS`, :data:`LAWS`, :data:`LAW_CODES`,
:data:`LAW_NAMES`, :data:`DAMPING_NAMES` and :data:`PAPER_LAWS` are derived from it, and
:func:`register` adds a law at run time (a study's or a test's own law), :func:`unregister`
takes it out again.

How a law reaches the compiled loop
-----------------------------------
numba cannot add a branch to a compiled dispatcher at run time, and its on-disk cache keeps
the compiled loop between processes. So the compiled side knows *kernel families*,
not laws: a family (:class:`~femoat.contact.spec.KernelFamily`) is a set of kernels with one params layout,
and a law names the family it runs on and packs its parameters in that layout. The families
are those of :data:`MODULES`, numbered in that order (:data:`FAMILIES`; a law's ``code`` is its
family's number), and the dispatcher that selects a family's kernel by that number,
:mod:`femoat.contact._dispatch`, is generated from them by ``python -m femoat.contact.generate``
(committed, like any source, so numba's cache sees a plain file;
:mod:`femoat.contact.kernels` refuses to import a dispatcher that lists other families). Hence:

* a law on an existing family (a linear spring of another stiffness, a Hertz law with another
  damping closed form) is one module and its line in :data:`MODULES`, or one :func:`register`
  call from anywhere, with no compilation: the compiled (and cached) kernels already run it;
* a law with new kernels is one module (kernels, dataclass, ``LAW``) and its line in
  :data:`MODULES`, then ``python -m femoat.contact.generate`` rewrites the dispatcher
  (``tests/test_law_registry.py`` fails until it has). :func:`register` refuses it at run
  time, since no compiled dispatcher could call its kernels.

A law's ``damping`` is ``None`` for the paper's closed form from ``params.e``, or a number that
replaces it (what :func:`femoat.impact.calibration.calibrate` finds so that a simulated impact
reaches ``e`` exactly).
"""

import math
from dataclasses import dataclass, replace

import numpy as np

from femoat.contact import hertzdamp, jankowski, kelvin_voigt, linear, muthukumar
from femoat.contact.history import H_DMAX, H_V0, N_HISTORY
from femoat.contact.parameters import ContactParameters
from femoat.contact.spec import LawSpec

MODULES = (linear, kelvin_voigt, jankowski, hertzdamp, muthukumar)
"""The built-in laws, one module each; the order numbers the kernel families."""

FAMILIES = tuple(dict.fromkeys(m.LAW.kernels for m in MODULES))
"""The kernel families compiled into the dispatcher, a law's ``code`` indexing this tuple."""

PAPER_LAWS = "".join(m.LAW.letter for m in MODULES if m.LAW.paper)
"""The letters of the paper's five laws, in the paper's order."""

LAW_SPECS = {}
"""Letter → :class:`~femoat.contact.spec.LawSpec` of every registered law."""
LAWS = {}
"""Letter → the law's frozen dataclass of kernel parameters (with units), in its own module."""
LAW_CODES = {}
"""Letter → integer code of the law's kernel family (what the compiled kernels dispatch on)."""
LAW_NAMES = {}
"""Letter → long name."""
DAMPING_NAMES = {}
"""Letter → name of the damping parameter, for the damped laws."""

_BUILT_IN = tuple(m.LAW.letter for m in MODULES)


def _rebuild():
    """Refill every registry from :data:`LAW_SPECS` (in place: importers hold these dicts)."""
    for registry in (LAWS, LAW_CODES, LAW_NAMES, DAMPING_NAMES):
        registry.clear()
    for letter, spec in LAW_SPECS.items():
        LAWS[letter] = spec.parameters
        LAW_CODES[letter] = FAMILIES.index(spec.kernels)
        LAW_NAMES[letter] = spec.name
        if spec.damping is not None:
            DAMPING_NAMES[letter] = spec.damping


def register(spec):
    """Add the contact law ``spec`` (a :class:`~femoat.contact.spec.LawSpec`) to every registry.

    Its kernels must be one of the compiled :data:`FAMILIES` (see the module docstring for a
    law with new kernels). The law then works everywhere a letter is read: :func:`make_law`,
    scenario files, single impacts and building runs, the plotting style. In a process pool,
    register it in every worker (e.g. in the module the workers import).
    """
    if not isinstance(spec, LawSpec):
        raise ValueError(f"spec = {spec!r}: register a femoat.contact.spec.LawSpec.")
    if spec.letter in LAW_SPECS:
        raise ValueError(f"letter = {spec.letter!r} is taken by the {LAW_NAMES[spec.letter]} "
                         "law: choose another capital letter.")
    if spec.name.lower() in {n.lower() for n in LAW_NAMES.values()}:
        raise ValueError(f"name = {spec.name!r} is taken: give the law another long name.")
    if spec.kernels not in FAMILIES:
        raise ValueError(
            f"law {spec.letter}: its kernels ({spec.kernels.name}) are not compiled into the "
            f"dispatcher, which runs the families {', '.join(f.name for f in FAMILIES)}. "
            "Reuse one of their KernelFamily records, or add a module to "
            "femoat.contact.laws.MODULES and run `python -m femoat.contact.generate`."
        )
    LAW_SPECS[spec.letter] = spec
    _rebuild()


def unregister(letter):
    """Take a law added by :func:`register` out of every registry (built-in laws stay)."""
    if letter in _BUILT_IN:
        raise ValueError(f"letter = {letter!r} is a built-in law (femoat.contact.laws.MODULES); "
                         "only laws added with register() can be unregistered.")
    if letter not in LAW_SPECS:
        raise ValueError(f"letter = {letter!r} is not registered.")
    del LAW_SPECS[letter]
    _rebuild()


for _module in MODULES:
    register(_module.LAW)


def _unknown(kind):
    return ValueError(
        f"law = {kind!r} is unknown: choose one of {', '.join(LAW_CODES)} "
        f"({', '.join(f'{k} = {v}' for k, v in LAW_NAMES.items())})."
    )


@dataclass(frozen=True)
class ContactLaw:
    """One contact law with its parameters.

    Parameters
    ----------
    kind : str
        The law's letter, one of :data:`LAW_CODES` (``"E", "V", "J", "H", "M"`` built in).
    params : ContactParameters
        The shared parameter set (k_h, m_eff, δ_me, e, a).
    damping : float or None
        Override of the damping parameter named in :data:`DAMPING_NAMES` (ξ_KV, ξ_J, ξ_h or, for
        M, the loss factor λ in [0, 1−a)) [-]; ``None`` uses the paper's closed form from e.
    allow_tension : bool
        Kelvin-Voigt only: keep contact (and pull) until δ = 0 instead of cutting the force at zero.
    v0_min : float
        Smallest approach velocity [in/s] Hertzdamp divides by; guards a gap closing at zero speed.

    Building one resolves its kernel parameters (:meth:`resolved`), whose dataclass validates
    them: an impossible law (a bilinear law with k2 <= 0, a Kelvin-Voigt law below e = 0.135)
    raises here, naming what to change.
    """

    kind: str
    params: ContactParameters
    damping: float | None = None
    allow_tension: bool = False
    v0_min: float = 1e-3

    def __post_init__(self):
        if self.kind not in LAW_SPECS:
            raise _unknown(self.kind)
        if not isinstance(self.params, ContactParameters):
            raise ValueError("params must be a ContactParameters instance.")
        spec = self.spec
        if self.damping is not None:
            if spec.damping is None:
                raise ValueError(f"damping: the {spec.name} law ({self.kind}) has no damping "
                                 "parameter.")
            if not (isinstance(self.damping, (int, float)) and math.isfinite(self.damping)
                    and self.damping >= 0):
                raise ValueError(f"damping ({spec.damping}) = {self.damping!r} must be a finite "
                                 "number >= 0.")
        if self.allow_tension and "allow_tension" not in spec.options:
            takers = [k for k, s in LAW_SPECS.items() if "allow_tension" in s.options]
            raise ValueError(f"allow_tension applies to the law(s) {', '.join(takers)} only "
                             f"({', '.join(LAW_NAMES[k] for k in takers)}).")
        if not (math.isfinite(self.v0_min) and self.v0_min > 0):
            raise ValueError(f"v0_min = {self.v0_min!r} must be a positive velocity [in/s].")
        self.resolved()

    @property
    def spec(self):
        """The :class:`~femoat.contact.spec.LawSpec` of this law's letter."""
        try:
            return LAW_SPECS[self.kind]
        except KeyError:
            raise _unknown(self.kind) from None

    @property
    def code(self):
        """Integer code of the law's kernel family, used by the compiled kernels."""
        return LAW_CODES[self.spec.letter]

    @property
    def name(self):
        return self.spec.name

    @property
    def calibratable(self):
        """Can :func:`femoat.impact.calibration.calibrate` tune its damping to reach e exactly?"""
        return self.spec.calibratable

    def damping_parameter(self):
        """The damping parameter in use (ξ_KV, ξ_J, ξ_h, M's loss factor λ); None if undamped."""
        spec = self.spec
        if spec.damping is None:
            return None
        if self.damping is not None:
            return self.damping
        return spec.damping_from_e(self.params.e)

    @property
    def c_eff(self):
        """Kelvin-Voigt dashpot 2ξ_KV√(m_eff·k_eff) [kip·s/in] (0 for laws without one)."""
        return getattr(self.resolved(), "c_eff", 0.0)

    def stiffnesses(self):
        """Muthukumar (k1, k2) [kip/in] for this law's loss factor."""
        r = self.resolved()
        if not (hasattr(r, "k1") and hasattr(r, "k2")):
            raise ValueError(f"stiffnesses(): the {self.name} law ({self.kind}) has no loading "
                             "stiffnesses k1, k2 (the bilinear law has).")
        return r.k1, r.k2

    def with_damping(self, value):
        """A copy with the damping parameter replaced (``None`` restores the closed form)."""
        return replace(self, damping=value)

    def resolved(self):
        """This law's kernel parameters (its damping resolved to numbers), an instance of its
        :data:`LAWS` dataclass (:class:`Linear`, :class:`KelvinVoigt`, ...), validated."""
        return self.spec.parameters.from_law(self)

    def packed(self):
        """Float array of the parameters in the layout of the law's kernel family (see
        :mod:`femoat.contact.kernels`)."""
        return self.resolved().params()

    def force(self, d, v, v0=None, delta_max=0.0):
        """Force [kip] and tangents at indentation d [in] and rate v [in/s] (for plots and tests).

        ``v0`` is Hertzdamp's approach velocity [in/s] (defaults to ``v``); ``delta_max`` the
        largest past indentation [in] for the bilinear law.
        """
        if d <= 0.0:
            return 0.0, 0.0, 0.0
        h = np.zeros(N_HISTORY)
        h[H_V0], h[H_DMAX] = v if v0 is None else v0, delta_max
        return self.spec.kernels.force(self.packed(), h, float(d), float(v))


def make_law(kind, params, **options):
    """Build a :class:`ContactLaw` from its letter (E, V, J, H, M, or a registered one) or its
    long name."""
    key = str(kind).strip()
    by_name = {v.lower(): k for k, v in LAW_NAMES.items()}
    key = by_name.get(key.lower(), key.upper() if len(key) == 1 else key)
    return ContactLaw(key, params, **options)
