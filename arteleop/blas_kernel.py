"""One OpenBLAS kernel on every x86-64 machine, so that a seed gives the same trial on each.

numpy and scipy bundle OpenBLAS, which picks its kernels by the CPU as it loads: the SkylakeX
kernels on a CPU with AVX-512, the Haswell kernels on other recent x86-64 CPUs (AMD's Zen shares
them). The two round the loop's small matrix products differently in the last bit, and a trial
is chaotic, so the same seed gave a different trial on each: 3 of 3 seeded trials differed, by
up to 9.5 mm of placement error and 3.9 s of time (and three tests failed on an AVX-512 machine).
Importing :mod:`arteleop` before numpy asks OpenBLAS for the Haswell kernels wherever the CPU
runs them (AVX2 and FMA, Linux), through ``OPENBLAS_CORETYPE``, which OpenBLAS reads as it loads
and which the processes a run starts (study workers, the render process) inherit.

A user's own ``OPENBLAS_CORETYPE`` is left alone (an empty one counts as unset, as for
OpenBLAS). Where numpy was imported first, OpenBLAS has already chosen: the variable is set to
that choice, so that the processes a run starts compute as this one does, with a
:class:`~arteleop.errors.BlasKernelWarning` where that choice computes otherwise than the
pinned kernel on a CPU that runs it. Elsewhere (another system or CPU) nothing is set:
trials are then the same from run to run on one machine, not necessarily across machines.
"""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import MutableMapping
from pathlib import Path

from arteleop.cpu import CPU_INFO, cpu_flags
from arteleop.errors import BlasKernelWarning

BLAS_KERNEL_VARIABLE = "OPENBLAS_CORETYPE"
PINNED_KERNEL = "Haswell"
"""OpenBLAS's name for the kernels every x86-64 CPU with AVX2 and FMA runs."""
SAME_AS_PINNED = frozenset({PINNED_KERNEL, "Zen"})
"""Kernels that compute as the pinned one: OpenBLAS's Zen target runs the Haswell kernels (asked
for Zen, numpy's OpenBLAS 0.3.31 reports Haswell; the same trials to the bit)."""


def choose_blas_kernel(
    environ: MutableMapping[str, str] = os.environ, cpu_info: Path = CPU_INFO
) -> str | None:
    """Set ``OPENBLAS_CORETYPE`` in ``environ`` as the module describes; return what it holds
    afterwards (None where it is unset). Imports nothing that loads OpenBLAS."""
    if environ.get(BLAS_KERNEL_VARIABLE):  # empty: OpenBLAS picks by the CPU, as if unset
        return environ[BLAS_KERNEL_VARIABLE]
    if "numpy" in sys.modules:
        kernel = running_blas_kernel()
        if kernel is not None and kernel not in SAME_AS_PINNED and cpu_runs_pinned_kernel(cpu_info):
            warnings.warn(
                f"numpy was imported before arteleop and its OpenBLAS runs the {kernel} "
                f"kernels, not {PINNED_KERNEL}: seeded trials will differ from other machines'. "
                f"Import arteleop before numpy, or set {BLAS_KERNEL_VARIABLE}={PINNED_KERNEL}.",
                BlasKernelWarning,
                stacklevel=2,
            )
    elif cpu_runs_pinned_kernel(cpu_info):
        kernel = PINNED_KERNEL
    else:
        kernel = None
    if kernel is not None:
        environ[BLAS_KERNEL_VARIABLE] = kernel
    return kernel


def running_blas_kernel() -> str | None:
    """The kernel numpy's OpenBLAS runs in this process (e.g. ``Haswell``), loading numpy if it
    is not loaded; None where numpy uses another BLAS."""
    library = _numpy_blas()
    if library is None or library.get("internal_api") != "openblas":
        return None
    return library.get("architecture") or None


def blas_description() -> str:
    """numpy's BLAS as a run's manifest records it, e.g. ``openblas 0.3.31 Haswell``."""
    library = _numpy_blas()
    if library is None:
        return "unknown"
    parts = (library.get("internal_api"), library.get("version"), library.get("architecture"))
    return " ".join(str(p) for p in parts if p)


def _numpy_blas() -> dict[str, object] | None:
    """threadpoolctl's record of the BLAS that numpy loaded."""
    import numpy as np  # noqa: F401  (loads its BLAS)
    from threadpoolctl import threadpool_info

    return next(
        (lib for lib in threadpool_info()
         if lib.get("user_api") == "blas" and "numpy" in str(lib.get("filepath"))),
        None,
    )  # fmt: skip


def cpu_runs_pinned_kernel(cpu_info: Path = CPU_INFO) -> bool:
    """Whether this is x86-64 Linux on a CPU with AVX2 and FMA, by ``cpu_info``'s flags."""
    return {"avx2", "fma"} <= cpu_flags(cpu_info)
