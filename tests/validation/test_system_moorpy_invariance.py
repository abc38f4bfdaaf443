"""The invariances NREL/MoorPy's own ``tests/test_system.py`` asserts of its systems
(licence in ``tests/data/moorpy/LICENSE.txt``), written as our system studies and run
through the command line to the netCDF file: a line defined from either end, a line
split at a free junction (suspended, and a few metres past the touchdown with seabed
friction 0, 1 and 10), and the U of a line between two floats with a free point at its
bottom. MoorPy's chain of 120 mm (``getLineProps``: 288 kg/m, volume diameter 0.216 m,
EA 1.2326e9 N), rho 1025, g 9.81.

Tolerances: the catenary answers are exact to the solvers' tolerances (line 1e-9, system
1e-9 of the largest tension, the default), so the anchor and fairlead forces of the
split and the single line must agree to 1e-8 of the largest tension (observed 1e-13).
The U runs by the discrete method (the catenary refuses a line touching the seabed
between two raised ends, by name); there the two layouts differ by the mesh (the
single U line has no node where the two-line U has its free point), an error that
must fall with the element size: halving the elements at least halves the float
positions' difference.

The split with friction failed before the system Newton's step slid along the seabed:
its first steps push the junction, which ends 0.84 m above the seabed, below it, and the
line search stalled there. Free points resting on the seabed (MoorPy's
``test_multiseg_seabed``, and a junction with a clump) pull as the single line, with
seabed friction too (MoorPy's convention, :mod:`cablestudy.statics.system_friction`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main
from tests.system_contract import run_study, statics_problems

SEG = {"diameter": 0.216, "mass_per_length": 288.0, "axial_stiffness": 1232572089.6}


def _study(name: str, depth: float, points: dict, lines: dict, **kw: object) -> str:
    env: dict = {"fluid": {"density": 1025.0}, "gravity": 9.81, "depth": depth}
    if "friction" in kw:
        env["seabed"] = {"friction": kw["friction"]}
    static = {"nodes": kw.get("nodes", 21)}
    if "method" in kw:
        static["method"] = kw["method"]
    return yaml.safe_dump(
        {
            "name": name,
            "environment": env,
            "points": points,
            "lines": {
                k: {"a": a, "b": b, "segments": [{"length": length, **SEG}]}
                for k, (a, b, length) in lines.items()
            },
            "analysis": {"static": static},
        },
        sort_keys=False,
    )


def _failed(tmp_path: Path, text: str) -> xr.Dataset:
    """``cablestudy run`` of a study whose every case fails (exit status 3); its dataset."""
    name = yaml.safe_load(text)["name"]
    (tmp_path / f"{name}.yaml").write_text(text)
    args = ["run", str(tmp_path / f"{name}.yaml"), "--out", str(tmp_path), "--no-cache"]
    assert main([*args, "--no-progress", "--scheduler", "synchronous"]) == 3
    return xr.load_dataset(tmp_path / f"{name}.nc")


def _fixed(p: list[float]) -> dict:
    return {"kind": "fixed", "position": p}


def _free(p: list[float], **kw: float) -> dict:
    return {"kind": "free", "position": p, **kw}


def _ends(ds) -> tuple[np.ndarray, np.ndarray, float]:  # noqa: ANN001
    """The first line's force at A, the last line's at B, the largest tension."""
    return (
        ds["force_a"].values[0],
        ds["force_b"].values[-1],
        float(max(ds["tension_a"].max(), ds["tension_b"].max())),
    )


def test_a_line_defined_from_either_end_pulls_the_same(tmp_path: Path) -> None:
    ds = run_study(
        tmp_path,
        _study(
            "swap",
            60.0,
            {"p1": _fixed([0.0, 0.0, -60.0]), "p2": _fixed([100.0, 10.0, -30.0])},
            {"l1": ("p1", "p2", 120.0), "l2": ("p2", "p1", 120.0)},
        ),
    )
    assert (ds["status"].values == 0).all()
    big = float(ds["tension_b"].max())
    np.testing.assert_allclose(ds["force_a"].values[0], ds["force_b"].values[1], atol=1e-8 * big)
    np.testing.assert_allclose(ds["force_b"].values[0], ds["force_a"].values[1], atol=1e-8 * big)


@pytest.mark.parametrize(
    ("split", "guess", "friction"),
    [(630.0, [-205.0, 0.0, -100.0], None)]
    + [(430.0, [-405.0, 0.0, -150.0], mu) for mu in (0.0, 1.0, 10.0)],
)
def test_a_line_split_at_a_free_junction_pulls_as_the_whole_line(
    tmp_path: Path, split: float, guess: list[float], friction: float | None
) -> None:
    kw = {} if friction is None else {"friction": friction}
    anchor, fair = _fixed([-800.0, 0.0, -200.0]), _fixed([0.0, 0.0, 0.0])
    one = run_study(
        tmp_path,
        _study("whole", 200.0, {"a": anchor, "f": fair}, {"l": ("a", "f", 860.0)}, **kw),
    )
    two = run_study(
        tmp_path,
        _study(
            "split",
            200.0,
            {"a": anchor, "m": _free(guess), "f": fair},
            {"l1": ("a", "m", split), "l2": ("m", "f", 860.0 - split)},
            **kw,
        ),
    )
    assert int(one["status"]) == 0 and int(two["status"]) == 0, str(two["message"].values)
    a1, b1, big = _ends(one)
    a2, b2, _ = _ends(two)
    np.testing.assert_allclose(a2, a1, atol=1e-8 * big)
    np.testing.assert_allclose(b2, b1, atol=1e-8 * big)
    if friction is not None:  # the junction lies past the touchdown, just off the seabed
        laid = float(one["laid_length"].values[0])
        assert laid < split and float(two["laid_length"].values[0]) == pytest.approx(laid)
        assert float(two["point_position"].values[0, 2]) > -200.0


def _u(tmp_path: Path, nodes: int) -> np.ndarray:
    """The floats' positions (2, 3) of the U as two lines with a free point at its bottom
    minus those of the U as one line, by the discrete method at ``nodes`` a line."""
    ends = {"a1": _fixed([-200.0, 0.0, -100.0]), "a2": _fixed([200.0, 0.0, -100.0])}
    f1, f2 = _free([-100.0, 0.0, -50.0], volume=50.0), _free([100.0, 0.0, -40.0], volume=50.0)
    two = run_study(
        tmp_path,
        _study(
            f"u4_{nodes}",
            100.0,
            {**ends, "fl1": f1, "mid": _free([0.0, 0.0, -100.0]), "fl2": f2},
            {
                "l1": ("a1", "fl1", 120.0),
                "l2": ("fl1", "mid", 125.0),
                "l3": ("mid", "fl2", 125.0),
                "l4": ("fl2", "a2", 120.0),
            },
            method="discrete",
            nodes=nodes,
        ),
    )
    one = run_study(
        tmp_path,
        _study(
            f"u3_{nodes}",
            100.0,
            {**ends, "fl1": f1, "fl2": f2},
            {"l1": ("a1", "fl1", 120.0), "l2": ("fl1", "fl2", 250.0), "l3": ("fl2", "a2", 120.0)},
            method="discrete",
            nodes=nodes,
        ),
    )
    assert int(one["status"]) == 0 and int(two["status"]) == 0
    return two["point_position"].values[[0, 2]] - one["point_position"].values


def test_a_u_between_floats_with_a_point_at_its_bottom_is_the_one_line_u(
    tmp_path: Path,
) -> None:
    coarse, fine = _u(tmp_path, 21), _u(tmp_path, 41)
    assert np.abs(fine).max() <= 0.5 * np.abs(coarse).max()
    assert np.abs(fine).max() < 0.05  # [m], of floats about 100 m from the centre


def test_the_u_by_the_catenary_with_a_point_resting_at_its_bottom_is_the_one_line_u(
    tmp_path: Path,
) -> None:
    """MoorPy's ``test_basicU`` by the catenary (exact): the floats of the two layouts
    agree to the Newton's tolerance (MoorPy asserts 1 mm). The free point at the bottom
    rests on the seabed; the U line's end stiffness (touching the seabed between two
    raised ends) comes from differences of its solves."""
    ends = {"a1": _fixed([-200.0, 0.0, -100.0]), "a2": _fixed([200.0, 0.0, -100.0])}
    f1, f2 = _free([-100.0, 0.0, -50.0], volume=50.0), _free([100.0, 0.0, -40.0], volume=50.0)
    four = {"l1": ("a1", "fl1", 120.0), "l2": ("fl1", "mid", 125.0)}
    four |= {"l3": ("mid", "fl2", 125.0), "l4": ("fl2", "a2", 120.0)}
    two = run_study(
        tmp_path,
        _study("u4", 100.0, {**ends, "fl1": f1, "mid": _free([0.0, 0.0, -100.0]), "fl2": f2}, four),
    )
    three = {"l1": ("a1", "fl1", 120.0), "l2": ("fl1", "fl2", 250.0), "l3": ("fl2", "a2", 120.0)}
    one = run_study(tmp_path, _study("u3", 100.0, {**ends, "fl1": f1, "fl2": f2}, three))
    assert int(one["status"]) == 0 and int(two["status"]) == 0
    floats = two["point_position"].values[[0, 2]]
    np.testing.assert_allclose(floats, one["point_position"].values, rtol=0.0, atol=1e-6)
    assert two["point_position"].values[1, 2] == -100.0  # on the seabed


@pytest.mark.parametrize(("z", "mu"), [(-200.0, 0.0), (-190.0, 0.0), (-200.0, 1.0)])
def test_free_points_resting_on_the_seabed_pull_as_the_whole_line(
    tmp_path: Path, z: float, mu: float
) -> None:
    """MoorPy's ``test_multiseg_seabed``: two junctions on the laid part of the chain
    (placed as MoorPy places them, or above), held on the seabed's plane (the seabed's
    reaction across it, their motion along it); every point balanced by the lines and
    the seabed to the system's tolerance. With friction the middle chain, lying wholly
    on the seabed between the two junctions, is pulled from the fairlead's side, as the
    single line's laid part."""
    anchor, fair = _fixed([-800.0, 0.0, -200.0]), _fixed([0.0, 0.0, 0.0])
    points = {"a": anchor, "m1": _free([-700.0, 0.0, z]), "m2": _free([-600.0, 0.0, z]), "f": fair}
    lines = {"l1": ("a", "m1", 100.0), "l2": ("m1", "m2", 100.0), "l3": ("m2", "f", 660.0)}
    three = run_study(tmp_path, _study("three", 200.0, points, lines, friction=mu))
    one = run_study(
        tmp_path,
        _study("whole", 200.0, {"a": anchor, "f": fair}, {"l": ("a", "f", 860.0)}, friction=mu),
    )
    assert int(three["status"]) == 0, str(three["message"].values)
    a1, b1, big = _ends(one)
    a3, b3, _ = _ends(three)
    np.testing.assert_allclose(a3, a1, atol=1e-8 * big)
    np.testing.assert_allclose(b3, b1, atol=1e-8 * big)
    assert (three["point_position"].values[:, 2] == -200.0).all()
    fa, fb = three["force_a"].values, three["force_b"].values
    net = np.stack((fb[0] + fa[1], fb[1] + fa[2])) + three["point_seabed_force"].values
    assert np.abs(net).max() <= 1e-8 * big
    assert (three["point_seabed_force"].values[:, 2] >= 0.0).all()
    assert statics_problems(three, balance=1e-8) == []  # the external checker's balance


@pytest.mark.parametrize(
    ("split", "mass", "guess"),
    [(402.0, 2000.0, -450.0), (242.3, 10000.0, -582.0)],
)
def test_a_clump_resting_on_the_seabed_is_the_clump_on_the_line(
    tmp_path: Path, split: float, mass: float, guess: float
) -> None:
    """A clump where two chains meet, resting on the laid part: the seabed carries its
    weight, and the pull is the one line's with the clump attached there. The 10 t
    clump's guess, 50 m above the seabed, makes the second chain a U (raised at both
    ends, laid between): the Newton's trial solves are not verified (only the answer
    is, at the study's nodes: a U sampled at its ends alone could not pass the check),
    so that start is taken too."""
    env = {"fluid": {"density": 1025.0}, "gravity": 9.81, "depth": 200.0}
    ends = {"a": {"kind": "fixed", "position": [-800.0, 0.0, -200.0]}}
    ends["b"] = {"kind": "fixed", "position": [0.0, 0.0, 0.0]}
    rest = 888.0 - 402.0 if split == 402.0 else 675.2
    segs = [{"length": split, **SEG}, {"length": rest, **SEG}]
    line = {"segments": segs, "attachments": [{"s": split, "mass": mass}]}
    one = run_study(
        tmp_path,
        yaml.safe_dump(
            {"name": "clumped", "environment": env, "line": line, "ends": ends,
             "analysis": {"static": {"nodes": 21}}}
        ),
    )  # fmt: skip
    pts = {"a": _fixed([-800.0, 0.0, -200.0]), "f": _fixed([0.0, 0.0, 0.0])}
    pts["m"] = _free([guess, 0.0, -150.0], mass=mass)
    two = run_study(
        tmp_path,
        _study("joined", 200.0, pts, {"l1": ("a", "m", split), "l2": ("m", "f", rest)}),
    )
    assert int(one["status"]) == 0 and int(two["status"]) == 0, str(two["message"].values)
    big = float(one["tension_b"].max())
    np.testing.assert_allclose(two["force_a"].values[0], one["force_a"].values, atol=1e-8 * big)
    np.testing.assert_allclose(two["force_b"].values[1], one["force_b"].values, atol=1e-8 * big)
    assert two["point_position"].values[0, 2] == -200.0
    weight = mass * 9.81  # in water: its volume is none
    assert two["point_seabed_force"].values[0, 2] == pytest.approx(weight, rel=1e-8)


def _junction(tmp_path: Path, name: str, length: float, split: float, mass: float, **kw: object):  # noqa: ANN202
    """The chain of ``length`` [m] from the anchor to the fairlead as one line with a
    clump of ``mass`` [kg] at ``split`` [m], and as two lines joined at a free point
    carrying that clump (``kw["swap"]``: each line defined from its other end)."""
    anchor, fair = _fixed([-800.0, 0.0, -200.0]), _fixed([0.0, 0.0, 0.0])
    env = {"fluid": {"density": 1025.0}, "gravity": 9.81, "depth": 200.0}
    env["seabed"] = {"friction": kw["friction"]}
    segs = [{"length": split, **SEG}, {"length": length - split, **SEG}]
    line = {"segments": segs, "attachments": [{"s": split, "mass": mass}]}
    one = {
        "name": f"{name}1",
        "environment": env,
        "line": line,
        "analysis": {"static": {"nodes": 21}},
    }
    one["ends"] = {"a": anchor, "b": fair}
    lines = {"l1": ("a", "m", split), "l2": ("m", "f", length - split)}
    if kw.get("swap"):
        lines = {k: (b, a, x) for k, (a, b, x) in lines.items()}
    pts = {"a": anchor, "m": _free([-800.0 + 0.9 * split, 0.0, -150.0], mass=mass), "f": fair}
    two = _study(f"{name}2", 200.0, pts, lines, friction=kw["friction"])
    return run_study(tmp_path, yaml.safe_dump(one, sort_keys=False)), run_study(tmp_path, two)


@pytest.mark.parametrize(
    ("friction", "length", "split", "mass"),
    [(0.0, 927.0, 373.0, 2000.0), (0.5, 927.0, 373.0, 2000.0), (1.0, 927.0, 373.0, 2000.0)]
    + [(1.0, 927.0, 373.0, 0.0), (0.5, 951.0, 501.0, 10000.0)],
)
def test_a_chain_split_at_a_junction_resting_on_the_seabed_is_the_one_line(
    tmp_path: Path, friction: float, length: float, split: float, mass: float
) -> None:
    """MoorPy's way to write a two-material chain, its junction (a clump) resting on the
    laid part, with seabed friction: each line takes friction as its own catenary does,
    from its touchdown towards its end on the seabed (the anchor chain, lying wholly on
    the seabed, pulled at the junction), and the junction, as the single line's clump on
    its laid part, the seabed's reaction and mu times it against the pull. So the pull
    is the one line's with the clump attached, to the solvers' tolerance (1e-9 of the
    tension; asserted 1e-8, observed 1e-13). In the last case friction takes the whole
    pull before the junction: the anchor chain lies straight at its length without
    tension, where the single line has it. The junction's own friction (mu times its
    weight, at most the pull) is in ``point_seabed_force`` beside the reaction."""
    one, two = _junction(tmp_path, "chain", length, split, mass, friction=friction)
    assert int(one["status"]) == 0 and int(two["status"]) == 0, str(two["message"].values)
    a2, b2, big = _ends(two)
    np.testing.assert_allclose(a2, one["force_a"].values, atol=1e-8 * big)
    np.testing.assert_allclose(b2, one["force_b"].values, atol=1e-8 * big)
    assert two["point_position"].values[0, 2] == -200.0  # resting on the seabed
    seabed, weight = two["point_seabed_force"].values[0], mass * 9.81  # no volume
    assert seabed[2] == pytest.approx(weight, rel=1e-8)
    assert -friction * weight * (1 + 1e-12) <= seabed[0] <= 0.0  # against the pull, +x
    if mass == 10000.0:  # held where the anchor chain lies straight at its length
        assert float(two["tension_a"].values[0]) == 0.0 == float(one["tension_a"])
        assert two["point_position"].values[0, 0] == pytest.approx(-800.0 + split, abs=1e-6)


@pytest.mark.parametrize("friction", [1.0])
def test_a_split_chain_defined_from_the_other_ends_pulls_the_same(
    tmp_path: Path, friction: float
) -> None:
    """MoorPy's invariance (a line defined A to B equals the same line B to A) where it
    matters with friction: which end of the anchor chain lying wholly on the seabed is
    pulled, and which way friction acts along the laid chain, follow the points (the
    moving end pulled, the fixed one anchored), not the order the ends are written in."""
    _, two = _junction(tmp_path, "ab", 927.0, 373.0, 2000.0, friction=friction)
    _, owt = _junction(tmp_path, "ba", 927.0, 373.0, 2000.0, friction=friction, swap=True)
    assert int(two["status"]) == 0 and int(owt["status"]) == 0, str(owt["message"].values)
    big = float(two["tension_b"].max())
    for f, g in (("force_a", "force_b"), ("force_b", "force_a")):
        np.testing.assert_allclose(owt[g].values, two[f].values, atol=1e-8 * big)
    np.testing.assert_allclose(
        owt["tension"].values[:, ::-1], two["tension"].values, atol=1e-8 * big
    )


def test_a_laid_stretch_between_two_suspended_parts_with_friction_is_refused_by_name(
    tmp_path: Path,
) -> None:
    """The U of a chain between two floats, its bottom point resting on the seabed (by
    the catenary frictionless above): with friction, which way it acts along the laid
    stretch between the two suspended parts is not determined by the statics."""
    ends = {"a1": _fixed([-200.0, 0.0, -100.0]), "a2": _fixed([200.0, 0.0, -100.0])}
    f1, f2 = _free([-100.0, 0.0, -50.0], volume=50.0), _free([100.0, 0.0, -40.0], volume=50.0)
    four = {"l1": ("a1", "fl1", 120.0), "l2": ("fl1", "mid", 125.0)}
    four |= {"l3": ("mid", "fl2", 125.0), "l4": ("fl2", "a2", 120.0)}
    points = {**ends, "fl1": f1, "mid": _free([0.0, 0.0, -100.0]), "fl2": f2}
    ds = _failed(tmp_path, _study("rubbing", 100.0, points, four, friction=0.5))
    message = str(ds["message"].values)
    assert "friction 0.5" in message and "friction: 0" in message
    assert "suspended parts" in message and "mid" in message
    assert np.isnan(ds["tension_a"].values).all()


def test_a_floating_body_with_a_waterplane_returns_to_its_symmetric_equilibrium(
    tmp_path: Path,
) -> None:
    """MoorPy's ``test_basic``: a free body (1e6 kg, 1e3 m^3 with its metacentre 100 m up,
    waterplane 1e6 m^2) on three 1800 m chains at 120 degrees in 600 m of water, started
    offset by (10, 10, 1) m, must come back to the axis (MoorPy asserts 0.01 m; by
    symmetry ours is exact to the Newton's tolerance, 1e-9 of the largest force over the
    stiffness, below 1e-9 m here), with its heave the hydrostatic balance
    rho g A_WP z = rho g V - m g + F_z(lines) to round-off."""
    angles = np.arange(3) * 2.0 * np.pi / 3.0
    points, lines = {}, {}
    for i, a in enumerate(angles):
        c, s = float(np.cos(a)), float(np.sin(a))
        points[f"anchor{i}"] = _fixed([1600.0 * c, 1600.0 * s, -600.0])
        points[f"fair{i}"] = {
            "kind": "body",
            "body": "float",
            "offset": [20.0 * c, 20.0 * s, -21.0],
        }
        lines[f"leg{i}"] = (f"anchor{i}", f"fair{i}", 1800.0)
    study = yaml.safe_load(_study("floating", 600.0, points, lines))
    study["bodies"] = {
        "float": {
            "kind": "free",
            "position": [10.0, 10.0, 1.0, 0.0, 0.0, 0.0],
            "mass": 1e6,
            "volume": 1e3,
            "center_of_buoyancy": [0.0, 0.0, 100.0],
            "waterplane_area": 1e6,
        }
    }
    ds = run_study(tmp_path, yaml.safe_dump(study, sort_keys=False))
    assert int(ds["status"]) == 0
    pose, lines_force = ds["body_position"].values[0], ds["body_force"].values[0]
    rho_g = 1025.0 * 9.81
    assert np.abs(pose[[0, 1]]).max() < 1e-9 and np.abs(pose[3:]).max() < 1e-12
    weight = 1e6 * 9.81
    assert abs(rho_g * 1e6 * pose[2] - (rho_g * 1e3 - weight + lines_force[2])) <= 1e-9 * weight
    assert -1e-3 < pose[2] < 0.0  # the lines pull it down by about 0.76 mm


@pytest.mark.parametrize(
    ("mu", "reach"), [(0.0, 300.1), (0.5, 300.01), (1.0, 300.05), (0.5, 300.2)]
)
def test_a_line_lying_wholly_on_the_seabed_pulled_at_one_end_is_moorpys(
    mu: float, reach: float
) -> None:
    """The anchor chain of a split chain, lying wholly on the seabed and pulled at its
    junction (:func:`laid_pulled`), against MoorPy's own catenary for such a line (ZF = 0,
    CB = mu): the pulled end's tension and the anchor's, the friction taking part of the
    pull (300.2 m) or all of it before the anchor (300.01, 300.05 m). Both are closed
    forms solved to round-off: 1e-9 of the tension (observed 1e-12)."""
    from moorpy.Catenary import catenary

    from cablestudy.analyses.system import system_model
    from cablestudy.statics.seabed import seabed_of
    from cablestudy.statics.semi_analytic_shape import laid_pulled
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    points = {"a": _fixed([0.0, 0.0, -200.0]), "b": _fixed([reach, 0.0, -200.0])}
    text = _study("laid", 200.0, points, {"l": ("a", "b", 300.0)}, friction=mu)
    prob = system_model(expand_cases(parse_study_text(text, "laid"))[1][0].study).lines[0].problem
    ends = (np.array([0.0, 0.0, -200.0]), np.array([reach, 0.0, -200.0]))
    ours, _ = laid_pulled(prob.line, ends, seabed_of(prob.medium), np.linspace(0, 300, 5), 1)
    fa, _, fb, _, _ = catenary(
        reach, 0.0, 300.0, SEG["axial_stiffness"], prob.line.weight[0], CB=mu
    )
    np.testing.assert_allclose(
        [ours.force_a[0], ours.force_b[0]], [fa, fb], rtol=0, atol=1e-9 * -fb
    )
