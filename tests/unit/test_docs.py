"""The user guide (docs/, mkdocs.yml): it builds in strict mode, the strict build fails on
a broken link, a broken anchor or a page left out of the nav, the key reference is the
one the schema generates today, and the README stays a front door that links into it."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from cablestudy.docs_reference import REFERENCE, current_reference
from cablestudy.study import Study
from cablestudy.study.analysis import DYNAMIC_METHODS, STATIC_METHODS

ROOT = Path(__file__).resolve().parents[2]


def _build(config: Path, site: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config), "-d", str(site)],
        capture_output=True,
        text=True,
        cwd=config.parent,
        timeout=600,  # a bound on a hang, not a speed check (the machine may be loaded)
    )


def test_docs_build_strict(tmp_path: Path) -> None:
    done = _build(ROOT / "mkdocs.yml", tmp_path / "site")
    assert done.returncode == 0, done.stderr
    assert "WARNING" not in done.stderr, done.stderr
    for page in ("", "conventions/", "reference/keys/", "tutorials/mooring-leg/"):
        assert (tmp_path / "site" / page / "index.html").exists(), page


@pytest.fixture
def copy(tmp_path: Path) -> Path:
    """A copy of the site's sources to break."""
    shutil.copy(ROOT / "mkdocs.yml", tmp_path / "mkdocs.yml")
    shutil.copytree(ROOT / "docs", tmp_path / "docs")
    return tmp_path


@pytest.mark.parametrize(
    ("what", "page", "text", "warning"),
    [
        ("orphan page", "docs/guide/orphan.md", "# Not in the nav\n", "not included in the"),
        ("broken link", "docs/conventions.md", "\n[gone](guide/no-such-page.md)\n", "no-such-page"),
        ("broken anchor", "docs/index.md", "\n[gone](conventions.md#no-such-heading)\n", "no-such"),
    ],
)
def test_strict_build_fails(copy: Path, what: str, page: str, text: str, warning: str) -> None:
    """The checks the strict build promises, each on a copy of the docs with one fault."""
    target = copy / page
    target.write_text((target.read_text() if target.exists() else "") + text)
    done = _build(copy / "mkdocs.yml", copy / "site")
    assert done.returncode != 0, f"{what}: the strict build passed"
    assert warning in done.stderr, done.stderr


def test_key_reference_is_current() -> None:
    """docs/reference/keys.md is what the schema generates: after a change to the study
    models run ``make reference`` (python -m cablestudy.docs_reference)."""
    assert (ROOT / REFERENCE).read_text() == current_reference()


def test_key_reference_lists_methods() -> None:
    """The methods are listed as allowed values, in the schema and in the reference, and
    the static ones are exactly the registry's solvers."""
    from cablestudy.statics import STATIC_SOLVERS

    assert set(STATIC_METHODS) == set(STATIC_SOLVERS)
    defs = Study.model_json_schema()["$defs"]
    assert defs["StaticSettings"]["properties"]["method"]["enum"] == list(STATIC_METHODS)
    assert defs["DynamicSettings"]["properties"]["method"]["enum"] == list(DYNAMIC_METHODS)
    text = (ROOT / REFERENCE).read_text()
    static_row = next(line for line in text.splitlines() if line.startswith("| `method` |"))
    for name in STATIC_METHODS:
        assert f"`{name}`" in static_row
    assert "see `cablestudy schema`" not in text
    # every key of every model has its row
    for name, model in defs.items():
        for key in model.get("properties", {}):
            assert re.search(rf"^\| `{key}` \|", text, flags=re.MULTILINE), (name, key)


def test_readme_is_short_and_links_into_docs() -> None:
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 260
    links = re.findall(r"\]\((docs/[^)#]+)", readme)
    assert links
    for link in links:
        assert (ROOT / link).exists(), link


def test_bench_writes_into_benchmarks_page(tmp_path: Path) -> None:
    """``make bench`` (``--readme docs/benchmarks.md --docs docs/bench``) replaces the
    table between the markers of the benchmarks page, with plot links relative to it
    that resolve to the plots it copies."""
    from cablestudy.bench import README_END, README_START, update_readme

    assert "--readme docs/benchmarks.md --docs docs/bench" in (ROOT / "Makefile").read_text()
    page = tmp_path / "docs" / "benchmarks.md"
    page.parent.mkdir()
    original = (ROOT / "docs" / "benchmarks.md").read_text()
    assert README_START in original and README_END in original
    page.write_text(original)
    plot = tmp_path / "docs" / "bench" / "example.png"
    plot.parent.mkdir()
    plot.write_bytes(b"png")
    update_readme(page, "| new table |\n", [plot])
    text = page.read_text()
    assert "| new table |" in text and "![example](bench/example.png)" in text
    assert text.split(README_START)[0] == original.split(README_START)[0]
    assert text.split(README_END)[1] == original.split(README_END)[1]
    for link in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", original):
        assert (ROOT / "docs" / link).exists(), link


def test_readme_layout_is_true() -> None:
    """Every file and folder the README's layout names exists (a move of the package
    must update it)."""
    readme = (ROOT / "README.md").read_text()
    layout = readme.split("## Layout", 1)[1].split("```")[1]
    names = re.findall(r"([\w*]+(?:/[\w*]+)*(?:\.py|/))", layout)  # folder/file.py too
    assert len(names) > 20
    for name in names:
        where = (
            ROOT if name in ("configs/", "docs/", "tests/", "benchmarks/") else ROOT / "cablestudy"
        )
        if name == "cablestudy/":
            where = ROOT
        assert list(where.glob(name.rstrip("/"))), name
