"""Run the whole analysis of a study: which comparisons, on which subsets, and why."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields, replace

import numpy as np
import pandas as pd

from arteleop.analysis.data import (
    AR_CLASSES,
    MEASURES,
    MODALITIES,
    StudyData,
    load_trajectory,
    questionnaire_items,
)
from arteleop.analysis.delay import (
    CELL_MEASURES,
    cell_table,
    cue_sets,
    delay_cue_anova,
    profiles,
    with_network,
)
from arteleop.analysis.errors import AnalysisInputError
from arteleop.analysis.order import order_effect
from arteleop.analysis.smoothness import (
    idle_share,
    log_dimensionless_jerk,
    normalized_jerk,
    spectral_arc_length,
    submovement_count,
)
from arteleop.analysis.statistics import (
    MIN_TEST_N,
    AnalysisOptions,
    NormalityResult,
    TestResult,
    compare,
    pairwise,
    tested,
    trim_extremes,
    untested,
)

EXPERTISE_KINDS = {"avr": "avr_hours", "games": "games_hours"}
EXPERT_MIN_BUCKET = 2  # at least two hours a week (docs/explanation/study.md §4)


@dataclass
class AnalysisResult:
    """Everything the report is made of."""

    tests: pd.DataFrame
    normality: pd.DataFrame
    order_effect: pd.DataFrame
    descriptives: pd.DataFrame
    trials: pd.DataFrame  # the analysed trials, with jerk filled in where it could be
    trajectories: dict[tuple[str, float], pd.DataFrame]
    notes: list[str] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)
    cells: pd.DataFrame | None = None  # per network profile and cue set, when there are several

    @property
    def left_out(self) -> dict[str, int]:
        """The experimental trials not analysed, by outcome (timeout, ...)."""
        return {k.removeprefix("excluded_"): v for k, v in self.counts.items()
                if k.startswith("excluded_")}  # fmt: skip


def analyse(study: StudyData, options: AnalysisOptions | None = None) -> AnalysisResult:
    """The comparisons of docs/explanation/study.md §5 (modalities, order, expertise,
    questionnaire), each by ``options``' method."""
    options = options or AnalysisOptions()
    notes: list[str] = []
    trials = study.analysed_trials()
    counts = {
        "rows": len(study.trials),
        "familiarization": int((study.trials["phase"] == "familiarization").sum()),
        "experimental": int((study.trials["phase"] == "experimental").sum()),
        "analysed": len(trials),
    }
    for outcome, n in (
        study.trials[study.trials["phase"] == "experimental"]["outcome"].value_counts().items()
    ):
        if outcome != "success":
            counts[f"excluded_{outcome}"] = int(n)
    trajectories = _load_trajectories(study, trials, notes)
    trials = _fill_smoothness(trials, trajectories, notes)
    measures = [m for m in MEASURES if trials[m].notna().any()]
    if "normalized_jerk_xy" not in measures:
        notes.append("Smoothness skipped: no normalized_jerk_xy values and no trajectory files.")

    tests: list[TestResult] = []
    norms: list[NormalityResult] = []
    order_rows = []
    trials = with_network(trials)
    networks = profiles(study.trials)
    crossed = len(networks) > 1
    for m in measures:
        # Crossed with delay, the thesis's comparisons run within each network profile.
        for network in networks if crossed else [None]:
            part = trials if network is None else trials[trials["network"] == network]
            sub = trim_extremes(part, m, ["modality"]) if options.drops_extremes else part
            groups = cue_sets(study.trials)
            if network is not None:
                groups = [g for g in groups if g in set(part["modality"])]
            t, n = pairwise(sub, m, "modality", groups, _subset(network), options)
            tests += t
            norms += n
        row, summary = order_effect(trials, m)
        tests.append(row)
        order_rows.append(summary)
    cells = None
    if crossed:
        filled = study.trials.copy()  # with the measures computed from trajectory files
        filled.loc[trials.index, list(CELL_MEASURES)] = trials[list(CELL_MEASURES)]
        cells = cell_table(filled)
        for m in CELL_MEASURES:
            if m in trials and trials[m].notna().any():
                rows, note = delay_cue_anova(trials, m)
                tests += rows
                if note:
                    notes.append(f"Delay x cue ANOVA of {m}: {note}.")

    if study.participants is None:
        notes.append("Expertise analysis skipped: no participants table.")
    else:
        t, n = _expertise(trials, study.participants, measures, options, notes)
        tests += t
        norms += n
    if study.questionnaire is None:
        notes.append("Questionnaire comparison skipped: no questionnaire.csv.")
    else:
        # Ratings 1-7 are compared untrimmed under every method: the thesis did not trim
        # them, and trimmed means of a few tied levels say little.
        ratings = replace(options, method="untrimmed")
        for item in questionnaire_items(study.questionnaire):
            q = study.questionnaire[study.questionnaire["item"] == item]
            if q.empty:
                continue
            t, n = pairwise(
                q, "score", "ar_class", AR_CLASSES, "all", ratings, f"questionnaire:{item}"
            )
            tests += t
            norms += n
    return AnalysisResult(
        # With no test to make (no trial placed, no questionnaire) the tables keep their columns.
        tests=pd.DataFrame([asdict(r) for r in tests], columns=_names(TestResult)),
        normality=pd.DataFrame([asdict(r) for r in norms], columns=_names(NormalityResult)),
        order_effect=pd.DataFrame(order_rows),
        descriptives=_descriptives(trials, measures, options),
        trials=trials,
        trajectories=trajectories,
        notes=notes,
        counts=counts,
        cells=cells,
    )


def _names(kind: type) -> list[str]:
    return [f.name for f in fields(kind)]


def _subset(network: str | None) -> str:
    """The subset of a family of pairwise tests: all trials, or those of one network profile."""
    return "all" if network is None else f"all @ {network}"


def _expertise(
    trials: pd.DataFrame,
    participants: pd.DataFrame,
    measures: list[str],
    options: AnalysisOptions,
    notes: list[str],
) -> tuple[list[TestResult], list[NormalityResult]]:
    tests: list[TestResult] = []
    norms: list[NormalityResult] = []
    between_groups = replace(options, paired=False)  # experts and novices are other people
    for kind, column in EXPERTISE_KINDS.items():
        known = participants.dropna(subset=[column])
        if known.empty:
            notes.append(f"Expertise ({kind}) skipped: the column {column} is empty.")
            continue
        expert = known.set_index("participant")[column] >= EXPERT_MIN_BUCKET
        df = trials[trials["participant"].isin(expert.index)].copy()
        df["expert"] = df["participant"].map(expert)
        for m in measures:
            groups = {}
            for label, is_expert in (("expert", True), ("novice", False)):
                g = df[df["expert"] == is_expert]
                groups[label] = trim_extremes(g, m, ["modality"]) if options.drops_extremes else g
                t, n = pairwise(
                    groups[label], m, "modality", MODALITIES, f"{kind}_{label}", options
                )
                tests += t
                norms += n
            for modality in MODALITIES:
                a = (
                    groups["expert"][groups["expert"]["modality"] == modality][m]
                    .dropna()
                    .to_numpy()
                )
                b = (
                    groups["novice"][groups["novice"]["modality"] == modality][m]
                    .dropna()
                    .to_numpy()
                )
                subset = f"experts_vs_novices:{kind}"
                if min(len(a), len(b)) < MIN_TEST_N:
                    why = f"too few values ({len(a)} and {len(b)}, need {MIN_TEST_N} each)"
                    tests.append(
                        untested(
                            subset,
                            m,
                            f"expert:{modality}",
                            f"novice:{modality}",
                            len(a),
                            len(b),
                            why,
                        )
                    )
                    continue
                result = compare(a, b, between_groups)
                tests.append(
                    tested(subset, m, f"expert:{modality}", f"novice:{modality}", a, b, result,
                           options)
                )  # fmt: skip
    return tests, norms


def _load_trajectories(
    study: StudyData, trials: pd.DataFrame, notes: list[str]
) -> dict[tuple[str, float], pd.DataFrame]:
    out = {}
    missing = 0
    for _, row in trials.iterrows():
        if not row["trajectory_file"]:
            continue
        path = study.base_dir / row["trajectory_file"]
        if not path.is_file():
            missing += 1
            continue
        out[(row["participant"], row["trial_index"])] = load_trajectory(path)
    if missing:
        notes.append(f"{missing} trajectory file(s) listed in trials.csv were not found.")
    return out


def _fill_smoothness(trials: pd.DataFrame, trajectories: dict, notes: list[str]) -> pd.DataFrame:
    """Each empty smoothness measure computed from the trial's trajectory file, where it has
    one (files of other labs, or of format versions before a measure's column)."""
    measures = {
        "normalized_jerk_xy": normalized_jerk, "ldlj_xy": log_dimensionless_jerk,
        "sparc_xy": spectral_arc_length, "submovements_xy": submovement_count,
        "idle_share_xy": idle_share,
    }  # fmt: skip
    trials = trials.copy()
    computed = dict.fromkeys(measures, 0)
    for i, row in trials.iterrows():
        traj = trajectories.get((row["participant"], row["trial_index"]))
        empty = [m for m in measures if np.isnan(row[m])]
        if not empty or traj is None:
            continue
        t, p = traj["time_s"].to_numpy(), traj[["hand_x_m", "hand_y_m", "hand_z_m"]].to_numpy()
        try:
            for m in empty:
                trials.loc[i, m] = float(measures[m](t, p, "xy"))
                computed[m] += 1
        except AnalysisInputError as err:
            notes.append(
                f"Smoothness of participant {row['participant']} trial {row['trial_index']:g} "
                f"not computed: {err}"
            )
    for m, n in computed.items():
        if n:
            notes.append(f"{m} computed from trajectory files for {n} trial(s).")
    return trials


def _descriptives(
    trials: pd.DataFrame, measures: list[str], options: AnalysisOptions
) -> pd.DataFrame:
    rows = []
    for m in measures:
        raw = _by_modality(trials, m)
        sub = trim_extremes(trials, m, ["modality"]) if options.drops_extremes else trials
        kept = _by_modality(sub, m)
        for modality in MODALITIES:
            v = kept.get(modality, np.empty(0))
            n_total = len(raw.get(modality, ()))
            rows.append({"measure": m, "modality": modality, "n_total": n_total, "n": len(v),
                         **_summary(v)})  # fmt: skip
    return pd.DataFrame(rows)


def _by_modality(trials: pd.DataFrame, measure: str) -> dict[str, np.ndarray]:
    """Each modality's values of ``measure`` (NaN dropped)."""
    values = trials[["modality", measure]].dropna()
    return {k: g[measure].to_numpy() for k, g in values.groupby("modality", sort=False)}


def _summary(v: np.ndarray) -> dict[str, float]:
    """Mean, SD (ddof 1), median, quartiles and range; NaN where there are too few values."""
    if not len(v):
        return dict.fromkeys(("mean", "sd", "median", "q1", "q3", "min", "max"), np.nan)
    q1, median, q3 = np.quantile(v, [0.25, 0.5, 0.75])
    sd = float(np.std(v, ddof=1)) if len(v) > 1 else np.nan
    return {"mean": float(np.mean(v)), "sd": sd, "median": median, "q1": q1, "q3": q3,
            "min": float(v.min()), "max": float(v.max())}  # fmt: skip
