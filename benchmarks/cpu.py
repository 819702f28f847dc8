"""The CPU time every benchmark reports: user + sys seconds, not wall time (the machines these
run on are shared: wall time measures the neighbours)."""

from __future__ import annotations

import resource


def cpu_seconds(children: bool = False) -> float:
    """User + sys CPU seconds of this process (and, with ``children``, its reaped children)."""
    whose = (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN) if children else (resource.RUSAGE_SELF,)
    return sum(u.ru_utime + u.ru_stime for u in map(resource.getrusage, whose))


def print_cpu() -> None:
    """The closing line of a benchmark: its whole CPU time."""
    print("CPU s (user + sys):", round(cpu_seconds(), 1))
