"""One OpenBLAS kernel wherever the CPU runs it, kept by the processes a run starts."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from arteleop.blas_kernel import (
    BLAS_KERNEL_VARIABLE,
    PINNED_KERNEL,
    SAME_AS_PINNED,
    blas_description,
    choose_blas_kernel,
    cpu_runs_pinned_kernel,
    running_blas_kernel,
)

REPORT = (
    "import json, os, subprocess, sys\n"
    "{first}\n"
    "from arteleop.blas_kernel import running_blas_kernel\n"
    "child = subprocess.run([sys.executable, '-c', 'from arteleop.blas_kernel import "
    "running_blas_kernel; print(running_blas_kernel())'], capture_output=True, text=True)\n"
    "print(json.dumps({{'variable': os.environ.get('OPENBLAS_CORETYPE'), "
    "'kernel': running_blas_kernel(), 'child': child.stdout.strip()}}))\n"
)


def _report(first: str, **env: str) -> dict[str, str | None]:
    """What a fresh interpreter that runs ``first`` sees, and a child process it starts; with
    whether it warned (``warned``)."""
    environ = {k: v for k, v in os.environ.items() if k != BLAS_KERNEL_VARIABLE} | env
    out = subprocess.run(
        [sys.executable, "-c", REPORT.format(first=first)],
        capture_output=True, text=True, env=environ, timeout=120, check=True,
    )  # fmt: skip
    return json.loads(out.stdout) | {"warned": "BlasKernelWarning" in out.stderr}


def _cpu_info(tmp_path: Path, flags: str) -> Path:
    path = tmp_path / "cpuinfo"
    path.write_text(f"processor\t: 0\nmodel name\t: test\nflags\t\t: fpu sse2 {flags}\n\n")
    return path


@pytest.fixture
def pinned_cpu() -> None:
    if not cpu_runs_pinned_kernel():
        pytest.skip("this CPU has no AVX2 and FMA, or this is not Linux on x86-64")


def test_this_process_runs_the_kernel_its_variable_names() -> None:
    """The tests import arteleop before numpy, as the command does."""
    assert running_blas_kernel() == os.environ[BLAS_KERNEL_VARIABLE]


def test_importing_arteleop_first_asks_for_the_haswell_kernels(pinned_cpu: None) -> None:
    seen = _report("import arteleop")
    assert seen == {"variable": PINNED_KERNEL, "kernel": PINNED_KERNEL, "child": PINNED_KERNEL,
                    "warned": False}  # fmt: skip


def test_numpy_imported_first_keeps_its_kernel_and_hands_it_to_children() -> None:
    environ = {k: v for k, v in os.environ.items() if k != BLAS_KERNEL_VARIABLE}
    own = subprocess.run(
        [sys.executable, "-c", "import numpy, threadpoolctl; print([i['architecture'] for i in "
         "threadpoolctl.threadpool_info() if 'numpy' in i['filepath']][0])"],
        capture_output=True, text=True, env=environ, timeout=120, check=True,
    ).stdout.strip()  # fmt: skip
    seen = _report("import numpy, arteleop")
    # It says so where the kernel is not the one other machines run.
    warned = own not in SAME_AS_PINNED and cpu_runs_pinned_kernel()
    assert seen == {"variable": own, "kernel": own, "child": own, "warned": warned}


@pytest.mark.parametrize(("loaded", "same"), [("Zen", True), ("Sandybridge", False)])
def test_numpy_loaded_first_warns_unless_its_kernel_computes_as_the_pinned_one(
    pinned_cpu: None, loaded: str, same: bool
) -> None:
    """Zen's kernels are Haswell's (asked for Zen, this OpenBLAS reports Haswell); Sandybridge's
    round otherwise. Any CPU with AVX2 runs both."""
    seen = _report(
        f"os.environ['OPENBLAS_CORETYPE'] = '{loaded}'; import numpy; "
        "del os.environ['OPENBLAS_CORETYPE']; import arteleop"
    )
    assert seen["variable"] == seen["kernel"] == seen["child"]
    assert (seen["kernel"] in SAME_AS_PINNED) == same
    assert seen["warned"] == (not same)


def test_a_users_own_kernel_is_kept(pinned_cpu: None) -> None:
    seen = _report("import arteleop", OPENBLAS_CORETYPE="Sandybridge")
    assert seen == {"variable": "Sandybridge", "kernel": "Sandybridge", "child": "Sandybridge",
                    "warned": False}  # fmt: skip


def test_the_cpu_must_run_avx2_and_fma(tmp_path: Path) -> None:
    if os.uname().machine not in ("x86_64", "amd64"):
        pytest.skip("the pin is for x86-64")
    assert cpu_runs_pinned_kernel(_cpu_info(tmp_path, "avx avx2 fma avx512f"))
    assert not cpu_runs_pinned_kernel(_cpu_info(tmp_path, "avx avx2"))
    assert not cpu_runs_pinned_kernel(_cpu_info(tmp_path, "avx fma"))
    assert not cpu_runs_pinned_kernel(tmp_path / "missing")


def test_an_empty_variable_counts_as_unset(pinned_cpu: None) -> None:
    seen = _report("import arteleop", OPENBLAS_CORETYPE="")
    assert seen == {"variable": PINNED_KERNEL, "kernel": PINNED_KERNEL, "child": PINNED_KERNEL,
                    "warned": False}  # fmt: skip


def test_a_variable_already_set_is_returned_unchanged() -> None:
    environ = {BLAS_KERNEL_VARIABLE: "Zen"}
    assert choose_blas_kernel(environ) == "Zen"
    assert environ == {BLAS_KERNEL_VARIABLE: "Zen"}


def test_the_description_names_the_library_and_its_kernel() -> None:
    words = blas_description().split()
    assert words[0] == "openblas" and words[-1] == running_blas_kernel()
