"""An OpenSees twin of the single impact (:mod:`femoat.impact.single`), for cross-checks.

A mass m (m_eff by default) flies at v0 [in/s] toward a zeroLength contact element whose
uniaxial material is the OpenSees counterpart of the femoat law, behind it either a fixed node
(rigid stop) or the Masroor SDOF wall (mass M1 tied to the ground by K1 and C_imp). Newmark's
average-acceleration rule (γ = 1/2, β = 1/4) integrates at the fixed step dt, Newton iterations.

OpenSees conventions (written once here)
----------------------------------------
* 1-D model, one dof per node. Node 1: the impactor, initial velocity +v0 (``setNodeVel``).
  Node 2: the far side of the contact (fixed for a rigid stop, else the wall mass M1).
  Node 3: the ground behind the wall. Element 1: contact, node 1 → node 2. Element 2: wall
  spring K1 with viscous ``eta`` = C_imp (``uniaxialMaterial Elastic``), node 3 → node 2.
* A zeroLength strain is u_j − u_i = u2 − u1: closing the contact makes it *negative*, so the
  gap materials are defined in compression: gap −g0 < 0, negative yield values, and their
  stress is negative in contact. femoat reads indentation δ = −(ε + g0) = u1 − u2 − g0 [in]
  and compressive-positive force f = −σ [kip].
* The run starts with the gap g0 open (default 10.5 steps of free flight, so that closure
  falls in the middle of a step, the generic case); contact starts at t_c = g0/v0 exactly,
  because the free flight at constant velocity is integrated exactly.

Material map
------------
Each law names its twin: the ``opensees_material(gap)`` method of its parameter dataclass (in
the law's module, e.g. :meth:`femoat.contact.kelvin_voigt.KelvinVoigt.opensees_material`) gives
the material's arguments after the tag (checked against the OpenSees sources,
SRC/material/uniaxial) and says how it differs from femoat's law. A law without that method has
no twin.
"""

import math

import numpy as np

from femoat.contact.laws import ContactLaw
from femoat.opensees.available import import_opensees
from femoat.walls.sdof import SdofWall


def opensees_contact_material(law, gap):
    """``(type, *args)`` of the OpenSees uniaxial material twin of ``law`` (tag omitted).

    Parameters
    ----------
    law : ContactLaw
        The femoat contact law.
    gap : float
        Initial open gap g0 [in], > 0 (passed to OpenSees as −g0, compression convention).
    """
    if not isinstance(law, ContactLaw):
        raise ValueError("law must be a ContactLaw (see femoat.contact.make_law).")
    if not (math.isfinite(gap) and gap > 0):
        raise ValueError(f"gap = {gap!r} must be a positive initial opening [in].")
    resolved = law.resolved()
    if not hasattr(resolved, "opensees_material"):
        raise ValueError(f"law = {law.kind!r}: the {law.name} law has no OpenSees twin (its "
                         "parameter class defines no opensees_material).")
    return resolved.opensees_material(gap)


def opensees_impact(law, v0, wall=None, dt=1e-6, mass=None, gap=None, t_max=None):
    """Simulate one impact in OpenSees and summarise it like :func:`simulate_impact`.

    Replaces any model in the openseespy interpreter (``wipe`` before and after).

    Parameters
    ----------
    law : ContactLaw
        The contact law; its OpenSees material is :func:`opensees_contact_material`.
    v0 : float
        Impact (approach) speed [in/s], > 0.
    wall : SdofWall or None
        The wall behind the contact spring; ``None`` for a rigid stop.
    dt : float
        Fixed time step [s], > 0.
    mass : float or None
        Impacting mass [kip·s²/in]; defaults to ``law.params.m_eff``.
    gap : float or None
        Initial opening g0 [in]; default 10.5·v0·dt (closure in the middle of step 11).
        A whole number of steps, n·v0·dt, puts closure on a step boundary, which removes
        ImpactMaterial's first-step offset (see the module docstring).
    t_max : float or None
        Time limit after closure [s]; default 50 linear contact times π√(m/k_eff), plus
        5 wall periods with a wall. Raises RuntimeError if the contact has not ended by then.

    Returns
    -------
    dict
        ``peak_force`` [kip], ``max_indentation`` [in], ``contact_duration`` [s] (closure
        t_c = g0/v0 to the step where δ returns to 0, interpolated linearly), ``restitution``
        (−mass velocity after separation / v0) [-], ``dt`` [s], ``gap`` [in], ``material``
        (the OpenSees material command), ``steps`` (number of steps run), ``closure_rate``
        (δ̇ at the end of the first step in contact [in/s], Hertzdamp's δ̇₀), and the histories
        ``time`` [s] (from closure), ``indentation`` [in], ``force`` [kip],
        ``velocity`` (of the mass) [in/s], ``wall_displacement`` [in].
    """
    ops = import_opensees()
    if not isinstance(law, ContactLaw):
        raise ValueError("law must be a ContactLaw (see femoat.contact.make_law).")
    if not (isinstance(v0, (int, float)) and math.isfinite(v0) and v0 > 0):
        raise ValueError(f"v0 = {v0!r} must be a positive impact speed [in/s].")
    if wall is not None and not isinstance(wall, SdofWall):
        raise ValueError("wall must be an SdofWall or None (rigid stop).")
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} must be a positive time step [s].")
    m = law.params.m_eff if mass is None else mass
    if not (math.isfinite(m) and m > 0):
        raise ValueError(f"mass = {mass!r} must be a positive mass [kip·s²/in].")
    g0 = 10.5 * v0 * dt if gap is None else gap
    material = opensees_contact_material(law, g0)
    t_contact = math.pi * math.sqrt(m / law.params.k_eff)
    if t_max is None:
        t_max = 50.0 * t_contact + (0.0 if wall is None else 5.0 * wall.period)
    t_c = g0 / v0
    n_max = int(math.ceil((t_c + t_max) / dt)) + 1

    ops.wipe()
    try:
        ops.model("basic", "-ndm", 1, "-ndf", 1)
        ops.node(1, 0.0)
        ops.node(2, 0.0)
        ops.mass(1, m)
        if wall is None:
            ops.fix(2, 1)
        else:
            ops.node(3, 0.0)
            ops.fix(3, 1)
            ops.mass(2, wall.mass)
            ops.uniaxialMaterial("Elastic", 2, wall.stiffness, wall.damping)
            ops.element("zeroLength", 2, 3, 2, "-mat", 2, "-dir", 1)
        ops.uniaxialMaterial(material[0], 1, *material[1:])
        ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
        ops.setNodeVel(1, 1, float(v0), "-commit")
        ops.constraints("Plain")
        ops.numberer("Plain")
        ops.system("BandGeneral")
        # Increments are ~v0·dt; converge to 1e-10 of that (a few iterations: m/dt² dominates).
        ops.test("NormDispIncr", 1e-10 * v0 * dt, 50)
        ops.algorithm("Newton")
        ops.integrator("Newmark", 0.5, 0.25)
        ops.analysis("Transient")
        return _run(ops, law, v0, dt, g0, t_c, n_max, wall is not None, material)
    finally:
        ops.wipe()


def _run(ops, law, v0, dt, g0, t_c, n_max, has_wall, material):
    n_hist = [0]
    d_hist, f_hist, v_hist, w_hist = [-g0], [0.0], [float(v0)], [0.0]
    rate_at_closure = None
    touched = False
    n_sep = None
    for n in range(1, n_max + 1):
        if ops.analyze(1, dt) != 0:
            raise RuntimeError(
                f"OpenSees did not converge at step {n} (t = {n * dt:.4e} s) with {material[0]}; "
                "try a smaller dt."
            )
        x, vx = ops.nodeDisp(1, 1), ops.nodeVel(1, 1)
        w = ops.nodeDisp(2, 1) if has_wall else 0.0
        d = x - w - g0
        f = -ops.eleResponse(1, "material", 1, "stress")[0]
        n_hist.append(n)
        d_hist.append(d)
        f_hist.append(f)
        v_hist.append(vx)
        w_hist.append(w)
        if d > 0.0:
            if not touched:
                # What Hertzdamp takes as δ̇₀: the rate at the end of the first contact step.
                rate_at_closure = vx - (ops.nodeVel(2, 1) if has_wall else 0.0)
            touched = True
        elif touched:
            n_sep = n
            break
    if n_sep is None:
        raise RuntimeError(
            f"The OpenSees contact ({material[0]}) did not end within {n_max} steps of "
            f"{dt:.3g} s; raise t_max or check the wall (K1, C_imp)."
        )
    d = np.array(d_hist)
    time = np.array(n_hist) * dt - t_c  # time is t0 + n·dt, counted from closure
    # Separation: δ crosses zero between the last two steps (linear interpolation).
    d_a, d_b = d[-2], d[-1]
    t_sep = time[-2] + dt * d_a / (d_a - d_b)
    return {
        "law": law.kind,
        "target": "sdof" if has_wall else "rigid",
        "v0": float(v0),
        "peak_force": float(max(f_hist)),
        "max_indentation": float(d.max()),
        "contact_duration": float(t_sep),
        # At the separation step the force is zero; afterwards the mass flies at this speed.
        "restitution": float(-v_hist[-1] / v0),
        "dt": float(dt),
        "gap": float(g0),
        "material": material,
        "steps": int(n_sep),
        "closure_rate": float(rate_at_closure),
        "time": time,
        "indentation": d,
        "force": np.array(f_hist),
        "velocity": np.array(v_hist),
        "wall_displacement": np.array(w_hist),
    }
