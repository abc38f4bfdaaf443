"""Whole mooring systems against MoorDyn's own initial condition (issue 22).

The peer files that import whole as systems (``tests/validation/test_system_moorpy.py``)
against MoorDyn (``moordyn.Create``, ``moordyn.Init`` with the coupled body or points
where the file puts them): each line's end tensions within 1 % of the largest tension
(the issue's bar). Among them MoorPy's ``case8.dat`` (three legs, each splitting at a
free junction into two bridles to a coupled body) and MoorDyn's
``tests/Mooring/lines.txt`` (OC3-Hywind: three chains from anchors on the seabed to
three coupled fairleads).

How MoorDyn is driven, and why not with the files exactly as they are:

- MoorDyn 2.7 finds its initial condition by default with a stationary solver
  (``ICgenDynamic 0``). On case8 it stops after 6 s of pseudo-time with a remaining
  acceleration of 93 m/s^2 and fairlead tensions of 926 kN where the equilibrium has
  512 kN (ours and MoorPy's, which agree to 1e-12): 81 % off. Its older dynamic
  relaxation (``ICgenDynamic 1``, a damped dynamic run, drag scaled by ``CdScaleIC``)
  stops when the fairlead tensions change by less than ``threshIC`` over ``dtIC``;
  case8's own ``threshIC 0.01`` ends it at 0.8 s with 642 kN (25 % off): the relaxation
  has not settled, the criterion is met because the tensions change slowly. Settling
  takes ``threshIC 1e-6``, which every file is given here, with ``ICgenDynamic 1``.
- ``lines.txt`` names a state file (``fileIC lines.txt.ic``) that MoorDyn's own test
  suite writes and that is not part of the input; MoorDyn refuses to start without it,
  so the option is dropped (MoorDyn then relaxes from its own catenary guess).
- Left out: ``example/MHK_RM1_Floating``, whose ``TmaxIC 10`` s caps the relaxation
  before it settles (2.4e-2 of the largest tension at threshIC 1e-6); with
  ``TmaxIC 100`` it settles, but at its ``dtM`` of 5e-5 s that takes 34 s of wall time
  (measured: anchor tensions within 4e-3 of the largest), too long for this suite.

What is compared: at a line end on a coupled point that holds only that line,
MoorDyn's force on the point (``GetPointForce``), which is the line's whole end force;
elsewhere (anchors, whose force MoorDyn leaves at zero for fixed points; junctions and
points holding several lines) the end node's tension (``GetLineNodeTen``), which in
MoorDyn's lumped-mass line is the end segment's tension, short of the end force by at
most half a segment's weight in water, w L / (2 N): 0.4 kN on case8's bridles, 15.7 kN
on lines.txt's 45 m chain segments (1.7 % of its 911 kN fairlead tension: the reason
coupled points use the point force) and 16.6 kN (8e-3 of 2.07 MN) on
``local_euler/duplicated.txt``, whose vessel point holds two lines. The rest of the
difference is MoorDyn's lumped-mass discretisation (N = 4 to 152 segments) and what is
left of its relaxation. Measured, of the largest tension: case8 1.9e-4, case9 1.8e-4,
sample.txt 7.5e-4, lines.txt and body.txt 1.7e-3, duplicated.txt 7.3e-3.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from cablestudy.analyses.system import evaluate_system_case
from cablestudy.interchange import import_model, imported_yaml, parse_moordyn
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

moordyn = pytest.importorskip("moordyn", reason="MoorDyn is in the optional extra `peers`")

DATA = Path(__file__).parents[1] / "data"
FILES = [
    "moordyn/example/body.txt",
    "moordyn/example/lines.txt",
    "moordyn/tests/Mooring/lines.txt",
    "moordyn/tests/Mooring/local_euler/duplicated.txt",
    "moorpy/examples/sample.txt",
    "moorpy/tests/case8.dat",
    "moorpy/tests/case9.dat",
]
#: the issue's bar: each end tension within this fraction of the largest tension
BAR = 0.01


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Silence MoorDyn's console output (file descriptors 1 and 2)."""
    saved = [os.dup(1), os.dup(2)]
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            for fd, target in zip(saved, (1, 2), strict=True):
                os.dup2(fd, target)
                os.close(fd)


def settled_input(text: str) -> str:
    """The file with MoorDyn's dynamic relaxation asked to settle (module docstring):
    ``threshIC 1e-6`` with ``ICgenDynamic 1`` (in place of the file's ``threshIC``, or
    first in its options section when it sets none), and no ``fileIC``."""
    lines = [ln for ln in text.splitlines() if not re.match(r"^\s*\S+\s+fileIC\b", ln, re.I)]
    settle = ["1.0e-6   threshIC", "1        ICgenDynamic"]
    thresh = [i for i, ln in enumerate(lines) if re.match(r"^\s*\S+\s+threshIC\b", ln, re.I)]
    if thresh:
        (i,) = thresh
        return "\n".join([*lines[:i], *settle, *lines[i + 1 :]]) + "\n"
    (i,) = [i for i, ln in enumerate(lines) if re.match(r"^\s*-+.*\bOPTIONS\b", ln, re.I)]
    return "\n".join([*lines[: i + 1], *settle, *lines[i + 1 :]]) + "\n"


def coupled_state(text: str, source: str) -> np.ndarray:
    """MoorDyn's coupled degrees of freedom where the file puts them, in MoorDyn's order:
    each coupled body's position and rotation [m, rad], then each coupled (``Vessel``,
    ``Coupled``) point's position [m]."""
    md = parse_moordyn(text, source)
    x: list[float] = []
    for body in sorted(md.bodies.values(), key=lambda b: b.id):
        if body.attachment.lower() in ("coupled", "vessel"):
            x += [*body.position, *np.radians(body.rotation_deg)]
    for point in sorted(md.points.values(), key=lambda p: p.id):
        if point.attachment.lower() in ("coupled", "vessel"):
            x += list(point.position)
    return np.asarray(x, dtype=float)


@pytest.mark.parametrize("rel", FILES)
def test_system_end_tensions_agree_with_moordyn_initial_condition(rel: str, tmp_path: Path) -> None:
    path = DATA / rel
    imported = import_model(path.read_text(), rel, folder=path.parent)
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, rel), "<imported>"))
    study = cases[0].study
    record = evaluate_system_case(cases[0])
    assert record.status == 0, record.message
    ours = np.column_stack([record.data["tension_a"], record.data["tension_b"]])

    names = list(study.lines)
    # lines held alone by a point: MoorDyn's force on that point is the line's end force
    holders: dict[str, int] = {}
    for line in study.lines.values():
        for end in (line.a, line.b):
            holders[end] = holders.get(end, 0) + 1

    copy = tmp_path / path.name
    copy.write_text(settled_input(path.read_text()))
    x = coupled_state(path.read_text(), rel)
    theirs = np.full_like(ours, np.nan)
    with _quiet():
        system = moordyn.Create(str(copy))
        assert moordyn.NCoupledDOF(system) == x.size
        assert moordyn.Init(system, x, np.zeros_like(x)) == 0
        for i, name in enumerate(names):
            line = study.lines[name]
            handle = moordyn.GetLine(system, int(name))
            n = moordyn.GetLineN(handle)
            for j, (end, node) in enumerate(((line.a, 0), (line.b, n))):
                point = study.points[end]
                if point.kind == "body" and holders[end] == 1:
                    pid = int(end.removeprefix("point"))
                    force = moordyn.GetPointForce(moordyn.GetPoint(system, pid))
                else:
                    force = moordyn.GetLineNodeTen(handle, node)
                theirs[i, j] = float(np.linalg.norm(force))
        moordyn.Close(system)

    largest = float(ours.max())
    worst = float(np.abs(theirs - ours).max()) / largest
    print(f"{rel}: largest difference {worst:.1e} of the largest tension {largest:.4g} N")
    np.testing.assert_allclose(theirs, ours, rtol=0.0, atol=BAR * largest)
