"""MoorDyn input files and RAFT/MoorPy mooring YAML into studies, and back.

The input files here are written for the tests from the format's documentation
(moordyn.readthedocs.io, "Input Files": the v1 and v2 layouts)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cablestudy.cli import main
from cablestudy.interchange import (
    FEATURES,
    InterchangeError,
    NotModelledError,
    import_model,
    imported_yaml,
    parse_moordyn,
)
from cablestudy.interchange.export import moordyn_input
from cablestudy.interchange.moordyn_format import attachment_ref
from cablestudy.physics.contact import default_seabed_stiffness
from cablestudy.study.loader import StudyError, parse_study_text, read_study_source, validate_data
from cablestudy.study.problem import line_model

V2 = """--------------------- MoorDyn Input File ------------------------------------
Chain - clump - polyester, version 2 layout
---------------------- LINE TYPES -----------------------------------------------------
TypeName   Diam    Mass/m     EA     BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)    (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
chain      0.1     150.0      1e9    -0.8        0          2.4    1.0    1.15    0.5   ! studless
# a comment line inside the table

poly       0.2     30.0       2e8    -0.5        12.5       1.2    0.9    0.01    0.1
---------------------- POINTS ---------------------------------------
ID   Attachment  X       Y     Z      Mass   Volume  CdA    Ca
(#)   (word/ID) (m)     (m)   (m)    (kg)   (m^3)   (m^2)  (-)
1     Fixed      -800    0     -200    0      0       0      0
2     Free       -400    0     -190    5000   0.5     0      0
3     Coupled    -40     0     -15     0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (ID)     (ID)      (m)       (-)      (-)
1     chain       1        2        450        30       -
2     poly        2        3        400        20       -
---------------------- OPTIONS -----------------------------------------
0.5           TmaxIC        max time for IC gen (s)
200           WtrDpth       water depth (m)
9.80665       g             % gravity

1025          rho
0.001         dtM           time step
3e6           kBot          bottom stiffness (Pa/m)
0.5           FrictionCoefficient
------------------------- need this line -------------------------------------
"""

# version 1: other section names, hydrodynamic columns Can Cat Cdn Cdt, point forces,
# lines as Line LineType UnstrLen NumSegs NodeAnch NodeFair; options in another order
V1 = """MoorDyn input file...
MoorDyn v1 sample input file
True          Echo          echo the input file data (flag)
----------------------- LINE DICTIONARY ---------------------------------------------
LineType  Diam    MassDen    EA       BA/-zeta   Can   Cat   Cdn   Cdt
(-)       (m)     (kg/m)     (N)      (Pa-s/-)   (-)   (-)   (-)   (-)
nylon    0.124    13.76    2515288.0    -0.8     1.0   0.2   1.6   0.05
----------------------- NODE PROPERTIES ----------------------------------------------
Node      Type      X        Y         Z        M        V        FX       FY      FZ     CdA   CA
(-)       (-)      (m)      (m)       (m)      (kg)     (m^3)    (kN)     (kN)    (kN)   (m^2)  (-)
1         Vessel     0.0     0      -10.00       0        0        0        0       0       0     0
2         Fixed    267.0     0      -70.00       0        0        0        0       0       0     0
3         Connect  150.0     0      -60.00       0        0        0        0     -100      0     0
-------------------------- LINE PROPERTIES -------------------------------------------------
Line     LineType  UnstrLen  NumSegs    NodeAnch  NodeFair  Flags/Outputs
(-)      (-)       (m)         (-)       (-)       (-)      (-)
1        nylon     150.0        20        2         3        p
2        nylon     160.0        20        3         1        -
-------------------------- SOLVER OPTIONS---------------------------------------------------
70       WtrDpth      - water depth
0.001    dtM          - time step to use in mooring integration
5.0      ICDfac       - factor by which to scale drag coefficients during dynamic relaxation
1020     rhoW         - water density
---------------------- OUTPUTS -----------------------------------------
FairTen1
AnchTen1
END
------------------------- need this line -------------------------------------
"""


def _validated(imported):
    text = imported_yaml(imported, "test")
    src = parse_study_text(text, "<imported>")
    return validate_data(src.data, src), text


def test_v2_file_with_comments_blank_lines_and_options_in_any_order() -> None:
    imported = import_model(V2, "v2.dat")
    study, text = _validated(imported)
    seg = study.line.segments
    assert [s.length for s in seg] == [450.0, 400.0]
    chain, poly = seg
    assert (chain.diameter, chain.mass_per_length, chain.axial_stiffness) == (0.1, 150.0, 1e9)
    assert (chain.drag_normal, chain.added_mass_normal) == (2.4, 1.0)
    assert (chain.drag_tangential, chain.added_mass_tangential) == (1.15, 0.5)
    assert chain.damping_ratio == 0.8  # BA/-zeta = -0.8: a ratio
    assert (poly.bending_stiffness, poly.added_mass_normal, poly.added_mass_tangential) == (
        12.5,
        0.9,
        0.1,
    )
    (att,) = study.line.attachments
    assert (att.s, att.mass, att.volume) == (450.0, 5000.0, 0.5)
    assert study.ends.a.position == [-800.0, 0.0, -200.0]  # the fixed point: anchor end
    assert study.ends.b.position == [-40.0, 0.0, -15.0]  # the coupled fairlead, held
    env = study.environment
    assert (env.depth, env.gravity, env.density, env.seabed.friction) == (200.0, 9.80665, 1025, 0.5)
    assert study.analysis.static.nodes == 51  # 30 + 20 MoorDyn segments
    # comments point at the source lines
    assert "v2.dat:6 type chain; v2.dat:19 line 1" in text
    assert "v2.dat:14 point 2" in text
    # not modelled: named, not dropped
    warned = "\n".join(imported.warnings)
    assert "kBot" in warned and "seabed stiffness" in warned
    assert "dtM" in warned and "TmaxIC" in warned


def test_v1_layout_maps_columns_by_version() -> None:
    md = parse_moordyn(V1, "v1.dat")
    assert md.version == 1
    imported = import_model(V1, "v1.dat")
    study, _ = _validated(imported)
    (seg,) = study.line.segments  # two nylon lines through a connect point: one segment
    assert seg.length == 310.0
    # v1 order Can Cat Cdn Cdt
    assert (seg.added_mass_normal, seg.added_mass_tangential) == (1.0, 0.2)
    assert (seg.drag_normal, seg.drag_tangential) == (1.6, 0.05)
    assert seg.bending_stiffness == 0.0
    (att,) = study.line.attachments
    assert att.s == 150.0 and att.force == [0.0, 0.0, -100.0]
    assert study.ends.a.position == [267.0, 0.0, -70.0]  # the fixed anchor starts the chain
    assert study.ends.b.position == [0.0, 0.0, -10.0]
    assert study.environment.density == 1020.0
    assert study.environment.gravity == 9.80665  # v1 default
    warned = "\n".join(imported.warnings)
    assert "Echo" not in warned or "Echo" in warned  # front matter is free-form
    assert "ICDfac" in warned and "FairTen1" in warned and "outputs 'p'" in warned


def test_chosen_lines_and_free_end() -> None:
    # line 1 alone ends at the clump point 2, which also holds line 2: where it settles
    # depends on line 2, so one line of it is refused, naming the junction
    with pytest.raises(NotModelledError, match="free point 2 joins the chosen lines") as info:
        import_model(V2, "v2.dat", lines=[1])
    assert info.value.features == ("systems",)
    # without line 2 the clump hangs on line 1 alone: a towing end loaded by the clump's
    # weight in water
    alone = V2.replace("2     poly        2        3        400        20       -\n", "")
    imported = import_model(alone, "v2.dat", lines=[1])
    study, _ = _validated(imported)
    assert study.ends.b.kind == "force"
    expected = -(5000.0 * 9.80665 - 0.5 * 1025.0 * 9.80665)
    assert study.ends.b.force == pytest.approx([0.0, 0.0, expected], rel=1e-15)
    assert study.line.attachments == []


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (("poly       0.2     30.0       2e8", "poly 0.2 30.0 polyEA.txt"), "tension-strain"),
        (("2     poly        2        3", "2     wire        2        3"), "line type 'wire'"),
        (("1     chain       1        2        450        30       -", "1 chain 1 2 450"), "needs"),
        (("2     Free       -400", "2     Fixed       -400"), "must be free"),
        (("3     Coupled    -40     0     -15", "3     Coupled    -40     0     x"), "Z must be"),
    ],
)
def test_errors_name_the_line_and_the_fault(edit: tuple[str, str], message: str) -> None:
    bad = V2.replace(*edit)
    assert bad != V2
    with pytest.raises(InterchangeError, match=message) as info:
        import_model(bad, "bad.dat")
    assert "bad.dat" in str(info.value)


def test_branched_system_is_refused_with_advice() -> None:
    bridle = V2.replace(
        "2     poly        2        3        400        20       -",
        "2     poly        2        3        400        20       -\n3 poly 2 1 100 5 -",
    )
    with pytest.raises(InterchangeError, match="meet at point 2.*without --line"):
        import_model(bridle, "bridle.dat", lines=[1, 2, 3])
    # without --line the whole file is one system study: the junction is a free point
    study, _ = _validated(import_model(bridle, "bridle.dat"))
    assert list(study.lines) == ["1", "2", "3"]
    assert study.points["point2"].kind == "free" and study.points["point2"].mass == 5000.0
    # one chain of it still meets line 3 at the free point 2, which line 3 pulls on
    with pytest.raises(NotModelledError, match="point 2 joins the chosen lines to line.s. 3"):
        import_model(bridle, "bridle.dat", lines=[1, 2])


def _roundtrip(text: str) -> tuple:
    src = parse_study_text(text, "<study>")
    study = validate_data(src.data, src)
    a, b = (np.asarray(e.position, dtype=float) for e in (study.ends.a, study.ends.b))
    s = np.linspace(0.0, study.line.length, 11)
    guess = a + (b - a) * (s / s[-1])[:, None]
    exported = moordyn_input(
        study,
        end_positions=(a, b),
        position_at=guess,
        s_nodes=s,
        coupled_ends={"b"},
        title="test",
    )
    back = import_model(exported.text, "exported.dat")
    back_src = parse_study_text(imported_yaml(back, "exported.dat"), "<back>")
    return study, validate_data(back_src.data, back_src), exported


STUDY = """
name: roundtrip
environment: {fluid: water, gravity: 9.80665, depth: 300.0, seabed: {friction: 0.3}}
line:
  segments:
    - {length: 120.0, diameter: 0.08, mass_per_length: 40.0, axial_stiffness: 5.0e8,
       drag_normal: 1.1, drag_tangential: 0.02, added_mass_normal: 0.8,
       added_mass_tangential: 0.1, bending_stiffness: 3.0, damping_ratio: 0.4}
    - {length: 100.0, diameter: 0.12, mass_per_length: 20.0, axial_stiffness: 2.0e8}
  attachments:
    - {s: 60.0, mass: 800.0, volume: 0.1}
    - {s: 120.0, volume: 2.5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -250.0]}
  b: {kind: fixed, position: [140.0, 0.0, -120.0]}
analysis:
  static: {nodes: 45}
"""


def test_import_of_export_gives_back_the_study() -> None:
    """Everything comes back as written, and the seabed contact comes back explicit:
    the default stiffness (the heaviest segment's weight over 1 mm) and damping ratio,
    through MoorDyn's kBot, cBot on the thickest segment's diameter; the undamped second
    segment comes back with the axial damping the file gives it for MoorDyn's RK2."""
    study, back, exported = _roundtrip(STUDY)
    sb = back.environment.seabed
    assert sb.stiffness == pytest.approx(
        default_seabed_stiffness(line_model(study).weight), rel=1e-14
    )
    assert sb.damping_ratio == pytest.approx(study.environment.seabed.damping_ratio, rel=1e-14)
    explicit = study.environment.seabed.model_copy(
        update={"stiffness": sb.stiffness, "damping_ratio": sb.damping_ratio}
    )
    assert back.environment == study.environment.model_copy(update={"seabed": explicit})
    zeta = back.line.segments[1].damping_ratio
    assert 0.0 < zeta < 0.07  # (omega dtM)^3 / 4 at omega dtM <= 2 pi / 10
    undamped = study.line.segments[1].model_copy(update={"damping_ratio": zeta})
    assert back.line == study.line.model_copy(
        update={"segments": [study.line.segments[0], undamped]}
    )
    assert back.ends == study.ends
    assert back.analysis.static.nodes == study.analysis.static.nodes
    assert exported.time_step > 0.0


def test_roundtrip_of_a_line_given_by_weight_keeps_its_physics() -> None:
    text = STUDY.replace("mass_per_length: 20.0", "weight_in_fluid: 80.0")
    study, back, _ = _roundtrip(text)
    mine, theirs = line_model(study), line_model(back)
    for name in ("weight", "mass", "length", "axial_stiffness", "attachment_force"):
        np.testing.assert_allclose(getattr(theirs, name), getattr(mine, name), rtol=1e-14)


def test_export_time_step_resolves_the_axial_mode() -> None:
    study, _, exported = _roundtrip(STUDY)
    # fastest segment: the stiffest per length; pi l / (10 c) must bound dtM from above
    seg = study.line.segments[0]
    l = 60.0 / max(1, round(44 * 60.0 / 220.0))
    area = math.pi * seg.diameter**2 / 4
    c = math.sqrt(seg.axial_stiffness / (seg.mass_per_length + 1025.0 * area * 0.1))
    assert exported.time_step <= math.pi * l / (10 * c)
    assert exported.time_step > math.pi * l / (10 * c) / 2.5  # 1-2-5 rounding loses < 2.5x
    assert "dtM" in exported.text and "explicit" in exported.text
    # the undamped second segment (5 m nodes): the damping ratio (omega dtM)^3 / 4 of its
    # fastest axial mode omega = 2 c / l keeps MoorDyn's RK2 from amplifying it
    c2 = math.sqrt(2.0e8 / 20.0)
    row = next(r for r in exported.text.splitlines() if r.startswith("seg2 "))
    zeta = (2.0 * c2 / 5.0 * exported.time_step) ** 3 / 4.0
    assert float(row.split()[4]) == pytest.approx(-zeta, rel=1e-12)
    assert any("BA = -" in w for w in exported.warnings)


MOORPY = """
mooring:
  water_depth: 200.0
  points:
    - {name: anchor, type: fixed, location: [-800.0, 0.0, -200.0], anchor_type: drag}
    - {name: clump, type: free, location: [-400.0, 0.0, -190.0], mass: 5000.0}
    - {name: fairlead, type: vessel, location: [-40.0, 0.0, -15.0]}
  lines:
    - {name: bottom, endA: anchor, endB: clump, type: chain, length: 450.0}
    - {name: top, endA: clump, endB: fairlead, type: chain, length: 400.0}
  line_types:
    - {name: chain, diameter: 0.1, mass_density: 150.0, stiffness: 1.0e9,
       breaking_load: 1.0e7, cost: 100.0, transverse_added_mass: 1.0,
       tangential_added_mass: 0.5, transverse_drag: 2.4, tangential_drag: 1.15}
  anchor_types:
    - {name: drag, mass: 1.0e4}
"""


def test_moorpy_mooring_yaml() -> None:
    imported = import_model(MOORPY, "design.yaml")
    study, _ = _validated(imported)
    (seg,) = study.line.segments
    assert (seg.length, seg.mass_per_length, seg.drag_normal) == (850.0, 150.0, 2.4)
    assert study.line.attachments[0].mass == 5000.0
    assert study.environment.depth == 200.0
    # a design YAML gives no gravity: MoorPy's default, not MoorDyn's 9.80665
    assert study.environment.gravity == 9.81 and study.environment.density == 1025.0
    assert imported.comments[("environment", "gravity")] == "MoorPy default g = 9.81"
    warned = "\n".join(imported.warnings)
    for key in ("breaking_load", "cost", "anchor_types", "anchor_type"):
        assert key in warned
    # lines by name; one of them alone ends at the clump that the other holds too
    both = import_model(MOORPY, "design.yaml", lines=["top", "bottom"])
    assert both.data["line"]["segments"][0]["length"] == 850.0
    with pytest.raises(NotModelledError, match="free point 2 joins"):
        import_model(MOORPY, "design.yaml", lines=["bottom"])


def test_current_table_is_read_beside_the_file(tmp_path: Path) -> None:
    (tmp_path / "current_profile.txt").write_text(
        "header\nnotes\nz ux uy uz\n-200 0.3 0.0 0\n-100 0.0 0.4 0\n0 0.6 0.8 0\n"
    )
    text = V2.replace("0.5           FrictionCoefficient", "1 Currents\n0.5 FrictionCoefficient")
    imported = import_model(text, "v2.dat", folder=tmp_path)
    study, _ = _validated(imported)
    cur = {p.z: (p.speed, p.heading_deg) for p in study.environment.current}
    assert cur[-200.0] == pytest.approx((0.3, 0.0))
    assert cur[-100.0] == pytest.approx((0.4, 90.0))
    assert cur[0.0] == pytest.approx((1.0, math.degrees(math.atan2(0.8, 0.6))))
    assert not any("Currents" in w for w in imported.warnings)


def _write_ref(tmp_path: Path, ref: str, extra: str = "") -> Path:
    (tmp_path / "models").mkdir(exist_ok=True)
    (tmp_path / "models" / "system.dat").write_text(V2)
    study = tmp_path / "study.yaml"
    study.write_text(
        f"""name: by-reference
environment: {{fluid: water, depth: 1000.0}}
line: {ref}
ends:
  a: {{kind: fixed, position: [-800.0, 0.0, -200.0]}}
  b: {{kind: fixed, position: [-40.0, 0.0, -15.0]}}
analysis:
  static: {{method: discrete}}  # the poly line type bends (EI 12.5 N m^2)
{extra}"""
    )
    return study


def test_study_refers_to_a_moordyn_file_and_sweeps_it(tmp_path: Path) -> None:
    from cablestudy.study.grid import expand_cases

    path = _write_ref(
        tmp_path,
        "{moordyn: models/system.dat, line: [1, 2]}",
        "sweep:\n  line.segments.0.length: [440.0, 450.0]\n",
    )
    src = read_study_source(path)
    assert any("seabed.stiffness" in n and "is not used" in n for n in src.notes)
    axes, cases = expand_cases(src)
    assert [c.study.line.segments[0].length for c in cases] == [440.0, 450.0]
    assert cases[0].study.line.attachments[0].mass == 5000.0
    # end to end: YAML -> netCDF
    import xarray as xr

    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "out" / "by-reference.nc") as ds:
        assert ds.sizes["length"] == 2
        assert (ds.status.values == 0).all()
        # the referenced file travels with the study text into the result
        assert "#| chain      0.1     150.0      1e9" in ds.attrs["study_yaml"]
        sha = ds.attrs["study_sha256"]
    (tmp_path / "models" / "system.dat").write_text(V2.replace("150.0 ", "151.0 "))
    assert read_study_source(path).sha256 != sha


def test_schema_allows_a_line_reference() -> None:
    from cablestudy.study import Study

    line = Study.model_json_schema()["properties"]["line"]
    assert line["anyOf"][0] == {"$ref": "#/$defs/Line"}
    assert set(line["anyOf"][1]["properties"]) == {"moordyn", "line"}


@pytest.mark.parametrize(
    ("ref", "message"),
    [
        ("{moordyn: ../outside.dat}", "outside the study file's folder"),
        ("{moordyn: /etc/passwd}", "absolute path"),
        ("{moordyn: models/none.dat}", "no such file"),
        ("{moordyn: models/system.dat, line: 7}", "no line 7"),
        ("{moordyn: models/system.dat, lines: 1}", "unknown key"),
    ],
)
def test_reference_errors_point_at_the_line_key(tmp_path: Path, ref: str, message: str) -> None:
    (tmp_path.parent / "outside.dat").write_text(V2)
    path = _write_ref(tmp_path, ref)
    with pytest.raises(StudyError, match=message) as info:
        read_study_source(path)
    assert "study.yaml:3: line" in str(info.value)


def test_cli_import_writes_a_valid_study(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    model = tmp_path / "Mooring System.dat"
    model.write_text(V1)
    assert main(["import", "moordyn", str(model)]) == 0
    out = capsys.readouterr()
    assert "not modelled" in out.err and "ICDfac" in out.err
    study_file = tmp_path / "study.yaml"
    study_file.write_text(out.out)
    assert main(["validate", str(study_file)]) == 0
    assert "Mooring-System" in capsys.readouterr().out
    assert main(["import", "moordyn", str(model), "--line", "9"]) == 2
    assert "no line 9" in capsys.readouterr().err


def test_moorpy_defaults_are_moorpys_own() -> None:
    """The gravity and density a design YAML leaves out are MoorPy's defaults, read from
    MoorPy itself (``moorpy.System``'s signature) when it is installed."""
    mp = pytest.importorskip("moorpy", reason="MoorPy is in the optional extra `peers`")
    import inspect

    from cablestudy.interchange.mapping import DEFAULT_DENSITY, MOORPY_GRAVITY

    params = inspect.signature(mp.System).parameters
    assert (params["g"].default, params["rho"].default) == (MOORPY_GRAVITY, DEFAULT_DENSITY)


def test_cli_import_moorpy_and_export_round_trip(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    design = tmp_path / "design.yaml"
    design.write_text(MOORPY)
    assert main(["import", "moorpy", str(design), "--line", "bottom", "--line", "top"]) == 0
    out = capsys.readouterr()
    assert "breaking_load" in out.err
    assert main(["import", "moorpy", str(tmp_path / "design.yaml").replace("design", "none")]) == 2
    capsys.readouterr()
    dat = tmp_path / "v1.dat"
    dat.write_text(V1)
    assert main(["import", "moorpy", str(dat)]) == 2
    assert "not a RAFT/MoorPy mooring YAML" in capsys.readouterr().err
    # export of a swept study needs its case
    study = tmp_path / "study.yaml"
    study.write_text(STUDY + "sweep:\n  line.segments.0.length: [110.0, 120.0]\n")
    assert main(["export", "moordyn", str(study)]) == 2
    assert "--case" in capsys.readouterr().err and True
    assert main(["export", "moordyn", str(study), "--case", "span=3"]) == 2
    assert "no sweep dimension 'span'; dimensions: length" in capsys.readouterr().err
    target = tmp_path / "out" / "case.dat"
    assert (
        main(["export", "moordyn", str(study), "--case", "length=110", "--out", str(target)]) == 0
    )
    capsys.readouterr()
    back = import_model(target.read_text(), "case.dat")
    assert back.data["line"]["segments"][0]["length"] == pytest.approx(110.0)


def test_current_round_trip_through_the_table_beside_the_file(tmp_path: Path) -> None:
    study = tmp_path / "study.yaml"
    current = (
        "  current:\n"
        "    - {z: -300.0, speed: 0.3, heading_deg: 45.0}\n"
        "    - {z: 0.0, speed: 0.5, heading_deg: 0.0}\n"
    )
    text = STUDY.replace(
        "environment: {fluid: water, gravity: 9.80665, depth: 300.0, seabed: {friction: 0.3}}",
        "environment:\n  fluid: water\n  depth: 300.0\n" + current,
    )
    study.write_text(text)
    target = tmp_path / "md" / "case.dat"
    assert main(["export", "moordyn", str(study), "--out", str(target)]) == 0
    assert (target.parent / "current_profile.txt").exists()
    assert main(["export", "moordyn", str(study)]) == 2  # the table needs a folder
    back = import_model(target.read_text(), "case.dat", folder=target.parent)
    src = parse_study_text(text, "<s>")
    original = validate_data(src.data, src).environment.current
    got = back.data["environment"]["current"]
    assert [p["z"] for p in got] == [p.z for p in original]
    for p, q in zip(got, original, strict=True):
        assert p["speed"] == pytest.approx(q.speed, rel=1e-15)
        assert p["heading_deg"] == pytest.approx(q.heading_deg, abs=1e-12)


def test_unmodelled_sections_and_moordyn_f_options_are_named() -> None:
    text = V2.replace(
        "---------------------- POINTS",
        "---------------------- ROD TYPES ------\nName Diam Mass Cd Ca CdEnd CaEnd\n"
        "(-) (m) (kg/m) (-) (-) (-) (-)\nBuoy 10 1e3 0.6 1.0 1.2 1.0\n"
        "---------------------- BODIES ------\nID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I V CdA Ca\n"
        "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m2) (m3) (m2) (-)\n"
        "1 coupled 0 0 0 0 0 0 0 0 0 0 0 0\n"
        "---------------------- POINTS",
    ).replace("0.5           FrictionCoefficient", "0.4 MU_KT\n0.2 MU_KA\n2 WaveKin")
    imported = import_model(text, "f.dat")
    warned = "\n".join(imported.warnings)
    assert "section ROD TYPES (1 entries)" in warned
    assert "section BODIES (1 entries)" in warned
    assert "MU_KA = 0.2" in warned and "WaveKin = 2" in warned
    assert imported.data["environment"]["seabed"]["friction"] == 0.4


def test_current_table_missing_or_unreadable(tmp_path: Path) -> None:
    text = V2.replace("0.5           FrictionCoefficient", "1 Currents")
    with pytest.raises(InterchangeError, match="current_profile.txt: no such file"):
        import_model(text, "v2.dat", folder=tmp_path)
    with pytest.raises(InterchangeError, match="Currents 1 reads current_profile.txt"):
        import_model(text, "v2.dat")
    (tmp_path / "current_profile.txt").write_text("a\nb\nc\n-10 0.5 0 0.2\n")
    with pytest.raises(InterchangeError, match="vertical current"):
        import_model(text, "v2.dat", folder=tmp_path)


def test_chain_between_two_free_points_is_imported_with_a_warning() -> None:
    text = V2.replace("1     Fixed      -800", "1     Free       -800").replace(
        "3     Coupled    -40", "3     Free       -40"
    )
    imported = import_model(text, "free.dat")
    assert {e["kind"] for e in imported.data["ends"].values()} == {"force"}
    assert any("no fixed end" in w for w in imported.warnings)
    assert "vessel frame" in imported_yaml(import_model(V1, "v1.dat"), "v1.dat")


def test_seabed_contact_and_point_bodies_map_both_ways() -> None:
    """kBot [Pa/m] x the thickest segment's diameter is the study's contact stiffness per
    length; cBot (default 3e5 Pa s/m) over that spring's critical damping its damping
    ratio; an inside point's CdA is a body's drag area and its Ca rho V its added mass;
    exporting writes them back (to the last digit)."""
    text = V2.replace(
        "2     Free       -400    0     -190    5000   0.5     0      0",
        "2     Free       -400    0     -190    5000   0.5     1.5    0.8",
    )
    imported = import_model(text, "v2.dat")
    env = imported.data["environment"]["seabed"]
    assert env["stiffness"] == pytest.approx(3e6 * 0.2, rel=1e-15)
    m_n = 30.0 + 1025.0 * math.pi * 0.2**2 / 4 * 0.9
    assert env["damping_ratio"] == pytest.approx(3e5 * 0.2 / (2 * math.sqrt(6e5 * m_n)))
    att = imported.data["line"]["attachments"][0]
    assert att["drag_area"] == 1.5
    assert att["added_mass"] == pytest.approx(0.8 * 1025.0 * 0.5)
    assert any("thinner segments rest on a stiffer seabed" in w for w in imported.warnings)
    assert not any("CdA" in w for w in imported.warnings)
    study, _ = _validated(imported)
    a, b = (np.asarray(e.position, dtype=float) for e in (study.ends.a, study.ends.b))
    s = np.linspace(0.0, study.line.length, 11)
    exported = moordyn_input(
        study,
        end_positions=(a, b),
        position_at=a + (b - a) * (s / s[-1])[:, None],
        s_nodes=s,
        coupled_ends={"b"},
        title="t",
    )
    back = import_model(exported.text, "e.dat")
    assert back.data["environment"]["seabed"]["stiffness"] == pytest.approx(6e5, rel=1e-14)
    assert back.data["line"]["attachments"][0]["drag_area"] == 1.5
    assert back.data["line"]["attachments"][0]["added_mass"] == pytest.approx(att["added_mass"])


# ---------------------------------------------------------------- the peers' own files
# Every MoorDyn input file of MoorDyn's and MoorPy's repositories (tests/data/README.md)
# is read whole, and each of its lines imported alone with `cablestudy import moordyn
# FILE --line N` (and all its lines as one chain where they form one): each import is
# a study that validates and whose statics solve (status 0), or a refusal that names
# features cablestudy does not have (FEATURES). A parse error fails the test.
DATA = Path(__file__).parents[1] / "data"
PEER_FILES = sorted(
    p
    for p in DATA.rglob("*")
    if p.suffix in (".txt", ".dat")
    and p.name != "current_profile.txt"
    and not p.name.startswith("LICENSE")
)
#: a file MoorDyn itself refuses (moordyn 2.7.2 Create fails: "Rod ID must be sequential
#: starting from 1"): the reader refuses it too, naming the fault
MOORDYN_REFUSES = {"moordyn/bench/Mooring/floating_rods.txt": "rod ID 3 is defined twice"}
#: imports whose statics are refused, naming why (the import itself is right): (file,
#: line or None for the whole chain) -> message. Both are shapes the statics cannot
#: determine or model, not solver failures (MoorDyn's pinnedBody.txt line 1 and MoorPy's
#: case4 solve since issue 22's follow-up: a vertical line's closed form, a lazy wave's
#: touchdown guess)
SOLVER_GAPS = {
    # 890 m of line on a 700 m path: the slack lies on the seabed, its shape undetermined
    ("moorpy/tests/case5.dat", 1): "laid shape is not determined",
    # a W: a 200 m^3 buoy between two stretches on the seabed (MoorPy's own
    # solveEquilibrium fails on this file too; method discrete solves it,
    # tests/validation/test_laid_buoy.py)
    ("moorpy/tests/case6.dat", None): "lifts the line off the seabed between two touchdowns",
}

#: files whose lines do not form one chain and which import whole (no --line) as one
#: system study; the others refused as systems name what a system lacks (README)
SYSTEMS = {
    "moordyn/example/MHK_RM1_Floating/MHK_RM1_Floating_MoorDyn.dat",
    "moordyn/example/body.txt",
    "moordyn/example/lines.txt",
    "moordyn/tests/Mooring/lines.txt",
    "moordyn/tests/Mooring/local_euler/duplicated.txt",
    "moorpy/examples/sample.txt",
    "moorpy/tests/case8.dat",
    "moorpy/tests/case9.dat",
}


def test_the_peer_files_are_all_here() -> None:
    """54 MoorDyn inputs from MoorDyn (tests/Mooring, example, bench) and 13 from MoorPy."""
    tops = [p.relative_to(DATA).parts[0] for p in PEER_FILES]
    assert (tops.count("moordyn"), tops.count("moorpy")) == (54, 13)
    for top in ("moordyn", "moorpy"):
        assert "BSD 3-Clause" in (DATA / top / "LICENSE.txt").read_text()
        assert all(
            p.relative_to(DATA / top).as_posix() in (DATA / "README.md").read_text()
            for p in PEER_FILES
            if p.is_relative_to(DATA / top)
        )


def _import_cli(path: Path, line: int | None, capsys: pytest.CaptureFixture) -> tuple:
    args = ["import", "moordyn", str(path)] + ([] if line is None else ["--line", str(line)])
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def _statics(study_text: str) -> tuple[int, str]:
    from cablestudy.analyses.evaluate import check_supported
    from cablestudy.analyses.static import solve_static
    from cablestudy.study.grid import expand_cases

    src = parse_study_text(study_text, "<imported>")
    _, cases = expand_cases(src)
    if cases[0].study.is_system:  # a whole file of lines joined at points
        from cablestudy.analyses.system import evaluate_system_case

        record = evaluate_system_case(cases[0])
        return record.status, record.message
    check_supported(cases, src)  # every key of the imported study is one a solver uses
    result = solve_static(cases[0], None)
    return result.status, result.message


@pytest.mark.parametrize("path", PEER_FILES, ids=lambda p: p.relative_to(DATA).as_posix())
def test_peer_file_imports_or_names_what_cablestudy_lacks(
    path: Path, capsys: pytest.CaptureFixture
) -> None:
    rel = path.relative_to(DATA).as_posix()
    if rel in MOORDYN_REFUSES:
        with pytest.raises(InterchangeError, match=MOORDYN_REFUSES[rel]):
            parse_moordyn(path.read_text(), rel)
        return
    md = parse_moordyn(path.read_text(), rel)
    # the parse is whole: every line's type and ends, every rod's type, every body point's
    # body are defined in the file
    for ln in md.lines.values():
        assert ln.line_type in md.line_types
        for end in (ln.attach_a, ln.attach_b):
            kind, number, _ = attachment_ref(end)
            assert number in (md.rods if kind == "rod" else md.points), (rel, end)
    assert all(rd.rod_type in md.rod_types for rd in md.rods.values())
    assert all(pt.body in md.bodies for pt in md.points.values() if pt.kind == "body")
    chains = [None] if len(md.lines) != 1 else []
    for line in [*sorted(md.lines), *chains]:
        code, out, err = _import_cli(path, line, capsys)
        if code != 0:
            assert err.startswith("cannot import:"), err
            named = [key for key, phrase in FEATURES.items() if phrase in err]
            assert named, f"{rel} line {line}: refused without naming a feature: {err}"
            continue
        study = parse_study_text(out, "<imported>")
        validate_data(study.data, study)
        assert ("lines" in study.data) == (line is None and rel in SYSTEMS), (rel, line)
        status, message = _statics(out)
        gap = SOLVER_GAPS.get((rel, line))
        if gap is None:
            assert status == 0, f"{rel} line {line}: {message}"
        else:
            assert status != 0 and gap in message, (rel, line, status, message)


def test_sections_open_by_key_word_and_tables_by_their_columns() -> None:
    """MoorDyn's rules: a key word anywhere in a --- line opens a section; the layout of a
    table is told by its columns (and, for lines, the header), not by the title."""
    text = (
        V2.replace(
            "---------------------- LINE TYPES ----", "---- LINE TYPES Chain studless 0.1m --"
        )
        .replace("---------------------- POINTS ----", "---- CONNECTION PROPERTIES ----")
        .replace("---------------------- LINES ----", "---- LINE PROPERTIES ----")
        .replace("---------------------- OPTIONS ----", "---- SOLVER OPTIONS ----")
    )
    md = parse_moordyn(text, "t.dat")
    assert (md.version, list(md.line_types), sorted(md.points)) == (2, ["chain", "poly"], [1, 2, 3])
    assert md.option("WtrDpth").value == "200"
    # a LINE DICTIONARY over 10 columns is the version 2 layout; 9 columns version 1
    v1 = parse_moordyn(V1, "v1.dat")
    assert v1.version == 1 and v1.line_types["nylon"].drag_normal == 1.6
    as_dict = parse_moordyn(text.replace("LINE TYPES Chain studless", "LINE DICTIONARY"), "d")
    assert as_dict.line_types["chain"].drag_tangential == 1.15  # CdAx, column 9
    # a header naming the v1 hydrodynamic order over 10 columns: read by position, noted
    mislabelled = text.replace("EI         Cd     Ca     CdAx    CaAx", "EI Can Cat Cdn Cdt")
    md = parse_moordyn(mislabelled, "m.dat")
    assert md.line_types["chain"].drag_normal == 2.4
    assert any("read by position as Cd Ca CdAx CaAx" in n for n in md.notes)
    # 12-column point rows carry a steady force, in either version
    forced = text.replace(
        "2     Free       -400    0     -190    5000   0.5     0      0",
        "2     Free       -400    0     -190    5000   0.5  0 0 -100   0      0",
    )
    assert parse_moordyn(forced, "f").points[2].force == (0.0, 0.0, -100.0)
    # the version 1 line order is told by the header's third column
    assert parse_moordyn(V1, "v1.dat").lines[1].attach_a == "2"


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ("---- LINES ----", "---- LINES and POINTS ----"),
            "names (lines and points|points and lines)",
        ),
        (("------------------------- need this line", "---- LINES ----\n"), "second"),
        (("3     Coupled    -40", "3     Tethered    -40"), "not one MoorDyn reads"),
        (("chain      0.1     150.0      1e9    -0.8 ", "chain 0.1 150.0 1e9 -0.8 0 1 "), "10, 11"),
    ],
)
def test_format_errors_name_line_and_rule(edit: tuple[str, str], message: str) -> None:
    text = V2.replace("---------------------- LINES ----", "---- LINES ----").replace(*edit)
    assert text != V2
    with pytest.raises(InterchangeError, match=message):
        parse_moordyn(text, "bad.dat")


def test_zero_gravity_rods_and_bodies_are_refused_by_name() -> None:
    no_g = V2.replace("9.80665       g ", "0.0           g ")
    with pytest.raises(NotModelledError, match=r"v2.dat:\d+: zero gravity \(option g = 0\)") as e:
        import_model(no_g, "v2.dat")
    assert e.value.features == ("zero_gravity",)
    rods_only = V2.split("---------------------- POINTS")[0].replace(
        "---------------------- LINE TYPES",
        "---- ROD TYPES ----\nName Diam Mass Cd Ca CdEnd CaEnd\n(-) (m) (kg/m) (-) (-) (-) (-)\n"
        "can 1 10 1 1 1 1\n---- RODS ----\nID Type Att Xa Ya Za Xb Yb Zb N Out\n"
        "(#) (-) (-) (m) (m) (m) (m) (m) (m) (-) (-)\n1 can free 0 0 0 0 0 -5 3 -\n"
        "---------------------- LINE TYPES",
    )
    md = parse_moordyn(rods_only, "r.dat")
    assert md.rods[1].end_b == (0.0, 0.0, -5.0) and md.rod_types["can"].drag_end == 1.0
    with pytest.raises(NotModelledError, match="no lines, only 1 rod") as e:
        import_model(rods_only, "r.dat")
    assert e.value.features == ("rods",)


BODY = """--- MoorDyn Input File ---
--- LINE TYPES ---
TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)
chain 0.1 150.0 1e9 -0.8 0 2.4 1.0 1.15 0.5
--- BODIES ---
ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*
(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1 coupled 10 20 -5 0 0 0 1e6 0|0|-2 1e8 1e3 0 0
--- POINTS ---
ID Attachment X Y Z Mass Volume CdA Ca
(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Fixed -400 20 -100 0 0 0 0
2 Body1 -30 0 -10 0 0 0 0
--- LINES ---
ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
(#) (name) (#) (#) (m) (-) (-)
1 chain 1 2 450 30 -
--- OPTIONS ---
100 WtrDpth
--- need this line ---
"""


def test_points_on_a_held_body_are_placed_by_it_and_moving_bodies_refused() -> None:
    """A point on a coupled (or fixed) body is at the body's position plus its offset;
    a free body is found by equilibrium, a pinned one turns, a rotated one turns its
    offsets: each is refused by name."""
    md = parse_moordyn(BODY, "b.dat")
    body = md.bodies[1]
    assert (body.center_of_gravity, body.inertia) == ((0.0, 0.0, -2.0), (1e8,) * 3)
    study, _ = _validated(import_model(BODY, "b.dat"))
    assert study.ends.b.position == [-20.0, 20.0, -15.0]
    for word, feature in (("free", "free_bodies"), ("CoupledPinned", "pinned_bodies")):
        with pytest.raises(NotModelledError) as e:
            import_model(BODY.replace("1 coupled 10", f"1 {word} 10"), "b.dat")
        assert e.value.features == (feature,)
    with pytest.raises(NotModelledError, match=r"turned by \[0.0, 0.0, 30.0\] deg"):
        import_model(BODY.replace("-5 0 0 0 1e6", "-5 0 0 30 1e6"), "b.dat")


def test_water_depth_as_moordyn_sets_it() -> None:
    """MoorDyn lowers the seabed to a point below WtrDpth (default 0)."""
    deep = BODY.replace("100 WtrDpth", "50 WtrDpth")
    imported = import_model(deep, "b.dat")
    assert imported.data["environment"]["depth"] == 100.0
    assert "point 1 lies below WtrDpth" in imported_yaml(imported, "b.dat")
    assert import_model(BODY, "b.dat").data["environment"]["depth"] == 100.0


def test_weightless_line_holding_a_mass_carries_its_weight() -> None:
    """MoorDyn's lifting test (tests/data, MoorDyn tests/Mooring/lifting.txt): a line of
    7.85398 kg/m, d = 0.1 m in water of 1000 kg/m^3 (nearly neutral) holds 1000 kg from a
    fixed point; the force on that point is the total weight in water, 1000 g plus the
    line's (m - rho pi d^2 / 4) g L, exactly, to the solver's relative tolerance 1e-9."""
    from cablestudy.analyses.static import solve_static
    from cablestudy.study.grid import expand_cases

    path = DATA / "moordyn/tests/Mooring/lifting.txt"
    imported = import_model(path.read_text(), path.name, folder=path.parent)
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, path.name), "<i>"))
    result = solve_static(cases[0], None)
    assert result.success
    g = 9.80665
    weight = 1000.0 * g + (7.85398 - 1000.0 * math.pi / 4.0 * 0.1**2) * g * 100.5
    assert result.force_a == pytest.approx([0.0, 0.0, -weight], abs=1e-9 * weight)


def test_lines_above_the_sea_surface() -> None:
    """MoorDyn gives segments above z = 0 no buoyancy: a line that cannot reach the
    surface from ends above it is a study in vacuum; one that may cross it is refused."""
    beam = DATA / "moordyn/tests/Mooring/BeamSimplySupported.txt"
    imported = import_model(beam.read_text(), beam.name)
    assert imported.data["environment"]["fluid"] == "vacuum"
    surface = DATA / "moordyn/tests/Mooring/wave_surface/wave_surface.txt"
    assert import_model(surface.read_text(), "s", lines=[3]).data["environment"]["fluid"] == (
        "water"
    )
    with pytest.raises(NotModelledError, match="ends at z = 3 m and 3 m, length 50 m") as e:
        import_model(surface.read_text(), "s", lines=[4])
    assert e.value.features == ("surface_crossing",)
