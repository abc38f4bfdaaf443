"""The system frequency domain (cablestudy.dynamics.system_frequency, issue 24): lines
condensed on their ends, free points solved in a junction system, drag linearised.

- two lines in series joined at a massless free point are one line through the
  single-line frequency domain (cablestudy.dynamics.frequency), to solver precision
  where the two models are the same equations (no added mass, no drag: the junction
  node's lumped mass, stiffness and damping are the sums of the two lines' end nodes);
  with added mass and drag the junction's tangent differs (each line's end element
  against the chord of the two neighbours), a first-order difference that halves with
  the element length;
- MoorPy's case8 spread (three legs with bridles, mirror-symmetric about the y-z
  plane) under pure surge: mirror legs respond with opposite tension variations (the
  mirror of +X is -X), and the leg in the mirror plane has none at first order;
- at low frequency the force of the lines on the body is the static system's body
  stiffness (exact catenary statics, free junctions re-equilibrated) times the motion,
  for each of the six degrees of freedom: the linear model's tangent stiffness is
  second-order accurate in the element length.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cablestudy.dynamics.frequency import ReducedLine, solve_harmonic
from cablestudy.dynamics.linear_model import linear_line
from cablestudy.dynamics.modal import ModalProblem
from cablestudy.dynamics.system_frequency import point_motion, system_linear
from cablestudy.statics import STATIC_SOLVERS, EndCondition
from cablestudy.statics.system import solve_system
from cablestudy.statics.system_model import BODY, FIXED, FREE, MooringSystem, SystemLine
from tests.system_drag_reference import mean_drag_jacobian, point_drag_fit
from tests.system_frequency_reference import solve_system_harmonic, system_frequency_outputs
from tests.system_models import CASE8_LINES, CASE8_POINTS, polyester, system_of

SOLVER = STATIC_SOLVERS["catenary"]
FAIRLEAD = np.array([80.0, 0.0, -30.0])


def _polyester(length: float, nodes: int, *, added_mass: float, drag: float) -> object:
    p = polyester(length, depth=None)
    line = replace(
        p.line,
        added_mass_normal=np.array([added_mass]),
        damping_ratio=np.array([0.5]),
        drag_normal=np.array([drag]),
        drag_tangential=np.array([0.01 * drag]),
    )
    return replace(p, line=line, n_nodes=nodes)


def _series(scale: int, *, added_mass: float, drag: float):  # noqa: ANN202
    """One 100 m line from a fixed point to a fairlead on a body, and the same as two
    lines (60 m, 40 m) joined at a free point, on the same nodes (2 m / scale apart)."""
    n1, n2 = 30 * scale + 1, 20 * scale + 1
    single = replace(
        _polyester(100.0, n1 + n2 - 1, added_mass=added_mass, drag=drag),
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=FAIRLEAD),
    )
    st = SOLVER.solve(single)
    assert st.status == 0, st.message
    system = MooringSystem(
        point_names=("anchor", "junction", "fairlead"),
        point_kind=np.array([FIXED, FREE, BODY]),
        # the junction's guess off its equilibrium: the system finds it
        point_position=np.array([np.zeros(3), st.position[n1 - 1] + [0.3, 0.0, 0.2], FAIRLEAD]),
        point_body=np.array([-1, -1, 0]),
        point_force=np.zeros((3, 3)),
        body_names=("body",),
        body_position=np.zeros((1, 6)),
        lines=(
            SystemLine(
                name="1", problem=_polyester(60.0, n1, added_mass=added_mass, drag=drag), a=0, b=1
            ),
            SystemLine(
                name="2", problem=_polyester(40.0, n2, added_mass=added_mass, drag=drag), a=1, b=2
            ),
        ),
        tolerance=1e-12,
    )
    res = solve_system(system, SOLVER)
    assert res.status == 0, res.message
    model, why = system_linear(system, res)
    assert model is not None, why
    red = ReducedLine.of(
        linear_line(
            ModalProblem(
                line=single.line,
                medium=single.medium,
                end_a=single.end_a,
                end_b=single.end_b,
                static=st,
            )
        )
    )
    return red, model, n1


MOTION = np.array([0.5, 0.0, 0.3])  # [m] fairlead amplitude, sin(w t) (complex -i a)


@pytest.mark.parametrize("frequency", [0.05, 0.3, 1.0])
def test_two_lines_in_series_are_one_line(frequency: float) -> None:
    """No added mass, no drag: the same equations, so the same answer up to the static
    junction's tolerance (1e-12 of the force scale) amplified by the conditioning of the
    dynamic matrix (measured 1.4e-9 at 0.05 Hz, 1e-12 above): bar 1e-7."""
    red, model, n1 = _series(1, added_mass=0.0, drag=0.0)
    w = 2.0 * np.pi * frequency
    one = solve_harmonic(red, w, np.array([np.zeros(3), -1j * MOTION]))
    two = solve_system_harmonic(model, w, np.array([[*(-1j * MOTION), 0.0, 0.0, 0.0]]))
    assert one.status == 0 and two.status == 0, two.message
    scale = np.abs(one.end_tension).max()
    np.testing.assert_allclose(two.end_tension[0, 0], one.end_tension[0], rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(two.end_tension[1, 1], one.end_tension[1], rtol=0, atol=1e-7 * scale)
    # the junction carries the line's tension through: both sides equal the single line's
    np.testing.assert_allclose(
        np.concatenate(two.element_tension), one.element_tension, rtol=0, atol=1e-7 * scale
    )
    u = np.abs(one.displacement).max()
    np.testing.assert_allclose(two.point_displacement[1], one.displacement[n1 - 1], atol=1e-7 * u)


def test_series_with_drag_and_added_mass_converges_to_one_line() -> None:
    """With added mass and drag at the junction node, its tangent is the end element's
    in each line and the neighbours' chord in the single line: an O(h) difference of
    the junction's added mass and drag, so the end tension difference halves as the
    elements halve (first order: ratio 0.5; bar 0.65), and the drag iterations of
    both converge."""
    diffs = []
    for scale in (1, 2):
        red, model, _ = _series(scale, added_mass=1.0, drag=1.2)
        w = 2.0 * np.pi * 0.3
        one = solve_harmonic(red, w, np.array([np.zeros(3), -1j * MOTION]))
        two = solve_system_harmonic(model, w, np.array([[*(-1j * MOTION), 0.0, 0.0, 0.0]]))
        assert one.status == 0 and two.status == 0 and two.converged, two.message
        got = np.array([two.end_tension[0, 0], two.end_tension[1, 1]])
        diffs.append(np.abs(got - one.end_tension).max() / np.abs(one.end_tension).max())
    assert diffs[0] < 1e-4, diffs
    assert diffs[1] < 0.65 * diffs[0], diffs


def _case8(nodes: int, *, drag: float, added_mass: float, damping: float) -> MooringSystem:
    s = system_of(CASE8_POINTS, CASE8_LINES, np.zeros(6))
    lines = []
    for sl in s.lines:
        line = replace(
            sl.problem.line,
            added_mass_normal=np.array([added_mass]),
            damping_ratio=np.array([damping]),
            drag_normal=np.array([drag]),
            drag_tangential=np.array([0.01 * drag]),
        )
        lines.append(replace(sl, problem=replace(sl.problem, line=line, n_nodes=nodes)))
    return replace(s, lines=tuple(lines))


def test_spread_mirror_legs_respond_in_mirror_under_surge() -> None:
    """case8 is symmetric about the y-z plane: legs 1 and 3 and their bridles swap
    (lines 1-8, 2-7, 3-9), leg 2's bridles swap (4-5) and leg 2 maps on itself. The
    mirror of surge +X is -X, so mirror lines' tension variations are opposite, and
    leg 2's is zero at first order; to round-off of the static state (1e-12) and of the
    solves (measured 2e-14 of the largest amplitude): bar 1e-9. Drag (iterated to
    1e-6) is symmetric too: the fit of -v is that of v shifted half a period."""
    system = _case8(41, drag=1.2, added_mass=1.0, damping=0.5)
    res = solve_system(system, SOLVER)
    assert res.status == 0, res.message
    model, why = system_linear(system, res)
    assert model is not None, why
    out = solve_system_harmonic(model, 2.0 * np.pi * 0.1, np.array([[-2j, 0, 0, 0, 0, 0]]))
    assert out.status == 0 and out.converged and out.iterations > 1, out.message
    big = np.abs(out.end_tension).max()
    assert big > 1e5  # 263 kN on the legs: a real response, not a trivial zero
    for i, j in ((0, 7), (1, 6), (2, 8), (3, 4)):
        np.testing.assert_allclose(out.end_tension[i], -out.end_tension[j], rtol=0, atol=1e-9 * big)
    assert np.abs(out.end_tension[5]).max() <= 1e-9 * big


def test_low_frequency_body_force_is_the_static_body_stiffness() -> None:
    """At 1e-3 rad/s (inertia w^2 m / k about 1e-9 of the stiffness; no damping or drag)
    the lines' force on the body is -K X with K the static system's body stiffness, per
    degree of freedom (rotations of 0.01 rad: a small-rotation amplitude; the response
    is linear in it). The linear model's stiffness at the nodes is second-order in the
    element length: measured 1.5e-6 at 20 elements per line, 3.6e-7 at 40, 8.9e-8 at
    80, so: bar 2e-6 at 40 elements, and the error falls by more than 3 (2nd order: 4)
    from 20 to 40."""
    worst = []
    for nodes in (21, 41):
        system = _case8(nodes, drag=0.0, added_mass=0.0, damping=0.0)
        res = solve_system(system, SOLVER)
        assert res.status == 0, res.message
        model, why = system_linear(system, res)
        assert model is not None, why
        K = res.body_stiffness[0]
        errs = []
        for dof in range(6):
            X = np.zeros(6, dtype=complex)
            X[dof] = 1.0 if dof < 3 else 0.01
            out = solve_system_harmonic(model, 1e-3, X[None])
            assert out.status == 0, out.message
            errs.append(np.abs(out.body_force[0] + K @ X).max() / np.abs(K @ X).max())
        worst.append(max(errs))
    assert worst[1] < 2e-6, worst
    assert worst[1] < worst[0] / 3.0, worst


def test_rigid_body_motion_of_points() -> None:
    """A point at arm a moves by X + Theta x a: a positive pitch (about +y) moves a
    point below the reference back (-x) by theta |z| and one at +x down by theta x."""
    system = system_of(CASE8_POINTS, CASE8_LINES, np.zeros(6))
    res = solve_system(system, SOLVER)
    model, _ = system_linear(system, res)
    assert model is not None
    pitch = np.array([[0, 0, 0, 0, 0.01, 0]], dtype=complex)
    u = point_motion(model, pitch)
    fair = 1  # point "2" at (6.82, 3.9375, -21)
    np.testing.assert_allclose(u[fair], [0.01 * -21.0, 0.0, -0.01 * 6.82], rtol=1e-12)
    assert np.all(u[model.point_kind != BODY] == 0.0)


def test_point_drag_fit_is_the_describing_function() -> None:
    """Isotropic drag c |w| w of a point oscillating along a line in still water: the
    equivalent damping is c 8 a / (3 pi) along the motion (the classical describing
    function), to the phase sampling's aliasing (about 1e-4 at 32 phases: bar 1e-3)."""
    c, a = 7.0, 0.8
    D = point_drag_fit(
        np.array([c]), np.zeros((1, 3)), np.array([[a, 0.0, 0.0]], dtype=complex), 32
    )
    assert D[0, 0, 0] == pytest.approx(c * 8.0 * a / (3.0 * np.pi), rel=1e-3)


def test_point_moved_on_its_own_equals_its_body_moved() -> None:
    """A body point moved on its own by u is the same excitation as its body translated
    by u when the point is the body's only point; outputs are static +- amplitude."""
    red, model, _ = _series(1, added_mass=1.0, drag=1.2)
    w = 2.0 * np.pi * 0.3
    by_body = solve_system_harmonic(model, w, np.array([[*(-1j * MOTION), 0.0, 0.0, 0.0]]))
    own = np.zeros((3, 3), dtype=complex)
    own[2] = -1j * MOTION
    by_point = solve_system_harmonic(model, w, np.zeros((1, 6)), point_excitation=own)
    assert by_body.status == 0 and by_point.status == 0
    np.testing.assert_array_equal(by_point.end_tension, by_body.end_tension)
    out = system_frequency_outputs(by_body, np.zeros((1, 6)))
    np.testing.assert_allclose(
        out["tension_max_a"] - out["tension_min_a"], 2.0 * np.abs(by_body.end_tension[:, 0])
    )
    assert out["body_force_max"].shape == (1, 6)
    # the envelope at the nodes ends on the end tensions' extremes
    for i, (hi, lo) in enumerate(
        zip(out["tension_envelope_max"], out["tension_envelope_min"], strict=True)
    ):
        assert hi.shape == (model.lines[i].line.n_nodes,)
        assert hi[0] == out["tension_max_a"][i] and lo[-1] == out["tension_min_b"][i]
        assert np.all(hi >= lo)


def test_mean_drag_jacobian_closed_form() -> None:
    """Still water, a node oscillating with amplitude a normal to its tangent (x): the
    mean Jacobian of c |w_N| w_N is 2 c <|w|> = 4 c a / pi along the motion and
    c <|w|> = 2 c a / pi across it in the normal plane; 64 phases of |cos| average to
    2/pi within 2e-3 (the rectified cosine's sampling error, O(1/k^2)): bar 5e-3."""
    system = system_of(CASE8_POINTS, CASE8_LINES, np.zeros(6))
    res = solve_system(system, SOLVER)
    model, _ = system_linear(system, res)
    assert model is not None
    line = replace(
        model.lines[0].line,
        drag_normal=np.full(model.lines[0].line.n_nodes, 3.0),
        drag_tangential=np.zeros(model.lines[0].line.n_nodes),
        tangent=np.tile([1.0, 0.0, 0.0], (model.lines[0].line.n_nodes, 1)),
        current=np.zeros((model.lines[0].line.n_nodes, 3)),
    )
    a = 0.7
    v = np.tile(np.array([0.0, a, 0.0], dtype=complex), (line.n_nodes, 1))
    J = mean_drag_jacobian(line, v, 64)
    assert J[3, 1, 1] == pytest.approx(3.0 * 4.0 * a / np.pi, rel=5e-3)
    assert J[3, 2, 2] == pytest.approx(3.0 * 2.0 * a / np.pi, rel=5e-3)
    assert J[3, 0, 0] == 0.0  # no tangential drag


@pytest.mark.parametrize("frequency", [0.3, 0.45])
def test_drag_iteration_converges_near_the_legs_resonance(frequency: float) -> None:
    """case8 with drag, surge 2 m between the legs' first transverse modes (about 0.4
    to 0.5 Hz): the nodes' nearly straight motion in three dimensions made a fit that
    leant towards the still-water tangent (zero) jump, and the iteration wandered (no
    convergence in 100 iterations from 0.2 Hz); leaning towards the mean Jacobian it
    converges (measured 6 to 14 iterations over 0.02-0.5 Hz)."""
    system = _case8(41, drag=1.2, added_mass=1.0, damping=0.5)
    res = solve_system(system, SOLVER)
    model, _ = system_linear(system, res)
    assert model is not None
    out = solve_system_harmonic(model, 2.0 * np.pi * frequency, np.array([[-2j, 0, 0, 0, 0, 0]]))
    assert out.status == 0 and out.converged, out.message
    assert out.iterations <= 30


def test_resampled_nodes_converge() -> None:
    """``nodes`` re-solves each line between its points at that many nodes: the end
    tension amplitudes of case8 under surge at 21 static samples linearised at 41 nodes
    equal those linearised at 41 static samples (the same static lines, to the static
    tolerance 1e-12: bar 1e-8)."""
    coarse = replace(
        _case8(21, drag=1.2, added_mass=1.0, damping=0.5),
    )
    fine = _case8(41, drag=1.2, added_mass=1.0, damping=0.5)
    motion = np.array([[-2j, 0, 0, 0, 0, 0]])
    amps = []
    for system, nodes in ((coarse, 41), (fine, None)):
        res = solve_system(system, SOLVER)
        model, why = system_linear(system, res, nodes=nodes, solve=SOLVER.solve)
        assert model is not None, why
        assert all(r.line.n_nodes == 41 for r in model.lines)
        out = solve_system_harmonic(model, 2.0 * np.pi * 0.1, motion)
        assert out.status == 0, out.message
        amps.append(np.abs(out.end_tension))
    np.testing.assert_allclose(amps[0], amps[1], rtol=1e-8)


def test_seabed_spread_low_frequency_is_the_static_body_stiffness() -> None:
    """MoorDyn's lines.txt (three chains, 135 m of each laid on the seabed): at 1e-3
    rad/s, without drag or damping, the surge force of the lines on the body is the
    static system's surge stiffness (exact catenary with its touchdown free to move).
    The linear model holds the laid nodes on the seabed's contact spring, so its
    touchdown moves only by whole elements: measured 3e-3 at 40 elements a line (22 m),
    1e-3 at 160: bar 5e-3 at 40."""
    from pathlib import Path

    from cablestudy.analyses.system import system_model
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    rel = "moordyn/tests/Mooring/lines.txt"
    path = Path(__file__).parents[1] / "data" / rel
    imported = import_model(path.read_text(), rel, folder=path.parent)
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, rel), "<imported>"))
    system = system_model(cases[0].study)
    zero = np.zeros(1)
    lines = []
    for sl in system.lines:
        line = replace(sl.problem.line, drag_normal=zero, drag_tangential=zero, damping_ratio=zero)
        lines.append(replace(sl, problem=replace(sl.problem, line=line, n_nodes=41)))
    system = replace(system, lines=tuple(lines))
    res = solve_system(system, SOLVER)
    assert res.status == 0, res.message
    assert all(r.laid_length > 100.0 for r in res.lines)  # on the seabed: the point
    model, why = system_linear(system, res)
    assert model is not None, why
    out = solve_system_harmonic(model, 1e-3, np.array([[1.0, 0, 0, 0, 0, 0]], dtype=complex))
    assert out.status == 0, out.message
    K = res.body_stiffness[0, 0, 0]
    assert -out.body_force[0, 0].real == pytest.approx(K, rel=5e-3)


def test_unconverged_drag_iteration_is_a_recorded_failure() -> None:
    """A drag iteration stopped before it converges is status 7 with the reason, and
    NaN outputs: never a number that was not verified."""
    from cablestudy.dynamics.frequency_model import STATUS_NOT_CONVERGED, DragSettings

    _, model, _ = _series(1, added_mass=1.0, drag=1.2)
    out = solve_system_harmonic(
        model,
        2.0 * np.pi * 0.3,
        np.array([[*(-1j * MOTION), 0.0, 0.0, 0.0]]),
        settings=DragSettings(max_iterations=2),
    )
    assert out.status == STATUS_NOT_CONVERGED
    assert "did not converge in 2 iterations" in out.message
    assert np.all(np.isnan(out.end_tension)) and np.all(np.isnan(out.body_force))
    values = system_frequency_outputs(out, np.zeros((1, 6)))
    assert np.all(np.isnan(values["tension_max_a"])) and np.all(np.isnan(values["body_force_max"]))
