"""Keys of a one-line study that no analysis of the study would use, refused before any
work (DESIGN.md: a study key that a solver does not support is refused at validation,
never ignored).

Each check names the field, the value given, and what uses it:

- ``environment.seabed`` keys other than their defaults without ``environment.depth``:
  there is no seabed to slope, rub or press on;
- ``environment.current`` in a fluid of density 0 (vacuum): it drags nothing;
- ``analysis.static.drag_elements`` outside method catenary with a current, and
  ``drag_diameter: stretched`` without a current or laying (it scales the drag only);
- ``ends.<a|b>.bending: clamped`` where nothing bends: no segment with
  ``bending_stiffness > 0``.

Keys that describe the line or the seabed for an analysis the study does not run (a
segment's added mass or damping, the seabed's contact stiffness in a statics-only
study, as a MoorDyn import writes them) are kept: the study is complete when that
analysis is added.

A key is checked only where the study gives it (a default is never refused); a system's
keys are checked by its own models.
"""

from __future__ import annotations

from typing import Any

from ..study.cases import Case
from ..study.ends import FixedEnd, ForceEnd, MooringEnd
from ..study.loader import StudySource


def _say(src: StudySource, loc: tuple[str, ...], what: str, value: Any, allowed: str) -> str:
    where = src.line_of(loc) or src.line_of(loc[:1]) or str(src.source)
    return f"{where}: {'.'.join(loc)}: {what} (got {value!r}); allowed: {allowed}"


def _seabed_problems(case: Case, src: StudySource) -> list[str]:
    study = case.study
    env = study.environment
    seabed = env.seabed
    given = [k for k in sorted(seabed.model_fields_set) if getattr(seabed, k) is not None]
    if env.depth is not None:
        return []  # each seabed key serves the analyses that read it
    defaults = type(seabed)()
    return [
        _say(
            src,
            ("environment", "seabed", key),
            "there is no seabed without environment.depth, so no analysis uses it",
            getattr(seabed, key),
            "give environment.depth, or leave the seabed key out",
        )
        for key in given
        if getattr(seabed, key) != getattr(defaults, key)
    ]


def _current_problems(case: Case, src: StudySource) -> list[str]:
    env = case.study.environment
    if env.current is None or env.density > 0.0:
        return []
    return [
        _say(
            src,
            ("environment", "current"),
            "a current in a fluid of density 0 (vacuum) exerts no drag, so no analysis uses it",
            [p.model_dump() for p in env.current],
            "a fluid with density > 0 (air, water, {density}), or leave the current out",
        )
    ]


def _static_problems(case: Case, src: StudySource) -> list[str]:
    study = case.study
    static = study.analysis.static
    current = study.environment.current is not None
    out: list[str] = []
    if static.drag_elements is not None and (static.method != "catenary" or not current):
        why = (
            f"method {static.method!r} has no drag elements"
            if static.method != "catenary"
            else "the study has no environment.current, so there is no drag to discretise"
        )
        out.append(
            _say(
                src,
                ("analysis", "static", "drag_elements"),
                why,
                static.drag_elements,
                "leave it out, or use it with method catenary and environment.current",
            )
        )
    if static.drag_diameter == "stretched" and not current and static.installation is None:
        out.append(
            _say(
                src,
                ("analysis", "static", "drag_diameter"),
                "the diameter of the drag law, with no environment.current and no "
                "installation: there is no drag",
                static.drag_diameter,
                "leave it out, or use it with a current (method shooting)",
            )
        )
    return out


def _bending_problems(case: Case, src: StudySource) -> list[str]:
    study = case.study
    line = study.line
    assert line is not None and study.ends is not None
    stiff = any(seg.bending_stiffness > 0.0 for seg in line.segments)
    out: list[str] = []
    for label in ("a", "b"):
        end = getattr(study.ends, label)
        if not isinstance(end, FixedEnd | ForceEnd | MooringEnd) or end.bending != "clamped":
            continue
        if stiff:
            continue
        why = "no segment has bending_stiffness > 0, so there is no moment to hold"
        out.append(
            _say(
                src,
                ("ends", label, "bending"),
                why,
                end.bending,
                "pinned (the default), or clamped with bending_stiffness > 0",
            )
        )
    return out


def unused_key_problems(case: Case, src: StudySource) -> list[str]:
    """Messages (file:line: path: why (got value); allowed: ...) for keys of a one-line
    case that none of its analyses would use; empty when every key given is used."""
    if case.study.is_system or case.study.line is None or case.study.line.is_spring:
        return []
    return [
        *_seabed_problems(case, src),
        *_current_problems(case, src),
        *_static_problems(case, src),
        *_bending_problems(case, src),
    ]
