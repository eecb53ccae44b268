"""numpy's math loops without AVX-512, so that a seed gives the same trial on every x86-64 machine.

numpy picks its vector loops by the CPU as it loads. On a CPU with AVX-512 it computes float64
sine, cosine, exponential, logarithm and their kin with Intel's SVML (its AVX-512 targets),
elsewhere with the C library's; the two differ in the last bit, and a trial is chaotic. On the
first AVX-512 machine checked (2026-12-01), one of ``benchmarks/trace_hashes.py``'s five seeded
trials differed from the AVX2 machines' (0.13 mm of placement error); with numpy's AVX-512
targets turned off, all five were theirs to the bit.

Importing :mod:`arteleop` before numpy turns those targets off where the CPU has them (x86-64
Linux with AVX-512), through ``NPY_DISABLE_CPU_FEATURES``, which numpy reads as it loads and
which the processes a run starts inherit. The AVX2 loops stay: they compute these trials as
numpy's baseline loops do (see ``docs/results/reproducibility.md``). The targets' names are
numpy 2.4's (checked) or, for an older numpy, those its documentation gives (not checked here);
a numpy whose version cannot be read is taken for 2.4 or later. A numpy built with AVX-512 as
its baseline cannot turn it off, and refuses to load with the variable set: there, set
``NPY_ENABLE_CPU_FEATURES`` yourself (to the features that build runs), which is left alone.

A user's own ``NPY_DISABLE_CPU_FEATURES`` or ``NPY_ENABLE_CPU_FEATURES`` is left alone (numpy
refuses both at once; an empty one counts as unset, as for numpy). Where numpy was imported
first with its AVX-512 targets on, a :class:`~arteleop.errors.NumpyLoopsWarning` says so and
names the targets to turn off, and ``NPY_ENABLE_CPU_FEATURES`` is set to the targets it runs,
so that the processes a run starts compute as this one does (they import arteleop first, and
would turn them off). Elsewhere nothing is set.
"""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import MutableMapping
from importlib import metadata
from pathlib import Path

from arteleop.cpu import CPU_INFO, cpu_flags
from arteleop.errors import NumpyLoopsWarning

LOOPS_VARIABLE = "NPY_DISABLE_CPU_FEATURES"
ENABLE_VARIABLE = "NPY_ENABLE_CPU_FEATURES"
AVX512_TARGETS = ("X86_V4", "AVX512_ICL", "AVX512_SPR")
"""numpy's AVX-512 dispatch targets, as numpy 2.4 and later name them."""
AVX512_TARGETS_BEFORE_2_4 = ("AVX512F", "AVX512_SKX", "AVX512_CLX", "AVX512_CNL", "AVX512_ICL")
"""The targets with float64 math loops as numpy 1.26 to 2.3 name them (2.4 grouped them by
x86-64 level). Only names every such numpy dispatches: numpy warns of another
(``ImportWarning``), and fails to load where warnings are errors."""
ANY_AVX512_TARGET = frozenset(AVX512_TARGETS + AVX512_TARGETS_BEFORE_2_4)
"""Every AVX-512 target's name, in any numpy's naming."""


def choose_numpy_loops(
    environ: MutableMapping[str, str] = os.environ, cpu_info: Path = CPU_INFO
) -> str | None:
    """Set ``NPY_DISABLE_CPU_FEATURES`` in ``environ`` as the module describes; return what it
    holds afterwards (None where it is unset). Imports nothing that loads numpy."""
    if environ.get(LOOPS_VARIABLE) or environ.get(ENABLE_VARIABLE):
        return environ.get(LOOPS_VARIABLE) or None
    if "numpy" in sys.modules:
        running = running_avx512_targets()
        if running:
            warnings.warn(
                f"numpy was imported before arteleop and runs its AVX-512 loops "
                f"({' '.join(running)}): seeded trials may differ from other machines'. Import "
                f'arteleop before numpy, or set {LOOPS_VARIABLE}="{" ".join(running)}".',
                NumpyLoopsWarning,
                stacklevel=2,
            )
            environ[ENABLE_VARIABLE] = " ".join(_running_targets())
        return None
    if "avx512f" not in cpu_flags(cpu_info):  # x86-64 Linux with AVX-512 only
        return None
    environ[LOOPS_VARIABLE] = " ".join(avx512_target_names())
    return environ[LOOPS_VARIABLE]


def running_avx512_targets() -> tuple[str, ...]:
    """numpy's AVX-512 targets that run in this process, loading numpy if it is not loaded."""
    return tuple(t for t in _running_targets() if t in ANY_AVX512_TARGET)


def numpy_loops_description() -> str:
    """numpy's dispatched loops that run here, as a run's manifest records them, e.g. ``X86_V3``
    (``baseline`` where none does)."""
    return " ".join(_running_targets()) or "baseline"


def avx512_target_names() -> tuple[str, ...]:
    """The AVX-512 targets to turn off, as the installed numpy names them (read without loading
    numpy)."""
    try:
        major, minor = (int(p) for p in metadata.version("numpy").split(".")[:2])
    except (metadata.PackageNotFoundError, ValueError):
        return AVX512_TARGETS
    return AVX512_TARGETS if (major, minor) >= (2, 4) else AVX512_TARGETS_BEFORE_2_4


def _running_targets() -> tuple[str, ...]:
    """numpy's dispatch targets that this CPU runs and nothing turned off (numpy reads a
    disabled one as absent)."""
    umath = _umath()
    return tuple(t for t in umath.__cpu_dispatch__ if umath.__cpu_features__.get(t))


def _umath():  # numpy's private extension module, untyped
    import numpy as np

    return (getattr(np, "_core", None) or np.core)._multiarray_umath
