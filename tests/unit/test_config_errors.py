"""Bad study files fail before any work, each fault reported as
``file:line: yaml.path: what is wrong and what is allowed (got value)``.

Each case edits one line of a valid study and checks, through ``cablestudy validate``
(cablestudy.cli.main), the line number, the YAML path, the bad value and the allowed
values named in the message."""

from __future__ import annotations

from pathlib import Path

import pytest

from cablestudy.cli import main

#: a valid study; the comments give the line numbers the cases below refer to
BASE = """\
name: errs
environment:
  fluid: water
  depth: 200.0
line:
  segments:
    - length: 100.0
      diameter: 0.02
      mass_per_length: 2.466
      axial_stiffness: 6.283e7
ends:
  a: {kind: fixed, position: [0.0, 0.0, -40.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 11, tolerance: 1e-12}
"""
SWEEP_LINE = 17  # "sweep:" is line 16; its first key line 17


def _validate(tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str) -> str:
    path = tmp_path / "study.yaml"
    path.write_text(text)
    code = main(["validate", str(path)])
    out = capsys.readouterr()
    assert code == 2, out.out
    return out.err


def _edit(old: str, new: str, extra: str = "") -> str:
    assert old in BASE, old
    return BASE.replace(old, new, 1) + extra


# id -> (study text, line, fragments the message must contain: path, value, allowed)
CASES: dict[str, tuple[str, int, tuple[str, ...]]] = {
    "unknown-key": (
        _edit("    - length: 100.0", "    - lenght: 100.0"),
        7,
        (
            "line.segments.0.lenght",
            "unknown key 'lenght'",
            "did you mean 'length'",
            "allowed keys here:",
            "(got 100.0)",
        ),
    ),
    "wrong-type": (
        _edit("diameter: 0.02", 'diameter: "thin"'),
        8,
        ("line.segments.0.diameter", "must be a number", "(got 'thin')"),
    ),
    "quoted-number": (
        _edit("mass_per_length: 2.466", 'mass_per_length: "2.466"'),
        9,
        ("line.segments.0.mass_per_length", "must be a number", "(got '2.466')"),
    ),
    "negative-length": (
        _edit("length: 100.0", "length: -100.0"),
        7,
        ("line.segments.0.length", "greater than 0", "(got -100.0)"),
    ),
    "nan": (
        _edit("axial_stiffness: 6.283e7", "axial_stiffness: .nan"),
        10,
        ("line.segments.0.axial_stiffness", "finite number", "(got nan)"),
    ),
    "infinity": (
        _edit("depth: 200.0", "depth: .inf"),
        4,
        ("environment.depth", "finite number", "(got inf)"),
    ),
    "zero-diameter": (
        _edit("diameter: 0.02", "diameter: 0"),
        8,
        ("line.segments.0.diameter", "greater than 0", "(got 0)"),
    ),
    "unknown-fluid": (
        _edit("fluid: water", "fluid: oil"),
        3,
        ("environment.fluid", "'air', 'water' or 'vacuum'", "mapping", "(got 'oil')"),
    ),
    "unknown-end-kind": (
        _edit("b: {kind: fixed,", "b: {kind: fixd,"),
        13,
        ("ends.b.kind", "'fixed', 'force', 'mooring'", "(got 'fixd')"),
    ),
    "short-vector": (
        _edit("position: [0.0, 0.0, -40.0]", "position: [0.0, -40.0]"),
        12,
        ("ends.a.position", "at least 3 items", "(got [0.0, -40.0])"),
    ),
    "count-not-whole": (
        _edit("nodes: 11,", "nodes: 11.5,"),
        15,
        ("analysis.static.nodes", "whole number", "(got 11.5)"),
    ),
    "unknown-method": (
        _edit("method: analytic", "method: magic"),
        15,
        (
            "analysis.static.method",
            "unknown static method",
            "allowed: ",
            "analytic",
            "(got 'magic')",
        ),
    ),
    "missing-key": (
        BASE.replace("      axial_stiffness: 6.283e7\n", ""),
        7,
        (
            "line.segments.0.axial_stiffness",
            "required key 'axial_stiffness' is missing",
            "axial stiffness EA [N]",
        ),
    ),
    "end-below-seabed": (
        _edit("position: [0.0, 0.0, -40.0]", "position: [0.0, 0.0, -250.0]"),
        12,
        (
            "ends.a.position",
            "below the seabed",
            "allowed z >= seabed height",
            "(got [0.0, 0.0, -250.0])",
        ),
    ),
    "negative-mass-from-weight": (
        _edit("mass_per_length: 2.466", "weight_in_fluid: -1000.0"),
        9,
        (
            "line.segments.0.weight_in_fluid",
            "negative mass per length",
            "allowed weight_in_fluid >= ",
            "(got -1000.0)",
        ),
    ),
    "no-fixed-end": (
        _edit(
            "a: {kind: fixed, position: [0.0, 0.0, -40.0]}",
            "a: {kind: force, force: [0.0, 0.0, -40.0]}",
        ).replace(
            "b: {kind: fixed, position: [92.5, 0.0, -8.6]}",
            "b: {kind: mooring, force: [100.0, 0.0], z: -8.6}",
        ),
        11,
        ("ends:", "at least one end must be 'fixed'", "(got {'a': 'force', 'b': 'mooring'})"),
    ),
    "weightless-slack-fixed-ends": (
        _edit("mass_per_length: 2.466", "weight_in_fluid: 0.0"),
        13,
        (
            "ends.b.position",
            "no weight",
            "allowed: ends more than the line length apart",
            "(got [92.5, 0.0, -8.6])",
        ),
    ),
    "attachment-beyond-end": (
        _edit(
            "      axial_stiffness: 6.283e7\n",
            "      axial_stiffness: 6.283e7\n  attachments:\n"
            "    - {s: 150.0, force: [0.0, 0.0, -10.0]}\n",
        ),
        12,
        (
            "line.attachments.0.s",
            "beyond the end of the line",
            "allowed 0 <= s <= 100",
            "(got 150.0)",
        ),
    ),
    "duplicate-key": (
        _edit("      diameter: 0.02\n", "      diameter: 0.02\n      diameter: 0.03\n"),
        9,
        (
            "line.segments.0.diameter",
            "duplicate key 'diameter' (first given on line 8, again on line 9)",
            "allowed: each key once",
        ),
    ),
    "bad-name": (
        _edit("name: errs", "name: 'my study/1'"),
        1,
        ("name:", "usable as a file name", "(got 'my study/1')"),
    ),
    "yaml-syntax": (
        _edit("  depth: 200.0", "  depth: [200.0"),
        5,
        ("not valid YAML",),
    ),
    "sweep-path-does-not-exist": (
        BASE + "sweep:\n  line.segments.0.lenght: [50.0, 60.0]\n",
        SWEEP_LINE,
        (
            "sweep.line.segments.0.lenght",
            "does not exist",
            "did you mean 'length'",
            "allowed keys under line.segments.0",
            "(got 'line.segments.0.lenght')",
        ),
    ),
    "sweep-index-out-of-range": (
        BASE + "sweep:\n  line.segments.3.length: [50.0, 60.0]\n",
        SWEEP_LINE,
        (
            "sweep.line.segments.3.length",
            "list of 1 items",
            "allowed 0..0",
            "(got 'line.segments.3.length')",
        ),
    ),
    "empty-sweep": (
        BASE + "sweep:\n  line.segments.0.length: []\n",
        SWEEP_LINE,
        ("sweep.line.segments.0.length", "empty sweep axis", "at least one value", "(got [])"),
    ),
    "sweep-range-wrong-step": (
        BASE + "sweep:\n  line.segments.0.length: {start: 50, stop: 100, step: -5}\n",
        SWEEP_LINE,
        (
            "sweep.line.segments.0.length.step",
            "nonzero step with the sign of stop - start",
            "(got -5.0)",
        ),
    ),
    "sweep-range-num-zero": (
        BASE + "sweep:\n  line.segments.0.length: {start: 50, stop: 100, num: 0}\n",
        SWEEP_LINE,
        ("sweep.line.segments.0.length.num", "whole number >= 1", "(got 0)"),
    ),
    "sweep-duplicate-values": (
        BASE + "sweep:\n  line.segments.0.length: [50.0, 50.0]\n",
        SWEEP_LINE,
        ("sweep.line.segments.0.length", "listed twice", "distinct values", "(got [50.0, 50.0])"),
    ),
    "sweep-bad-value": (
        BASE + "sweep:\n  line.segments.0.length: [120.0, -5.0, 130.0]\n",
        SWEEP_LINE,
        (
            "line.segments.0.length (value from sweep.line.segments.0.length)",
            "greater than 0",
            "(got -5.0)",
            "[in sweep case {'length': -5.0}",
        ),
    ),
    "sweep-bad-value-in-a-block-list": (
        BASE + "sweep:\n  line.segments.0.length:\n    - 120.0\n    - .nan\n",
        19,
        (
            "line.segments.0.length (value from sweep.line.segments.0.length)",
            "finite number",
            "(got nan)",
            "[in sweep case {'length': 1}",
        ),
    ),
    "sweep-dimension-clash": (
        BASE + "sweep:\n  line.segments.0.length: [120.0, 130.0]\n"
        "  environment.depth: [150.0, 300.0]\n"
        "  zip:\n    - {name: length, analysis.static.nodes: [11, 21]}\n",
        20,
        ("sweep.zip.0", "dimension 'length' is already used", "explicit name"),
    ),
    "sweep-overlapping-paths": (
        BASE + "sweep:\n  ends.b.position: [[90.0, 0.0, -5.0], [80.0, 0.0, -5.0]]\n"
        "  ends.b.position.0: [70.0, 75.0]\n",
        18,
        (
            "sweep.ends.b.position.0",
            "overlaps the swept path 'ends.b.position'",
            "each setting on one axis",
            "(got 'ends.b.position.0')",
        ),
    ),
    "sweep-zip-unequal": (
        BASE + "sweep:\n  zip:\n    - name: pair\n      line.segments.0.length: [120.0, 130.0]\n"
        "      environment.depth: [150.0]\n",
        18,
        ("sweep.zip.0", "equal lengths", "line.segments.0.length: 2", "environment.depth: 1"),
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_study_is_reported_at_its_line(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text, line, fragments = CASES[case]
    err = _validate(tmp_path, capsys, text)
    located = [m for m in err.splitlines() if m.startswith(f"{tmp_path / 'study.yaml'}:{line}:")]
    assert located, f"no message at line {line}:\n{err}"
    message = "\n".join(located)
    for fragment in fragments:
        assert fragment in message, f"{fragment!r} not in:\n{message}"


def test_base_study_is_valid(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "study.yaml"
    path.write_text(BASE)
    assert main(["validate", str(path)]) == 0
    assert "valid study 'errs': 1 cases" in capsys.readouterr().out


def test_several_faults_are_all_reported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = _edit("length: 100.0", "length: -1.0").replace("depth: 200.0", "depth: -3.0")
    err = _validate(tmp_path, capsys, text)
    assert ":7: line.segments.0.length:" in err and ":4: environment.depth:" in err


def test_run_with_a_bad_study_does_no_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + "sweep:\n  line.segments.0.length: [120.0, -5.0]\n")
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out)]) == 2
    assert ":17: line.segments.0.length (value from sweep" in capsys.readouterr().err
    assert not out.exists()  # nothing computed, no cache, no result file


def test_missing_file_is_a_clear_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", str(tmp_path / "nope.yaml")]) == 2
    assert "cannot read the study file" in capsys.readouterr().err


def test_non_utf8_file_is_a_clear_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "latin1.yaml"
    text = BASE.replace("name: errs", "name: errs\ndescription: caf\xe9")
    path.write_bytes(text.encode("latin-1"))
    assert main(["validate", str(path)]) == 2
    assert f"{path}:2: the study file is not UTF-8 text" in capsys.readouterr().err


def test_a_duration_beyond_max_periods_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A fixed duration of more periods of the slowest harmonic than max_periods may be
    (1e5) only ever reached the per-case time limit: refused before any work, naming
    the key, the value and the bound; 1e5 periods exactly is allowed."""
    dynamic = (
        "  dynamic:\n"
        "    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.1, frequency: 0.2}\n"
        "    method: time\n    duration: %s\n"
    )
    err = _validate(tmp_path, capsys, BASE + dynamic % "1.0e12")
    assert "duration: 1e+12 s is 2e+11 periods" in err and "at most 100000 periods" in err
    path = tmp_path / "ok.yaml"
    path.write_text(BASE + dynamic % "5.0e5")  # 0.2 Hz x 5e5 s = 1e5 periods
    assert main(["validate", str(path)]) == 0
