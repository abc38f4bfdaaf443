"""Issue 24: a system of one line is the one-line study, in the frequency domain, bit
for bit (first found by the outside check tests/integration/test_contract_external_system.py:
the system's lines lacked the single line's touchdown node; fixed, and the check moved
here).

A system of one line between prescribed points (fixed points, points of prescribed
bodies; no free point) is a single line with prescribed end motions: its cases go
through the single line's solve and outputs (cablestudy/analyses/system_one_line.py).
Each pair below is a system and the one-line study whose end motions are the system's
points' motions to the bit (the rotations' arms and amplitudes are powers of two, so
``Theta x a`` is exact and equals the one-line study's ``amplitude * direction``), run
YAML -> netCDF; every output both write is compared with ``==``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from tests.system_contract import run_study

SEG = (
    "{length: 320.0, diameter: 0.1, mass_per_length: 60.0, axial_stiffness: 6.0e8, "
    "drag_normal: 1.2}"
)
#: the anchor of the 3-D line (its plane is not the x-z plane: no in-plane reduction)
ANCHOR_3D = (-290.0, 20.0, -100.0)
#: the anchor of the line in the x-z plane (the single line's in-plane reduction)
ANCHOR_2D = (-290.0, 0.0, -100.0)


def _vec(v: tuple[float, ...]) -> str:
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def _dynamic(excitation: str, method: str, elements: int, sweep: str) -> str:
    return (
        f"  dynamic:\n    excitation: {excitation}\n    method: {method}\n"
        f"    elements: {elements}\n" + (f"sweep:\n{sweep}" if sweep else "")
    )


def _one(
    name: str,
    depth: float,
    a: tuple[float, ...],
    b: tuple[float, ...],
    excitation: str,
    *,
    method: str = "frequency",
    elements: int = 10,
    sweep: str = "",
    seg: str = SEG,
) -> str:
    """The one-line study between fixed ends ``a`` and ``b``."""
    return (
        f"name: {name}\nenvironment: {{fluid: water, depth: {depth!r}}}\n"
        f"line:\n  segments: [{seg}]\nends:\n  a: {{kind: fixed, position: {_vec(a)}}}\n"
        f"  b: {{kind: fixed, position: {_vec(b)}}}\nanalysis:\n  static: {{nodes: 13}}\n"
        + _dynamic(excitation, method, elements, sweep)
    )


def _system(
    name: str,
    depth: float,
    points: str,
    bodies: str,
    excitation: str,
    *,
    method: str = "frequency",
    elements: int = 10,
    sweep: str = "",
    seg: str = SEG,
) -> str:
    """The system of one line from point p to point q."""
    return (
        f"name: {name}\nenvironment: {{fluid: water, depth: {depth!r}}}\npoints:\n{points}"
        f"bodies:\n{bodies}lines:\n  only: {{a: p, b: q, segments: [{seg}]}}\n"
        "analysis:\n  static: {nodes: 13}\n" + _dynamic(excitation, method, elements, sweep)
    )


def _ship_points(anchor: tuple[float, ...], offset: tuple[float, ...]) -> str:
    """A fixed anchor p and a point q on the ship (at the origin) at ``offset``."""
    return (
        f"  p: {{kind: fixed, position: {_vec(anchor)}}}\n"
        f"  q: {{kind: body, body: ship, offset: {_vec(offset)}}}\n"
    )


SHIP = "  ship: {kind: prescribed, position: [0, 0, 0, 0, 0, 0]}\n"

#: the outputs written by both, the system's on ``line`` (its one line)
PER_LINE = (
    "tension_amplitude_a",
    "tension_amplitude_b",
    "tension_envelope_max",
    "tension_envelope_min",
    "z_envelope_max",
)
PER_CASE = ("status", "message", "warning", "linearisation_iterations", "dynamic_method")


def _assert_same(one: xr.Dataset, system: xr.Dataset, excited: str) -> None:
    """Every output both studies write is the same, bit for bit (``==``, NaN nowhere:
    status 0; every drag iteration settled); the one-line study's tension_max/min/mean
    are at its excited end."""
    assert np.all(one["status"].values == 0), one["message"].values
    assert np.all(one["dynamic_method"].values == "frequency")
    assert np.all(one["linearisation_converged"].values == 1)
    pairs = [(one[k], system[k].isel(line=0)) for k in PER_LINE]
    pairs += [(one[k], system[k]) for k in PER_CASE]
    pairs += [
        (one[f"tension_{q}"], system[f"tension_{q}_{excited}"].isel(line=0))
        for q in ("max", "min", "mean")
    ]
    pairs += [(one[f"tension_{e}"], system["tension_" + e].isel(line=0)) for e in "ab"]
    for want, got in pairs:
        w, g = want.values, got.values
        assert w.shape == g.shape, (want.name, w.shape, g.shape)
        if w.dtype.kind == "f":
            assert np.all(np.isfinite(w)), want.name
        assert np.array_equal(w, g), (want.name, w, g)


def _body_force_bounds(system: xr.Dataset, end: str) -> None:
    """Physics of the bodies' force (the line's end force, not in a one-line study):
    the tension amplitude is the end force's variation projected on a unit vector, so
    (Cauchy-Schwarz, complex) it is at most the norm of the force amplitudes, each the
    half range of body_force over the motion; 1e-12 allows the rounding of the
    additions to and subtractions from the static force (1e5 N against 1e4 N)."""
    half = 0.5 * (system["body_force_max"] - system["body_force_min"]).sel(body="ship")
    norm = np.sqrt((half.isel(dof=slice(0, 3)) ** 2).sum("dof"))
    amp = system[f"tension_amplitude_{end}"].isel(line=0)
    big = float(system[f"tension_{end}"].max())
    assert bool((amp <= norm + 1e-12 * big).all()), (amp.values, norm.values)


@pytest.mark.parametrize("depth", [100.0, 300.0])
def test_a_surged_system_of_one_line_is_the_one_line_study_bit_for_bit(
    tmp_path: Path, depth: float
) -> None:
    """One 320 m line in 3-D (its anchor 20 m off the x-z plane), surged 1.5 m at
    0.1 Hz at end B through its ship: lying on the seabed (depth 100 m, a touchdown
    node in both models) and hanging free (300 m). Before issue 24's change the
    answers differed by 2.3e-7 (laid) and 1.7e-6 (hanging) relative (the two solves'
    drag fits and iterations), the envelopes by 1 % (the system interpolated the
    linear model's static tension); now every output is the same."""
    tag = "laid" if depth == 100.0 else "hang"
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            f"one{tag}",
            depth,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            f"sys{tag}",
            depth,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: surge, amplitude: 1.5, frequency: 0.1}",
        ),
    )
    assert (float(one["laid_length"]) > 0.0) == (depth == 100.0)
    _assert_same(one, system, "b")
    _body_force_bounds(system, "b")


@pytest.mark.parametrize("depth", [100.0, 300.0])
def test_heave_and_a_pitch_about_an_offset_point_are_the_one_line_study(
    tmp_path: Path, depth: float
) -> None:
    """A line in the x-z plane (the single line's in-plane solve, both paths): its ship
    point at offset (8, 0, -16) pitched 0.0625 rad at phase 30 deg moves by ``Theta x
    a`` = -16 theta in x and -8 theta in z (1 m along -x and 0.5 m along -z in the
    one-line study); and, separately, heaved 0.75 m with the anchor moved on its own
    0.25 m along x at phase 90 deg."""
    tag = "laid" if depth == 100.0 else "hang"
    b = (8.0, 0.0, -16.0)
    pts = _ship_points(ANCHOR_2D, b)
    one = run_study(
        tmp_path,
        _one(
            f"onepitch{tag}",
            depth,
            ANCHOR_2D,
            b,
            "[{end: b, direction: [-1, 0, 0], amplitude: 1.0, frequency: 0.1, phase_deg: 30},"
            " {end: b, direction: [0, 0, -1], amplitude: 0.5, frequency: 0.1, phase_deg: 30}]",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            f"syspitch{tag}",
            depth,
            pts,
            SHIP,
            "{body: ship, dof: pitch, amplitude: 0.0625, frequency: 0.1, phase_deg: 30}",
        ),
    )
    _assert_same(one, system, "b")
    one = run_study(
        tmp_path,
        _one(
            f"oneheave{tag}",
            depth,
            ANCHOR_2D,
            b,
            "[{end: b, direction: [0, 0, 1], amplitude: 0.75, frequency: 0.08},"
            " {end: a, direction: [1, 0, 0], amplitude: 0.25, frequency: 0.08, phase_deg: 90}]",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            f"sysheave{tag}",
            depth,
            pts,
            SHIP,
            "[{body: ship, dof: heave, amplitude: 0.75, frequency: 0.08},"
            " {point: p, direction: [1, 0, 0], amplitude: 0.25, frequency: 0.08,"
            " phase_deg: 90}]",
        ),
    )
    _assert_same(one, system, "b")
    _body_force_bounds(system, "b")


def test_sway_of_a_line_out_of_the_x_z_plane_is_the_one_line_study(tmp_path: Path) -> None:
    """Sway (motion out of the line's plane) of the 3-D line: no in-plane reduction in
    either; the same numbers."""
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            "onesway",
            300.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [0, 1, 0], amplitude: 1.0, frequency: 0.12}",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            "syssway",
            300.0,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: sway, amplitude: 1.0, frequency: 0.12}",
        ),
    )
    _assert_same(one, system, "b")


def test_two_bodies_moving_both_ends_are_the_one_line_study(tmp_path: Path) -> None:
    """Both ends on two prescribed bodies moved differently: the buoy (at (-290, 20,
    0), its point 100 m below) heaved 0.5 m at phase 90 deg, the ship surged 1 m. The
    one-line study moves its end A 0.5 m along z and end B 1 m along x."""
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            "onetwo",
            300.0,
            ANCHOR_3D,
            b,
            "[{end: a, direction: [0, 0, 1], amplitude: 0.5, frequency: 0.1, phase_deg: 90},"
            " {end: b, direction: [1, 0, 0], amplitude: 1.0, frequency: 0.1}]",
        ),
    )
    points = (
        "  p: {kind: body, body: buoy, offset: [0.0, 0.0, -100.0]}\n"
        f"  q: {{kind: body, body: ship, offset: {_vec(b)}}}\n"
    )
    bodies = SHIP + "  buoy: {kind: prescribed, position: [-290, 20, 0, 0, 0, 0]}\n"
    system = run_study(
        tmp_path,
        _system(
            "systwo",
            300.0,
            points,
            bodies,
            "[{body: buoy, dof: heave, amplitude: 0.5, frequency: 0.1, phase_deg: 90},"
            " {body: ship, dof: surge, amplitude: 1.0, frequency: 0.1}]",
        ),
    )
    _assert_same(one, system, "a")


def test_a_sweep_of_frequency_amplitude_and_dof_is_the_one_line_sweep(tmp_path: Path) -> None:
    """A sweep over 3 frequencies x 2 amplitudes x 2 degrees of freedom (surge, heave;
    the one-line study's directions x, z) of the 3-D line laid on the seabed: every case
    is the one-line study's, bit for bit (the system's cases solved as one group, each
    as alone), the surges at 0.2 Hz included, which the single line's drag iteration
    did not settle while its fit leaned on the small-motion tangent (zero in still
    water; dynamics/drag_lean.py) and the system then answered by its own iteration.
    Run alone, a case is the same in both kinds (a chunk of one)."""
    b = (0.0, 0.0, -12.0)
    axes = (
        "  analysis.dynamic.excitation.frequency: [0.05, 0.1, 0.2]\n"
        "  analysis.dynamic.excitation.amplitude: [0.5, 1.5]\n"
    )
    one = run_study(
        tmp_path,
        _one(
            "onesweep",
            100.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
            sweep=axes + "  analysis.dynamic.excitation.direction: [[1, 0, 0], [0, 0, 1]]\n",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            "syssweep",
            100.0,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: surge, amplitude: 1.5, frequency: 0.1}",
            sweep=axes + "  analysis.dynamic.excitation.dof: [surge, heave]\n",
        ),
    )
    assert one["status"].size == system["status"].size == 12
    one = one.rename({"direction": "excitation_dof"}).assign_coords(
        excitation_dof=system["excitation_dof"].values
    )
    _assert_same(one, system, "b")
    assert np.all(system["linearisation_iterations"].values < 100)
    for f, dof, direction in ((0.2, "surge", "[1, 0, 0]"), (0.05, "heave", "[0, 0, 1]")):
        tag = f"{dof}{int(f * 100)}"
        alone = run_study(
            tmp_path,
            _system(
                f"sysalone{tag}",
                100.0,
                _ship_points(ANCHOR_3D, b),
                SHIP,
                f"{{body: ship, dof: {dof}, amplitude: 0.5, frequency: {f}}}",
            ),
        )
        case = system.sel(frequency=f, amplitude=0.5, excitation_dof=dof)
        for k in (*PER_LINE, "linearisation_iterations", "body_force_max", "status"):
            assert np.array_equal(alone[k].values, case[k].values), (tag, k)
        one_alone = run_study(
            tmp_path,
            _one(
                f"onealone{tag}",
                100.0,
                ANCHOR_3D,
                b,
                f"{{end: b, direction: {direction}, amplitude: 0.5, frequency: {f}}}",
            ),
        )
        _assert_same(one_alone, alone, "b")


def test_auto_picking_the_frequency_domain_is_the_one_line_study(tmp_path: Path) -> None:
    """``method: auto`` on a small surge of the hanging line: both studies trust the
    frequency domain (each by its own checks; the system's judge the line's motion
    against its chord, dynamics/system_validity.py) and give the same outputs."""
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            "oneauto",
            300.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 0.25, frequency: 0.1}",
            method="auto",
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            "sysauto",
            300.0,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: surge, amplitude: 0.25, frequency: 0.1}",
            method="auto",
        ),
    )
    assert str(system["dynamic_method_reason"].values).startswith("auto: linear")
    _assert_same(one, system, "b")


def test_a_system_of_two_lines_keeps_the_system_solve(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Two lines (two anchors, one ship, no free point) are not one line: the system's
    own solve answers (the one-line path is never called), each line within the
    system solve's bound of its one-line study. Bound: both drag fits lean, where a
    node hardly moves, on the drag's Jacobian averaged over the motion
    (dynamics/drag_lean.py), and the two iterations (Anderson depth 1 and 3) stop at
    different iterates within the tolerance 1e-6 of the velocities, which the step to
    tension amplitudes may amplify a few times: measured 4.7e-8 of the tension
    amplitude (1.7e-6 while the single line leaned on the small-motion tangent);
    bound 1e-5."""
    import cablestudy.analyses.system_one_line as one_line

    def refuse(*args: Any) -> Any:
        raise AssertionError("a system of two lines went through the one-line path")

    monkeypatch.setattr(one_line, "solve_one_line_group", refuse)
    mirror = (ANCHOR_3D[0], -ANCHOR_3D[1], ANCHOR_3D[2])
    b = (0.0, 0.0, -12.0)
    points = (
        f"  p: {{kind: fixed, position: {_vec(ANCHOR_3D)}}}\n"
        f"  r: {{kind: fixed, position: {_vec(mirror)}}}\n"
        f"  q: {{kind: body, body: ship, offset: {_vec(b)}}}\n"
    )
    text = _system(
        "systwolines",
        300.0,
        points,
        SHIP,
        "{body: ship, dof: surge, amplitude: 1.5, frequency: 0.1}",
    )
    text = text.replace("lines:\n", f"lines:\n  other: {{a: r, b: q, segments: [{SEG}]}}\n")
    system = run_study(tmp_path, text)
    assert int(system["status"]) == 0, system["message"].values
    for name, anchor in (("only", ANCHOR_3D), ("other", mirror)):
        one = run_study(
            tmp_path,
            _one(
                f"one{name}",
                300.0,
                anchor,
                b,
                "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
            ),
        )
        for end in "ab":
            want = float(one[f"tension_amplitude_{end}"])
            got = float(system[f"tension_amplitude_{end}"].sel(line=name))
            assert abs(got - want) <= 1e-5 * want, (name, end, got, want)


def test_a_system_of_one_laid_line_linearises_about_the_one_line_model(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The linear models the two studies solve (taken as the runner builds them) are
    the same bytes: the nodes (with the touchdown node), mass, stiffness, damping,
    drag coefficients and free basis. Exact: the same static samples through the same
    functions."""
    import cablestudy.analyses.frequency as single
    import cablestudy.analyses.system_frequency as system

    got: dict[str, Any] = {}
    build_one, build_sys = single.linearised, system.system_frequency_model

    def one(*args: Any) -> Any:
        got["one"] = build_one(*args)
        return got["one"]

    def sys_model(*args: Any) -> Any:
        got["sys"] = build_sys(*args)
        return got["sys"]

    monkeypatch.setattr(single, "linearised", one)
    monkeypatch.setattr(system, "system_frequency_model", sys_model)
    b = (0.0, 0.0, -12.0)
    run_study(
        tmp_path,
        _one(
            "one",
            100.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
            elements=6,
        ),
    )
    run_study(
        tmp_path,
        _system(
            "sys",
            100.0,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: surge, amplitude: 1.5, frequency: 0.1}",
            elements=6,
        ),
    )
    a, b_ = got["one"][0].line, got["sys"].lines[0].line
    s_fine = np.linspace(0.0, 320.0, 6 * 16 + 1)
    assert a.n_nodes == 8 and np.all(np.isin(a.s, s_fine))  # 7 uniform and the touchdown
    for name in (
        "s",
        "position",
        "mass",
        "rest_length",
        "direction",
        "axial_stiffness",
        "axial_damping",
        "tension",
        "end_force",
        "drag_normal",
        "drag_tangential",
        "current",
        "tangent",
    ):
        assert getattr(a, name).tobytes() == getattr(b_, name).tobytes(), name
    for name in ("stiffness", "damping", "free_basis"):
        x, y = getattr(a, name), getattr(b_, name)
        assert x.shape == y.shape and (x != y).nnz == 0, name


def test_a_line_without_drag_is_the_one_line_study(tmp_path: Path) -> None:
    """Without drag (both coefficients 0) the single line's solve is one LAPACK band
    solve a case (harmonic_cases._one_by_one), whose end force the system's body takes:
    the same outputs, and the ship's force amplitude at least the tension amplitude
    (_body_force_bounds)."""
    seg = SEG.replace("drag_normal: 1.2", "drag_normal: 0.0, drag_tangential: 0.0")
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            "onenodrag",
            300.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
            seg=seg,
        ),
    )
    system = run_study(
        tmp_path,
        _system(
            "sysnodrag",
            300.0,
            _ship_points(ANCHOR_3D, b),
            SHIP,
            "{body: ship, dof: surge, amplitude: 1.5, frequency: 0.1}",
            seg=seg,
        ),
    )
    assert "drag_normal: 0.0" in system.attrs["study_yaml"]
    _assert_same(one, system, "b")
    _body_force_bounds(system, "b")


def test_a_line_between_fixed_points_moved_on_their_own_is_the_one_line_study(
    tmp_path: Path,
) -> None:
    """No body: a line between two fixed points, the fairlead moved on its own 1.5 m
    along x (a point harmonic): the same outputs."""
    b = (0.0, 0.0, -12.0)
    one = run_study(
        tmp_path,
        _one(
            "onefixed",
            300.0,
            ANCHOR_3D,
            b,
            "{end: b, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
        ),
    )
    text = _system(
        "sysfixed",
        300.0,
        f"  p: {{kind: fixed, position: {_vec(ANCHOR_3D)}}}\n"
        f"  q: {{kind: fixed, position: {_vec(b)}}}\n",
        "",
        "{point: q, direction: [1, 0, 0], amplitude: 1.5, frequency: 0.1}",
    ).replace("bodies:\n", "")
    system = run_study(tmp_path, text)
    assert "body" not in system.dims
    _assert_same(one, system, "b")
