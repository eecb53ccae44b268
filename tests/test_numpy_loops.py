"""numpy's AVX-512 math loops turned off wherever the CPU has them, kept off by the processes a
run starts."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from arteleop import numpy_loops
from arteleop.cpu import cpu_flags
from arteleop.numpy_loops import (
    AVX512_TARGETS,
    AVX512_TARGETS_BEFORE_2_4,
    ENABLE_VARIABLE,
    LOOPS_VARIABLE,
    avx512_target_names,
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


def _report(first: str, *flags: str) -> dict[str, str | None]:
    """What a fresh interpreter (with ``flags``) that runs ``first`` sees, and a child process
    it starts; with whether it warned (``warned``)."""
    environ = {k: v for k, v in os.environ.items() if k not in (LOOPS_VARIABLE, ENABLE_VARIABLE)}
    out = subprocess.run(
        [sys.executable, *flags, "-c", REPORT.format(first=first)],
        capture_output=True, text=True, env=environ, timeout=120, check=True,
    )  # fmt: skip
    return json.loads(out.stdout) | {"warned": "NumpyLoopsWarning" in out.stderr}


@pytest.fixture
def avx512_cpu() -> None:
    if "avx512f" not in cpu_flags():
        pytest.skip("this CPU has no AVX-512, or this is not Linux on x86-64")


@pytest.fixture
def numpy_unloaded(monkeypatch: pytest.MonkeyPatch) -> None:
    """As if numpy were not loaded yet (the function under test then never loads it)."""
    monkeypatch.delitem(sys.modules, "numpy")


def _cpu_info(tmp_path: Path, flags: str) -> Path:
    path = tmp_path / "cpuinfo"
    path.write_text(f"processor\t: 0\nmodel name\t: test\nflags\t\t: fpu sse2 {flags}\n\n")
    return path


def test_this_process_runs_no_avx512_loop(avx512_cpu: None) -> None:
    """The tests import arteleop before numpy, as the command does."""
    assert running_avx512_targets() == ()


def test_importing_arteleop_first_turns_them_off_here_and_in_children(avx512_cpu: None) -> None:
    # Where warnings are errors too: a target name this numpy does not know would stop it.
    seen = _report("import arteleop", "-W", "error")
    assert seen == {"variable": " ".join(avx512_target_names()), "running": "", "child": "",
                    "warned": False}  # fmt: skip


def test_numpy_imported_first_keeps_them_and_says_so(avx512_cpu: None) -> None:
    seen = _report("import numpy, arteleop")
    assert seen["variable"] is None and seen["warned"]
    assert set(seen["running"].split()) & set(avx512_target_names())
    assert seen["child"] == seen["running"], "the processes it starts compute as it does"


@pytest.mark.parametrize(
    ("version", "names"),
    [("2.4.6", AVX512_TARGETS), ("2.4.0rc1", AVX512_TARGETS), ("3.0.0", AVX512_TARGETS),
     ("2.3.5", AVX512_TARGETS_BEFORE_2_4), ("1.26.4", AVX512_TARGETS_BEFORE_2_4),
     (None, AVX512_TARGETS)],
)  # fmt: skip
def test_the_names_follow_numpys_version(
    monkeypatch: pytest.MonkeyPatch, version: str | None, names: tuple[str, ...]
) -> None:
    def installed(name: str) -> str:
        if version is None:
            raise numpy_loops.metadata.PackageNotFoundError(name)
        return version

    monkeypatch.setattr(numpy_loops.metadata, "version", installed)
    assert avx512_target_names() == names


@pytest.mark.parametrize(
    ("flags", "expected"),
    [("avx avx2 fma avx512f avx512cd", " ".join(avx512_target_names())), ("avx avx2 fma", None),
     ("fpu", None)],
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


@pytest.mark.parametrize("variable", [LOOPS_VARIABLE, ENABLE_VARIABLE])
def test_an_empty_variable_counts_as_unset(
    numpy_unloaded: None, tmp_path: Path, variable: str
) -> None:
    if os.uname().machine not in ("x86_64", "amd64"):
        pytest.skip("the pin is for x86-64")
    environ = {variable: ""}
    chosen = choose_numpy_loops(environ, _cpu_info(tmp_path, "avx2 fma avx512f"))
    assert chosen == environ[LOOPS_VARIABLE] == " ".join(avx512_target_names())


def test_the_description_names_the_loops_that_ran(capsys: pytest.CaptureFixture[str]) -> None:
    """As numpy's own report has them; a process with every dispatched target off runs
    numpy's baseline loops alone."""
    np.show_runtime()
    found = re.search(r"'found': \[([^\]]*)\]", capsys.readouterr().out)
    assert found is not None
    assert numpy_loops_description() == (" ".join(re.findall(r"'(\w+)'", found[1])) or "baseline")
    __cpu_dispatch__ = numpy_loops._umath().__cpu_dispatch__
    environ = {k: v for k, v in os.environ.items() if k != ENABLE_VARIABLE}
    environ[LOOPS_VARIABLE] = " ".join(__cpu_dispatch__)
    out = subprocess.run(
        [sys.executable, "-c", "from arteleop.numpy_loops import numpy_loops_description as d; "
         "print(d())"],
        capture_output=True, text=True, env=environ, timeout=120, check=True,
    )  # fmt: skip
    assert out.stdout.strip() == "baseline"
