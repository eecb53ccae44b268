"""Figures of the analysis (PNG, matplotlib's non-interactive Agg backend)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from arteleop.analysis.data import AR_CLASSES, MODALITIES, questionnaire_items

LABELS = {
    "completion_time_s": "completion time (s)",
    "placement_error_m": "placement error (m)",
    "normalized_jerk_xy": "normalised jerk, x-y (-)",
    "ldlj_xy": "LDLJ, x-y (-)",
    "sparc_xy": "SPARC, x-y (-)",
    "submovements_xy": "submovements, x-y",
}


def measure_boxplot(
    values: dict[str, np.ndarray], tests: pd.DataFrame, measure: str, path: Path
) -> None:
    """Boxes per modality with brackets and stars for the significant pairs."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    data = [values.get(m, np.array([])) for m in MODALITIES]
    ax.boxplot(data, tick_labels=list(MODALITIES), showmeans=True)
    ax.set_ylabel(LABELS.get(measure, measure))
    ax.set_title(f"{LABELS.get(measure, measure)} per modality")
    sig = tests[
        (tests["measure"] == measure) & (tests["stars"] != "") & tests["group_b"].isin(MODALITIES)
    ]
    finite = [v for d in data for v in d if np.isfinite(v)]
    if finite and len(sig):
        top, span = max(finite), (max(finite) - min(finite)) or 1.0
        for k, (_, row) in enumerate(sig.iterrows()):
            x1, x2 = MODALITIES.index(row["group_a"]) + 1, MODALITIES.index(row["group_b"]) + 1
            y = top + span * (0.08 + 0.09 * k)
            ax.plot([x1, x1, x2, x2], [y - span * 0.02, y, y, y - span * 0.02], color="black", lw=1)
            ax.text((x1 + x2) / 2, y, row["stars"], ha="center", va="bottom")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def questionnaire_boxplot(questionnaire: pd.DataFrame, path: Path) -> None:
    """Likert scores per AR class, one panel per item."""
    items = questionnaire_items(questionnaire)
    fig, axes = plt.subplots(1, len(items), figsize=(11, 3.8), sharey=True, squeeze=False)
    axes = axes[0]
    for ax, item in zip(axes, items, strict=True):
        q = questionnaire[questionnaire["item"] == item]
        ax.boxplot(
            [q[q["ar_class"] == c]["score"].dropna().to_numpy() for c in AR_CLASSES],
            tick_labels=list(AR_CLASSES),
        )
        ax.set_title(item)
        ax.set_ylim(0.5, 7.5)
    axes[0].set_ylabel("score (1-7)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def expertise_bars(
    trials: pd.DataFrame, expert: pd.Series, measure: str, kind: str, path: Path
) -> None:
    """Mean and standard error per modality for experts and novices."""
    df = trials.assign(expert=trials["participant"].map(expert)).dropna(subset=["expert", measure])
    fig, ax = plt.subplots(figsize=(7, 4))
    x = np.arange(len(MODALITIES))
    for offset, (label, flag) in zip(
        (-0.2, 0.2), (("experts", True), ("novices", False)), strict=True
    ):
        g = df[df["expert"] == flag].groupby("modality")[measure]
        mean = g.mean().reindex(MODALITIES)
        se = (g.std(ddof=1) / np.sqrt(g.count())).reindex(MODALITIES)
        ax.bar(
            x + offset,
            mean,
            0.4,
            yerr=se,
            capsize=3,
            label=f"{label} (n={df[df['expert'] == flag]['participant'].nunique()})",
        )
    ax.set_xticks(x, MODALITIES)
    ax.set_ylabel(LABELS.get(measure, measure))
    ax.set_title(f"{kind} expertise: {LABELS.get(measure, measure)}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def trajectory_plot(trials: pd.DataFrame, trajectories: dict, path: Path) -> None:
    """Every hand trajectory in the x-y plane, one panel per modality."""
    fig, axes = plt.subplots(1, len(MODALITIES), figsize=(16, 3.6), sharex=True, sharey=True)
    for ax, modality in zip(axes, MODALITIES, strict=True):
        for _, row in trials[trials["modality"] == modality].iterrows():
            traj = trajectories.get((row["participant"], row["trial_index"]))
            if traj is not None:
                ax.plot(traj["hand_x_m"], traj["hand_y_m"], lw=0.7, alpha=0.7)
        ax.set_title(modality)
        ax.set_xlabel("x (m)")
        ax.set_aspect("equal", adjustable="box")
    axes[0].set_ylabel("y (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
