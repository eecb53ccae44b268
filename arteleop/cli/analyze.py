"""'arteleop analyze': a study's statistics, figures and report from its files."""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import tyro


@dataclass(frozen=True)
class AnalyzeCommand:
    """Analyse a study's files (docs/study.md §5) and write tables, figures and report.md."""

    source: tyro.conf.Positional[Path]
    """run folder (trials.csv, participants.csv, questionnaire.csv, trajectories/) or trials CSV"""
    out: Path = Path("arteleop-report")
    """report folder"""
    participants: Path | None = None
    """participants.csv for a bare trials CSV"""
    trim: bool = True
    """drop each group's maximum and minimum participant (the thesis)"""
    paired: bool = False
    """within-subject tests (paired t-test / Wilcoxon) between modalities"""
    holm: bool = False
    """Holm-correct each family of pairwise tests"""


def analyze(cmd: AnalyzeCommand) -> int:
    from arteleop.analysis import (
        AnalysisInputError,
        AnalysisOptions,
        analyse,
        load_study,
        write_report,
    )

    try:
        study = load_study(cmd.source, cmd.participants)
        options = AnalysisOptions(trim=cmd.trim, paired=cmd.paired, holm=cmd.holm)
        result = analyse(study, options)
        files = write_report(study, result, options, cmd.out)
    except AnalysisInputError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2
    n_people = result.trials["participant"].nunique()
    print(f"analysed {result.counts['analysed']} trials of {n_people} participants")
    significant = result.tests[(result.tests["stars"] != "") & result.tests["stars"].notna()]
    print(f"{len(result.tests)} tests, {len(significant)} significant at p <= 0.05")
    for note in result.notes:
        print(f"note: {note}")
    print(f"wrote {len(files)} files to {cmd.out}, see {files['report.md']}")
    return 0
