"""The key reference of the user guide, ``docs/reference/keys.md``, generated from the
study schema (:meth:`cablestudy.config.Study.model_json_schema`).

One section per model of the study file (the root first, then in the order a reader
meets them), each with the paths where it appears and a table of its keys: type,
units, default, allowed values and description, all read from the schema, and which
analyses and methods use the key (or refuse it), from :data:`USED_BY` below.

``python -m cablestudy.docs_reference`` rewrites the file; ``--check`` only says
whether the committed file is current (tests/unit/test_docs.py does the same).
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path
from typing import Any

from .config.analysis import TIME_ONLY_KEYS

#: where the reference goes, relative to the repository root
REFERENCE = Path("docs/reference/keys.md")

_TIME_ONLY = "time domain (methods time, auto); method frequency refuses it"

#: which analyses and methods use a key ("Model.key") or every key of a model
#: ("Model"), and which refuse it; the refusals are made at validation, naming the
#: method that supports the key
USED_BY: dict[str, str] = {
    "Environment": "every analysis",
    "CustomFluid": "every analysis",
    "Line": "every analysis (a kind: spring line: statics and its algebraic dynamics)",
    "FixedEnd": "every analysis",
    "Segment": "statics, modal, time and frequency domain",
    "Segment.axial": "statics: methods catenary, shooting, discrete (analytic refuses it); "
    "time domain; modal and frequency domain: the law's tangent at the static strain",
    "Segment.axial_stiffness": "all analyses (modal and frequency domain: its tangent)",
    "Segment.bending_stiffness": "statics: method discrete (catenary, shooting and "
    "analytic refuse EI > 0); modal, time and frequency domain",
    "Segment.damping_ratio": "time and frequency domain (modal: undamped modes)",
    "Segment.damping_transverse": "time and frequency domain (modal: undamped modes)",
    "Segment.drag_normal": "statics with a current; time and frequency domain",
    "Segment.drag_tangential": "statics with a current; time and frequency domain",
    "Segment.added_mass_normal": "modal, time and frequency domain",
    "Segment.added_mass_tangential": "modal, time and frequency domain",
    "Segment.failure": "statics: status 10 (broken); time domain: parts the line; "
    "method frequency refuses it (auto runs the time domain)",
    "Line.failure": "statics: status 10 (broken); time domain: parts the line; "
    "method frequency refuses it (auto runs the time domain)",
    "Line.winch": "time domain only (statics: the state before it runs); refused without "
    "analysis.dynamic and by method frequency",
    "Line.pulleys": "statics: methods catenary, shooting, analytic (discrete refuses "
    "them); time domain; modal, frequency domain, history, transfer_function, database "
    "and seabed friction refuse them",
    "Attachment": "statics, modal, time and frequency domain",
    "Attachment.added_mass": "modal, time and frequency domain (statics: not used)",
    "Attachment.drag_area": "statics with a current: method discrete (catenary, shooting "
    "and analytic refuse it); time and frequency domain",
    "Seabed": "statics, modal (stick spring), time and frequency domain (stick spring)",
    "Seabed.friction_lateral": "modal and frequency domain (stick spring), time domain",
    "Seabed.stiffness": "statics: method discrete (the cable solvers' seabed is rigid); "
    "modal, time and frequency domain",
    "Seabed.damping_ratio": "time and frequency domain",
    "CurrentPoint": "statics (catenary, shooting, discrete; analytic refuses a current); "
    "time and frequency domain (drag on the relative velocity)",
    "FixedEnd.bending": "modal, time and frequency domain (with bending_stiffness > 0)",
    "ForceEnd.bending": "modal, time and frequency domain (with bending_stiffness > 0)",
    "MooringEnd.bending": "modal, time and frequency domain (with bending_stiffness > 0)",
    "ForceEnd": "statics (methods catenary, shooting, discrete); unexcited: a free node in "
    "modal and time domain, refused by method frequency",
    "MooringEnd": "statics (methods catenary, shooting, discrete); unexcited: refused by "
    "the time and frequency domain (excite it, fix it, or make it a force end)",
    "StaticSettings": "statics (and the static state every other analysis starts from)",
    "FreePoint.drag_area": "system statics with a current (refused without one): the "
    "point's drag in the current at its height",
    "StaticSettings.method": "statics; a system (lines, points): catenary or discrete "
    "(discrete for lines with EI > 0; analytic and shooting refused)",
    "StaticSettings.drag_elements": "method catenary with a current",
    "StaticSettings.strain_warning": "statics, every method: a `strain` warning above it "
    "(the case keeps status 0; an axial law's max_strain fails it)",
    "Segment.line_type": "every analysis: fills the segment's unset keys (line types page)",
    "StaticSettings.installation": "method shooting (the others refuse it)",
    "StaticSettings.drag_diameter": "stretched: method shooting with a current (the other "
    "methods refuse it there)",
    "Installation": "static method shooting",
    "DatabaseSettings": "statics (the method of analysis.static); end A fixed, catenary "
    "lines; grid radial refuses environment.depth",
    "GridAxis": "analysis.database",
    "ModalSettings": "modal analysis",
    "DynamicSettings": "time and frequency domain",
    "DynamicSettings.after_break": _TIME_ONLY + "; refused without a failure key",
    "DynamicSettings.linearisation": "methods frequency and auto",
    "DynamicSettings.auto": "method auto only (the other methods refuse it)",
    "DynamicSettings.transfer_function": "methods frequency and auto",
    "HarmonicExcitation": "time and frequency domain",
    "TimeSeriesExcitation": "time domain (method frequency refuses a time table)",
    "SpectrumExcitation": "frequency domain (statistical linearisation); time domain: a "
    "seeded random-phase realisation",
    "Jonswap": "spectrum excitation (with a motion rao table)",
    "HistorySettings": _TIME_ONLY,
    "LinearisationSettings": "methods frequency and auto",
    "LinearisationSettings.samples": "methods frequency and auto with a harmonic "
    "excitation (refused with a spectrum)",
    "AutoSettings": "method auto",
    "FrequencyRange": "methods frequency and auto",
    "Winch": "time domain",
    "Pulley": "statics and time domain",
    "BreakCondition": "statics and time domain (method frequency refuses it)",
    "BreakCondition.time": "time domain only (refused without analysis.dynamic)",
    "LinearAxial": "as Segment.axial (in a spring line: its statics and dynamics)",
    "PolynomialAxial": "as Segment.axial (in a spring line: its statics and dynamics)",
    "SteelWireAxial": "as Segment.axial (in a spring line: its statics and dynamics)",
    "TableAxial": "as Segment.axial (in a spring line: its statics and dynamics)",
}
for _key in TIME_ONLY_KEYS:  # the validator's own list (after_break has its own row)
    USED_BY.setdefault(f"DynamicSettings.{_key}", _TIME_ONLY)

_UNIT = re.compile(r"\[([^\],]+)\]")


def _ref_name(ref: str) -> str:
    return ref.rsplit("/", 1)[-1]


def _cell(text: str) -> str:
    """Text fit for one table cell: one line, pipes escaped."""
    return " ".join(str(text).split()).replace("|", "\\|")


def _json(value: Any) -> str:
    return json.dumps(value, separators=(", ", ": "))


class _Walker:
    """Walks the schema from the root, collecting each model once (in the order a
    reader meets them) with the paths where it appears."""

    def __init__(self, schema: dict[str, Any]) -> None:
        self.defs: dict[str, dict[str, Any]] = schema.get("$defs", {})
        self.models: dict[str, dict[str, Any]] = {}
        self.paths: dict[str, list[str]] = {}
        self._add("Study", schema, "(the file itself)")

    def _add(self, name: str, node: dict[str, Any], path: str) -> None:
        self.paths.setdefault(name, [])
        if path not in self.paths[name]:
            self.paths[name].append(path)
        if name in self.models:
            return
        self.models[name] = node
        for key, prop in node.get("properties", {}).items():
            if name == "Study" and key == "sweep":
                continue  # paths into the file itself: described in the Study table
            self._visit(prop, f"{key}" if path == "(the file itself)" else f"{path}.{key}")

    def _visit(self, node: dict[str, Any], path: str) -> None:
        if "$ref" in node:
            name = _ref_name(node["$ref"])
            self._add(name, self.defs[name], path)
            return
        if node.get("type") == "object" and "properties" in node:
            self._add(node.get("title", path), node, path)
            return
        for key in ("anyOf", "oneOf", "allOf"):
            for sub in node.get(key, []):
                self._visit(sub, path)
        if "items" in node and isinstance(node["items"], dict):
            self._visit(node["items"], f"{path}[]")
        if isinstance(node.get("additionalProperties"), dict):  # named entries
            self._visit(node["additionalProperties"], f"{path}.<name>")

    def type_of(self, node: dict[str, Any]) -> str:
        """A short type: number, integer, string, boolean, list of ..., a model link."""
        if "$ref" in node:
            name = _ref_name(node["$ref"])
            return f"[{name}](#{name.lower()})"
        if "const" in node:
            return "string"
        for key in ("anyOf", "oneOf"):
            if key in node:
                parts = [self.type_of(sub) for sub in node[key] if sub.get("type") != "null"]
                nullable = any(sub.get("type") == "null" for sub in node[key])
                text = " or ".join(dict.fromkeys(p for p in parts if p))
                return text + (" (optional)" if nullable and "default" not in node else "")
        kind = node.get("type")
        if kind == "array":
            items = node.get("items")
            inner = self.type_of(items) if isinstance(items, dict) else "values"
            size = ""
            if node.get("minItems") is not None and node.get("minItems") == node.get("maxItems"):
                size = f" [{node['minItems']}]"
            return f"list of {inner}{size}"
        if kind == "object":
            if "properties" in node and node.get("title") in self.models:
                return f"[{node['title']}](#{node['title'].lower()})"
            values = node.get("additionalProperties")
            if isinstance(values, dict) and values:
                return f"mapping of name to {self.type_of(values)}"
            return "mapping"
        return kind or "any"


def _allowed(node: dict[str, Any]) -> str:
    """Allowed values of a key: enums, constants and bounds, from the schema."""
    parts: list[str] = []
    if "enum" in node:
        parts.append(", ".join(f"`{v}`" for v in node["enum"]))
    if "const" in node:
        parts.append(f"`{node['const']}`")
    bounds = [
        ("exclusiveMinimum", "> "),
        ("minimum", ">= "),
        ("exclusiveMaximum", "< "),
        ("maximum", "<= "),
    ]
    for key, sign in bounds:
        if key in node:
            parts.append(f"{sign}{node[key]:g}")
    if node.get("type") == "array":
        lo, hi = node.get("minItems"), node.get("maxItems")
        if lo is not None and lo == hi:
            pass  # the size is in the type
        elif hi is not None:
            parts.append(f"at most {hi} items")
        elif lo:
            parts.append(f"at least {lo} items")
    if node.get("minLength"):
        parts.append("not empty")
    for key in ("anyOf", "oneOf"):
        for sub in node.get(key, []):
            if "$ref" not in sub and sub.get("type") != "null":
                text = _allowed(sub)
                if text:
                    parts.append(text)
    return "; ".join(parts)


def _units(key: str, description: str) -> str:
    found = _UNIT.search(description)
    if found:
        return found.group(1)
    if key.endswith("_deg"):
        return "deg"
    return ""


def _default(prop: dict[str, Any], required: bool) -> str:
    if required:
        return "required"
    if "default" not in prop:
        return "not set"
    value = prop["default"]
    if value is None:
        return "not set"
    if isinstance(value, (dict, list)) and len(_json(value)) > 60:
        return "see its model" if isinstance(value, dict) else f"{len(value)} items"
    return f"`{_json(value)}`"


def reference_markdown(schema: dict[str, Any]) -> str:
    """The text of ``docs/reference/keys.md`` for ``schema`` (the study's JSON Schema)."""
    walker = _Walker(schema)
    lines = [
        "# Study keys",
        "",
        "Generated from the study schema by `python -m cablestudy.docs_reference`; do not "
        "edit (tests/unit/test_docs.py fails when this page and the schema differ). The "
        "same schema, as JSON, is what `cablestudy schema` prints for editors.",
        "",
        "Every key of a study file, model by model. Units are SI (a non-SI input says so "
        "in its name, `heading_deg`). *Default* is the value used when the key is left "
        "out (*required*: it must be given; *not set*: no value, and the description "
        "says what that means). A key that a chosen analysis or method cannot use is refused "
        "before any work, naming the method that can (*used by*; where a row leaves it "
        "empty, the key serves whatever its model's *Used by* line names).",
        "",
        "Models: " + ", ".join(f"[{name}](#{name.lower()})" for name in walker.models) + ".",
        "",
    ]
    for name, node in walker.models.items():
        lines += [f"## {name}", ""]
        paths = ", ".join(f"`{p}`" if p[0] != "(" else p for p in walker.paths[name])
        lines += [f"At: {paths}.", ""]
        description = node.get("description", "")
        if description and name != "Study":
            lines += [" ".join(description.replace("``", "`").split()), ""]
        if name in USED_BY:
            lines += [f"Used by: {USED_BY[name]}.", ""]
        required = set(node.get("required", []))
        lines += [
            "| key | type | units | default | allowed | description | used by |",
            "|---|---|---|---|---|---|---|",
        ]
        for key, prop in node.get("properties", {}).items():
            text = prop.get("description", "").replace("``", "`")
            if key == "sweep" and name == "Study":
                text = (
                    "parameter sweeps: dotted path -> a list of values, {start, stop, num}, "
                    "{start, stop, step} or {values}, each with an optional name and labels; and "
                    "`zip:` groups (see the sweeps guide)"
                )
            kind = walker.type_of(prop)
            row = [
                f"`{key}`",
                kind,
                "" if "](#" in kind else _units(key, text),  # a model's keys carry their own
                _default(prop, key in required),
                _allowed(prop),
                text,
                USED_BY.get(f"{name}.{key}", ""),
            ]
            lines.append("| " + " | ".join(_cell(c) for c in row) + " |")
        lines.append("")
    return "\n".join(lines)


def current_reference() -> str:
    """The reference for the schema of the installed code."""
    from .config import Study

    return reference_markdown(Study.model_json_schema())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", default=str(REFERENCE), help="file to write")
    parser.add_argument("--check", action="store_true", help="only say whether the file is current")
    args = parser.parse_args(argv)
    out = Path(args.out)
    text = current_reference()
    if args.check:
        if out.exists() and out.read_text() == text:
            return 0
        print(f"{out} is out of date: run python -m cablestudy.docs_reference", file=sys.stderr)
        return 1
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
