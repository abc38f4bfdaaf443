"""Random valid single lines through every static method (issue 21, item 6; hypothesis,
derandomized): lengths 1e-3 to 1e5 m, EA 1 to 1e15 N, weights of both signs, with and
without a seabed, 2 to 5000 nodes.

* A result with status 0 passes the whole-line verification and agrees with method
  ``catenary`` within that method's error (below).
* Any other result has a nonzero status and a message.

Agreement. Both answers meet their end positions to their tolerance, so they may differ
by a position error ``delta`` at the ends, which moves the end forces by the line's
stiffness times ``delta``. The stiffness is the inverse of the exact flexibility of the
elastic catenary (:func:`cablestudy.statics.pieces.piece_integrals`, the Jacobian of the
end position in the end force), so the forces must agree within
``10 tol F + |K| delta`` (F the total load, |K| the largest stiffness eigenvalue), with
``delta`` from each method's error:

* ``analytic`` (closed form, bracketed root to 1e-15) and ``shooting`` (DOP853, its
  Newton stops at max(tol, 100 rtol) = 1e-10 of the line length): 10 tol_eff reach;
* ``discrete`` (straight elements between nodes): each element's chord is shorter than
  its arc by ``h (kappa h)^2 / 24`` (kappa = w / T_min the largest curvature), so the
  lumped line is short by at most ``L (kappa h)^2 / 24`` and its nodes sit off the arc by
  the element sagitta ``kappa h^2 / 8`` (both on the stretched length): delta = both
  plus the tolerance term. That is the h^2 error of the method, derived rather than
  fitted; it holds while an element turns by less than a radian (kappa h < 1). On a
  coarser mesh no agreement is claimed: such a result is only required to pass the
  verification.

Positions at the same s must agree within the same delta plus the force difference over
the stiffness (already in delta) - checked as ``10 tol reach + delta``.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cablestudy.physics.contact import default_seabed_stiffness
from cablestudy.statics import STATIC_SOLVERS, STATUS_OK, Medium, StaticProblem
from cablestudy.statics.pieces import piece_integrals
from cablestudy.statics.verify import check_one
from tests.statics_helpers import fixed, make_line

METHODS = ("analytic", "shooting", "discrete")
#: per method: examples with status 0, others, and the worst agreement (difference over
#: allowance, <= 1)
TALLY: dict[str, list[float]] = {m: [0, 0, 0.0] for m in ("catenary", *METHODS)}
#: wall time a solve may take before it is stopped (a time limit is a status, not a pass)
SOLVE_SECONDS = 0.5


@st.composite
def lines(draw: st.DrawFn) -> StaticProblem:
    L = 10 ** draw(st.floats(-3.0, 5.0))
    EA = 10 ** draw(st.floats(0.0, 15.0))
    w = draw(st.sampled_from([1.0, -1.0])) * 10 ** draw(st.floats(-2.0, 4.0))
    nodes = draw(st.sampled_from([2, 3, 11, 101, 1001, 5000]))
    ratio = draw(st.sampled_from([0.1, 0.5, 0.9, 0.99, 0.999, 1.001]))
    elev = math.radians(draw(st.floats(-80.0, 80.0)))
    heading = math.radians(draw(st.floats(-180.0, 180.0)))
    seabed = w > 0.0 and draw(st.booleans())
    if seabed:  # anchor A on the seabed, B above it
        elev = abs(elev)
    d = (
        ratio
        * L
        * np.array(
            [math.cos(elev) * math.cos(heading), math.cos(elev) * math.sin(heading), math.sin(elev)]
        )
    )
    depth = 2.0 * L if not seabed else None
    medium = Medium(density=1025.0, gravity=9.80665, depth=L if seabed else None)
    a = np.array([0.0, 0.0, -L if seabed else -depth])  # type: ignore[operator]
    line = make_line([L], [w], EA, diameter=0.01)
    # a valid line has a positive mass: its weight in water plus the water it displaces
    line = replace(line, mass=np.array([abs(w) / 9.80665 + 1025.0 * math.pi * 0.01**2 / 4]))
    return StaticProblem(
        line=line,
        medium=medium,
        end_a=fixed(*a),
        end_b=fixed(*(a + d)),
        n_nodes=nodes,
        tolerance=1e-9,
    )


def _allowed(prob: StaticProblem, cat, method: str) -> tuple[float, float]:  # noqa: ANN001
    """(force, position) allowances of the module docstring [N], [m]; (inf, inf) where
    the mesh does not resolve the line (an element turns by a radian or more)."""
    line = prob.line
    L, w, EA = float(line.length[0]), float(line.weight[0]), float(line.axial_stiffness[0])
    q = np.array([0.0, 0.0, -w])
    _, jac, _ = piece_integrals(cat.force_a, q, np.array(L), np.array(EA))
    assert jac is not None
    stiffness = 1.0 / float(np.min(np.linalg.eigvalsh(jac)))
    F = abs(w) * L + float(np.linalg.norm(cat.force_a) + np.linalg.norm(cat.force_b))
    reach = max(L, float(np.max(np.abs(cat.position))))
    tol = max(prob.tolerance, 1e-10 if method == "shooting" else 1e-12)
    delta = 20.0 * tol * reach
    if method == "discrete":
        h = L / (prob.n_nodes - 1)
        t_min = float(np.min(cat.tension))
        # the turn over an element, w h / T, on the stretched element length
        # h (1 + T_max / EA); the h^2 estimate holds for turns below a radian
        kh = abs(w) * h / t_min if t_min > 0.0 else math.inf
        if kh >= 1.0:
            return math.inf, math.inf
        stretch = 1.0 + float(np.max(cat.tension)) / EA
        delta += stretch * (L * kh * kh / 24.0 + kh * h / 8.0)
        if prob.medium.depth is not None and float(cat.laid_length or 0.0) > 0.0:
            # on the seabed the discrete model differs from the catenary in two more
            # ways, each bounded here: (1) its seabed is compliant, so laid nodes sink
            # by the weight over the seabed stiffness, w / k; (2) an element across the
            # touchdown cannot follow the kink from the laid to the hanging part: where
            # the hanging part is shorter than an element its whole turn (the fairlead
            # angle above the seabed, theta) happens inside one element, whose chord is
            # short of the arc by h theta^2 / 8 (the same estimate as above, with the
            # turn concentrated). And a laid line is held axially by its laid part, so
            # its end stiffness is up to EA / L, not only the hanging part's.
            k_seabed = float(default_seabed_stiffness(line.weight))
            delta += abs(w) / k_seabed
            fb = np.asarray(cat.force_b, dtype=float)
            theta = math.atan2(abs(fb[2]), max(float(np.hypot(fb[0], fb[1])), 1e-300))
            delta += stretch * h * theta * theta / 8.0
            stiffness = max(stiffness, EA / L)
    return 20.0 * tol * F + stiffness * delta, delta


def _solve(method: str, prob: StaticProblem):  # noqa: ANN202
    return STATIC_SOLVERS[method].solve(prob, deadline=time.monotonic() + SOLVE_SECONDS)


@settings(
    max_examples=100,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(lines())
def test_every_method_is_verified_or_says_why(prob: StaticProblem) -> None:
    cat = _solve("catenary", prob)
    for method in ("catenary", *METHODS):
        if STATIC_SOLVERS[method].unsupported(prob):
            continue
        res = cat if method == "catenary" else _solve(method, prob)
        if res.status != STATUS_OK:
            TALLY[method][1] += 1
            assert res.message.strip(), f"{method}: status {res.status} without a message"
            continue
        TALLY[method][0] += 1
        assert bool(check_one(prob, res, method=method).ok[0])
        if method == "catenary" or cat.status != STATUS_OK:
            continue
        f_allow, x_allow = _allowed(prob, cat, method)
        df = max(
            float(np.linalg.norm(res.force_a - cat.force_a)),
            float(np.linalg.norm(res.force_b - cat.force_b)),
        )
        dx = float(np.max(np.linalg.norm(res.position - cat.position, axis=1)))
        worst = max(df / f_allow, dx / x_allow)
        if math.isinf(f_allow):
            continue  # no agreement claimed on a mesh that does not resolve the line
        TALLY[method][2] = max(TALLY[method][2], worst)
        assert worst <= 1.0, (method, df, f_allow, dx, x_allow)


def test_report_tally() -> None:
    """Runs after the property test in file order: how many examples each method
    answered, failed honestly, and its worst agreement (printed with ``-s``)."""
    for method, (ok, failed, worst) in TALLY.items():
        print(f"{method:9s} status 0: {ok:3.0f}  nonzero: {failed:3.0f}  worst {worst:.3g}")
    assert sum(v[0] + v[1] for v in TALLY.values()) > 0
