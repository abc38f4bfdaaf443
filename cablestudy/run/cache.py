"""The per-study cache: finished chunks of cases on disk as data, never as code.

One file per finished chunk (:class:`cablestudy.analyses.grid_chunk.GridChunk`, the one
record form of every study), ``grid-<chunk key>-<sha256>.npz``: a NumPy ``.npz``
archive of plain numeric and text arrays (no object arrays), read back with
``allow_pickle=False`` so that nothing in the cache folder can run code when it is
loaded. The file is named by the sha256 of its own bytes: on load the bytes are hashed
again and a file whose hash does not match its name (truncated, garbled, edited) is
reported once on standard error, removed, and its cases are recomputed. A chunk of rows
of a grid is found again by its content key (:meth:`CaseGrid.chunk_key`); a chunk of
cases picked from the grid holds each case's content hash (everything that affects the
case), so a case is only ever reused for the same case, wherever it now is in the sweep.

Files written atomically (temporary file, fsync, rename). Files of other names are never
opened; the ``chunk-*.npz`` files of earlier versions are removed when the cache is
tidied (:meth:`GridChunkStore.keep`).
"""

from __future__ import annotations

import hashlib
import io
import os
import re
import sys
import tempfile
from collections import Counter
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .outputs import read_regular, regular_file, temporary_prefix, written

#: messages of records that must not be cached (transient: a rerun may succeed)
LOST_PREFIX = "task failed: "
TRANSIENT_PREFIXES = (
    "time limit",
    LOST_PREFIX,
    # a modal or dynamic analysis over the time limit names itself first
    # (cablestudy.analyses.evaluate.evaluate_case)
    "modal analysis: time limit",
    "dynamic analysis: time limit",
)


class CacheFormatError(ValueError):
    """An output that cannot be kept in a chunk file as plain data."""


def _warn_stderr(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)


def _as_data_array(name: str, value: object) -> np.ndarray:
    """``value`` as a plain (numeric, boolean or unicode) array; text held as Python
    objects becomes unicode. Anything else is refused (it could not be stored as data)."""
    arr = np.asarray(value)
    if arr.dtype.kind == "O":
        if all(isinstance(v, str) for v in arr.ravel()):
            arr = arr.astype(str)
        else:
            raise CacheFormatError(f"output {name!r} holds Python objects ({arr.dtype})")
    if arr.dtype.kind not in "biufcU":
        raise CacheFormatError(f"output {name!r} has dtype {arr.dtype}, not plain data")
    return arr


def _write_atomic(path: Path, payload: bytes, stem: str) -> None:
    """``payload`` to ``path`` through a temporary file named after this process
    (:func:`cablestudy.run.outputs.temporary_prefix`), fsync and rename; a full disk raises
    :class:`cablestudy.run.outputs.OutputWriteError`."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=temporary_prefix(stem), suffix=".tmp")

    def complete() -> None:
        with os.fdopen(fd, "wb") as fh:
            fh.write(payload)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)

    try:
        written(path, complete)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


#: temporary files of cache writes (removed by a later run once their writer is gone)
TEMPORARY_PATTERNS = (".chunk-*.tmp", ".grid-*.tmp")


def _odd_entry(path: Path) -> str:
    """Why the cache entry ``path`` is left alone ('' for a regular file)."""
    if regular_file(path):
        return ""
    return (
        f"cache entry {path} is not a regular file (a folder, link, FIFO or device); "
        "skipped and left in place"
    )


GRID_FORMAT = "cablestudy-grid-chunk-1"
_GRID_NAME = re.compile(r"^grid-([0-9a-f]{32})-([0-9a-f]{64})\.npz$")


@dataclass
class GridSummary:
    """What the chunk files of a grid study hold, read one file at a time: the output
    variables and their extra-dimension shapes, the arc lengths every successful case
    shares (None if they differ), the failure messages and the warnings with their
    counts, the number of cases with a warning, and per warning text the first case
    that has it (its flat index in C order)."""

    names: list[str]
    tails: dict[str, tuple[int, ...]]
    arc: np.ndarray | None
    failures: Counter[str]
    warnings: Counter[str] = field(default_factory=Counter)
    n_warned: int = 0
    warned_at: dict[str, int] = field(default_factory=dict)
    #: why cases were solved by the general solver (no batch kernel took them), counted
    fallbacks: Counter[str] = field(default_factory=Counter)
    #: the messages of the cases whose line broke in statics (status 10, their results
    #: kept: an answer, not a failure, as the file's ``cases_broken``), counted
    broken: Counter[str] = field(default_factory=Counter)


def summarise(chunks: Iterable[Any]) -> GridSummary:
    """The :class:`GridSummary` of chunks
    (:class:`cablestudy.analyses.grid_chunk.GridChunk`), in the order of the grid's
    rows."""
    names: set[str] = set()
    tails: dict[str, tuple[int, ...]] = {}
    arc: np.ndarray | None = None
    same_arc = True
    failures: Counter[str] = Counter()
    warnings: Counter[str] = Counter()
    n_warned = 0
    warned_at: dict[str, int] = {}
    offset = 0
    fallbacks: Counter[str] = Counter()
    broken: Counter[str] = Counter()
    from ..analyses.variables import STATUS_BROKEN

    for chunk in chunks:
        status, message, warning, data = chunk.status, chunk.message, chunk.warning, chunk.data
        fallbacks.update(str(r) for r in chunk.fallback_reason[chunk.fallback_reason != ""])
        parted = status == STATUS_BROKEN
        bad = (status != 0) & ~parted
        if bad.any():
            failures.update(str(m) for m in message[bad])
        if parted.any():
            broken.update(str(m) for m in message[parted])
        warned = np.flatnonzero(warning != "")
        n_warned += len(warned)
        if len(warned):
            texts, first, counts = np.unique(warning[warned], return_index=True, return_counts=True)
            for text, i, count in zip(texts.tolist(), first, counts, strict=True):
                warnings[text] += int(count)
                warned_at.setdefault(text, offset + int(warned[i]))
        offset += len(status)
        for k, v in data.items():
            names.add(k)
            old = tails.get(k, tuple(v.shape[1:]))
            tails[k] = tuple(max(a, b) for a, b in zip(old, v.shape[1:], strict=True))
        # (a shared coordinate where each case has one arc length per node; a system's
        # arc_length per line and node stays a variable); the cases whose statics kept
        # them (the others hold NaN)
        if "arc_length" in data and same_arc and data["arc_length"].ndim == 2:
            arcs = data["arc_length"]
            ok = arcs[~np.all(np.isnan(arcs), axis=1)] if arcs.shape[1] else arcs[:0]
            if arc is not None and len(ok) and ok.shape[1] != len(arc):
                same_arc = False
            elif len(ok):
                ref = ok[0] if arc is None else arc
                if np.all(ok == ref):
                    arc = ref
                else:
                    same_arc = False
    return GridSummary(
        sorted(names),
        tails,
        arc if same_arc else None,
        failures,
        warnings,
        n_warned,
        warned_at,
        fallbacks,
        broken,
    )


#: members every chunk file has, and the kinds of array they must be (numpy dtype kinds)
_REQUIRED = {"key": "U", "rows": "iu", "v_status": "iu", "v_message": "U", "v_wall_time": "f"}
_TEXT = ("v_message", "v_warning", "v_fallback", "v_hash")


def _chunk_fault(members: dict[str, np.ndarray], key_prefix: str) -> str:
    """What makes the members of a chunk file unusable as one
    (:meth:`GridChunkStore.chunk`), or '': the members it needs, of the right kinds, its
    key the one its name starts with, its rows ``lo <= hi``, and one record per case in
    every variable (a file that passed its hash check can still have been written by
    hand to look like a chunk; it is recomputed, never half-read)."""
    for name, kinds in _REQUIRED.items():
        if name not in members:
            return f"no member {name!r}"
        if members[name].dtype.kind not in kinds:
            return f"member {name!r} holds {members[name].dtype} data"
    if not str(members["key"]).startswith(key_prefix) or members["key"].ndim != 0:
        return "its key is not the one its name starts with"
    rows = members["rows"]
    if rows.shape != (2,) or not 0 <= rows[0] <= rows[1]:
        return f"rows {rows.tolist()} are not lo <= hi"
    n = members["v_status"].shape[0] if members["v_status"].ndim == 1 else -1
    if n < 0:
        return "v_status is not one status per case"
    for name, arr in members.items():
        if name.startswith("v_") and (arr.ndim == 0 or arr.shape[0] != n):
            return f"{name[2:]} has shape {arr.shape}, not {n} records (one per case)"
        if name in _TEXT and arr.dtype.kind != "U":
            return f"member {name!r} holds {arr.dtype} data"
    if "v_hash" not in members and n != 0 and (rows[1] - rows[0]) and n % (rows[1] - rows[0]):
        return f"{n} records do not fill rows {rows[0]}:{rows[1]}"
    return ""


class GridChunkStore:
    """Chunks of a study run as arrays (:class:`cablestudy.analyses.grid_chunk.GridChunk`), one
    data file
    each, ``grid-<chunk key>-<sha256 of the file>.npz``: plain arrays, read with
    ``allow_pickle=False``, checked against their hash before use (a damaged file is
    reported once, removed and recomputed)."""

    def __init__(self, directory: Path, *, warn: Callable[[str], None] = _warn_stderr) -> None:
        self.directory = directory
        self.warn = warn

    def find(self, key: str) -> Path | None:
        """The intact file of the chunk with content key ``key``, if any."""
        return next(self._intact(f"grid-{key[:32]}-*.npz"), None)

    def _intact(self, pattern: str) -> Iterator[Path]:
        """The files matching ``pattern`` in order, each checked (:meth:`_check`) before
        it is given: an entry that is not a regular file is reported and left in place, a
        damaged file reported once and removed (its cases are recomputed)."""
        if not self.directory.is_dir():
            return
        for path in sorted(self.directory.glob(pattern)):
            odd = _odd_entry(path)
            if odd:
                self.warn(odd)
                continue
            reason = self._check(path)
            if reason:
                self.warn(f"cache file {path} {reason}; its cases will be recomputed")
                path.unlink(missing_ok=True)
                continue
            yield path

    @staticmethod
    def _check(path: Path) -> str:
        match = _GRID_NAME.match(path.name)
        if not match:
            return "is not named grid-<key>-<sha256>.npz"
        try:
            payload = read_regular(path)
        except OSError as exc:
            return f"cannot be read ({exc})"
        digest = hashlib.sha256(payload).hexdigest()
        if digest != match.group(2):
            return f"is damaged (sha256 of its {len(payload)} bytes is {digest[:12]}...)"
        try:
            with np.load(io.BytesIO(payload), allow_pickle=False) as z:
                if "format" not in z.files or str(z["format"]) != GRID_FORMAT:
                    return "is not a grid chunk archive"
                members = {k: z[k] for k in z.files}  # every member loads as plain data
        except Exception as exc:  # noqa: BLE001 - whatever is wrong, the cases are recomputed
            return f"is not a grid chunk archive ({type(exc).__name__})"
        fault = _chunk_fault(members, match.group(1))
        return f"is not a grid chunk archive ({fault})" if fault else ""

    def write(self, chunk: object) -> Path:
        """Write ``chunk`` (a GridChunk) atomically; returns its file."""
        arrays: dict[str, np.ndarray] = {
            "format": np.array(GRID_FORMAT),
            "key": np.array(chunk.key),  # type: ignore[attr-defined]
            "rows": np.array([chunk.lo, chunk.hi], dtype=np.int64),  # type: ignore[attr-defined]
            "v_status": np.asarray(chunk.status, dtype=np.int64),  # type: ignore[attr-defined]
            "v_message": np.asarray(chunk.message, dtype=str),  # type: ignore[attr-defined]
            "v_warning": np.asarray(chunk.warning, dtype=str),  # type: ignore[attr-defined]
            "v_wall_time": np.asarray(chunk.wall_time, dtype=np.float64),  # type: ignore[attr-defined]
            "v_fallback": np.asarray(chunk.fallback_reason, dtype=str),  # type: ignore[attr-defined]
        }
        if chunk.hashes is not None:  # type: ignore[attr-defined]
            arrays["v_hash"] = np.asarray(chunk.hashes, dtype=str)  # type: ignore[attr-defined]
        for name, arr in chunk.data.items():  # type: ignore[attr-defined]
            arrays[f"v_{name}"] = _as_data_array(name, arr)
        buf = io.BytesIO()
        np.savez(buf, **arrays)
        payload = buf.getvalue()
        digest = hashlib.sha256(payload).hexdigest()
        path = self.directory / f"grid-{chunk.key[:32]}-{digest}.npz"  # type: ignore[attr-defined]
        self.directory.mkdir(parents=True, exist_ok=True)
        _write_atomic(path, payload, ".grid-")
        return path

    def summary(self, paths: list[Path]) -> GridSummary:
        """The :func:`summarise` of chunk files, read one at a time."""
        return summarise(self.chunk(p) for p in paths)

    @staticmethod
    def chunk(path: Path) -> Any:
        """A chunk file as a :class:`cablestudy.analyses.grid_chunk.GridChunk`."""
        from ..analyses.grid_chunk import GridChunk

        with np.load(path, allow_pickle=False) as z:
            v = {k[2:]: z[k] for k in z.files if k.startswith("v_")}
            lo, hi = (int(r) for r in z["rows"])
            key = str(z["key"])
        return GridChunk(
            lo=lo,
            hi=hi,
            key=key,
            status=v.pop("status"),
            message=v.pop("message"),
            wall_time=v.pop("wall_time"),
            warning=v.pop("warning", None),
            fallback_reason=v.pop("fallback", None),
            hashes=v.pop("hash", None),
            data=v,
        )

    def cases(self, wanted: set[str]) -> tuple[list[Any], set[Path]]:
        """The chunks of cases picked by content hash (the case-record path) that hold
        cases of ``wanted``, each reduced to those (a case in two files: the first
        found), and the files they came from. Every intact file is read; a damaged one
        is reported once, removed and its cases recomputed."""
        from ..analyses.grid_chunk import take_rows

        found: list[Any] = []
        files: set[Path] = set()
        seen: set[str] = set()
        for path in self._intact("grid-*.npz"):
            chunk = self.chunk(path)
            if chunk.hashes is None:
                continue
            rows = []
            for i, h in enumerate(chunk.hashes.tolist()):
                if h in wanted and h not in seen:
                    seen.add(h)
                    rows.append(i)
            if rows:
                found.append(take_rows(chunk, np.array(rows, dtype=np.intp)))
                files.add(path)
        return found, files

    def files(self) -> list[Path]:
        """The chunk files here (regular files only), of this version and earlier ones."""
        found = [*self.directory.glob("grid-*.npz"), *self.directory.glob("chunk-*.npz")]
        return [p for p in found if regular_file(p)]

    def keep(self, paths: set[Path]) -> None:
        """Remove the grid chunk files not in ``paths`` (cases edited away), and the
        ``chunk-*.npz`` files of earlier versions (never read); call it only when no other
        run of the study is writing here (:class:`cablestudy.run.outputs.CacheLock`).
        Entries that are not regular files are left alone."""
        for path in self.files():
            if path not in paths:
                path.unlink(missing_ok=True)
