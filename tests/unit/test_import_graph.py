"""The package's layout shows its pipeline (issue 20 item 6): study -> grid -> chunks ->
analyses -> dataset, with the solvers and laws beneath.

The import graph is read from the source (the AST, nothing imported): every import
statement of every module, at module level or inside a function, relative or absolute,
except those under ``if TYPE_CHECKING:`` (never executed). A function-level import is
an edge like any other: importing inside a function defers the load, it does not break
a circle.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "cablestudy"

#: the pure core: arrays in, arrays out, no runner, no study file, no command line
CORE = ("cablestudy.physics", "cablestudy.statics", "cablestudy.dynamics")
#: what the core never imports
ABOVE_CORE = ("cablestudy.study", "cablestudy.run", "cablestudy.analyses", "cablestudy.cli")
#: the study layer converts a study into solver inputs; it never runs anything
ABOVE_STUDY = ("cablestudy.run", "cablestudy.analyses", "cablestudy.cli")
#: the analyses turn cases into records; moving and writing them is the runner's
ABOVE_ANALYSES = ("cablestudy.run", "cablestudy.cli")

MAX_LINES = 800


def _modules() -> dict[str, tuple[Path, bool]]:
    """Module name -> (file, whether it is a package's ``__init__``)."""
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        package = parts[-1] == "__init__"
        if package:
            parts = parts[:-1]
        out[".".join(parts)] = (path, package)
    return out


MODULES = _modules()


def _type_checking(node: ast.AST) -> bool:
    test = getattr(node, "test", None)
    return isinstance(node, ast.If) and (
        (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
        or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")
    )


def _imported(name: str, source: str, package: bool) -> list[tuple[str, int]]:
    """(module, line) of every import in the module ``name``, TYPE_CHECKING blocks
    skipped (their ``else:`` kept); a name imported from a package that is itself a
    module counts as that module."""
    found: list[tuple[str, int]] = []

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if _type_checking(child):
                for stmt in child.orelse:  # type: ignore[attr-defined]
                    visit_one(stmt)
            else:
                visit_one(child)

    def visit_one(node: ast.AST) -> None:
        if isinstance(node, ast.Import):
            found.extend((alias.name, node.lineno) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if package else name.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            for alias in node.names:
                sub = f"{module}.{alias.name}"
                found.append((sub if sub in MODULES else module, node.lineno))
        else:
            visit(node)

    visit(ast.parse(source))
    return found


def _graph() -> dict[str, dict[str, int]]:
    """Module -> {imported package module: first line importing it}."""
    graph: dict[str, dict[str, int]] = {}
    for name, (path, package) in MODULES.items():
        edges: dict[str, int] = {}
        for target, line in _imported(name, path.read_text(), package):
            while target and target not in MODULES:
                target = target.rpartition(".")[0]
            if target and target != name:
                edges.setdefault(target, line)
        graph[name] = edges
    return graph


GRAPH = _graph()


def _circles(graph: dict[str, dict[str, int]]) -> list[tuple[frozenset[str], list[str]]]:
    """The strongly connected sets of more than one module (Tarjan), each with one
    circle through its members (module -> module -> ... back to the first)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    sets: list[set[str]] = []

    def connect(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            members = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                members.add(w)
                if w == v:
                    break
            if len(members) > 1:
                sets.append(members)

    for v in sorted(graph):
        if v not in index:
            connect(v)
    return [(frozenset(members), _cycle_through(graph, members)) for members in sets]


def _cycle_through(graph: dict[str, dict[str, int]], members: set[str]) -> list[str]:
    """One circle inside a strongly connected set: from its first member, breadth-first
    back to it."""
    start = min(members)
    paths = {start: [start]}
    frontier = [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(graph[v]):
                if w == start:
                    return paths[v] + [start]
                if w in members and w not in paths:
                    paths[w] = paths[v] + [w]
                    nxt.append(w)
        frontier = nxt
    raise AssertionError(f"no circle through {sorted(members)}")  # not strongly connected


def _shown(graph: dict[str, dict[str, int]], cycle: list[str]) -> str:
    return (
        " -> ".join(f"{a} (line {graph[a][b]})" for a, b in zip(cycle, cycle[1:], strict=False))
        + f" -> {cycle[-1]}"
    )


SAMPLE = """\
from __future__ import annotations
from typing import TYPE_CHECKING
from . import scheduler
from ..statics.batch import solve_batch
import cablestudy.study.grid
if TYPE_CHECKING:
    from ..dynamics.model import DiscreteLine
else:
    from ..physics import axial
def f():
    from ..analyses.static import solve_static
    if TYPE_CHECKING:
        import cablestudy.cli
"""


def test_the_graph_sees_every_kind_of_import() -> None:
    """The reader of the graph finds relative, absolute, package-member and
    function-level imports and skips what only ``if TYPE_CHECKING:`` imports (its
    ``else:`` runs); a circle is found and shown with the lines that make it."""
    got = _imported("cablestudy.run.sample", SAMPLE, package=False)
    assert [m for m, _ in got if m.startswith("cablestudy")] == [
        "cablestudy.run.scheduler",
        "cablestudy.statics.batch",
        "cablestudy.study.grid",
        "cablestudy.physics.axial",
        "cablestudy.analyses.static",
    ]
    # on the package itself: the CLI loads the runner only when a study runs
    assert "cablestudy.run.runner" in GRAPH["cablestudy.cli"]
    toy = {"a": {"b": 3}, "b": {"c": 7}, "c": {"a": 1}, "d": {"a": 2}}
    ((members, cycle),) = _circles(toy)
    assert members == {"a", "b", "c"} and cycle == ["a", "b", "c", "a"]
    assert _shown(toy, cycle) == "a (line 3) -> b (line 7) -> c (line 1) -> a"


def test_no_import_circles() -> None:
    """No module imports, directly or through others, a module that imports it."""
    found = _circles(GRAPH)
    assert not found, "import circles:\n" + "\n".join(_shown(GRAPH, c) for _, c in found)


def test_the_core_never_imports_the_layers_above_it() -> None:
    """physics/, statics/ and dynamics/ (arrays in, arrays out) never import the study
    file, the analyses, the runner or the command line; the study layer never imports
    the analyses or the runner; the analyses never import the runner."""
    rules = [(CORE, ABOVE_CORE), (("cablestudy.study",), ABOVE_STUDY)]
    rules.append((("cablestudy.analyses",), ABOVE_ANALYSES))
    bad = [
        f"{module} imports {target} (line {line})"
        for lower, above in rules
        for module, edges in GRAPH.items()
        if module.startswith(lower)
        for target, line in edges.items()
        if target.startswith(above)
    ]
    assert not bad, "\n".join(bad)


def test_no_module_over_800_lines() -> None:
    """No module over :data:`MAX_LINES` lines."""
    lines = {name: len(path.read_text().splitlines()) for name, (path, _) in MODULES.items()}
    long = sorted(name for name, n in lines.items() if n > MAX_LINES)
    assert not long, "over 800 lines: " + ", ".join(f"{m} ({lines[m]})" for m in long)
