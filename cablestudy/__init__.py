"""cablestudy: configuration-driven batch studies of marine cable mechanics."""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

__version__ = "0.1.0"


def _numba_cache_dir() -> None:
    """Keep the compiled kernels' on-disk cache per version of the source.

    numba's cache (``cache=True``) is checked against the file that defines a kernel,
    not the files of the kernels it calls: a kernel of integrator.py compiled with the
    assemble of model.py kept its machine code after model.py changed. The cache goes
    to ``$XDG_CACHE_HOME/cablestudy/numba/<checkout>/<hash of every source file's name,
    size and modification time>`` (about 2 ms), so any change to the package compiles
    afresh. Each checkout of the package (a clone, a worktree) prunes only its own old
    versions, so checkouts side by side do not evict each other's kernels. A
    NUMBA_CACHE_DIR set by the user is kept."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    root = Path(__file__).resolve().parent
    digest = hashlib.sha1()
    for path in sorted(root.rglob("*.py")):
        st = path.stat()
        name = path.relative_to(root).as_posix()
        digest.update(f"{name}:{st.st_size}:{st.st_mtime_ns};".encode())
    home = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    numba_base = Path(home) / "cablestudy" / "numba"
    checkout = hashlib.sha1(str(root).encode()).hexdigest()[:8]
    base = numba_base / checkout
    where = str(base / digest.hexdigest()[:16])
    if not os.path.isdir(where):
        _prune(base, KEEP_CACHES)
        _prune(numba_base, KEEP_CHECKOUTS)
    else:  # mark this checkout used: pruning keeps the most recently used checkouts
        try:
            os.utime(base)
        except OSError:
            pass
    os.environ["NUMBA_CACHE_DIR"] = where
    config = sys.modules.get("numba.core.config")
    if config is not None:  # numba imported before cablestudy: tell it too
        config.CACHE_DIR = where


#: compiled-kernel caches kept (other versions of the source), the newest first
KEEP_CACHES = 3
#: checkouts whose caches are kept, the most recently used first
KEEP_CHECKOUTS = 12


def _prune(base: Path, keep: int) -> None:
    """Remove all but the ``keep`` most recently modified caches under ``base``."""
    import shutil

    try:
        old = sorted(base.iterdir(), key=lambda p: p.stat().st_mtime, reverse=True)[keep:]
    except OSError:
        return
    for path in old:
        shutil.rmtree(path, ignore_errors=True)


_numba_cache_dir()
