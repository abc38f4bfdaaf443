"""Work counters of this process (static solves, linear-model assemblies), so tests and
benchmarks can check that a sweep reuses what it may, and the trimming of the
process's solution caches. Light: imports nothing heavy."""

from __future__ import annotations

from collections import Counter, OrderedDict

#: counts by kind of work: ``static_solves``, ``linear_assemblies`` (frequency domain),
#: ``line_assemblies`` (the time domain's lumped-mass line and its discrete equilibrium)
COUNTERS: Counter[str] = Counter()


def trim_lru(cache: OrderedDict, size: int) -> None:
    """Drop the least recently used entries of ``cache`` beyond ``size``. Safe when
    threads share the cache: one that finds it already trimmed by another stops."""
    while len(cache) > size:
        try:
            cache.popitem(last=False)
        except KeyError:  # emptied meanwhile by another thread
            return
