"""Whole-file MoorDyn import of systems and export of system studies (issue 22, item 5).

Round trips compare two statics of the same system: the exported file writes every
number in its shortest exact decimal form, so the re-imported study holds the same
lines, points and bodies, and its statics differ only by where Newton starts (the free
points and bodies at their solved positions instead of the study's guesses). Both stop
at the study's tolerance 1e-10 on the relative end-force residual, so end tensions agree
to 1e-9 of the largest tension (measured: 1e-14).
"""

from __future__ import annotations

from pathlib import Path

import moordyn
import numpy as np
import pytest

from cablestudy.analyses.system import evaluate_system_case
from cablestudy.cli import main
from cablestudy.interchange import NotModelledError, import_model, imported_yaml
from cablestudy.statics.system import rotation
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text, read_study_source

CONFIGS = Path(__file__).parents[2] / "configs"

#: a buoyant free body held by three legs, one a chain of two segments with a clump
#: attachment, one through a free clump point
FREE_BODY = """name: free-buoy
environment:
  fluid: water
  gravity: 9.80665
  depth: 100.0
points:
  anchor1: {kind: fixed, position: [300.0, 0.0, -100.0]}
  anchor2: {kind: fixed, position: [-150.0, 259.8, -100.0]}
  anchor3: {kind: fixed, position: [-150.0, -259.8, -100.0]}
  clump: {kind: free, position: [-80.0, 138.6, -60.0], mass: 2000.0, volume: 0.2}
  fair1: {kind: body, body: buoy, offset: [5.0, 0.0, -5.0]}
  fair2: {kind: body, body: buoy, offset: [-2.5, 4.33, -5.0]}
  fair3: {kind: body, body: buoy, offset: [-2.5, -4.33, -5.0]}
bodies:
  buoy:
    kind: free
    position: [0.0, 0.0, -10.0, 0.0, 0.0, 0.0]
    mass: 20000.0
    volume: 80.0
    center_of_gravity: [0.0, 0.0, -4.0]
lines:
  leg1:
    a: anchor1
    b: fair1
    segments:
      - {length: 200.0, diameter: 0.1, mass_per_length: 150.0, axial_stiffness: 8.0e8}
      - {length: 120.0, diameter: 0.12, mass_per_length: 10.0, axial_stiffness: 1.0e8}
    attachments:
      - {s: 250.0, mass: 500.0}
  leg2a:
    a: anchor2
    b: clump
    segments: [{length: 130.0, diameter: 0.1, mass_per_length: 150.0, axial_stiffness: 8.0e8}]
  leg2b:
    a: clump
    b: fair2
    segments: [{length: 170.0, diameter: 0.12, mass_per_length: 10.0, axial_stiffness: 1.0e8}]
  leg3:
    a: anchor3
    b: fair3
    segments: [{length: 320.0, diameter: 0.1, mass_per_length: 150.0, axial_stiffness: 8.0e8}]
analysis:
  static: {nodes: 41, tolerance: 1.0e-10}
"""


def _solve(src) -> dict:
    _, cases = expand_cases(src)
    record = evaluate_system_case(cases[0])
    assert record.status == 0, record.message
    return record.data


def _round_trip(config: Path, tmp_path: Path, capsys, case: list[str]) -> tuple:
    out = tmp_path / "exported.dat"
    assert main(["export", "moordyn", str(config), *case, "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["import", "moordyn", str(out)]) == 0
    text = capsys.readouterr().out
    back = tmp_path / "back.yaml"
    back.write_text(text)
    return out.read_text(), read_study_source(back)


def test_spread_with_bridles_survives_export_and_import(tmp_path: Path, capsys) -> None:
    config = CONFIGS / "system-spread-bridles.yaml"
    text, back = _round_trip(config, tmp_path, capsys, ["--case", "surge=4.0"])
    assert "BODIES" in text and "Body1" in text
    src = read_study_source(config)
    _, cases = expand_cases(src)
    (case,) = [c for c in cases if c.coords["surge"] == 4.0]
    original = evaluate_system_case(case).data
    again = _solve(back)
    assert list(back.data["lines"]) == [str(i) for i in range(1, 10)]  # in the study's order
    largest = float(np.max(original["tension_b"]))
    for key in ("tension_a", "tension_b"):
        np.testing.assert_allclose(again[key], original[key], rtol=0.0, atol=1e-9 * largest)
    np.testing.assert_allclose(
        again["body_position"], original["body_position"], rtol=0.0, atol=1e-12
    )
    k = np.abs(original["body_stiffness"]).max()
    np.testing.assert_allclose(
        again["body_stiffness"], original["body_stiffness"], rtol=0.0, atol=1e-8 * k
    )


def test_free_body_and_chained_line_survive_export_and_import(tmp_path: Path, capsys) -> None:
    config = tmp_path / "free.yaml"
    config.write_text(FREE_BODY)
    text, back = _round_trip(config, tmp_path, capsys, [])
    original = _solve(read_study_source(config))
    again = _solve(back)
    # single-segment lines keep their place (1-3: leg2a, leg2b, leg3); leg1 becomes lines
    # 4, 5, 6 cut at its segment joint (s = 200 m) and its clump (s = 250 m)
    body = back.data["bodies"]["body1"]
    assert body["kind"] == "free" and body["mass"] == 20000.0 and body["volume"] == 80.0
    assert body["center_of_gravity"] == [0.0, 0.0, -4.0]
    masses = sorted(p.get("mass", 0.0) for p in back.data["points"].values())
    assert masses[-2:] == [500.0, 2000.0]
    ta, tb = original["tension_a"], original["tension_b"]
    largest = float(max(ta.max(), tb.max()))
    pairs = [(1, 0, 0), (2, 1, 1), (3, 2, 2), (0, 3, 5)]  # original, line of A, line of B
    for i, ia, ib in pairs:
        assert again["tension_a"][ia] == pytest.approx(ta[i], abs=1e-9 * largest)
        assert again["tension_b"][ib] == pytest.approx(tb[i], abs=1e-9 * largest)
    # the body is found again where it was: the same equilibrium to Newton's tolerance
    np.testing.assert_allclose(
        again["body_position"], original["body_position"], rtol=0.0, atol=1e-9
    )


SPREAD = """--- MoorDyn Input File ---
three legs to a turned body, one through a clump
--- LINE TYPES ---
TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)
chain 0.1 150.0 1e9 -0.8 0 2.4 1.0 1.15 0.5
--- BODIES ---
ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*
(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1 Fixed 0 0 -10 30 20 10 0 0 0 0 0 0
--- POINTS ---
ID Attachment X Y Z Mass Volume CdA Ca
(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Body1 1 2 3 0 0 0 0
2 Fixed 300 0 -100 0 0 0 0
3 Fixed -150 260 -100 0 0 0 0
4 Fixed -150 -260 -100 0 0 0 0
5 Free -100 170 -80 1000 0.1 2.0 1.0
6 Coupled 5 0 -12 0 0 0 0
--- LINES ---
ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
(#) (name) (#) (#) (m) (-) (-)
1 chain 2 1 320 20 -
2 chain 3 5 120 20 -
3 chain 5 1 200 20 -
4 chain 4 1 320 20 -
5 chain 2 6 320 20 -
--- OPTIONS ---
100 WtrDpth
--- need this line ---
"""


def test_whole_file_import_maps_every_point_and_body(tmp_path: Path) -> None:
    imported = import_model(SPREAD, "spread.dat")
    src = parse_study_text(imported_yaml(imported, "spread.dat"), "<imported>")
    data = src.data
    assert list(data["lines"]) == ["1", "2", "3", "4", "5"]
    assert data["lines"]["3"] == {**data["lines"]["3"], "a": "point5", "b": "point1"}
    assert data["points"]["point5"] == {
        "kind": "free",
        "position": [-100.0, 170.0, -80.0],
        "mass": 1000.0,
        "volume": 0.1,
    }
    assert data["points"]["point6"] == {
        "kind": "body",
        "body": "vessel",
        "offset": [5.0, 0.0, -12.0],
    }
    assert data["bodies"]["vessel"] == {"kind": "prescribed", "position": [0.0] * 6}
    assert any("point 5: CdA = 2 m^2 and Ca = 1" in w for w in imported.warnings)
    # the fixed body is prescribed; its turn is MoorDyn's (R = Rx Ry Rz), so point 1 lies
    # where MoorDyn puts it (moordyn 2.x, same file)
    body = data["bodies"]["body1"]
    assert body["kind"] == "prescribed"
    pos = np.asarray(body["position"], dtype=float)
    ours = pos[:3] + rotation(pos[3:]) @ np.array([1.0, 2.0, 3.0])
    (tmp_path / "spread.txt").write_text(SPREAD)
    system = moordyn.Create(str(tmp_path / "spread.txt"))
    moordyn.Init(system, [5.0, 0.0, -12.0], [0.0] * 3)  # the coupled point 6, at rest
    theirs = np.array(moordyn.GetPointPos(moordyn.GetPoint(system, 1)))
    moordyn.Close(system)
    np.testing.assert_allclose(ours, theirs, rtol=0.0, atol=1e-12)
    _solve(src)  # and it runs


@pytest.mark.parametrize(
    ("edit", "feature", "named"),
    [
        (("1 Fixed 0 0 -10", "1 CoupledPinned 0 0 -10"), "pinned_bodies", "body 1"),
        (("100 WtrDpth", "100 WtrDpth\n2 Currents"), "dynamic_current", "Currents 2"),
        (("2 Fixed 300 0 -100", "2 Fixed 300 0 5"), "surface_crossing", "z = 5 m"),
        (
            (
                "--- POINTS ---",
                "--- RODS ---\nID T A Xa Ya Za Xb Yb Zb N O\n(#) (-) (-) (m) (m) "
                "(m) (m) (m) (m) (-) (-)\n1 can Body1 0 0 0 0 0 -5 3 -\n--- POINTS ---",
            ),
            "rods",
            "rod 1 on body 1",
        ),
    ],
)
def test_what_a_system_cannot_hold_is_refused_by_name(
    edit: tuple[str, str], feature: str, named: str
) -> None:
    text = SPREAD.replace(*edit)
    if feature == "rods":
        text = text.replace(
            "--- LINE TYPES ---",
            "--- ROD TYPES ---\nName Diam Mass Cd Ca CdEnd CaEnd\n(-) (m) (kg/m) (-) (-) (-) (-)"
            "\ncan 1 10 1 1 1 1\n--- LINE TYPES ---",
        )
    assert text != SPREAD
    with pytest.raises(NotModelledError, match=named) as info:
        import_model(text, "spread.dat")
    assert feature in info.value.features


def test_a_system_in_a_current_imports_with_its_drag_and_solves(tmp_path: Path) -> None:
    """``Currents 1`` with its table beside the file: the system study carries the
    current, the free point its CdA as drag_area (its drag in the current, as MoorDyn
    gives it in the initial condition), and its statics solve."""
    (tmp_path / "current_profile.txt").write_text("a\nb\nc\n0 0.5 0 0\n-100 0.1 0 0\n")
    text = SPREAD.replace("100 WtrDpth", "100 WtrDpth\n1 Currents")
    imported = import_model(text, "spread.dat", folder=tmp_path)
    data = imported.data
    assert [p["speed"] for p in data["environment"]["current"]] == [0.5, 0.1]
    assert data["points"]["point5"]["drag_area"] == 2.0
    assert not any("CdA = 2" in w for w in imported.warnings)  # used, not listed
    (_, [case]) = expand_cases(parse_study_text(imported_yaml(imported, "s.dat"), "<imported>"))
    record = evaluate_system_case(case)
    assert record.status == 0, record.message
    still = import_model(SPREAD, "spread.dat")  # no current: CdA acts in dynamics only
    assert "drag_area" not in still.data["points"]["point5"]
    assert any("CdA = 2" in w for w in still.warnings)


def test_a_study_line_from_a_system_file_asks_for_its_lines(tmp_path: Path) -> None:
    """``line: {moordyn: FILE}`` takes one chain; a whole system is not one line."""
    from cablestudy.interchange import InterchangeError, line_from_reference

    (tmp_path / "spread.dat").write_text(SPREAD)
    with pytest.raises(InterchangeError, match="do not form one chain.*line: \\[ids\\]"):
        line_from_reference("spread.dat", None, tmp_path)
    line, _ = line_from_reference("spread.dat", [5], tmp_path)  # anchor to coupled point
    assert [s["length"] for s in line["segments"]] == [320.0]


def test_a_system_in_a_current_survives_export_and_import(tmp_path: Path, capsys) -> None:
    """The current table and the free points' drag (MoorDyn's CdA) are written and read
    back: the re-imported system (the same lines, each its own drag elements: NumSegs 20
    as nodes 21) has the same statics, to 1e-9 of the largest tension (the two solves'
    tolerance 1e-10; only Newton's start differs)."""
    config = tmp_path / "cur.yaml"
    text = (CONFIGS / "system-spread-bridles.yaml").read_text()
    text = text.replace(
        "  depth: 100.0\n",
        "  depth: 100.0\n  current: [{z: 0.0, speed: 0.8, heading_deg: 30.0}, "
        "{z: -100.0, speed: 0.2, heading_deg: 30.0}]\n",
    )
    for k in "123":
        text = text.replace(
            f"junction{k}: {{kind: free, position: [",
            f"junction{k}: {{kind: free, drag_area: 3.0, position: [",
        )
    config.write_text(text)
    exported, back = _round_trip(config, tmp_path, capsys, ["--case", "surge=4.0"])
    assert "1  Currents" in exported and (tmp_path / "current_profile.txt").exists()
    assert [p.get("drag_area", 0.0) for p in back.data["points"].values()].count(3.0) == 3
    _, cases = expand_cases(read_study_source(config))
    (case,) = [c for c in cases if c.coords["surge"] == 4.0]
    original = evaluate_system_case(case)
    assert original.status == 0, original.message
    again = _solve(back)
    largest = float(np.max(original.data["tension_b"]))
    for key in ("tension_a", "tension_b"):
        np.testing.assert_allclose(again[key], original.data[key], rtol=0.0, atol=1e-9 * largest)


def test_a_body_waterplane_is_refused_by_the_moordyn_export(tmp_path: Path, capsys) -> None:
    config = tmp_path / "free.yaml"
    config.write_text(
        FREE_BODY.replace("    mass: 20000.0\n", "    mass: 20000.0\n    waterplane_area: 3.0\n")
    )
    out = tmp_path / "exported.dat"
    assert main(["export", "moordyn", str(config), "--out", str(out)]) != 0
    err = capsys.readouterr().err
    assert "bodies.buoy.waterplane_area: 3.0 m^2" in err and "allowed: 0" in err
    assert not out.exists()
