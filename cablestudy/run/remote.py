"""A running dask.distributed scheduler given by its address (``--scheduler
tcp://host:port``): the address checked, the scheduler's handshake awaited with a
timeout before dask's own client talks to it, and its workers awaited with a timeout.

Whatever answers at the address (nothing, a listener that never speaks, a web server, a
scheduler without workers), the run neither hangs nor fails with a traceback: a
malformed address is :class:`SchedulerAddressError` (the user's mistake), anything else
:class:`SchedulerUnreachable` (the machine's state), each one line naming the address.
"""

from __future__ import annotations

import math
import os
import socket
import struct
import time
from typing import Any
from urllib.parse import urlsplit

#: seconds allowed for the whole handshake with a scheduler, and again for a worker to
#: be there, unless ``--connect-timeout`` or :data:`TIMEOUT_ENV` says otherwise
DEFAULT_TIMEOUT = 10.0
TIMEOUT_ENV = "CABLESTUDY_CONNECT_TIMEOUT"
#: the largest first message a dask scheduler sends (its handshake: a few hundred bytes)
MAX_HANDSHAKE_BYTES = 1 << 20


class SchedulerAddressError(ValueError):
    """``--scheduler`` names no address dask can connect to without more settings."""


class SchedulerUnreachable(RuntimeError):
    """The dask.distributed scheduler named by ``--scheduler ADDRESS`` did not answer as
    one, or has no workers."""


def connect_timeout(value: float | None = None) -> float:
    """Seconds for the handshake and for the workers: ``value`` if given, else
    ``$CABLESTUDY_CONNECT_TIMEOUT``, else :data:`DEFAULT_TIMEOUT`."""
    if value is None:
        text = os.environ.get(TIMEOUT_ENV, "")
        try:
            value = float(text) if text else DEFAULT_TIMEOUT
        except ValueError:
            raise SchedulerAddressError(
                f"${TIMEOUT_ENV} {text!r}: not a number of seconds"
            ) from None
    if not (value > 0 and math.isfinite(value)):
        raise SchedulerAddressError(f"connect timeout {value!r}: must be a positive number of s")
    return float(value)


def parse_address(address: str) -> tuple[str, int]:
    """(host, port) of ``tcp://host:port``; anything else is
    :class:`SchedulerAddressError` saying what is wrong with it."""
    scheme, sep, _ = address.partition("://")
    if not sep:
        raise SchedulerAddressError(f"--scheduler {address}: not an address scheme://host:port")
    if scheme == "tls":
        raise SchedulerAddressError(
            f"--scheduler {address}: tls:// needs the cluster's certificates, which "
            "cablestudy does not take; give the scheduler's tcp:// address"
        )
    if scheme != "tcp":
        raise SchedulerAddressError(
            f"--scheduler {address}: unknown scheme {scheme + '://'!r}; allowed: tcp://host:port"
        )
    parts = urlsplit(address)
    try:
        port = parts.port
    except ValueError:
        port = -1
    host = parts.hostname
    if not host:
        raise SchedulerAddressError(f"--scheduler {address}: no host (tcp://host:port)")
    if port is None:
        raise SchedulerAddressError(f"--scheduler {address}: no port (tcp://host:port)")
    if not 0 < port < 65536 or parts.path not in ("", "/") or parts.query or parts.fragment:
        raise SchedulerAddressError(
            f"--scheduler {address}: not an address tcp://host:port with a port from 1 to 65535"
        )
    return host, port


def await_handshake(address: str, timeout: float) -> None:
    """Connect to ``address`` and read the handshake a dask scheduler sends first, all
    within ``timeout`` seconds, without sending anything (a web server or another
    service waits for a request, and is not asked). Raises
    :class:`SchedulerUnreachable`."""
    host, port = parse_address(address)
    deadline = time.monotonic() + timeout
    where = f"--scheduler {address}"
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except TimeoutError:
        raise SchedulerUnreachable(f"{where}: no connection within {timeout:g} s") from None
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
        raise SchedulerUnreachable(f"{where}: cannot connect ({reason})") from None
    with sock:
        try:
            header = _read(sock, 8, deadline)
            (size,) = struct.unpack("<Q", header)
            if not 0 < size <= MAX_HANDSHAKE_BYTES:
                raise SchedulerUnreachable(
                    f"{where}: answered, but not as a dask scheduler (it sent {header!r})"
                )
            _read(sock, size, deadline)
        except TimeoutError:
            raise SchedulerUnreachable(
                f"{where}: accepted the connection but sent no dask handshake within "
                f"{timeout:g} s (not a dask scheduler, or one too busy to answer)"
            ) from None
        except (ConnectionError, EOFError) as exc:
            raise SchedulerUnreachable(
                f"{where}: closed the connection during the dask handshake ({exc})"
            ) from None


def _read(sock: socket.socket, n: int, deadline: float) -> bytes:
    out = bytearray()
    while len(out) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(min(n - len(out), 1 << 16))
        if not chunk:
            raise EOFError("end of stream")
        out += chunk
    return bytes(out)


def connect(address: str, timeout: float) -> Any:
    """A ``dask.distributed.Client`` of the scheduler at ``address`` with at least one
    worker: the handshake awaited first (:func:`await_handshake`), then dask's client
    connected and a worker awaited, each within ``timeout`` seconds. Raises
    :class:`SchedulerUnreachable`."""
    await_handshake(address, timeout)
    from dask.distributed import Client

    where = f"--scheduler {address}"
    try:
        client = Client(address, timeout=timeout)
    except (OSError, TimeoutError) as exc:
        raise SchedulerUnreachable(
            f"{where}: the dask client did not connect within {timeout:g} s "
            f"({type(exc).__name__}: {exc})"
        ) from None
    try:
        client.wait_for_workers(1, timeout=timeout)
    except (OSError, TimeoutError):
        client.close()
        raise SchedulerUnreachable(
            f"{where}: the scheduler answers but has no workers (none joined within {timeout:g} s)"
        ) from None
    return client
