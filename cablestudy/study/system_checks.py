"""The checks a study makes of its excitations that need the whole study: a system's
body and point motions resolved against its bodies and points, and refused (naming the
field, the value and what supports it) where the system dynamics do not model them; a
one-line study's motions per line end."""

from __future__ import annotations

from .base import FieldError
from .spectrum import BodySpectrumExcitation, PointSpectrumExcitation
from .system import FreePoint
from .system_dynamics import (
    BODY_DOFS,
    SYSTEM_EXCITATIONS,
    SYSTEM_HARMONICS,
    SYSTEM_TABLES,
    BodyHarmonic,
    BodyTable,
)


def check_system_dynamics(study: object) -> None:
    """Refuse (naming the field, the value and what supports it) what the system time
    domain does not model; resolve every body and point an excitation names. Called by
    the study model for a system with ``analysis.dynamic``."""

    bodily = (BodyHarmonic, BodyTable, BodySpectrumExcitation)
    kinds = (*SYSTEM_EXCITATIONS, BodySpectrumExcitation, PointSpectrumExcitation)

    dyn = study.analysis.dynamic  # type: ignore[attr-defined]
    points = study.points  # type: ignore[attr-defined]
    bodies = study.bodies  # type: ignore[attr-defined]
    root = ("analysis", "dynamic")
    items = dyn.excitations
    many = isinstance(dyn.excitation, list)

    def at(i: int, key: str) -> tuple:
        return (*root, "excitation", *((i,) if many else ()), key)

    tables: set[tuple[str, str]] = set()
    for i, e in enumerate(items):
        if not isinstance(e, kinds):
            raise FieldError(
                at(i, "end"),
                "a system's motion is given per body degree of freedom (body, dof) or per "
                "point (point, direction), not per line end; allowed: "
                f"body: one of {sorted(bodies) or 'none defined'} with dof: one of "
                f"{list(BODY_DOFS)}, or point: one of {sorted(points)} with direction",
                getattr(e, "end", None),
            )
        if isinstance(e, bodily):
            if e.body not in bodies:
                raise FieldError(
                    at(i, "body"),
                    f"no body of that name; allowed: {sorted(bodies) or 'none defined'}",
                    e.body,
                )
            if bodies[e.body].kind != "prescribed":
                raise FieldError(
                    at(i, "body"),
                    "a free body's own equation of motion is not modelled in the dynamics; "
                    "allowed: a prescribed body (kind: prescribed)",
                    e.body,
                )
            key = (e.body, e.dof)
        else:
            if e.point not in points:
                raise FieldError(
                    at(i, "point"), f"no point of that name; allowed: {sorted(points)}", e.point
                )
            if isinstance(points[e.point], FreePoint):
                raise FieldError(
                    at(i, "point"),
                    "a free point moves by the lines' pull, it cannot be moved as well; "
                    "allowed: a fixed point or a body point",
                    e.point,
                )
            key = (e.point, "point")
        if isinstance(e, SYSTEM_TABLES):
            if key in tables:
                what = f"{e.dof} of body {key[0]}" if key[1] != "point" else f"point {key[0]}"
                raise FieldError(
                    at(i, "table"),
                    f"{what} is already moved by a table; allowed: one table per degree of "
                    "freedom (or per point); add harmonics for more",
                    "table",
                )
            tables.add(key)
    for name, body in bodies.items():
        if body.kind != "prescribed":
            raise FieldError(
                ("bodies", name, "kind"),
                "a free body's own equation of motion is not modelled in the dynamics; "
                "allowed with analysis.dynamic: kind: prescribed (a free body is solved by "
                "analysis.static)",
                body.kind,
            )
    if dyn.method == "frequency":  # the system frequency domain (dynamics/system_frequency)
        for i, e in enumerate(items):
            if not isinstance(e, SYSTEM_HARMONICS):
                raise FieldError(
                    at(i, "spectrum" if hasattr(e, "spectrum") else "table"),
                    "a system's frequency domain solves harmonic motions of one frequency; "
                    "allowed with method 'frequency': body or point harmonics (a spectrum or "
                    "a table is solved by method 'time')",
                    type(e).__name__,
                )
    if dyn.transfer_function is not None:
        raise FieldError(
            (*root, "transfer_function"),
            "transfer_function is not built for a system's frequency domain; allowed for "
            "a system: remove the key (method 'frequency' runs the harmonic response, "
            "'time' the time domain, 'auto' either per case)",
            "transfer_function",
        )
    if "after_break" in dyn.model_fields_set:
        raise FieldError(
            (*root, "after_break"),
            "a system's lines do not part (no failure condition in a system); allowed: "
            "remove the key (it is supported by a one-line study)",
            dyn.after_break,
        )
    hist = dyn.history
    if hist is not None and (hist.points or hist.whole_line):
        key = "points" if hist.points else "whole_line"
        raise FieldError(
            (*root, "history", key),
            "a system keeps the history of each line's end tensions (history_tension_a, "
            "history_tension_b on line and time); points along a "
            "line and whole-line histories are supported by a one-line study; allowed: "
            "history with periods and samples_per_period",
            getattr(hist, key),
        )


def check_one_line_excitation(study: object) -> None:
    """A one-line study's motions are per line end: a body or point motion needs a
    system."""

    dyn = study.analysis.dynamic  # type: ignore[attr-defined]
    many = isinstance(dyn.excitation, list)
    kinds = (*SYSTEM_EXCITATIONS, BodySpectrumExcitation, PointSpectrumExcitation)
    for i, e in enumerate(dyn.excitations):
        if isinstance(e, kinds):
            key = "body" if hasattr(e, "body") else "point"
            raise FieldError(
                ("analysis", "dynamic", "excitation", *((i,) if many else ()), key),
                f"a {key} motion moves a mooring system (points, bodies, lines); a one-line "
                "study moves its ends: allowed: end: a or b with direction",
                getattr(e, key),
            )
