"""From sections and their velocities to the force on the body (paper, Eq. 12).

``F_z = sum_j F^j``, ``F^j = f^j d^j`` with ``f^j`` the force per metre the 2D solver gives
for slice ``j`` and ``d^j`` its thickness. Dry slices (zero penetration) carry no force.

**Penetration velocity of a section.** The planes of the slices are fixed in the earth. A
body point at ``r`` from the centre of gravity moves at ``dX/dt = u - q (Z - Z_g)``,
``dZ/dt = w + q (X - X_g)`` (``u`` forward speed, ``w`` vertical velocity, ``q`` pitch rate,
nose up positive). The keel height ``Z_k(X, t)`` at a fixed plane changes as the body point
at the keel moves up or down and as the keel line slides through the plane:

    v = dZ_k/dt |_X = w + q (X - X_g) - (u - q (Z_k - Z_g)) dZ_k/dX

With no pitch rate and no forward speed, ``v = w``. A body moving forward with its keel
rising towards the bow (``dZ_k/dX > 0``, nose up) pushes each plane's section down.

**Horizontal force and pitch moment.** The slice force acts normal to the keel line (the
pressure on the body's bottom), so it has a horizontal part ``F_x^j = -F^j dZ_k/dX`` (a
drag when the keel rises forward). The pitch moment about the centre of gravity, nose up
positive, is ``sum_j (X^j - X_g) F^j - (Z^j - Z_g) F_x^j``, each force applied at its
station halfway between the keel and the waterline. Friction is not modelled.

**The momentum form** (solvers of the kind ``"momentum"``). The solver gives each
section's added mass per metre ``m_a`` and its rate ``m_a' = dm_a/dp``; the force per metre
is the rate of change of the fluid's momentum at the fixed plane,

    f = d/dt [m_a (-v)] = m_a' v^2 - m_a a + extra      (N/m, positive up)

with ``dp/dt = -v``. On a section leaving the water (``v >= 0``) the flux term ``m_a' v^2``
is dropped (the flow separates; no suction), the inertia term stays. The section's
acceleration ``a = dv/dt |_X`` at the fixed plane follows from differentiating ``v`` above
(``dX_g/dt = u``, ``dZ_k/dt |_X = v``, ``ds/dt |_X = dv/dX`` with ``s = dZ_k/dX``):

    a = dw/dt + dq/dt (X - X_g + (Z_k - Z_g) s) - du/dt s + b,
    b = - q u + q (v - w) s - U q (1 + s^2) + U^2 kappa,     U = u - q (Z_k - Z_g),

with ``kappa = d^2 Z_k / dX^2`` the keel line's curvature. The first line is linear in the
body's accelerations, ``a = J . (dw/dt, dq/dt, du/dt) + b``; ``b`` holds the terms that
multiply no acceleration (the pitch rate's and the keel line's slide through the plane).
By virtual work, the generalised forces of a section force ``f`` along the penetration are
``J f``: the vertical force ``f``, the moment ``f (X - X_g + (Z_k - Z_g) s)`` (each force
applied at its keel point, normal to the keel line) and the horizontal force ``- f s``. The
added-mass matrix of the body is then ``A = sum m_a J J^T dx``, symmetric and positive
semi-definite, and the equations of motion read ``(M_body + A) q'' = Q0 + gravity`` with
``Q0 = sum J f0 dx``, ``f0 = m_a' v^2 [v < 0] - m_a b + extra`` (:class:`MomentumTerms`).
A solver's ``vertical`` force (buoyancy) is vertical whatever the keel's slope: it adds
``(1, X - X_g, 0) f_v dx`` instead.

A momentum solver that reads an entry's wetted width from the section's own contour says
so with the diagnostic ``contour`` (1): such an entry is not flagged for a deadrise below
:data:`MIN_DEADRISE`, which limits the equivalent wedge only.

The package's modules, in the order the data flows through them:

- :mod:`~hullslice.forces.kinematics`: each section's penetration velocity and how its
  acceleration follows from the body's.
- :mod:`~hullslice.forces.evaluate`: a 2D solver run on the wetted sections, its output
  checked and spread over every section.
- :mod:`~hullslice.forces.momentum`: the momentum form's terms and the body's
  accelerations.
- :mod:`~hullslice.forces.result`: :class:`ForceResult`, the force per slice and in total.
- :mod:`~hullslice.forces.compute`: :func:`compute_force`, :func:`force_on` and the
  convergence study.
"""

from __future__ import annotations

from .compute import ConvergenceStudy, compute_force, convergence, force_on
from .evaluate import (
    CHINE_REASON,
    FLAT_REASON,
    MASSLESS_REASON,
    MIN_DEADRISE,
    evaluate,
    evaluate_added_mass,
)
from .kinematics import section_kinematics, section_velocity
from .momentum import MomentumTerms, momentum_terms, solve_accelerations, solve_bounded
from .result import MIN_SLENDERNESS, ForceResult

__all__ = [
    "CHINE_REASON",
    "FLAT_REASON",
    "MASSLESS_REASON",
    "MIN_DEADRISE",
    "MIN_SLENDERNESS",
    "ConvergenceStudy",
    "ForceResult",
    "MomentumTerms",
    "compute_force",
    "convergence",
    "evaluate",
    "evaluate_added_mass",
    "force_on",
    "momentum_terms",
    "section_kinematics",
    "section_velocity",
    "solve_accelerations",
    "solve_bounded",
]
