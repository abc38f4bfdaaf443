"""Interchange with the open mooring tools: MoorDyn input files (versions 1 and 2) and
the RAFT/MoorPy design YAML in, MoorDyn version 2 input files out.

Everything here is text in, data out: files are read only where the caller allows
(:func:`read_in_scope`), and nothing in them is executed.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from .mapping import ImportedStudy, moordyn_to_study, parse_current_profile
from .moordyn_format import InterchangeError, MoorDynFile, MoorDynFormatError, parse_moordyn
from .moordyn_scope import FEATURES, NotModelledError
from .moorpy_yaml import is_mooring_yaml, line_names, parse_mooring_yaml
from .study_yaml import study_yaml
from .system_import import moordyn_system_to_study

__all__ = [
    "ImportedStudy",
    "InterchangeError",
    "MoorDynFile",
    "FEATURES",
    "MoorDynFormatError",
    "NotModelledError",
    "import_model",
    "imported_yaml",
    "line_from_reference",
    "parse_moordyn",
    "read_in_scope",
]

#: largest model file read [bytes] (MoorDyn files are a few kB; a bigger file is not one)
MAX_BYTES = 5_000_000
#: MoorDyn's steady current table (option ``Currents 1``), beside the input file
CURRENT_FILE = "current_profile.txt"


def read_in_scope(path: str | Path, root: Path | None) -> tuple[str, Path]:
    """Text of a model file, and its resolved path.

    With ``root``, ``path`` is taken relative to it and must stay inside it after
    resolving ``..`` and symbolic links (a study may refer to files in its own folder
    tree only); absolute paths are refused."""
    p = Path(path)
    if root is not None:
        if p.is_absolute():
            raise InterchangeError(
                f"{path}: an absolute path; allowed: a path relative to the study file's folder"
            )
        base = root.resolve()
        p = (base / p).resolve()
        if not p.is_relative_to(base):
            raise InterchangeError(
                f"{path}: leads outside the study file's folder ({base}); allowed: files in "
                "that folder or below it"
            )
    if not p.is_file():
        raise InterchangeError(f"{path}: no such file")
    size = p.stat().st_size
    if size > MAX_BYTES:
        raise InterchangeError(f"{path}: {size} bytes; a model file is at most {MAX_BYTES} bytes")
    try:
        return p.read_text(encoding="utf-8"), p
    except UnicodeDecodeError as exc:
        raise InterchangeError(
            f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start})"
        ) from None


def _line_ids(
    lines: list[str] | int | str | list[int] | None, names: dict[str, int] | None
) -> list[int] | None:
    if lines is None:
        return None
    items = lines if isinstance(lines, list) else [lines]
    out = []
    for item in items:
        text = str(item)
        if names is not None and text in names:
            out.append(names[text])
        elif re.fullmatch(r"\d+", text):
            out.append(int(text))
        else:
            known = f"; line names: {', '.join(names)}" if names else ""
            raise InterchangeError(f"line {text!r} is not a line number{known}")
    return out


def import_model(
    text: str,
    source: str,
    *,
    lines: list[str] | list[int] | int | str | None = None,
    name: str = "moordyn-import",
    folder: Path | None = None,
) -> ImportedStudy:
    """A study from the text of a MoorDyn input file or a RAFT/MoorPy mooring YAML
    (detected by content: a YAML mapping with ``lines`` and ``line_types``).

    Parameters
    ----------
    text, source : the file's text and its name (for messages and comments)
    lines : line IDs (MoorDyn) or names/numbers (mooring YAML) of one line, end to end;
        None: all lines, as one line where they form one chain, else as a system study
        (points, bodies, lines)
    name : the study's name
    folder : the file's folder, where MoorDyn's ``current_profile.txt`` is read when
        the file sets ``Currents 1`` (None: the current table is not read, and says so)
    """
    if is_mooring_yaml(text):
        md, warnings = parse_mooring_yaml(text, source)
        ids = _line_ids(lines, line_names(text))
        imported = _study(md, ids, name=name, current=None)
        imported.warnings[:0] = warnings
        return imported
    md = parse_moordyn(text, source)
    current = None
    opt = md.option("Currents")
    if opt is not None and opt.value.strip() in ("1", "3"):  # steady: grid or node approach
        if folder is None:
            raise InterchangeError(
                f"{source}:{opt.source_line}: Currents {opt.value.strip()} reads {CURRENT_FILE} "
                "beside the file, "
                "which is not available here"
            )
        cur_text, cur_path = read_in_scope(CURRENT_FILE, folder)
        current = parse_current_profile(cur_text, str(cur_path))
    return _study(md, _line_ids(lines, None), name=name, current=current)


def _study(
    md: MoorDynFile, ids: list[int] | None, *, name: str, current: list[dict[str, float]] | None
) -> ImportedStudy:
    """One line (or chain) of ``md``; without chosen ``ids``, a file whose lines do not
    form one chain is imported whole as a system study."""
    try:
        return moordyn_to_study(md, ids, name=name, current=current)
    except NotModelledError as exc:
        if ids is not None or exc.features != ("systems",):
            raise
    return moordyn_system_to_study(md, name=name, current=current)


def imported_yaml(imported: ImportedStudy, source: str) -> str:
    """The imported study as commented YAML text."""
    header = [
        f"study imported by `cablestudy import` from {source}",
        "comments name the source lines; review the ends and the analysis before running",
    ]
    return study_yaml(imported.data, imported.comments, header)


def line_from_reference(
    path: str, lines: Any, study_folder: Path
) -> tuple[dict[str, Any], list[str]]:
    """The ``line:`` mapping (segments, attachments) of ``line: {moordyn: path, line: N}``
    in a study file, and the warnings of what the file holds and is not modelled.

    The path is relative to the study file's folder and must stay inside it."""
    text, resolved = read_in_scope(path, study_folder)
    imported = import_model(
        text, str(path), lines=lines, folder=resolved.parent if resolved else None
    )
    if "line" not in imported.data:
        raise InterchangeError(
            f"{path}: its lines do not form one chain (a system of lines); a study's line "
            "is one chain: choose its lines with line: [ids], or import the whole system "
            "with `cablestudy import moordyn`"
        )
    notes = list(imported.warnings)
    env = imported.data.get("environment", {})
    keys = sorted(
        f"{k}.{sub}" if isinstance(v, dict) else k
        for k, v in env.items()
        for sub in (v if isinstance(v, dict) else [None])
    )
    if keys:
        notes.append(
            f"the file's environment ({', '.join(keys)}) is not used: the study's "
            "environment applies to a referenced line"
        )
    return imported.data["line"], notes
