"""'arteleop study power': how many participants a design needs, by resampling a pilot's."""

from __future__ import annotations

import csv
import shutil
import sys
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Annotated, Literal

import tyro

from arteleop.cli.analyze import check_report_folder
from arteleop.cli.interrupt import check_ctrl_c
from arteleop.errors import ConfigurationError, ReportWriteError


@dataclass(frozen=True)
class StudyPowerCommand:
    """Estimate the power of a design's tests for each number of participants, by resampling the participants of run folders (or a lab's trials CSV) and running on each resampled study the tests 'arteleop analyze' runs."""

    sources: Annotated[
        tyro.conf.Positional[tuple[Path, ...]], tyro.conf.arg(metavar="RUN_DIR_OR_CSV ...")
    ]
    """the pool: run folders or trials CSVs of one design (a real pilot, a simulated cohort, or both)"""
    out: Path = Path("arteleop-power")
    """the folder for power.csv, power.md and power_curves.png"""
    n: str = "8:40:4"
    """the numbers of participants: first:last:step, or a list such as 10,20,40 (each 3 or more)"""
    resamples: int = 1000
    """resampled studies per number of participants (1 to 100000)"""
    alpha: float = 0.05
    """significance level of the tests (between 0 and 1)"""
    compare: str = ""
    """the conditions compared with the reference, comma-separated; empty: all"""
    reference: str = "none"
    """the condition the others are compared with"""
    paired: bool = False
    """within-subject tests, as 'arteleop analyze --paired'"""
    method: Literal["untrimmed", "yuen", "thesis"] = "untrimmed"
    """how two conditions are compared, as 'arteleop analyze --method'"""
    holm: bool = False
    """Holm-correct each family of pairwise tests, as 'arteleop analyze --holm'"""
    simulate: int = 0
    """add this many simulated participants of the first run folder's design to the pool, run first into the folder OUT-simulated-run (a run folder of its own; --force simulates them anew there)"""
    workers: int = 0
    """processes running the simulated participants' trials; 0: one per core"""
    seed: int = 0
    """seed of the resampling (and of the simulated participants)"""
    force: bool = False
    """replace --out if it holds an earlier report"""
    quiet: bool = False
    """no progress bar"""


def parse_sizes(text: str) -> tuple[int, ...]:
    """``first:last:step`` (last included) or ``a,b,c``."""
    try:
        if ":" in text:
            first, last, step = (int(x) for x in text.split(":"))
            if step < 1 or last < first:
                raise ValueError
            return tuple(range(first, last + 1, step))
        return tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise ConfigurationError(
            f"--n {text}: give first:last:step (such as 8:40:4) or a list (such as 10,20,40) "
            "of whole numbers, 3 or more."
        ) from None


def study_power(cmd: StudyPowerCommand) -> int:
    from tqdm import tqdm

    from arteleop.analysis import AnalysisInputError, load_study
    from arteleop.analysis.power import (
        PowerOptions,
        check_pool_size,
        comparisons,
        make_pool,
        power,
    )
    from arteleop.analysis.power_report import write_power_report

    if not cmd.sources:
        raise ConfigurationError(
            "arteleop study power needs the pool: one or more run folders or trials CSVs, "
            "such as 'arteleop study power my-run --out my-power'."
        )
    sizes = parse_sizes(cmd.n)
    compare = tuple(c.strip() for c in cmd.compare.split(",") if c.strip())
    try:
        options = PowerOptions(sizes, cmd.resamples, cmd.alpha, cmd.paired, cmd.method,
                               cmd.holm, compare, cmd.reference, cmd.seed)  # fmt: skip
    except AnalysisInputError as err:
        raise ConfigurationError(f"{err}.") from None
    if cmd.simulate < 0:
        raise ConfigurationError(f"--simulate {cmd.simulate}: give 0 or more participants.")
    check_report_folder(cmd.out, cmd.sources, cmd.force)
    simulated = cmd.out.parent / f"{cmd.out.name}-simulated-run"
    if cmd.simulate:
        _check_simulated_folder(simulated, cmd.force)
    sources = list(cmd.sources)
    try:
        studies = [load_study(path) for path in sources]
        pool = make_pool(studies, [str(p) for p in sources])
        check_pool_size(pool, ", ".join(map(str, sources)), cmd.simulate)
        comparisons(pool, options)  # an unknown condition is refused before anything runs
        if cmd.simulate:
            _simulate(sources[0], cmd.simulate, cmd.seed, simulated, cmd.workers)
            sources.append(simulated)
            studies.append(load_study(simulated))
            pool = make_pool(studies, [str(p) for p in sources])
            check_pool_size(pool, ", ".join(map(str, sources)))
    except AnalysisInputError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2
    simulated_pool = {k for s in studies for k in s.sources} == {"synthetic"}
    parts = []
    interrupted = False
    bar = tqdm(total=len(sizes), desc="sizes", unit="n", disable=cmd.quiet, leave=False)
    try:
        for part in power(pool, options):
            parts.append(part)
            bar.update(1)
            check_ctrl_c()
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()
    import pandas as pd

    table = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame()
    try:
        files = write_power_report(pool, options, table, cmd.out, simulated_pool, interrupted)
    except OSError as err:
        raise ReportWriteError(f"Cannot write {cmd.out}: {err.strerror or err}.") from None
    print(f"pool: {len(pool.participants)} participants from {len(sources)} source(s); "
          f"{len(parts)} of {len(sizes)} sizes x {options.resamples} resamples")  # fmt: skip
    print(f"wrote {len(files)} files to {cmd.out}, see {files['power.md']}")
    if interrupted:
        raise KeyboardInterrupt(f"the sizes done are in {files['power.csv']}")
    return 0


def _check_simulated_folder(target: Path, force: bool) -> None:
    """Make way for the simulated participants' run folder ``target``: replaced with ``force``
    if an earlier --simulate wrote it, else refused."""
    from arteleop.study import RunFolder

    if not target.exists():
        return
    if not force:
        raise ConfigurationError(
            f"--simulate: {target} holds the simulated participants of an earlier power "
            "analysis; give --force to simulate them anew there, or another --out."
        )
    if not (RunFolder(target).is_run_folder() and _all_simulated(target)):
        raise ConfigurationError(
            f"--simulate: {target} is in the way and is not a run of simulated participants; "
            "move it, or give another --out (--force replaces only what power wrote)."
        )
    shutil.rmtree(target)


def _all_simulated(folder: Path) -> bool:
    """Whether ``folder``'s participants table lists only simulated participants."""
    people = folder / "participants.csv"
    if not people.is_file():
        return False
    with people.open(encoding="utf-8", newline="") as f:
        sources = [row.get("source") for row in csv.DictReader(f)]
    return bool(sources) and all(source == "synthetic" for source in sources)


def _simulate(first: Path, size: int, seed: int, target: Path, workers: int) -> None:
    """``size`` simulated participants of the design of the run folder ``first``, run into
    the new folder ``target``."""
    from arteleop.study import RunFolder, parse_study, run_study

    folder = RunFolder(first)
    if not folder.is_run_folder():
        raise ConfigurationError(
            f"--simulate {size}: {first} is not a run folder with a study.toml: the simulated "
            "participants need the design of the first source."
        )
    study = parse_study((first / "study.toml").read_text(encoding="utf-8"), str(first))
    # The same shares of experts as the design's cohort, another seed than the pilot's.
    c = study.cohort
    both = round(c.both_experts * size / c.size)
    avr, games = (max(round(k * size / c.size), both) for k in (c.avr_experts, c.games_experts))
    cohort = replace(c, size=size, avr_experts=avr, games_experts=games, both_experts=both)
    study = replace(study, participants=(), cohort=cohort, seed=seed + 1000)
    run_study(study, target, workers or None)
