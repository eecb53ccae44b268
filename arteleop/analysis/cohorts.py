"""A design's answer over several cohorts (run folders of one design, any lab's): each cohort's
medians per condition, and each cue set's effect against no AR pooled over the cohorts.

A participant is paired with themself: a cue set's trial against their trial without AR at the
same network profile. Only experimental trials that succeeded under both make a pair, and the
pairs of every cohort are pooled:

- time and error: the ratio of the cue set to none, the geometric mean of the paired ratios
  with its 95 % t-interval (both are positive and skewed; below 1 is faster or more accurate);
- smoothness: the mean paired difference with its 95 % t-interval (LDLJ and SPARC: above 0 is
  smoother; submovements: below 0 is fewer; normalised jerk: below 0 is smoother, and it grows
  with duration).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.data import StudyData, sources_in
from arteleop.analysis.delay import cue_sets, profiles, with_network
from arteleop.analysis.output import whole_folder
from arteleop.analysis.pooling import DIFFERENT
from arteleop.analysis.statistics import mean_interval

REFERENCE = "none"
RATIOS = {"completion_time_s": "time", "placement_error_m": "error"}
DIFFERENCES = {
    "ldlj_xy": "LDLJ",
    "sparc_xy": "SPARC",
    "submovements_xy": "submovements",
    "normalized_jerk_xy": "normalised jerk",
}
MIN_PAIRS = 3
"""Fewer pairs than this give no interval."""


def pool_cohorts(studies: Sequence[StudyData]) -> pd.DataFrame:
    """The experimental trials of every study, with its ``cohort`` (1, 2, ...), each trial's
    ``network`` profile and, where a participants table came with it, ``expert`` (at least two
    hours a week of AR/VR or of video games, docs/explanation/study.md §5) and the participant's
    ``source`` (synthetic or real)."""
    frames = []
    for k, data in enumerate(studies, start=1):
        trials = with_network(data.trials[data.trials["phase"] == "experimental"])
        trials["cohort"] = k
        if data.participants is not None:
            people = data.participants.set_index("participant")
            expert = (people["avr_hours"] >= 2) | (people["games_hours"] >= 2)
            trials["expert"] = trials["participant"].map(expert).fillna(False).astype(bool)
            trials["source"] = trials["participant"].map(people["source"]).fillna("")
        frames.append(trials)
    return pd.concat(frames, ignore_index=True)


def cohort_medians(trials: pd.DataFrame) -> pd.DataFrame:
    """Per cohort, network profile and cue set: successes and the medians of the successful
    trials' time (s), error (m) and smoothness."""
    rows = []
    for k in sorted(trials["cohort"].unique()):
        source = cohort_source(trials, k)
        for network in profiles(trials):
            for cues in cue_sets(trials):
                cell = trials[(trials["cohort"] == k) & (trials["network"] == network)
                              & (trials["modality"] == cues)]  # fmt: skip
                if cell.empty:
                    continue
                ok = cell[cell["outcome"] == "success"]
                medians = {c: ok[c].median() for c in (*RATIOS, *DIFFERENCES)}
                rows.append({"cohort": k, "source": source, "network": network,
                             "modality": cues, "successes": len(ok), "trials": len(cell),
                             **medians})  # fmt: skip
    return pd.DataFrame(rows)


def cohort_source(trials: pd.DataFrame, cohort: int) -> str:
    """Who a cohort's participants are: ``real``, ``synthetic``, both ``+``-joined, or empty
    where its participants table does not say."""
    return "+".join(sources_in(trials[trials["cohort"] == cohort]))


def pooled_effects(trials: pd.DataFrame) -> pd.DataFrame:
    """Each cue set against none at the same network profile, pooled over the cohorts and
    paired by participant: ``effect`` with its interval ``low`` to ``high`` (a ratio for time
    and error, a difference for smoothness), and ``direction`` (lower, higher, no difference;
    too few pairs under :data:`MIN_PAIRS`)."""
    ok = trials[trials["outcome"] == "success"]
    rows = []
    for network in profiles(trials):
        here = ok[ok["network"] == network]
        for cues in cue_sets(trials):
            if cues == REFERENCE or not (trials["modality"] == cues).any():
                continue
            for column in (*RATIOS, *DIFFERENCES):
                wide = here.pivot_table(index=["cohort", "participant"], columns="modality",
                                        values=column)  # fmt: skip
                both = wide[[cues, REFERENCE]].dropna() if {cues, REFERENCE} <= set(wide) else None
                pairs = np.empty((0, 2)) if both is None else both.to_numpy()
                measure = RATIOS.get(column) or DIFFERENCES[column]
                row = {"network": network, "modality": cues, "measure": measure,
                       "pairs": len(pairs), "effect": np.nan, "low": np.nan, "high": np.nan,
                       "direction": "too few pairs"}  # fmt: skip
                if len(pairs) >= MIN_PAIRS:
                    if column in RATIOS:
                        mean, low, high = np.exp(mean_interval(np.log(pairs[:, 0] / pairs[:, 1])))
                        middle = 1.0
                    else:
                        mean, low, high = mean_interval(pairs[:, 0] - pairs[:, 1])
                        middle = 0.0
                    direction = ("lower" if high < middle else "higher" if low > middle
                                 else "no difference")  # fmt: skip
                    row.update(effect=mean, low=low, high=high, direction=direction)
                rows.append(row)
    return pd.DataFrame(rows)


def expert_gaps(trials: pd.DataFrame) -> pd.DataFrame | None:
    """Per network profile and cue set, the experts' and the others' median time (s) and the
    gap; None without a participants table."""
    if "expert" not in trials:
        return None
    ok = trials[trials["outcome"] == "success"]
    rows = []
    for network in profiles(trials):
        for cues in cue_sets(trials):
            cell = ok[(ok["network"] == network) & (ok["modality"] == cues)]
            if cell.empty:
                continue
            experts = cell[cell["expert"]]["completion_time_s"].median()
            others = cell[~cell["expert"]]["completion_time_s"].median()
            rows.append({"network": network, "modality": cues, "experts_s": experts,
                         "others_s": others, "gap_s": others - experts})  # fmt: skip
    # Its columns even without a row: no cell had a success (a short pilot's timeouts).
    return pd.DataFrame(rows, columns=["network", "modality", "experts_s", "others_s", "gap_s"])


def _table(frame: pd.DataFrame, columns: dict[str, str]) -> list[str]:
    lines = ["| " + " | ".join(columns.values()) + " |", "|" + " --- |" * len(columns)]
    for _, row in frame.iterrows():
        lines.append("| " + " | ".join(str(row[c]) for c in columns) + " |")
    return lines


def write_cohort_report(
    sources: Sequence[Path], trials: pd.DataFrame, out_dir: Path, notes: Sequence[str] = ()
) -> dict[str, Path]:
    """``cohort_medians.csv``, ``pooled_effects.csv``, ``experts.csv`` (with participants) and
    ``cohorts.md`` in ``out_dir``, whole or not at all (it replaces an existing ``out_dir``);
    returns them by name. ``notes``: what :func:`~arteleop.analysis.check_cohorts` said of
    the cohorts."""
    with whole_folder(out_dir) as partial:
        files = _write(sources, trials, partial, notes)
    return {name: out_dir / path.relative_to(partial) for name, path in files.items()}


def _write(
    sources: Sequence[Path], trials: pd.DataFrame, out_dir: Path, notes: Sequence[str]
) -> dict[str, Path]:
    medians, effects, experts = cohort_medians(trials), pooled_effects(trials), expert_gaps(trials)
    files = {"cohort_medians.csv": medians, "pooled_effects.csv": effects}
    if experts is not None:
        files["experts.csv"] = experts
    written = {}
    for name, frame in files.items():
        written[name] = out_dir / name
        frame.to_csv(written[name], index=False)

    def number(form: str) -> Callable[[float], str]:
        return lambda v: "" if np.isnan(v) else form.format(v)

    shown = medians.assign(
        time=medians["completion_time_s"].map(number("{:.1f}")),
        error=(1000 * medians["placement_error_m"]).map(number("{:.1f}")),
        ok=medians["successes"].astype(str) + "/" + medians["trials"].astype(str),
        ldlj=medians["ldlj_xy"].map(number("{:.2f}")),
    )
    ratio = effects["measure"].isin(list(RATIOS.values()))
    said = effects.assign(
        shown=[number("x {:.2f}" if r else "{:+.3g}")(e)
               for e, r in zip(effects["effect"], ratio, strict=True)],
        ci=[number("{:.2f}" if r else "{:+.3g}")(lo) + ("" if np.isnan(lo) else " to ")
            + number("{:.2f}" if r else "{:+.3g}")(hi)
            for lo, hi, r in zip(effects["low"], effects["high"], ratio, strict=True)],
    )  # fmt: skip
    lines = [
        f"# {len(sources)} cohorts of "
        + ("different designs" if any(n.startswith(DIFFERENT) for n in notes) else "one design"),
        "",
        *(f"{k}. `{path}`" + (f" ({who})" if (who := cohort_source(trials, k)) else "")
          for k, path in enumerate(sources, start=1)), "",
        *(line for note in notes for line in (f"**{note}**", "")),
        "Experimental trials only. Each cue set is paired with the same participant's trial "
        "without AR at the same network profile; ratios (time, error) are geometric means of "
        "the paired ratios, differences (smoothness) mean paired differences, each with its "
        "95 % t-interval. Below 1 (or 0) is lower.", "",
        "## Medians per cohort (successful trials)", "",
        *_table(shown, {"cohort": "cohort", "network": "network", "modality": "cues",
                        "ok": "successes", "time": "time (s)", "error": "error (mm)",
                        "ldlj": "LDLJ"}),
        "", "## Each cue set against none, pooled over the cohorts", "",
        *_table(said, {"network": "network", "modality": "cues", "measure": "measure",
                       "pairs": "pairs", "shown": "effect", "ci": "95 % CI",
                       "direction": "direction"}),
    ]  # fmt: skip
    if experts is not None:
        gaps = experts.assign(**{c: experts[c].map(number("{:.1f}"))
                                 for c in ("experts_s", "others_s", "gap_s")})  # fmt: skip
        lines += ["", "## Experts and the others (pooled medians of time)", "",
                  *_table(gaps, {"network": "network", "modality": "cues",
                                 "experts_s": "experts (s)", "others_s": "others (s)",
                                 "gap_s": "gap (s)"})]  # fmt: skip
    written["cohorts.md"] = out_dir / "cohorts.md"
    written["cohorts.md"].write_text("\n".join(lines) + "\n")
    return written
