"""``cablestudy validate`` on random mutations of the shipped studies: it accepts the file
(exit 0) or refuses it (exit 2) with every message at a line (``file:line: ...``); it
never ends in a traceback.

Two kinds of mutation: edits of the text (a line deleted, repeated, re-indented, cut,
its value replaced by a YAML token, stray characters), which exercise the YAML layer,
and edits of the parsed data (a value replaced by another type, a key removed or
renamed, an entry added), dumped back to YAML, which reach the model and sweep checks.
Numbers stay small: a valid sweep of a million cases is a legitimate (slow) study, not
a fault, and is not what this test looks for.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cablestudy.cli import main

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = sorted((ROOT / "configs").glob("*.yaml"))

TOKENS = [
    "", "0", "-1", "1e308", "-1e-308", ".nan", "-.inf", "null", "~", "true", "no", "[]",
    "{}", "[1, 2]", "[0.0, 0.0]", "{kind: fixed}", "{start: 1, stop: 0, num: 3}", "'x'",
    "abc", "&a 1", "*a", "*missing", "&b [1, *b]", "!!int x", "!!str 3", "!!float [1]",
    "!!map 1", "!x 1", "2024-13-45", "1:30", "0x1F", "1_000", "9" * 40, "[[[[[[1]]]]]]",
    "{a: 1, a: 2}", "- 1", "? [1]", "<<: *a", "'", '"\\x"', "|", ">-", "#", "%YAML 1.1",
    "---", "...", "@", "`", "\t", "\u00e9", "\ufeff", "\x85", "1e", "- - -", ": :",
]  # fmt: skip
values = st.one_of(
    st.sampled_from(TOKENS),
    st.integers(-3, 40).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.text(max_size=12),
)


@st.composite
def text_mutations(draw: st.DrawFn) -> str:
    lines = draw(st.sampled_from(CONFIGS)).read_text().splitlines()
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["value", "delete", "repeat", "indent", "cut", "insert"]))
        if op == "value" and ":" in lines[i]:
            lines[i] = lines[i].split(":", 1)[0] + ": " + draw(values)
        elif op == "delete" and len(lines) > 1:
            del lines[i]
        elif op == "repeat":
            lines.insert(i, lines[i])
        elif op == "indent":
            lines[i] = " " * draw(st.integers(0, 6)) + lines[i].lstrip()
        elif op == "cut":
            lines[i] = lines[i][: draw(st.integers(0, len(lines[i])))]
        else:
            pos = draw(st.integers(0, len(lines[i])))
            lines[i] = lines[i][:pos] + draw(values) + lines[i][pos:]
    return "\n".join(lines) + "\n"


def _paths(node: Any, loc: tuple = ()) -> list[tuple]:
    out = [loc]
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, loc + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, loc + (i,))
    return out


data_values = st.recursive(
    st.one_of(
        st.none(),
        st.booleans(),
        st.integers(-5, 50),
        st.floats(allow_nan=True, allow_infinity=True),
        st.text(max_size=8),
        st.sampled_from(["fixed", "force", "mooring", "water", "air", "analytic", "time"]),
    ),
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=3)
    ),
    max_leaves=8,
)


@st.composite
def data_mutations(draw: st.DrawFn) -> str:
    data = yaml.safe_load(draw(st.sampled_from(CONFIGS)).read_text())
    for _ in range(draw(st.integers(1, 3))):
        loc = draw(st.sampled_from(_paths(data)[1:]))
        parent = data
        for part in loc[:-1]:
            parent = parent[part]
        op = draw(st.sampled_from(["replace", "delete", "rename", "add"]))
        if op == "replace":
            parent[loc[-1]] = draw(data_values)
        elif op == "delete":
            del parent[loc[-1]]
        elif op == "rename" and isinstance(parent, dict):
            parent[draw(st.text(max_size=8))] = parent.pop(loc[-1])
        elif op == "add" and isinstance(parent[loc[-1]], dict):
            parent[loc[-1]][draw(st.text(max_size=8))] = draw(data_values)
        elif op == "add" and isinstance(parent[loc[-1]], list):
            parent[loc[-1]].append(draw(data_values))
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True)


def _check(text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "mutant.yaml"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    capsys.readouterr()
    code = main(["validate", str(path)])
    out, err = capsys.readouterr()
    if code == 0:
        assert "valid study" in out
        return
    assert code == 2, (code, err)
    assert err.startswith("invalid study:\n"), err
    located = re.compile(re.escape(str(path)) + r":\d+: ")
    for message in err.splitlines()[1:]:
        assert located.match(message), f"a message without a line:\n{message}\nin\n{text}"


@settings(
    max_examples=50,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(text=text_mutations())
def test_validate_accepts_or_refuses_a_mutated_text(
    text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _check(text, tmp_path, capsys)


@settings(
    max_examples=50,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(text=data_mutations())
def test_validate_accepts_or_refuses_mutated_data(
    text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _check(text, tmp_path, capsys)
