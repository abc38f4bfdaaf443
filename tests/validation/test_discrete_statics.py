"""Static method ``discrete`` (the shared line model's equilibrium): against the exact
elastic catenary (h^2 convergence), the exact tensioned-beam deflection with EI, the
semi-analytic solver on a laid chain mooring, and the refusal of EI by the cable
solvers."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main

from .test_dynamics_beam_seabed import exact_deflection


def run(tmp_path: Path, data: dict, name: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(yaml.safe_dump({**data, "name": name}))
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp_path / f"{name}.nc")


CATENARY = {
    "environment": {"fluid": "air"},
    "line": {
        "segments": [
            {
                "length": 100.0,
                "diameter": 0.02,
                "mass_per_length": 2.466,
                "axial_stiffness": 6.283e5,
            }
        ]
    },
    "ends": {
        "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
        "b": {"kind": "fixed", "position": [92.5, 0.0, -8.6]},
    },
    "analysis": {"static": {"method": "analytic", "nodes": 21, "tolerance": 1e-12}},
    "sweep": {"analysis.static.nodes": [21, 41, 81]},
}


def test_discrete_statics_converge_to_the_exact_elastic_catenary_as_h_squared(
    tmp_path: Path,
) -> None:
    """The catenary-in-air line made soft (EA 6.3e5 N: 1 % strain) against Irvine's exact
    elastic catenary: lumped weight on straight elements errs by O(h^2), so the end
    tensions' error falls by 4 +- 0.3 per halving, and is under 1e-3 at 80 elements."""
    exact = run(tmp_path, CATENARY, "exact")
    data = yaml.safe_load(yaml.safe_dump(CATENARY))
    data["analysis"]["static"]["method"] = "discrete"
    disc = run(tmp_path, data, "disc")
    assert np.all(disc["status"].values == 0)
    errors = []
    for var in ("tension_a", "tension_b"):
        err = np.abs(disc[var].values / exact[var].values - 1.0)
        errors.append(err)
        ratios = err[:-1] / err[1:]
        assert np.all((ratios > 3.7) & (ratios < 4.3)), (var, err, ratios)
    assert max(e[-1] for e in errors) < 1e-3


def test_discrete_statics_carry_bending_stiffness(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A horizontal line between pinned supports in vacuum, pretensioned, with EI: the
    deflection is the exact beam-string solution (EI w'''' - T w'' = q) to O(h^2):
    within 1e-3 of the midspan sag at 40 elements; the cable solvers refuse EI, naming
    the method that models it."""
    span, q, tension, ei, ea = 10.0, 100.0, 1.0e4, 4.0e4, 1.0e10
    data = {
        "environment": {"fluid": "vacuum", "gravity": 9.80665},
        "line": {
            "segments": [
                {
                    "length": span / (1.0 + tension / ea),
                    "diameter": 0.1,
                    "mass_per_length": q / 9.80665,
                    "axial_stiffness": ea,
                    "bending_stiffness": ei,
                }
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [span, 0.0, 0.0]},
        },
        "analysis": {"static": {"method": "discrete", "nodes": 41, "tolerance": 1e-10}},
    }
    ds = run(tmp_path, data, "beam")
    assert int(ds["status"]) == 0, str(ds["message"].values)
    h = float(ds["tension"].isel(s=20))  # horizontal at midspan
    exact = exact_deflection(ds["x"].values, span=span, q=q, tension=h, ei=ei)
    np.testing.assert_allclose(-ds["z"].values, exact, atol=1e-3 * exact.max())

    data["analysis"]["static"]["method"] = "catenary"
    cfg = tmp_path / "refused.yaml"
    cfg.write_text(yaml.safe_dump({**data, "name": "refused"}))
    capsys.readouterr()
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 2
    err = capsys.readouterr().err
    assert "analysis.static.method: 'catenary' does not support bending stiffness" in err
    assert "method 'discrete' models it" in err
    assert not (tmp_path / "refused.nc").exists()


def test_discrete_statics_of_a_laid_chain_match_the_cable_solution(tmp_path: Path) -> None:
    """The chain mooring resting on a frictional seabed: the penalty seabed (1 mm
    penetration) and 80 lumped elements against the semi-analytic rigid-seabed
    solution: fairlead tension within the lumping error O((h/L)^2) ~ 1e-3, laid
    length within two elements (the contact ends at a node)."""
    data = {
        "environment": {"fluid": "water", "depth": 200.0, "seabed": {"friction": 0.5}},
        "line": {
            "segments": [
                {
                    "length": 800.0,
                    "diameter": 0.1533,
                    "mass_per_length": 141.0,
                    "axial_stiffness": 6.0e8,
                }
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, -200.0]},
            "b": {"kind": "fixed", "position": [750.0, 0.0, -10.0]},
        },
        "analysis": {"static": {"method": "catenary", "nodes": 81}},
    }
    cable = run(tmp_path, data, "cable")
    data["analysis"]["static"]["method"] = "discrete"
    disc = run(tmp_path, data, "lumped")
    assert int(disc["status"]) == 0, str(disc["message"].values)
    assert abs(float(disc["tension_b"]) / float(cable["tension_b"]) - 1.0) < 2e-3
    assert abs(float(disc["laid_length"]) - float(cable["laid_length"])) <= 2 * 800.0 / 80


BODY_IN_CURRENT = {
    "environment": {
        "fluid": "water",
        "depth": 100.0,
        "current": [{"z": -100.0, "speed": 1.2}, {"z": 0.0, "speed": 1.2}],
    },
    "line": {
        "segments": [
            {
                "length": 60.0,
                "diameter": 0.05,
                "mass_per_length": 8.0,
                "axial_stiffness": 1.0e8,
                "drag_normal": 1.2,
                "drag_tangential": 0.02,
            }
        ],
        "attachments": [{"s": 30.0, "mass": 50.0, "volume": 0.3, "drag_area": 0.8}],
    },
    "ends": {
        "a": {"kind": "fixed", "position": [0.0, 0.0, -80.0]},
        "b": {"kind": "fixed", "position": [30.0, 0.0, -30.0]},
    },
    "analysis": {"static": {"method": "discrete", "nodes": 41, "tolerance": 1e-12}},
}


def test_a_body_in_a_uniform_current_is_the_constant_force_of_its_drag(tmp_path: Path) -> None:
    """A body at rest in a uniform current U carries the drag 1/2 rho C_D A U^2 along the
    current, whatever its position: the discrete statics with the body's drag_area must
    equal the same line with that force given as the attachment's constant force. Both
    are then the same equations, solved from different starts down to the solver's
    rounding floor per node, 256 eps EA (reach) / l_min (statics/discrete.py: about
    5e-4 N here): the tensions must agree within ten times that, the positions within
    ten times that force over the softest stiffness a node has, the transverse one
    T / l (3000 N / 1.5 m): 2.6e-6 m."""
    dragged = run(tmp_path, BODY_IN_CURRENT, "dragged")
    data = yaml.safe_load(yaml.safe_dump(BODY_IN_CURRENT))
    att = data["line"]["attachments"][0]
    drag = 0.5 * 1025.0 * att.pop("drag_area") * 1.2**2
    att["force"] = [drag, 0.0, 0.0]
    forced = run(tmp_path, data, "forced")
    assert int(dragged["status"]) == 0 and int(forced["status"]) == 0
    floor = 256 * np.finfo(float).eps * 1.0e8 * (80.0 + 60.0) / 1.5
    for var in ("tension_a", "tension_b", "tension"):
        assert np.allclose(dragged[var].values, forced[var].values, rtol=0, atol=10 * floor), var
    t_min = float(forced["tension"].min())
    for var in ("x", "z"):
        atol = 10 * floor / (t_min / 1.5)
        assert np.allclose(dragged[var].values, forced[var].values, rtol=0, atol=atol), var
    # and the drag matters: without it the line sits elsewhere, by far more than that
    data["line"]["attachments"][0]["force"] = [0.0, 0.0, 0.0]
    still = run(tmp_path, data, "still")
    assert float(np.max(np.abs(still["x"].values - forced["x"].values))) > 1e3 * atol


def test_cable_solvers_refuse_a_body_drag_in_a_current_naming_discrete(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = yaml.safe_load(yaml.safe_dump(BODY_IN_CURRENT))
    data["analysis"]["static"]["method"] = "catenary"
    cfg = tmp_path / "refused.yaml"
    cfg.write_text(yaml.safe_dump({**data, "name": "refused"}))
    capsys.readouterr()
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 2
    err = capsys.readouterr().err
    assert "'catenary' does not support the drag of lumped bodies in a current" in err
    assert "method 'discrete' models it" in err
    assert not (tmp_path / "refused.nc").exists()
