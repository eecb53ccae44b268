"""What the CPU can do, as Linux lists it: the vector units that decide how numpy and OpenBLAS
round (:mod:`arteleop.blas_kernel`, :mod:`arteleop.numpy_loops`). Reads files only: nothing here
loads numpy."""

from __future__ import annotations

import platform
from pathlib import Path

CPU_INFO = Path("/proc/cpuinfo")


def cpu_flags(cpu_info: Path = CPU_INFO) -> frozenset[str]:
    """The CPU's feature flags (``avx2``, ``avx512f``, ...) on x86-64 as ``cpu_info`` (Linux's
    ``/proc/cpuinfo``) lists them; empty on another architecture or where it cannot be read."""
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return frozenset()
    try:
        with cpu_info.open(encoding="ascii", errors="replace") as lines:
            # The first processor's flags: every core of a machine has the same.
            flags = next((line for line in lines if line.startswith("flags")), "")
    except OSError:
        return frozenset()
    return frozenset(flags.partition(":")[2].split())
