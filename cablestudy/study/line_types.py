"""The line-type library as users see it: the listing of ``cablestudy line-types`` and
the record of what a study's line types filled (the ``line_types`` attribute of its
dataset). The numbers come from :mod:`cablestudy.physics.line_types`."""

from __future__ import annotations

import json
from typing import Any

from ..physics.line_types import (
    CHAIN_GRADES,
    CHAIN_MAX_DIAMETER,
    DEFAULT_CHAIN_GRADE,
    FORMULAS,
    MATERIALS,
    line_type_properties,
)

#: segment keys a line type can fill (besides failure.minimum_breaking_load)
FILLED_KEYS = (
    "diameter",
    "mass_per_length",
    "axial_stiffness",
    "drag_normal",
    "drag_tangential",
    "added_mass_normal",
    "added_mass_tangential",
)


def listing(nominal_diameter: float | None = None) -> str:
    """The text of ``cablestudy line-types``: per material its coefficients, formulas
    and sources; with ``nominal_diameter`` [m], the filled values at that diameter."""
    from ..physics import line_types as lib

    lines = [
        "Line types: line.segments.N.line_type: {material, nominal_diameter [m], grade}",
        "d: nominal diameter [m]; keys the segment gives itself win over the filled ones.",
        "Formulas:",
        *(f"  {k}: {v}" for k, v in FORMULAS.items()),
        "  chain grades (c [kN/mm^2]): "
        + ", ".join(f"{g} {c}" for g, c in CHAIN_GRADES.items())
        + f"; default {DEFAULT_CHAIN_GRADE}; chains up to d = {CHAIN_MAX_DIAMETER:.4f} m",
        "",
    ]
    for name, m in MATERIALS.items():
        lines.append(f"{name}: {m.description}")
        ea = (
            f"k2 = {m.stiffness_d2:.4g} N/m^2"
            if m.stiffness_d2
            else f"EA/MBL = {m.stiffness_per_mbl:g}"
        )
        mbl = "by grade" if m.chain else f"b2 = {m.mbl_d2:.4g} N/m^2, b3 = {m.mbl_d3:.4g} N/m^3"
        lines.append(
            f"  r = {m.diameter_ratio:.4g}, m2 = {m.mass_d2:.6g} kg/m^3, {ea}, MBL {mbl}, "
            f"C_n = {m.drag_normal_nominal:g}"
            + (f", C_a = {m.drag_axial_nominal:g}" if m.drag_axial_nominal is not None else "")
            + (f", Ca_n = {m.added_mass_normal:g}" if m.added_mass_normal is not None else "")
            + (
                f", Ca_t = {m.added_mass_tangential:g}"
                if m.added_mass_tangential is not None
                else ""
            )
        )
        missing = [k for k in FILLED_KEYS if k not in m.sources]
        sources = sorted(set(m.sources.values()))
        lines.append(
            f"  sources: {', '.join(sources)}"
            + (f"; not filled (segment value or default): {', '.join(missing)}" if missing else "")
        )
        if nominal_diameter is not None:
            props = line_type_properties(name, nominal_diameter)
            lines.append(
                f"  at d = {nominal_diameter:g} m: "
                + ", ".join(f"{k} {v:.6g}" for k, v in props.items())
            )
    lines.append("")
    lines.append("Sources:")
    doc = lib.__doc__ or ""
    start = doc.index("Sources (cited")
    end = doc.index("Where no source")
    lines.extend(f"  {row}" if row else "" for row in doc[start:end].strip().splitlines()[1:])
    return "\n".join(lines).rstrip() + "\n"


def _filled(segment: dict[str, Any], line_type: dict[str, Any]) -> dict[str, float]:
    props = line_type_properties(
        line_type["material"], line_type["nominal_diameter"], line_type.get("grade")
    )
    return {
        k: v
        for k, v in props.items()
        if k not in segment and not (k == "axial_stiffness" and "axial" in segment)
    }


def record(study_data: dict[str, Any], sweep: dict[str, list[Any]]) -> str:
    """JSON of what the line types of a (valid) study filled, one entry per segment with a
    ``line_type``: the line type, the values it filled (SI), the keys the segment gave
    itself instead, and, per sweep path into the line type, the values filled at each
    swept value (``sweep`` maps each swept path to its values). Empty text when no
    segment has a line type."""
    line = study_data.get("line")
    segments = line.get("segments") if isinstance(line, dict) else None
    out = []
    for i, seg in enumerate(segments or []):
        if not isinstance(seg, dict) or not isinstance(seg.get("line_type"), dict):
            continue
        lt = seg["line_type"]
        props = line_type_properties(lt["material"], lt["nominal_diameter"], lt.get("grade"))
        entry: dict[str, Any] = {
            "segment": i,
            "line_type": lt,
            "filled": _filled(seg, lt),
            "minimum_breaking_load": props["minimum_breaking_load"],
            "given_in_segment": sorted(k for k in props if k in seg),
            "sources": MATERIALS[lt["material"]].sources,
        }
        prefix = f"line.segments.{i}.line_type"
        swept = {}
        for path, values in sweep.items():
            if path != prefix and not path.startswith(prefix + "."):
                continue
            rows = []
            for value in values:
                case = dict(value) if path == prefix else {**lt, path.rsplit(".", 1)[1]: value}
                rows.append({"value": value, "filled": _filled(seg, case)})
            swept[path] = rows
        if swept:
            entry["swept"] = swept
        out.append(entry)
    return json.dumps(out, sort_keys=True) if out else ""


def line_type_attrs(src: Any) -> dict[str, str]:
    """The dataset attribute ``line_types`` (:func:`record`) of the study ``src`` (a
    :class:`~cablestudy.study.loader.StudySource`), when a segment has a line type."""
    line = src.data.get("line")
    segments = line.get("segments") if isinstance(line, dict) else None
    if not any(isinstance(s, dict) and "line_type" in s for s in segments or []):
        return {}
    from .cases import parse_sweep

    sweep = {p: list(v) for a in parse_sweep(src) for p, v in zip(a.paths, a.values, strict=True)}
    text = record(src.data, sweep)
    return {"line_types": text} if text else {}
