"""'arteleop analyze': a study's statistics, figures and report from its files; or, given
several run folders of one design, its answer pooled over those cohorts."""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Literal

import tyro

from arteleop.errors import ConfigurationError, ReportWriteError

if TYPE_CHECKING:
    from arteleop.analysis import AnalysisOptions


@dataclass(frozen=True)
class AnalyzeCommand:
    """Analyse a study's files (docs/explanation/study.md §5) and write tables,
    figures and report.md; given several run folders of one design (cohorts), pool them:
    medians per cohort and each cue set's effect against none, paired by participant."""

    sources: Annotated[
        tyro.conf.Positional[tuple[Path, ...]], tyro.conf.arg(metavar="RUN_DIR_OR_CSV ...")
    ]
    """a run folder (trials.csv, participants.csv, questionnaire.csv, trajectories/) or a trials CSV; several run folders: one per cohort, pooled; or a pointing study's table (pointing.csv, or a folder holding it): its ISO 9241-9 analysis"""
    out: Path = Path("arteleop-report")
    """report folder"""
    participants: Path | None = None
    """participants.csv for a bare trials CSV (one source)"""
    method: Literal["untrimmed", "yuen", "thesis"] = "untrimmed"
    """how two modalities are compared (one source): untrimmed (everyone; t-test or rank test by Lilliefors), yuen (20 % trimmed means, robust to outliers), thesis (the original's dropped extremes, to reproduce it: rejects a true null about twice as often as it says)"""
    paired: bool = False
    """within-subject tests (paired t-test / Wilcoxon) between modalities (one source)"""
    holm: bool = False
    """Holm-correct each family of pairwise tests (one source)"""
    allow_different_designs: bool = False
    """pool run folders whose study files differ in more than seed and cohort size, as a deliberate comparison of designs (several sources; the report says so)"""
    force: bool = False
    """replace --out if it holds an earlier report (never a folder of anything else)"""


def analyze(cmd: AnalyzeCommand) -> int:
    from arteleop.analysis import AnalysisInputError, AnalysisOptions

    if not cmd.sources:
        raise ConfigurationError(
            "arteleop analyze needs a run folder or a trials CSV: 'arteleop analyze my-run "
            "--out my-report'; several run folders of one design are pooled."
        )
    try:
        options = AnalysisOptions(method=cmd.method, paired=cmd.paired, holm=cmd.holm)
    except AnalysisInputError as err:
        raise ConfigurationError(f"{err}.") from None
    check_report_folder(cmd.out, cmd.sources, cmd.force)
    try:
        from arteleop.analysis.pointing import pointing_table_path

        tables = [pointing_table_path(source) for source in cmd.sources]
        if all(table is not None for table in tables):
            _refuse_study_options(cmd)
            return _analyse_pointing([t for t in tables if t is not None], cmd.out)
        if any(table is not None for table in tables):
            pointing = cmd.sources[[t is not None for t in tables].index(True)]
            raise ConfigurationError(
                f"{pointing} is a pointing study's table, and the others are not: give pointing "
                "tables alone (compared side by side) or run folders alone (pooled)."
            )
        if len(cmd.sources) == 1:
            return _analyse_one(cmd, options)
        return _pool(cmd)
    except AnalysisInputError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        raise ReportWriteError(
            f"Cannot write the report to {cmd.out}: {err.strerror or err}. Nothing of it was "
            "kept; free space or fix permissions and analyse again."
        ) from None


def check_report_folder(out: Path, sources: tuple[Path, ...], force: bool) -> None:
    """Refuse an ``--out`` that would lose something: a file, a folder of data or a source of
    the analysis, or an earlier report without ``--force``."""
    from arteleop.analysis.output import is_report_folder

    resolved = out.resolve()
    for source in sources:
        folder = source.resolve() if source.is_dir() else source.resolve().parent
        if resolved == folder or resolved in folder.parents:
            raise ConfigurationError(
                f"--out {out}: it holds the data analysed ({source}); give a new folder, such "
                f"as {source / 'report' if source.is_dir() else folder / 'report'}."
            )
    if out.exists() and not out.is_dir():
        raise ConfigurationError(f"--out {out}: a file, not a folder; give a new folder.")
    if out.is_dir() and any(out.iterdir()):
        if not is_report_folder(out):
            raise ConfigurationError(
                f"--out {out}: a folder that holds other files than a report; give a new folder."
            )
        if not force:
            raise ConfigurationError(
                f"--out {out} holds an earlier report; give a new folder, or --force to replace it."
            )


def _analyse_one(cmd: AnalyzeCommand, options: AnalysisOptions) -> int:
    from arteleop.analysis import analyse, load_study, write_report
    from arteleop.analysis.pooling import changed_constants_notes

    study = load_study(cmd.sources[0], cmd.participants)
    result = analyse(study, options)
    source = cmd.sources[0]
    result.notes[:0] = changed_constants_notes([source if source.is_dir() else source.parent])
    files = write_report(study, result, options, cmd.out)
    n_people = result.trials["participant"].nunique()
    said = ", ".join(f"{outcome} {n}" for outcome, n in result.left_out.items())
    print(f"analysed {result.counts['analysed']} successful experimental trials of {n_people} "
          f"participants" + (f"; left out: {said}" if said else ""))  # fmt: skip
    significant = result.tests[(result.tests["stars"] != "") & result.tests["stars"].notna()]
    print(f"{len(result.tests)} tests, {len(significant)} significant at p <= 0.05")
    for note in result.notes:
        print(f"note: {note}")
    print(f"wrote {len(files)} files to {cmd.out}, see {files['report.md']}")
    return 0


def _refuse_study_options(cmd: AnalyzeCommand) -> None:
    """A pointing table has no modalities to compare, participants' file or designs to pool."""
    given = [option for option, on in (
        (f"--participants {cmd.participants}", cmd.participants is not None),
        (f"--method {cmd.method}", cmd.method != "untrimmed"), ("--paired", cmd.paired),
        ("--holm", cmd.holm), ("--allow-different-designs", cmd.allow_different_designs),
    ) if on]  # fmt: skip
    if given:
        raise ConfigurationError(
            f"{given[0]}: compares a study's modalities; a pointing table is analysed as "
            "ISO 9241-9 asks, with no such option. Leave it out."
        )


def _analyse_pointing(tables: list[Path], out: Path) -> int:
    from arteleop.analysis.pointing import load_pointing
    from arteleop.analysis.pointing_report import (
        source_name,
        write_pointing_comparison,
        write_pointing_report,
    )

    seen: dict[object, Path] = {}
    for table in tables:
        try:
            content = table.read_bytes()
        except OSError as err:
            raise ConfigurationError(f"{table}: cannot read it ({err.strerror or err}).") from None
        for key, what in ((table.resolve(), "is given twice"),
                          (content, "holds the same trials as"),
                          (source_name(table), "has the same name as")):  # fmt: skip
            if key in seen:
                raise ConfigurationError(
                    f"{table} {what} {seen[key]}: each source is compared once, by a name of "
                    "its own (its folder's for pointing.csv, else its file's)."
                )
            seen[key] = table
    trials = [load_pointing(table) for table in tables]
    if len(tables) == 1:
        files = write_pointing_report(tables[0], trials[0], out)
    else:
        files = write_pointing_comparison(tables, trials, out)
    for table, these in zip(tables, trials, strict=True):
        print(f"analysed {len(these)} pointing trials of {these['participant'].nunique()} "
              f"participants under {these['round_trip_ms'].nunique()} lags ({table})")  # fmt: skip
    print(files["report.md"].read_text(), end="")
    print(f"wrote {len(files)} files to {out}, see {files['report.md']}")
    return 0


def _pool(cmd: AnalyzeCommand) -> int:
    from arteleop.analysis import check_cohorts, load_study, pool_cohorts, write_cohort_report
    from arteleop.analysis.pooling import changed_constants_notes

    if cmd.participants is not None:
        raise ConfigurationError(
            "--participants goes with one bare trials CSV; pooled run folders each bring "
            "their own participants.csv."
        )
    seen: dict[Path, Path] = {}
    for path in cmd.sources:
        if path.resolve() in seen:
            raise ConfigurationError(
                f"{path} is given twice (as {seen[path.resolve()]}): each cohort is pooled once."
            )
        seen[path.resolve()] = path
    studies = [load_study(path) for path in cmd.sources]
    notes = check_cohorts(cmd.sources, studies, cmd.allow_different_designs)
    notes += changed_constants_notes(cmd.sources)
    trials = pool_cohorts(studies)
    files = write_cohort_report(cmd.sources, trials, cmd.out, notes)
    print(f"pooled {len(cmd.sources)} cohorts: {len(trials)} experimental trials of "
          f"{trials.groupby('cohort')['participant'].nunique().sum()} participants")  # fmt: skip
    for note in notes:
        print(f"note: {note}")
    print(files["cohorts.md"].read_text(), end="")
    print(f"wrote {len(files)} files to {cmd.out}, see {files['cohorts.md']}")
    return 0
