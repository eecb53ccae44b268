"""numpy's AVX-512 math loops turned off wherever the CPU has them, kept off by the processes a
run starts."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from arteleop.blas_kernel import cpu_flags, cpu_runs_pinned_kernel
from arteleop.numpy_loops import (
    AVX512_TARGETS,
    ENABLE_VARIABLE,
    LOOPS_VARIABLE,
    choose_numpy_loops,
    numpy_loops_description,
    running_avx512_targets,
)

REPORT = (
    "import json, os, subprocess, sys\n"
    "{first}\n"
    "from arteleop.numpy_loops import running_avx512_targets as r\n"
    "child = subprocess.run([sys.executable, '-c', 'from arteleop.numpy_loops import "
    'running_avx512_targets as r; print(" ".join(r()))\'], capture_output=True, text=True)\n'
    "print(json.dumps({{'variable': os.environ.get('NPY_DISABLE_CPU_FEATURES'), "
    "'running': ' '.join(r()), 'child': child.stdout.strip()}}))\n"
)


def _report(first: str) -> dict[str, str | None]:
    """What a fresh interpreter that runs ``first`` sees, and a child process it starts; with
    whether it warned (``warned``)."""
    environ = {k: v for k, v in os.environ.items() if k not in (LOOPS_VARIABLE, ENABLE_VARIABLE)}
    out = subprocess.run(
        [sys.executable, "-c", REPORT.format(first=first)],
        capture_output=True, text=True, env=environ, timeout=120, check=True,
    )  # fmt: skip
    return json.loads(out.stdout) | {"warned": "NumpyLoopsWarning" in out.stderr}


@pytest.fixture
def avx512_cpu() -> None:
    if not (cpu_runs_pinned_kernel() and "avx512f" in cpu_flags()):
        pytest.skip("this CPU has no AVX-512, or this is not Linux on x86-64")


@pytest.fixture
def numpy_unloaded(monkeypatch: pytest.MonkeyPatch) -> None:
    """As if numpy were not loaded yet (the function under test then never loads it)."""
    monkeypatch.delitem(sys.modules, "numpy")


def _cpu_info(tmp_path: Path, flags: str) -> Path:
    path = tmp_path / "cpuinfo"
    path.write_text(f"processor\t: 0\nmodel name\t: test\nflags\t\t: fpu sse2 {flags}\n\n")
    return path


def test_this_process_runs_no_avx512_loop() -> None:
    """The tests import arteleop before numpy, as the command does."""
    assert running_avx512_targets() == ()


def test_importing_arteleop_first_turns_them_off_here_and_in_children(avx512_cpu: None) -> None:
    assert _report("import arteleop") == {"variable": " ".join(AVX512_TARGETS), "running": "",
                                          "child": "", "warned": False}  # fmt: skip


def test_numpy_imported_first_keeps_them_and_says_so(avx512_cpu: None) -> None:
    seen = _report("import numpy, arteleop")
    assert seen["variable"] is None and seen["warned"]
    assert seen["running"].split()[0] == AVX512_TARGETS[0]


@pytest.mark.parametrize(
    ("flags", "expected"),
    [("avx avx2 fma avx512f avx512cd", " ".join(AVX512_TARGETS)), ("avx avx2 fma", None),
     ("avx avx512f", None)],
)  # fmt: skip
def test_only_a_cpu_with_avx512_has_them_turned_off(
    numpy_unloaded: None, tmp_path: Path, flags: str, expected: str | None
) -> None:
    if os.uname().machine not in ("x86_64", "amd64"):
        pytest.skip("the pin is for x86-64")
    environ: dict[str, str] = {}
    assert choose_numpy_loops(environ, _cpu_info(tmp_path, flags)) == expected
    assert environ.get(LOOPS_VARIABLE) == expected


@pytest.mark.parametrize("variable", [LOOPS_VARIABLE, ENABLE_VARIABLE])
def test_a_users_own_choice_is_kept(numpy_unloaded: None, tmp_path: Path, variable: str) -> None:
    environ = {variable: "AVX512_SPR"}
    chosen = choose_numpy_loops(environ, _cpu_info(tmp_path, "avx2 fma avx512f"))
    assert environ == {variable: "AVX512_SPR"}
    assert chosen == ("AVX512_SPR" if variable == LOOPS_VARIABLE else None)


def test_the_description_names_the_loops_that_run() -> None:
    described = numpy_loops_description().split()
    assert described and not set(described) & set(AVX512_TARGETS)
