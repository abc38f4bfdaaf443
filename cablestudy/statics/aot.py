"""The still-water batch kernels compiled ahead of time, so that the commonest sweeps start
without numba.

numba compiles a kernel on its first call and keeps the machine code on disk, but even
a cached kernel is loaded through numba: importing it (about 0.12 s on the 2-core
development machine), setting up its target context (about 0.1 s, and 0.07 s more for
the scipy.linalg it imports to look for a BLAS), then the kernel itself (6 ms). For the
commonest sweeps, run as arrays (:func:`cablestudy.analyses.static_grid._compiled_solve`) -- lines
hanging free between fixed ends, and lines from an anchor on the seabed to a fairlead
-- that was 40 % of a 20,000-case run end to end.

``numba.pycc`` compiles the same Python functions, :func:`._fast.solve_cases` and
:func:`._fast_contact.contact_cases` with the kernels they call, into a plain extension
module, which imports in well under a millisecond and needs neither numba nor scipy. It
computes the same numbers bit for bit (numba's lowering of the same functions, without
fast-math; tested against the JIT kernels). :func:`build` writes it beside numba's
cache, in the directory per version of the source that :mod:`cablestudy` chooses (a
change to any source file builds afresh), when the static kernels are compiled
(``cablestudy compile``, or the first run that compiles them: :mod:`cablestudy.kernels`).
Where it cannot be built (no C compiler, no numba) or loaded, :func:`kernel` returns
numba's kernel: the same answer, a slower start.
"""

from __future__ import annotations

import importlib.util
import inspect
import os
import shutil
import sysconfig
import tempfile
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

#: the extension module's name (its init function is PyInit_<name>)
MODULE = "cablestudy_static_kernels"

#: per kernel: its numba module (in this package) and the types its callers pass (any
#: layout: 'A' arrays)
KERNELS = {
    "solve_cases": (
        "_fast",
        "void(f8[:,:], f8[:,:], f8[:,:], f8[:,:,:], f8[:,:], i8[:], f8[:,:], f8[:,:], "
        "f8[:,:], f8[:], i8[:], f8[:,:], f8[:,:,:], f8[:,:], f8[:,:], f8[:,:], i8[:], f8[:], "
        "i8[:])",
    ),
    "contact_cases": (
        "_fast_contact",
        "void(f8[:,:], f8[:,:], f8[:,:], f8[:,:,:], f8[:,:], f8[:,:], f8[:,:], i8[:], "
        "f8[:,:], f8[:,:], f8[:,:,:], f8[:], f8[:], b1[:], f8[:], i8[:], f8[:,:], f8[:,:,:], "
        "f8[:,:], f8[:,:], f8[:,:], f8[:], i8[:], f8[:], i8[:])",
    ),
}

#: per module path, the kernels loaded from it (None where it is missing or broken)
_LOADED: dict[str, Any] = {}
#: per cache directory, the module's path (a kernel is looked up at every batch call)
_PATHS: dict[str, Path] = {}


def module_path() -> Path:
    """Where the compiled module of this version of the source lives."""
    where = os.environ.get("NUMBA_CACHE_DIR") or "."
    path = _PATHS.get(where)
    if path is None:
        suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
        path = _PATHS[where] = Path(where) / f"{MODULE}{suffix}"
    return path


def build() -> bool:
    """Compile the module unless it is there; True when it is there afterwards. A failure
    (no C compiler, no numba) leaves nothing behind and is not an error: the kernel then
    comes from numba. Built in a temporary folder and moved into place in one rename, so
    that processes compiling at the same time never load a half-written file."""
    target = module_path()
    if target.is_file():
        return True
    tmp = None
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = tempfile.mkdtemp(prefix=".aot-", dir=target.parent)
        with warnings.catch_warnings():
            # numba.pycc announces its pending deprecation on import; it is the only
            # ahead-of-time compiler numba ships, and a failure here only costs start-up
            warnings.simplefilter("ignore")
            from numba.pycc import CC

            cc = CC(MODULE)
            cc.output_dir = tmp
            for name, (where, signature) in KERNELS.items():
                jitted = getattr(importlib.import_module(f"{__package__}.{where}"), name)
                cc.export(name, signature)(_entry(jitted))
            cc.compile()
        built = next(Path(tmp).glob(f"{MODULE}*"))
        os.replace(built, target)
    except Exception:  # noqa: BLE001 - no compiler, no numba: numba's kernel is used
        return False
    finally:
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)
    return target.is_file()


def _entry(jitted: Any) -> Callable[..., None]:
    """A function of the kernel's own arguments that calls the numba kernel ``jitted``:
    what is exported. pycc compiles an exported function with its default options
    (``error_model="python"``: a division by zero raises), not the kernel's own; called
    from this entry, the kernel is compiled with its options (``error_model="numpy"``: a
    division by zero gives inf or NaN, which the kernel's checks then catch), so that it
    computes what numba's kernel computes in every case, not only where nothing divides
    by zero. The entry holds no arithmetic of its own."""
    names = ", ".join(inspect.signature(jitted.py_func).parameters)
    scope: dict[str, Any] = {"kernel": jitted}
    exec(f"def entry({names}):\n    kernel({names})\n", scope)  # noqa: S102 - our names
    return scope["entry"]  # type: ignore[no-any-return]


def _load(path: Path) -> Any:
    """The compiled module at ``path``, or None when it cannot be loaded or lacks a kernel
    (a truncated copy, a module of another version)."""
    try:
        spec = importlib.util.spec_from_file_location(MODULE, path)
        if spec is None or spec.loader is None:
            return None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    except (ImportError, OSError):
        return None
    return module if all(hasattr(module, name) for name in KERNELS) else None


def kernel(name: str) -> Callable[..., Any]:
    """The batch kernel ``name`` of :data:`KERNELS` (same arguments, same results as
    numba's): compiled ahead of time when the module is built for this source, else
    numba's (loaded, or compiled, on first call)."""
    path = module_path()
    key = str(path)
    if key not in _LOADED:
        _LOADED[key] = _load(path) if path.is_file() else None
    module = _LOADED[key]
    if module is not None:
        return getattr(module, name)  # type: ignore[no-any-return]
    jitted = importlib.import_module(f"{__package__}.{KERNELS[name][0]}")
    return getattr(jitted, name)  # type: ignore[no-any-return]
