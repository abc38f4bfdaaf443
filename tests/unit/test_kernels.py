"""Kernels compiled ahead of the first study (issue 20, item 4): a run whose analyses need
a kind of kernel not yet compiled for this source says so before it starts, compiles it
once and leaves a marker, so the next run says nothing; ``cablestudy compile`` leaves
every marker. In this process the kernels are already loaded, so these runs are quick:
what is tested is the bookkeeping and the message, not numba."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from cablestudy import cli, kernels
from cablestudy.statics import aot
from cablestudy.study.loader import parse_study_text, validate_data

STUDY = """\
name: k
environment: {fluid: water}
line:
  segments:
    - {length: 12.0, diameter: 0.01, mass_per_length: 0.6, axial_stiffness: 7.8e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [11.8, 0.0, 0.0]}
"""


@pytest.fixture()
def fresh_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    where = tmp_path / "numba"
    # the kernel compiled ahead of time is a file, not loaded in this process as numba's
    # kernels are: where this source's is built, it is not built again (about 8 s)
    built = aot.module_path()
    if built.is_file():
        where.mkdir()
        shutil.copy2(built, where / built.name)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(where))
    return where


def test_a_run_says_it_compiles_once(
    tmp_path: Path, fresh_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "k.yaml"
    path.write_text(STUDY)
    args = ["run", str(path), "--out", str(tmp_path / "out"), "--scheduler", "synchronous"]
    assert cli.main([*args, "--no-cache"]) == 0
    first = capsys.readouterr().err
    assert "compiling the static kernels, first run only, about" in first
    assert "time-domain" not in first  # a static study needs no time-domain kernels
    assert (fresh_cache / "statics.compiled").is_file()
    assert cli.main([*args, "--no-cache"]) == 0
    assert "compiling" not in capsys.readouterr().err


def test_kinds_follow_the_analyses() -> None:
    def kinds(extra: str) -> list[str]:
        src = parse_study_text(STUDY + extra, "k.yaml")
        return kernels.kinds_of(validate_data(src.data, src))

    dyn = "analysis:\n  dynamic:\n    excitation: {end: b, direction: [1, 0, 0], amplitude: 0.01, "
    dyn += "frequency: 0.5}\n    method: "
    assert kinds("") == ["statics"]
    assert kinds(dyn + "time\n") == ["statics", "time"]
    assert kinds(dyn + "frequency\n") == ["statics", "frequency"]
    assert kinds(dyn + "auto\n") == ["statics", "time", "frequency"]
    # a system's dynamics (time or frequency domain): its own kernels, compiled at install
    system = kernels._warm_system_text("s", kernels._WARM_DYNAMIC)
    for method in ("time", "frequency", "auto"):
        src = parse_study_text(system.replace("METHOD", method), "s.yaml")
        assert kernels.kinds_of(validate_data(src.data, src)) == ["statics", "systems"]


def test_compile_command_leaves_every_marker(
    fresh_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["compile", "--jobs", "1"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("compiling ") and "compiled in" in out
    for kind in kernels.KINDS:
        assert kernels.is_compiled(kind), kind
