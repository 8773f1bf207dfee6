"""The open phase's step by Tsitouras' 5(4) pair: dp5's step with another tableau.

Tsitouras (Comput. Math. Appl. 62, 2011, "Runge-Kutta pairs of order 5(4) satisfying only the
first column simplifying assumption"; SciML's ``Tsit5``) has the shape of Dormand-Prince 5(4):
seven stages, the seventh the acceleration at the step's end and the next step's first (first
same as last), a fifth-order solution and an embedded fourth-order one. Its coefficients trade
dp5's simplifying assumptions for smaller fifth-order error terms, so that at the same tolerance
a step may be longer. Everything but the tableau is :mod:`~femoat.integration.methods.dp5`'s
(the walls advanced exactly, the energy by the pair's quadrature, the error measured as dp5's,
the controller's constants): the loop runs both pairs through one compiled copy of that step,
with the pair's tuple (:data:`PAIR`) as an argument.

Like dp5 it reads a plan bearing's friction state from a path between stage values, so it is
refused on plan bearings with coupled friction (``femoat.integration.solve``); a model without
one (every 1D model) runs on it.

Units: kip, in, s.
"""

from decimal import Decimal

import numpy as np

from femoat.compilation.jit import njit
from femoat.integration.methods import dp5

# ---- the Tsitouras 5(4) tableau: the paper's coefficients, each rounded once to double --------


def _num(x):
    return float(Decimal(x))


TS_C = np.array([_num(x) for x in (
    "0", "0.161", "0.327", "0.9",
    "0.98002554090450968572981028628702459549421379795630247688547642932", "1", "1")])
"""The stage times c_s."""
_ROWS = (
    (),
    ("0.161",),
    ("-0.0084806554923569885444268742502307746751211773934303915373692342",
     "0.33548065549235698854442687425023077467512117739343039153736923425"),
    ("2.8971530571054934321304325941929387649248872877018664903148666935",
     "-6.3594484899750748431481599123838256259527006474156267033059288502",
     "4.3622954328695814110177273181908868610278133597137602129910621568"),
    ("5.3258648284392566044288779208405113178364762530970401012023603977",
     "-11.748883564062827877747170339785772961887441782598628992886669280",
     "7.4955393428898362083046047845643581556586791615181867210101328162",
     "-0.092495066361755249256502079332071916113499834060295352440347504529"),
    ("5.8614554429464200286592514869826478903943376661648144348181572391",
     "-12.920969317847109291706118681783359395417807519557434591663122504",
     "8.1593678985761586431804007945392534851819183211350533057483554240",
     "-0.071584973281400997224530542525829738691272131473635448827211396595",
     "-0.028269050394068382909003057212712241467176336268797700076178762013"),
    ("0.096460766818065229518167313165128763337119952381579971819033191458",
     "0.01",
     "0.47988965041449957477524953229059651991304046219903324883326349443",
     "1.3790085741037418931922748218568727707564626430913605259349400674",
     "-3.2900695154360806799010475857113638501156832908949361585312967996",
     "2.3247105240997739824153559183987657961090602332229624119440600463"),
)
TS_A = np.zeros((7, 6))
for _s, _row in enumerate(_ROWS):
    for _j, _x in enumerate(_row):
        TS_A[_s, _j] = _num(_x)
"""Stage coefficients a_sj (row s, j < s); the last row is the fifth-order weights b."""
TS_E = -np.array([_num(x) for x in (
    "-0.0017800110522257714433785506075395347759446788043336595576374507998",
    "-0.00081643445965674690322363606335468624018625375901590476109406046708",
    "0.0078808780102619960103147276725263042386287337771031286032581296050",
    "-0.14471100717326290753716514797263511672092271234316767761951423390",
    "0.58235716545255522501993761065204217942607812395673877976730454388",
    "-0.45808210592918694666163651883255429744280472797883981794746844347")] + [1.0 / 66.0])
"""b − b̂: the fifth- minus the embedded fourth-order weights, as dp5's ``DP_E`` (the paper
tabulates the embedded minus the fifth-order ones: negated here)."""
TS_B = TS_A[6, :6].copy()
"""The fifth-order weights of the stages before the last (whose weight is zero)."""
N_STAGES = 7
PAIR = (TS_A, TS_C, TS_B, TS_E)
"""The pair as :func:`femoat.integration.methods.dp5.explicit_step` reads it."""

NAME = "tsit5"
"""The method's name (``Integrator(method=...)``)."""
EXPLICIT = True
"""Every stage is evaluated from the committed state (as dp5's)."""
QUINTIC_DENSE = True
"""Its dense output is fifth order (the quintic Hermite interpolant on the step's end values)."""
DEFAULT_RTOL = dp5.DEFAULT_RTOL
"""dp5's (``benchmarks/explicit_pairs.py`` measures every peak at it)."""
ERROR_EXPONENT = dp5.ERROR_EXPONENT
SAFETY = dp5.SAFETY
SHRINK_MIN = dp5.SHRINK_MIN
GROW_MAX = dp5.GROW_MAX


@njit(cache=True, inline="always")
def step(hh, ag1, any_closed, model, state, settings, work):
    """(the step has a finite state, its scaled error): dp5's step with this pair (the loop's
    dispatcher calls :func:`~femoat.integration.methods.dp5.pair_step` with :data:`PAIR`)."""
    return dp5.pair_step(PAIR, hh, ag1, model, state, settings, work)


retry = dp5.retry
"""After a step with no finite state: dp5's rule."""
next_step = dp5.next_step
"""The step after an accepted one: dp5's rule (h ∝ err^(−1/5))."""
