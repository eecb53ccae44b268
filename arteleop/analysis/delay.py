"""Studies that cross network delay with AR cues: the table of cells and the two-way
repeated-measures ANOVA of cue x delay (statsmodels' ``AnovaRM``)."""

from __future__ import annotations

import itertools

import pandas as pd
from statsmodels.stats.anova import AnovaRM

from arteleop.analysis.data import MODALITIES, NETWORK_COLUMNS, network_label
from arteleop.analysis.statistics import TestResult, stars, untested

CELL_MEASURES = ("completion_time_s", "placement_error_m", "idle_share_xy")
"""What the cell table gives the median of: time, error and the share of time the hand is
still (move and wait)."""
ANOVA_SUBSET = "delay x cue"
EFFECTS = {"modality": "cue", "network": "delay", "modality:network": "cue x delay"}


def with_network(trials: pd.DataFrame) -> pd.DataFrame:
    """``trials`` with a ``network`` column naming each trial's profile (``250ms``)."""
    out = trials.copy()
    out["network"] = [
        network_label(*row) for row in out[list(NETWORK_COLUMNS)].itertuples(index=False)
    ]
    return out


def profiles(trials: pd.DataFrame) -> list[str]:
    """The network profiles of the experimental trials, shortest round trip first."""
    exp = with_network(trials[trials["phase"] == "experimental"])
    ordered = exp.sort_values(list(NETWORK_COLUMNS), kind="stable")
    return list(dict.fromkeys(ordered["network"]))


def cue_sets(trials: pd.DataFrame) -> list[str]:
    """The cue sets compared: the original study's five, then any other in order of first
    appearance."""
    present = list(dict.fromkeys(trials[trials["phase"] == "experimental"]["modality"]))
    return [*MODALITIES, *(m for m in present if m not in MODALITIES)]


def cell_table(trials: pd.DataFrame) -> pd.DataFrame:
    """Per network profile and cue set: trials, successes, and the medians of
    :data:`CELL_MEASURES` over the successful trials."""
    exp = with_network(trials[trials["phase"] == "experimental"])
    rows = []
    for network in profiles(trials):
        for modality in (m for m in cue_sets(trials) if m in set(exp["modality"])):
            cell = exp[(exp["network"] == network) & (exp["modality"] == modality)]
            if cell.empty:
                continue
            done = cell[cell["outcome"] == "success"]
            row = {
                "network": network, "modality": modality, "trials": len(cell),
                "successes": len(done), "success_rate": len(done) / len(cell),
            }  # fmt: skip
            row |= {f"median_{m}": done[m].median() for m in CELL_MEASURES}
            rows.append(row)
    return pd.DataFrame(rows)


def delay_cue_anova(analysed: pd.DataFrame, measure: str) -> tuple[list[TestResult], str]:
    """The two-way repeated-measures ANOVA of ``measure`` over cue set x network profile, on
    the participants with a successful trial in every cell (AnovaRM needs them all); one row
    per effect, with partial eta squared, and a note on who was left out."""
    data = with_network(analysed).dropna(subset=[measure])
    design = set(zip(with_network(analysed)["modality"], with_network(analysed)["network"],
                     strict=True))  # fmt: skip
    cues, networks = crossed_part(design)
    notes = []
    if len(cues) < 2 or len(networks) < 2:
        why = ("the design does not cross cue sets with delays (no two cue sets share two "
               "network profiles); the pairwise tests within each profile stand")  # fmt: skip
        return [untested(ANOVA_SUBSET, measure, effect, "", 0, len(design), why)
                for effect in EFFECTS.values()], why  # fmt: skip
    if len(cues) * len(networks) < len(design):
        notes.append(f"on the crossed part of the design: {', '.join(cues)} x "
                     f"{', '.join(networks)}")  # fmt: skip
    data = data[data["modality"].isin(cues) & data["network"].isin(networks)]
    cells = len(cues) * len(networks)
    complete = data.groupby("participant").filter(lambda g: len(g) == cells)
    left_out = data["participant"].nunique() - complete["participant"].nunique()
    if left_out:
        notes.append(f"{left_out} participant(s) without a value in every cell left out")
    note = "; ".join(notes)
    people = complete["participant"].nunique()
    if people < 2:
        why = f"needs 2 or more participants with all {cells} cells, has {people}"
        return [
            untested(ANOVA_SUBSET, measure, effect, "", people, cells, why)
            for effect in EFFECTS.values()
        ], note
    table = (
        AnovaRM(complete, measure, "participant", within=["modality", "network"]).fit().anova_table
    )
    rows = []
    for term, effect in EFFECTS.items():
        f, df1, df2, p = (
            float(table.loc[term, k]) for k in ("F Value", "Num DF", "Den DF", "Pr > F")
        )
        partial_eta2 = f * df1 / (f * df1 + df2)
        rows.append(
            TestResult(
                ANOVA_SUBSET, measure, effect, f"F({df1:g}, {df2:g})", "anova_rm", people,
                cells, f, p, partial_eta2, "partial_eta_squared", stars(p), note,
            )
        )  # fmt: skip
    return rows, note


def crossed_part(design: set[tuple[str, str]]) -> tuple[list[str], list[str]]:
    """The largest part of a design's (cue set, network profile) cells that crosses every one of
    its cue sets with every one of its profiles: (cue sets, profiles), most cells first, then
    most profiles; empty where no two cue sets share two profiles."""
    networks = sorted({n for _, n in design}, key=lambda n: float(n[: n.index("ms")]))
    cue_names = sorted({c for c, _ in design})
    best: tuple[list[str], list[str]] = ([], [])
    for k in range(len(networks), 1, -1):
        for chosen in itertools.combinations(networks, k):
            cues = [c for c in cue_names if all((c, n) in design for n in chosen)]
            if len(cues) >= 2 and len(cues) * k > len(best[0]) * len(best[1]):
                best = (cues, list(chosen))
    return best
