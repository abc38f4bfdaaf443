"""Semi-analytic 3D statics of a segmented elastic line (registry name ``catenary``).

After Dodaran & Park (dodaran-park seed): the line is cut into pieces at segment
boundaries, attachments and (with current) drag elements; each piece carries its weight
and a constant drag load, and its end position follows in closed form from the tension
at its start (:func:`.pieces.piece_integrals`, the seed's eqs. 23-25 for a load of any
direction). The tension at end A, ``T_A``, is the only unknown of a free-hanging line:

* both ends fixed (submersible cable, seed 3.1): three equations r_B(T_A) = r_B. The end
  position is the gradient of the convex complementary energy
  Psi(T_A) = sum int(|T| + |T|^2 / 2EA) ds - (r_B - r_A) . T_A, whose Hessian is the
  analytic flexibility matrix; Newton's method with an Armijo line search on Psi
  therefore converges from any start;
* one end fixed, known force at the other (towing, seed 3.2): T_A follows explicitly;
* one end fixed, known horizontal force and height at the other (mooring, seed 3.3):
  one unknown, the vertical component of T_A, by the same Newton restricted to z.

If end A is the free end it is solved as the reversed line. Drag (seed eqs. 38-39) is
piecewise constant along drag elements and updated from the shape by an outer
fixed-point iteration, accelerated by Anderson mixing and damped, with the seed's
current-speed continuation as fallback. Seabed contact: a line anchored on the
seabed is :mod:`.seabed` (the laid part, with friction) plus a Newton on (tension at
the touchdown point, laid length); a line whose ends are both above the seabed but
which sags onto it is :mod:`.midspan`.

Force conventions: ``force_a`` = T_A and ``force_b`` = -T(L) are the forces the line
exerts on its end attachments; a given ``force`` end is the force applied to the line,
so T(L) = given force.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics.current import current_velocity
from ..physics.hydro import drag_per_length
from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_TIME_LIMIT,
    StaticProblem,
    StaticResult,
)
from .line_state import CatenaryState
from .seabed import Plane, seabed_of
from .semi_analytic_newton import initial_contact, initial_tension, solve_contact, solve_free
from .semi_analytic_shape import (
    _DIRECTION_ONLY,
    _Z,
    Ends,
    Layout,
    Shape,
    _check_deadline,
    _ends,
    _Failure,
    _laid_between,
    _mid_unknowns,
    _offsets,
    _penetrates,
    _td_tension,
    make_layout,
    reversed_line,
)
from .vertical import solve_vertical

# --------------------------------------------------------------------------- drag


@dataclass
class DragModel:
    """Drag per piece of a layout: ``diameter`` [m], ``cn``, ``ct`` [-] per piece,
    fluid ``density`` [kg/m^3], current profile (``z`` [m], ``velocity`` [m/s])."""

    diameter: np.ndarray
    cn: np.ndarray
    ct: np.ndarray
    density: float
    z: np.ndarray
    velocity: np.ndarray

    def load(self, shape: Shape, lay: Layout, factor: float) -> np.ndarray:
        """Drag per unstretched length [N/m] (P, 3) on each layout piece, from the chord
        of the piece in ``shape`` and the current at its mid-height times ``factor``
        (seed eqs. 38-39; the seed's l is the stretched chord). Zero on the laid part."""
        if shape.nodes is not None and len(shape.nodes) == len(lay.bounds):
            r = shape.nodes
        else:
            r, _ = shape.sample(lay.bounds)
        chord = np.diff(r, axis=0)
        lc = np.linalg.norm(chord, axis=1)
        t = chord / np.where(lc > 0.0, lc, 1.0)[:, None]
        U = factor * current_velocity(0.5 * (r[:-1, 2] + r[1:, 2]), self.z, self.velocity)
        f = drag_per_length(
            U,
            t,
            density=self.density,
            diameter=self.diameter,
            drag_normal=self.cn,
            drag_tangential=self.ct,
        )
        D = f * (lc / lay.ell)[:, None]
        if shape.laid_length > 0.0:
            mid = 0.5 * (lay.bounds[:-1] + lay.bounds[1:])
            lo = shape.laid_start
            D[(mid >= lo) & (mid <= lo + shape.laid_length)] = 0.0
        return D


class _Anderson:
    """Anderson acceleration (type II, depth ``m``, mixing ``beta``) of x = G(x)."""

    def __init__(self, m: int = 5, beta: float = 0.7) -> None:
        self.m = m
        self.beta = beta
        self.xs: list[np.ndarray] = []
        self.fs: list[np.ndarray] = []

    def reset(self) -> None:
        self.xs.clear()
        self.fs.clear()

    def step(self, x: np.ndarray, gx: np.ndarray) -> np.ndarray:
        f = gx - x
        self.xs.append(x.copy())
        self.fs.append(f.copy())
        if len(self.xs) > self.m + 1:
            self.xs.pop(0)
            self.fs.pop(0)
        if len(self.xs) == 1:
            return x + self.beta * f
        dX = np.stack([self.xs[i + 1] - self.xs[i] for i in range(len(self.xs) - 1)], axis=1)
        dF = np.stack([self.fs[i + 1] - self.fs[i] for i in range(len(self.fs) - 1)], axis=1)
        gamma, *_ = np.linalg.lstsq(dF, f, rcond=None)
        return x + self.beta * f - (dX + self.beta * dF) @ gamma


# --------------------------------------------------------------------------- solver


@dataclass
class _State:
    TA: np.ndarray | None = None
    contact: tuple[np.ndarray, float] | None = None
    newton: int = 0
    drag: int = 0
    mid: np.ndarray | None = None


class SemiAnalyticSolver:
    """Registry entry ``catenary``: the general 3D semi-analytic solver (segments,
    attachments, sheared and turning currents with drag, the three boundary types,
    seabed contact with friction). See the module docstring."""

    name = "catenary"

    def __init__(
        self,
        *,
        drag_elements: int | None = None,
        max_drag_iterations: int = 300,
        continuation_steps: tuple[int, ...] = (4, 16),
    ) -> None:
        self.drag_elements = drag_elements
        self.max_drag_iterations = max_drag_iterations
        self.continuation_steps = continuation_steps

    def unsupported(self, problem: StaticProblem) -> list[str]:
        out = []
        if problem.end_a.kind != "fixed" and problem.end_b.kind != "fixed":
            out.append("lines with no fixed end (one end must be 'fixed')")
        if problem.is_installation:
            out.append("installation (pay-out speed, touchdown velocity): use method 'shooting'")
        if problem.stretched_drag_diameter and problem.medium.has_current:
            out.append(
                "drag on the stretched diameter (drag_diameter: stretched): use method 'shooting'"
            )
        return out

    # ------------------------------------------------------------------ public

    def solve(
        self,
        problem: StaticProblem,
        *,
        deadline: float | None = None,
        drag_elements: int | None = None,
        compiled: bool = True,
    ) -> StaticResult:
        """Solve ``problem``. A still-water problem hanging free, or anchored at end A on
        the seabed with end B fixed above it, and one hanging free or anchored on the
        seabed in a current (the drag iteration compiled, :mod:`.batch_drag`, with this
        solver's default drag settings), first takes the compiled kernels of
        :mod:`.batch` (when numba is available and ``compiled``); anything they do not
        settle takes the general path below, which gives the same answer to round-off."""
        if compiled:
            from .batch_drag import CONTINUATION, MAX_DRAG_ITERATIONS
            from .batch_kernels import solve_compiled

            left: dict[int, str] = {}
            # the compiled drag iteration runs this solver's default drag settings
            default_drag = (
                drag_elements is None
                and self.drag_elements is None
                and self.max_drag_iterations == MAX_DRAG_ITERATIONS
                and tuple(self.continuation_steps) == CONTINUATION
            )
            fast = solve_compiled(problem, why=left, drag=default_drag, deadline=deadline)
            if fast is not None:
                return fast
            fallback = left.get(0, "")
        else:
            fallback = ""
        line = problem.line
        L = line.total_length
        s = np.linspace(0.0, L, problem.n_nodes)
        state = _State()
        try:
            result = self._solve(problem, s, deadline, drag_elements, state)
        except _Failure as exc:
            result = StaticResult.failed(
                s,
                exc.status,
                exc.message,
                iterations=state.newton + exc.iterations,
                residual=exc.residual,
            )
        except (FloatingPointError, np.linalg.LinAlgError, ValueError, ZeroDivisionError) as exc:
            result = StaticResult.failed(
                s,
                STATUS_NUMERICAL,
                f"{type(exc).__name__} in the catenary solver: {exc}",
                iterations=state.newton,
            )
        result.drag_iterations = state.drag
        result = result.check_finite()
        result.fallback = fallback
        return result

    # ------------------------------------------------------------------ internals

    def _solve(
        self,
        problem: StaticProblem,
        s: np.ndarray,
        deadline: float | None,
        drag_elements: int | None,
        state: _State,
    ) -> StaticResult:
        a, b = problem.end_a, problem.end_b
        vertical = solve_vertical(problem, s)  # ends on one vertical: closed form
        if vertical is not None:
            return vertical
        line = problem.line
        L = line.total_length
        medium = problem.medium
        plane = seabed_of(medium)
        reverse = a.kind != "fixed"
        if a.kind == "fixed" and b.kind == "fixed" and plane is not None:
            assert a.position is not None and b.position is not None
            ha = float(plane.height_above(a.position))
            hb = float(plane.height_above(b.position))
            reverse = hb <= 1e-6 * L and ha > 1e-6 * L
        if a.kind != "fixed" and b.kind != "fixed":
            raise _Failure(STATUS_NO_SOLUTION, "neither end is fixed; one end must be 'fixed'")
        if reverse:
            line = reversed_line(line)
            a, b = b, a
            s_eval = L - s
        else:
            s_eval = s
        ends = _ends(a, b)
        ends.flip = L if reverse else None
        grounded = False
        if plane is not None:
            for label, pos in (("A", ends.rA), ("B", ends.rB)):
                if pos is not None and float(plane.height_above(pos)) < -1e-6 * L:
                    name = label if not reverse else ("B" if label == "A" else "A")
                    raise _Failure(
                        STATUS_NO_SOLUTION,
                        f"end {name} lies {-float(plane.height_above(pos)):.4g} m below the seabed",
                    )
            # a buoyant line (every segment and load lifting) rises off the seabed from
            # an end on it: it neither lies along it nor touches down
            buoyant = bool(np.all(line.weight < 0.0)) and bool(
                np.all(line.attachment_force[:, 2] >= 0.0)
            )
            grounded = float(plane.height_above(ends.rA)) <= 1e-6 * L and not buoyant
        if grounded and ends.kind == "fixed" and plane is not None:
            assert ends.rB is not None
            if float(plane.height_above(ends.rB)) <= 1e-6 * L:
                return _laid_between(line, ends, s_eval, s, reverse)
        has_current = medium.drags(line)
        n_el = 0
        if has_current:
            n_el = (
                drag_elements
                or problem.drag_elements
                or self.drag_elements
                or max(problem.n_nodes - 1, 20)
            )
        lay = make_layout(line, n_el)
        tol = problem.tolerance
        maxit = problem.max_iterations
        grav = lay.gravity

        def inner(q: np.ndarray, tol_inner: float, polish: bool = True) -> Shape:
            return self._inner(
                lay, q, ends, plane, state, tol_inner, maxit, deadline, polish, grounded
            )

        loads = None  # the drag-frozen loads per piece (line_state), in a current
        if not has_current:
            shape = inner(grav, tol)
            drag_res = 0.0
        else:
            seg = lay.segment
            drag = DragModel(
                line.diameter[seg],
                line.drag_normal[seg],
                line.drag_tangential[seg],
                medium.density,
                medium.current_z,
                medium.current_velocity,
            )
            shape, drag_res, D = self._drag_loop(lay, grav, drag, inner, tol, deadline, state, ends)
            loads = CatenaryState(layout=lay, q=grav + D, reversed=reverse)
        pos, tension = shape.sample(s_eval)
        if plane is not None:
            height = plane.height_above(pos)
            depth_below = float(-np.min(height))
            if depth_below > max(1e-6 * L, 1e3 * tol * L):
                where = "" if grounded else " between its ends"
                raise _Failure(
                    STATUS_NO_SOLUTION,
                    f"the line passes {depth_below:.4g} m below the seabed{where} "
                    "(a contact the solver could not resolve)",
                    state.newton,
                    shape.residual,
                )
        force_a = shape.force_a
        force_b = -shape.tension_end
        if reverse:
            force_a, force_b = force_b, force_a
        res = max(shape.residual, drag_res)
        return StaticResult(
            s=s,
            position=pos,
            tension=tension,
            force_a=np.asarray(force_a),
            force_b=np.asarray(force_b),
            laid_length=shape.laid_length,
            iterations=state.newton,
            residual=res,
            state=loads,
        )

    def _inner(
        self,
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        plane: Plane | None,
        state: _State,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool = True,
        grounded: bool = False,
    ) -> Shape:
        """One solve with known loads: free-hanging, or with a laid part (from an end
        anchored on the seabed, or between the ends)."""
        if plane is not None and not grounded:
            return self._inner_midspan(lay, q, ends, plane, state, tol, maxit, deadline, polish)
        if plane is not None and state.contact is not None:
            shape = solve_contact(
                lay, q, ends, plane, state.contact, tol=tol, max_iterations=maxit, deadline=deadline
            )
            if shape is not None:
                state.newton += shape.iterations
                state.contact = (_td_tension(shape), shape.laid_length)
                return shape
            state.contact = None
        if plane is not None and state.TA is None and not np.any(q[:, :2]) and plane.slope == 0.0:
            # first solve of a line anchored on a flat seabed in still water: when the
            # classical mooring formula lays part of it, solve with the laid part at
            # once (the free-hanging solve would only find the line through the seabed)
            try:
                guess = initial_contact(lay, ends, plane, still=True)
            except _Failure:
                guess = None
            if guess is not None and guess[1] > 0.0:
                try:
                    cshape = solve_contact(
                        lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
                    )
                except _Failure as exc:  # the usual path below decides, as before
                    if exc.status == STATUS_TIME_LIMIT or exc.final:  # final: the same again
                        raise
                    cshape = None
                if cshape is not None:
                    state.newton += cshape.iterations
                    state.contact = (_td_tension(cshape), cshape.laid_length)
                    return cshape
        TA = state.TA if state.TA is not None else initial_tension(lay, q, ends)
        try:
            try:
                shape = solve_free(
                    lay,
                    q,
                    ends,
                    TA,
                    tol=tol,
                    max_iterations=maxit,
                    deadline=deadline,
                    polish=polish,
                )
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                shape = self._regularised(lay, q, ends, tol, maxit, deadline, polish, exc)
            free_ok = True
        except _Failure as exc:
            # a time limit is the answer's status, never a switch to the contact path
            # (which path answered would depend on the machine's load)
            if plane is None or exc.status == STATUS_TIME_LIMIT:
                raise
            free_ok = False
            shape = None
        if free_ok:
            assert shape is not None
            state.newton += shape.iterations
            state.TA = shape.force_a.copy()
            if plane is None or not _penetrates(shape, lay, plane):
                return shape
        assert plane is not None
        still = not np.any(q[:, :2]) and plane.slope == 0.0
        guess = initial_contact(lay, ends, plane, still=still)
        cshape = solve_contact(
            lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
        )
        if cshape is None:
            if shape is not None:
                return shape
            raise _Failure(
                STATUS_NOT_CONVERGED,
                "neither the free-hanging nor the seabed-contact solution converged",
            )
        state.newton += cshape.iterations
        state.contact = (_td_tension(cshape), cshape.laid_length)
        return cshape

    def _inner_midspan(
        self,
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        plane: Plane,
        state: _State,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool,
    ) -> Shape:
        """Neither end on the seabed: free-hanging, unless that dips into the seabed, then
        resting on it between the ends (:mod:`.midspan`)."""
        from .midspan import initial_midspan, solve_midspan

        if state.mid is not None:
            try:
                shape = solve_midspan(
                    lay,
                    q,
                    ends,
                    plane,
                    state.mid,
                    tol=tol,
                    max_iterations=maxit,
                    deadline=deadline,
                )
                state.newton += shape.iterations
                state.mid = _mid_unknowns(shape, plane)
                return shape
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                state.mid = None
        shape = self._inner(lay, q, ends, None, state, tol, maxit, deadline, polish)
        if not _penetrates(shape, lay, plane, anchored=False):
            return shape
        guess = initial_midspan(shape, plane, lay.total)
        mshape = solve_midspan(
            lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
        )
        state.newton += mshape.iterations
        state.mid = _mid_unknowns(mshape, plane)
        return mshape

    @staticmethod
    def _regularised(
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool,
        failure: _Failure,
    ) -> Shape:
        """Retry a line with unloaded (weightless) pieces with a small weight on them,
        reduced from 1e-2 to 1e-10 (at least 1e-6) of the point loads per length. A
        weightless piece that goes slack has no determined shape and its energy a kink at
        zero tension where Newton stalls; the
        light chain is its physical limit; the end forces change by that fraction of the
        loads (1e-10 to 1e-6)."""
        unloaded = np.linalg.norm(q, axis=1) == 0.0
        if not np.any(unloaded):
            raise failure
        _, Cend = _offsets(lay, q)
        scale = float(np.sum(np.linalg.norm(lay.point, axis=1)))
        if ends.force is not None:
            scale += float(np.linalg.norm(ends.force))
        if scale <= 0.0:
            raise failure
        qr = q.copy()
        TA = None
        shape = None
        # continuation in the regularising weight, each level warm-starting the next. A
        # slack light piece folds, and the height of its far end moves by 2/w per newton
        # of vertical force: with w -> 0 the position tolerance becomes unattainable in
        # double precision, so the smallest level that converges (at least 1e-6) stands
        for level in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10):
            qr[unloaded, 2] = -level * scale / lay.total
            if TA is None:
                TA = initial_tension(lay, qr, ends)
            try:
                shape = solve_free(
                    lay,
                    qr,
                    ends,
                    TA,
                    tol=tol if level <= 1e-6 else max(tol, 1e-6),
                    max_iterations=maxit,
                    deadline=deadline,
                    polish=polish and level <= 1e-6,
                )
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT or level > 1e-6:
                    raise _Failure(
                        exc.status,
                        f"{failure.message}; retried with a small "
                        f"regularising weight on the weightless pieces: "
                        f"{exc.message}",
                        exc.iterations,
                        exc.residual,
                    ) from None
                break
            TA = shape.force_a
        assert shape is not None
        return shape

    def _drag_loop(
        self,
        lay: Layout,
        grav: np.ndarray,
        drag: DragModel,
        inner,
        tol: float,  # noqa: ANN001
        deadline: float | None,
        state: _State,
        ends: Ends,
    ) -> tuple[Shape, float, np.ndarray]:
        """Outer iteration on the drag loads; continuation in current speed on failure.
        Returns the shape, the load residual and the converged drag loads (P, 3)."""
        Fscale = float(np.sum(np.abs(lay.weight) * lay.ell) + np.sum(np.abs(lay.point)))
        attempts: list[int] = [1, *self.continuation_steps]
        last: _Failure | None = None
        for n_steps in attempts:
            D = np.zeros_like(grav)
            saved_TA, saved_contact = state.TA, state.contact
            try:
                shape, res = None, math.inf
                for k in range(1, n_steps + 1):
                    factor = k / n_steps
                    final = k == n_steps
                    if k > 1:  # drag grows with the square of the speed
                        D = D * (k / (k - 1)) ** 2
                    shape, D, res = self._drag_fixed_point(
                        lay,
                        grav,
                        drag,
                        D,
                        factor,
                        inner,
                        tol if final else max(tol, 1e-4),
                        Fscale,
                        deadline,
                        state,
                        first=shape is None,
                        ends=ends,
                        lenient=not final,
                    )
                assert shape is not None
                return shape, res, D
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                last = exc
                state.TA, state.contact = saved_TA, saved_contact
                if exc.final or (exc.status == STATUS_NO_SOLUTION and n_steps > 1):
                    break  # confirmed with continuation: no static solution
        assert last is not None
        raise _Failure(
            last.status,
            f"drag iteration failed even with current-speed "
            f"continuation in {n_steps} steps: {last.message}",
            0,
            last.residual,
        )

    def _drag_fixed_point(
        self,
        lay: Layout,
        grav: np.ndarray,
        drag: DragModel,
        D: np.ndarray,
        factor: float,
        inner,
        tol: float,
        Fscale: float,  # noqa: ANN001
        deadline: float | None,
        state: _State,
        first: bool,
        ends: Ends,
        lenient: bool = False,
    ) -> tuple[Shape, np.ndarray, float]:
        """Fixed point on the drag loads, Anderson-accelerated. ``lenient`` (an
        intermediate continuation step, which only has to give the next step a start)
        accepts the best iterate when the loop stalls within 1e-2 of the loads."""
        if first:
            try:
                shape = inner(grav + D, max(tol, 1e-6))
            except _Failure:
                shape = self._straight_start(lay, ends)
            D = drag.load(shape, lay, factor)
        acc = _Anderson()
        best = math.inf
        best_res, best_iterate = math.inf, None
        stall = 0
        res = math.inf
        for it in range(1, self.max_drag_iterations + 1):
            _check_deadline(deadline, it, "the drag iteration")
            state.drag += 1
            # inexact inner solves while the loads are still far from converged
            tol_inner = max(tol, min(1e-4, 1e-2 * res))
            shape = inner(grav + D, tol_inner, False)
            Dn = drag.load(shape, lay, factor)
            scale = Fscale + float(np.sum(np.linalg.norm(Dn, axis=1) * lay.ell))
            # summed change of the drag loads: bounds the force imbalance of the line
            res = float(np.sum(np.linalg.norm(Dn - D, axis=1) * lay.ell)) / max(scale, 1e-300)
            if res <= tol and tol_inner <= tol:
                return shape, Dn, res
            if res < best_res:
                best_res, best_iterate = res, (shape, Dn)
            if res < 0.5 * best:
                best = res
                stall = 0
            else:
                stall += 1
                if stall >= 12:
                    acc.reset()
                    acc.beta = max(acc.beta * 0.5, 0.05)
                    stall = 0
            D = acc.step(D.ravel(), Dn.ravel()).reshape(D.shape)
        if lenient and best_iterate is not None and best_res < 1e-2:
            return best_iterate[0], best_iterate[1], best_res
        raise _Failure(
            STATUS_NOT_CONVERGED,
            f"drag iteration did not converge in "
            f"{self.max_drag_iterations} iterations (relative load residual "
            f"{res:.3g}, tolerance {tol:.3g})",
            0,
            res,
        )

    @staticmethod
    def _straight_start(lay: Layout, ends: Ends) -> Shape:
        """A straight line from A (to B, or along the given end force, or down) whose only
        use is a first drag estimate when the still-water problem has no solution (a
        slack weightless line)."""
        if ends.kind == "fixed":
            assert ends.rB is not None
            d = ends.rB - ends.rA
        else:
            assert ends.force is not None
            d = ends.force.copy() if np.linalg.norm(ends.force) > 0.0 else -_Z
            if ends.kind == "mooring":
                d[2] = ends.zB - float(ends.rA[2])
        n = float(np.linalg.norm(d))
        e = d / n if n > 0.0 else -_Z
        L = lay.total
        return Shape(
            s0=np.zeros(1),
            ell=np.array([L]),
            T0=(_DIRECTION_ONLY * e)[None, :],
            q=np.zeros((1, 3)),
            EA=np.array([1.0]),
            r0=ends.rA[None, :],
            force_a=np.zeros(3),
            tension_end=np.zeros(3),
        )
