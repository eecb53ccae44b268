"""Write an analysis to a report folder: CSV tables, figures and a readable report.md."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.data import MEASURES, MODALITIES, StudyData
from arteleop.analysis.delay import ANOVA_SUBSET
from arteleop.analysis.figures import (
    expertise_bars,
    measure_boxplot,
    questionnaire_boxplot,
    trajectory_plot,
)
from arteleop.analysis.output import whole_folder
from arteleop.analysis.statistics import AnalysisOptions, trim_extremes
from arteleop.analysis.study_analysis import EXPERT_MIN_BUCKET, EXPERTISE_KINDS, AnalysisResult

TEST_COLUMNS = (
    "subset", "measure", "group_a", "group_b", "test", "n_a", "n_b", "statistic", "p_value",
    "effect_size", "effect_size_kind", "stars", "note",
)  # fmt: skip


def write_report(
    study: StudyData, result: AnalysisResult, options: AnalysisOptions, out_dir: Path
) -> dict[str, Path]:
    """Write tests.csv, normality.csv, order_effect.csv, descriptives.csv, report.md, figures/
    into ``out_dir``, whole or not at all (it replaces an existing ``out_dir``); returns the
    files by name."""
    with whole_folder(out_dir) as partial:
        files = _write(study, result, options, partial)
    return {name: out_dir / path.relative_to(partial) for name, path in files.items()}


def _write(
    study: StudyData, result: AnalysisResult, options: AnalysisOptions, out_dir: Path
) -> dict[str, Path]:
    figures = out_dir / "figures"
    figures.mkdir(exist_ok=True)
    files = {}
    tests = result.tests.reindex(columns=TEST_COLUMNS)
    for name, df in (
        ("tests.csv", tests),
        ("normality.csv", result.normality),
        ("order_effect.csv", result.order_effect),
        ("descriptives.csv", result.descriptives),
    ):
        df.to_csv(out_dir / name, index=False, float_format="%.6g")
        files[name] = out_dir / name
    if result.cells is not None:
        result.cells.to_csv(out_dir / "cells.csv", index=False, float_format="%.6g")
        files["cells.csv"] = out_dir / "cells.csv"
    files |= _figures(study, result, options, figures)
    (out_dir / "report.md").write_text(_markdown(study, result, options, tests, files, out_dir))
    files["report.md"] = out_dir / "report.md"
    return files


def _figures(
    study: StudyData, result: AnalysisResult, options: AnalysisOptions, figures: Path
) -> dict[str, Path]:
    files = {}
    trials = result.trials
    all_tests = result.tests[result.tests["subset"] == "all"] if len(result.tests) else result.tests
    for m in MEASURES:
        if m not in trials or not trials[m].notna().any():
            continue
        sub = trim_extremes(trials, m, ["modality"]) if options.drops_extremes else trials
        values = {mod: sub[sub["modality"] == mod][m].dropna().to_numpy() for mod in MODALITIES}
        path = figures / f"boxplot_{m}.png"
        measure_boxplot(values, all_tests, m, path)
        files[path.name] = path
    if study.questionnaire is not None and not study.questionnaire.empty:
        path = figures / "questionnaire.png"
        questionnaire_boxplot(study.questionnaire, path)
        files[path.name] = path
    if study.participants is not None:
        for kind, column in EXPERTISE_KINDS.items():
            known = study.participants.dropna(subset=[column]).set_index("participant")[column]
            if known.empty:
                continue
            expert = known >= EXPERT_MIN_BUCKET
            for m in ("completion_time_s", "placement_error_m"):
                path = figures / f"expertise_{kind}_{m}.png"
                expertise_bars(trials, expert, m, kind, path)
                files[path.name] = path
    if result.trajectories:
        path = figures / "trajectories_xy.png"
        trajectory_plot(trials, result.trajectories, path)
        files[path.name] = path
    return files


def _fmt(v: float, digits: int = 3) -> str:
    return "" if v is None or (isinstance(v, float) and not np.isfinite(v)) else f"{v:.{digits}g}"


def _markdown(
    study: StudyData,
    result: AnalysisResult,
    options: AnalysisOptions,
    tests: pd.DataFrame,
    files: dict[str, Path],
    out_dir: Path,
) -> str:
    c = result.counts
    excluded = ", ".join(f"{k}: {v}" for k, v in result.left_out.items()) or "none"
    lines = [
        "# Study analysis",
        "",
        f"Source: `{study.trials_path}`",
        "",
        f"- Trials in the file: {c['rows']} ({c['familiarization']} familiarisation, {c['experimental']} experimental).",
        f"- Analysed: {c['analysed']} experimental trials with outcome `success`. Experimental trials left out, by outcome: {excluded}.",
        f"- Participants: {result.trials['participant'].nunique()}.",
        "",
        "## Method",
        "",
        "Only experimental trials that succeeded are analysed.",
        "",
        *_method(options),
    ]
    lines += [
        "",
        "Order effects: one-way ANOVA of each measure over trial position 1-5 (untrimmed). "
        "Questionnaire ratings are compared untrimmed under every method. "
        + (
            "p-values of each family (subset x measure) are Holm-corrected. "
            if options.holm
            else "p-values are not corrected for multiple comparisons. "
        )
        + "Effect sizes: Cohen's d (pooled SD; d_z for paired tests) with t-tests, the robust d (Algina, Keselman & Penfield 2005; d_z on paired differences) with trimmed means, the rank-biserial correlation with rank tests, eta squared with ANOVA. Stars: * p <= 0.05, ** p < 0.01.",
        "",
        "## Comparisons between modalities (all participants)",
        "",
        "| measure | a | b | test | n | statistic | p | effect | |",
        "| --- | --- | --- | --- | --- | ---: | ---: | ---: | --- |",
    ]
    in_all = tests["subset"].str.match(r"all( @ |$)")
    all_rows = tests[in_all & (tests["test"] != "anova")]
    for _, r in all_rows.iterrows():
        why = f" ({r['note']})" if isinstance(r["note"], str) and r["note"] else ""
        network = r["subset"].removeprefix("all")  # " @ 250ms" within a network profile
        lines.append(
            f"| {r['measure']}{network} | {r['group_a']} | {r['group_b']} | {r['test'] or '-'}{why} | {r['n_a']}/{r['n_b']} "
            f"| {_fmt(r['statistic'])} | {_fmt(r['p_value'])} | {_fmt(r['effect_size'])} {r['effect_size_kind'] or ''} | {r['stars'] or ''} |"
        )
    lines += [
        "",
        "## Order effect (one-way ANOVA over trial position)",
        "",
        "| measure | F | df | p | eta squared |",
        "| --- | ---: | ---: | ---: | ---: |",
    ]
    for _, r in result.order_effect.iterrows():
        lines.append(
            f"| {r['measure']} | {_fmt(r['F'])} | {_fmt(r['df_between'])}, {_fmt(r['df_within'])} | {_fmt(r['p_value'])} | {_fmt(r.get('eta_squared', np.nan))} |"
        )
    if result.cells is not None:
        lines += _delay_section(result.cells, tests[tests["subset"] == ANOVA_SUBSET])
    subsets = ~in_all & (tests["subset"] != ANOVA_SUBSET)  # the ANOVA has its own section
    sig = tests[(tests["stars"] != "") & tests["stars"].notna() & subsets]
    if len(sig):
        lines += ["", "## Significant results in subsets", ""]
        lines += [
            f"- {r['subset']}, {r['measure']}: {r['group_a']} vs {r['group_b']} ({r['test']}, p = {_fmt(r['p_value'])}) {r['stars']}"
            for _, r in sig.iterrows()
        ]
    if result.notes:
        lines += ["", "## Notes", ""] + [f"- {n}" for n in result.notes]
    lines += ["", "## Files", ""] + [f"- `{p.relative_to(out_dir)}`" for p in files.values()]
    return "\n".join(lines) + "\n"


def _method(options: AnalysisOptions) -> list[str]:
    """What test ran, and why: the report's first lines on its method."""
    lilliefors = "Lilliefors' test (p > 0.05 = normal) decides between"
    if options.method == "yuen":
        tests = (
            "the paired differences' 20 % trimmed mean against zero (Tukey & McLaughlin's "
            "test; the differences are trimmed, not each modality)"
            if options.paired
            else "Yuen's test of 20 % trimmed means (Welch's degrees of freedom)"
        )
        return [
            f"Method `yuen`: every participant, each pair of modalities compared with {tests}. "
            "The 20 % at each end weigh less, so an outlier moves the answer little, and the "
            "standard error comes from the winsorized variance, which accounts for the "
            "trimming: the test keeps its stated error rate."
        ]
    if options.paired:
        tests = (f"Modalities are compared within subjects: {lilliefors} the paired t-test "
                 "(differences normal) and the Wilcoxon signed-rank test (two-sided).")  # fmt: skip
    else:
        tests = (f"Each pair of modalities is compared as independent groups: {lilliefors} "
                 "Student's t-test (both samples normal) and the Mann-Whitney U test (two-sided, "
                 "normal approximation with continuity correction, as MATLAB's `ranksum`).")  # fmt: skip
    if options.method == "thesis":
        return [
            "Method `thesis`, the original study's procedure (docs/explanation/study.md §5), to reproduce "
            "it: per modality and measure, the participant with the maximum and the one with "
            f"the minimum value are removed, and the rest tested as an ordinary sample. {tests}",
            "",
            "**Its error rate is not the one stated.** The values left after dropping the "
            "extremes spread less than the sample did, so the standard error is too small: on "
            "data with no effect, about 8-12 % of these tests reject at p <= 0.05, not 5 %. Use "
            "it to compare with the thesis; judge a new study by the default method.",
        ]
    return [f"Method `untrimmed` (the default): every participant. {tests}"]


def _delay_section(cells: pd.DataFrame, anova: pd.DataFrame) -> list[str]:
    """The cells of a study crossing network profiles with cue sets, and the two-way
    repeated-measures ANOVA of each measure."""
    lines = [
        "",
        "## Delay x cue",
        "",
        "Per network profile (round trip, jitter, loss) and cue set: successful trials of all, and "
        "the medians over them of completion time, placement error and the share of the time the "
        "hand was still (moving and waiting raises it).",
        "",
        "| network | cues | successes | time (s) | error (mm) | hand still |",
        "| --- | --- | ---: | ---: | ---: | ---: |",
    ]
    for _, c in cells.iterrows():
        lines.append(
            f"| {c['network']} | {c['modality']} | {c['successes']}/{c['trials']} "
            f"| {_fmt(c['median_completion_time_s'])} | {_fmt(c['median_placement_error_m'] * 1000)} "
            f"| {_fmt(c['median_idle_share_xy'], 2)} |"
        )
    lines += [
        "",
        "Two-way repeated-measures ANOVA (statsmodels' AnovaRM) over cue set x network profile, "
        "on the participants with a successful trial in every cell.",
        "",
        "| measure | effect | F | p | partial eta squared | participants | |",
        "| --- | --- | ---: | ---: | ---: | ---: | --- |",
    ]
    for _, r in anova.iterrows():
        why = f" ({r['note']})" if isinstance(r["note"], str) and r["note"] else ""
        lines.append(
            f"| {r['measure']} | {r['group_a']} | {_fmt(r['statistic'])} {r['group_b']}{why} "
            f"| {_fmt(r['p_value'])} | {_fmt(r['effect_size'])} | {r['n_a']} | {r['stars'] or ''} |"
        )
    return lines
