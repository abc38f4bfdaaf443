"""Where a run writes, checked before any work, and kept tidy and safe between runs.

- :func:`check_output_paths`: the output folder can hold ``<name>.nc`` (not a file, the
  target not a folder, writable), or :class:`OutputPathError` (the user's to fix).
- :func:`written`: a write that fails for lack of space says so
  (:class:`OutputWriteError`, "no space left on device at PATH"), whatever library
  reported it and how.
- Temporary files carry their writer's process id and host (:func:`temporary_prefix`),
  so that a later run removes those of writers that died
  (:func:`remove_stale_temporaries`) and never those of a run still writing.
- :class:`CacheLock`: every run holds a shared lock on its cache folder; a run removes
  cache files it no longer needs only when it can take the lock alone, so that runs of
  one study at the same time never delete each other's files.

No module of the package is imported here (results, cache and runner import this).
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import shutil
import socket
import stat
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

T = TypeVar("T")

#: errors that mean the device (or the user's quota on it) is full
FULL_ERRNOS = (errno.ENOSPC, errno.EDQUOT)
#: free bytes below which a failed write is taken as the disk being full (HDF5 reports
#: a full disk as "NetCDF: HDF error", without the errno)
FULL_BELOW_BYTES = 1 << 20


class OutputPathError(ValueError):
    """The output folder given cannot take the results (a file, a folder named as the
    result, not writable): the user's to fix, found before any work."""


class OutputWriteError(OSError):
    """Writing a result or cache file failed because of the machine's state (a full
    disk)."""


def check_output_paths(out_dir: Path, name: str, *, cache: bool = False) -> None:
    """Raise :class:`OutputPathError` unless ``out_dir`` is (or can be made) a folder in
    which ``<name>.nc`` can be written, and with ``cache`` its cache folder
    ``.cache/<name>`` one (cablestudy.run.runner): one line naming the path and what is
    wrong."""
    out_dir = Path(out_dir)
    where = f"--out {out_dir}"
    if out_dir.exists() and not out_dir.is_dir():
        raise OutputPathError(f"{where}: is a file, not a folder")
    target = out_dir / f"{name}.nc"
    if target.is_dir():
        raise OutputPathError(f"{where}: {target} is a folder, not a result file")
    if target.exists() and not target.is_file():
        raise OutputPathError(f"{where}: {target} is not a regular file")
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputPathError(f"{where}: cannot create the folder ({_reason(exc)})") from None
    try:
        fd, probe = tempfile.mkstemp(prefix=f".{name}.write-check.", dir=out_dir)
    except OSError as exc:
        raise OutputPathError(f"{where}: cannot write in the folder ({_reason(exc)})") from None
    os.close(fd)
    os.unlink(probe)
    if cache:
        folder = out_dir / ".cache" / name
        for path in (folder.parent, folder):
            if path.exists() and not path.is_dir():
                raise OutputPathError(
                    f"{where}: the cache folder {path} is not a folder (remove it, or run "
                    "with --no-cache)"
                )
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise OutputPathError(
                f"{where}: cannot create the cache folder {folder} ({_reason(exc)})"
            ) from None


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def disk_full(exc: BaseException, folder: Path) -> bool:
    """Whether ``exc``, raised while writing in ``folder``, means the disk is full: an
    OSError with errno ENOSPC or EDQUOT, or an I/O error (OSError, or RuntimeError as
    netCDF4 raises) while the folder's file system has less than
    :data:`FULL_BELOW_BYTES` free."""
    if isinstance(exc, OSError) and exc.errno in FULL_ERRNOS:
        return True
    if not isinstance(exc, OSError | RuntimeError):  # not an I/O failure
        return False
    try:
        return shutil.disk_usage(folder).free < FULL_BELOW_BYTES
    except OSError:
        return False


def written(path: Path, write: Callable[[], T]) -> T:
    """``write()`` (of the file ``path``), with a failure that means a full disk
    re-raised as :class:`OutputWriteError` ("no space left on device at ``path``")."""
    try:
        return write()
    except Exception as exc:
        if disk_full(exc, Path(path).parent):
            raise OutputWriteError(errno.ENOSPC, f"no space left on device at {path}") from None
        raise


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9]", "_", socket.gethostname())[:40] or "host"


def temporary_prefix(stem: str) -> str:
    """The prefix of a temporary file of this process: ``<stem>pid<pid>@<host>.``."""
    return f"{stem}pid{os.getpid()}@{_host()}."


_OWNER = re.compile(r"pid(\d+)@([A-Za-z0-9_]+)\.")


def _owner_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def stale(path: Path, started: float) -> bool:
    """Whether the temporary ``path`` is left by a writer that died: one of this host
    whose process is gone; or, without an owner in its name (written by an earlier
    version), one last changed before ``started`` (the start of this run, epoch s)."""
    match = _OWNER.search(path.name)
    if match:
        return match.group(2) == _host() and not _owner_alive(int(match.group(1)))
    try:
        return os.lstat(path).st_mtime < started
    except OSError:
        return False


def remove_stale_temporaries(
    folder: Path, patterns: tuple[str, ...], started: float, warn: Callable[[str], None]
) -> list[Path]:
    """Remove from ``folder`` the temporary files and folders matching ``patterns``
    (globs) whose writer died (:func:`stale`); returns them. Each removal is reported
    through ``warn``."""
    removed = []
    if not folder.is_dir():
        return removed
    for pattern in patterns:
        for path in sorted(folder.glob(pattern)):
            if not stale(path, started):
                continue
            with contextlib.suppress(OSError):
                if stat.S_ISDIR(os.lstat(path).st_mode):
                    shutil.rmtree(path)
                else:
                    path.unlink()
                removed.append(path)
                warn(f"removed {path}, left by a run that was stopped while writing it")
    return removed


def regular_file(path: Path) -> bool:
    """Whether ``path`` is a regular file itself (not a folder, FIFO, device or link)."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def read_regular(path: Path) -> bytes:
    """The bytes of the regular file ``path``, opened without following a link and
    without blocking (a FIFO is refused, not waited on). Raises OSError otherwise."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0)
    fd = os.open(path, flags)
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            raise OSError(errno.EINVAL, "not a regular file", str(path))
        return fh.read()


class CacheLock:
    """A shared lock on a cache folder for the life of a run (``<folder>/.lock``, flock:
    released by the system when the process ends, however it ends). :meth:`alone`
    tells whether no other run holds it, so that this run may remove files it does not
    need; where locks are not available, never."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self._fd: int | None = None
        try:
            import fcntl
        except ImportError:  # not on POSIX: no pruning
            return
        folder.mkdir(parents=True, exist_ok=True)
        self._fd = os.open(folder / ".lock", os.O_RDWR | os.O_CREAT, 0o666)
        fcntl.flock(self._fd, fcntl.LOCK_SH)

    def alone(self) -> bool:
        """Take the lock exclusively if no other run holds it (without waiting): True if
        taken. Either way this run's shared lock is given up (it is asked at the end)."""
        if self._fd is None:
            return False
        import fcntl

        try:
            fcntl.flock(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.release()
            return False
        return True

    def release(self) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def __del__(self) -> None:  # a run that raised: its lock goes with it
        self.release()

    def __enter__(self) -> CacheLock:
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()


def now() -> float:
    """The wall-clock time a run starts [epoch s], a little before it (file times are
    rounded by some file systems)."""
    return time.time() - 1.0
