"""A study crossing delay with cues: cells, the cue x delay ANOVA and per-delay comparisons."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from statsmodels.stats.anova import AnovaRM

from arteleop.analysis import AnalysisOptions, analyse, load_study, write_report

PEOPLE = 8
COST_S = 6.0  # what 500 ms costs without the predictive cue


def write_crossed(path: Path, interaction: bool) -> pd.DataFrame:
    """trials.csv of 8 participants x {none, predictive} x {0, 500 ms round trip}; the delay
    costs COST_S without the cue and nothing with it (or, without ``interaction``, COST_S in
    both)."""
    rng = np.random.default_rng(0)
    rows = []
    for k in range(PEOPLE):
        person = rng.normal(0.0, 2.0)
        cells = [("none", 0), ("predictive", 0), ("none", 500), ("predictive", 500)]
        for position, (cue, delay) in enumerate(cells, start=1):
            cost = COST_S if delay and (cue == "none" or not interaction) else 0.0
            rows.append({
                "participant": f"P{k:02d}", "phase": "experimental", "modality": cue,
                "position": position, "outcome": "success",
                "completion_time_s": 20.0 + person + cost + rng.normal(0.0, 0.5),
                "placement_error_m": 0.01 + rng.normal(0.0, 0.001) ** 2,
                "round_trip_ms": delay,
            })  # fmt: skip
    rows[3] |= {"outcome": "timeout", "completion_time_s": "", "placement_error_m": ""}
    table = pd.DataFrame(rows)
    table.to_csv(path, index=False)
    return table


def test_the_interaction_is_found_as_statsmodels_finds_it(tmp_path: Path) -> None:
    table = write_crossed(tmp_path / "trials.csv", interaction=True)
    result = analyse(load_study(tmp_path / "trials.csv"))
    anova = result.tests[result.tests["subset"] == "delay x cue"]
    time = anova[anova["measure"] == "completion_time_s"].set_index("group_a")
    # P00 lost a cell (a timeout): AnovaRM needs every cell, so the others are analysed.
    done = table[(table["outcome"] == "success") & (table["participant"] != "P00")].copy()
    done["completion_time_s"] = done["completion_time_s"].astype(float)
    done["network"] = done["round_trip_ms"].map(lambda d: f"{d:g}ms")
    expected = AnovaRM(done, "completion_time_s", "participant", ["modality", "network"]).fit()
    f = expected.anova_table["F Value"]
    assert time.loc["cue x delay", "statistic"] == pytest.approx(f["modality:network"])
    assert time.loc["delay", "statistic"] == pytest.approx(f["network"])
    assert time.loc["cue x delay", "p_value"] < 0.001
    assert time.loc["cue x delay", "n_a"] == PEOPLE - 1
    assert time.loc["cue x delay", "group_b"] == "F(1, 6)"
    assert "1 participant(s) without a value in every cell left out" in time.loc["delay", "note"]
    cells = result.cells.set_index(["network", "modality"])
    assert cells.loc[("500ms", "predictive"), "successes"] == PEOPLE - 1  # P00's timeout
    assert cells.loc[("500ms", "none"), "successes"] == PEOPLE
    slow = cells.loc[("500ms", "none"), "median_completion_time_s"]
    fast = cells.loc[("500ms", "predictive"), "median_completion_time_s"]
    assert slow - fast == pytest.approx(COST_S, abs=1.5)
    # The thesis's pairwise comparisons run within each delay.
    assert {"all @ 0ms", "all @ 500ms"} <= set(result.tests["subset"])


def test_without_an_interaction_it_is_not_found(tmp_path: Path) -> None:
    write_crossed(tmp_path / "trials.csv", interaction=False)
    result = analyse(load_study(tmp_path / "trials.csv"))
    anova = result.tests[result.tests["subset"] == "delay x cue"]
    time = anova[anova["measure"] == "completion_time_s"].set_index("group_a")
    assert time.loc["cue x delay", "p_value"] > 0.05
    assert time.loc["delay", "p_value"] < 0.001


def test_the_report_has_the_cells_and_the_anova(tmp_path: Path) -> None:
    write_crossed(tmp_path / "trials.csv", interaction=True)
    study = load_study(tmp_path / "trials.csv")
    files = write_report(study, analyse(study), AnalysisOptions(), tmp_path / "report")
    text = files["report.md"].read_text()
    assert "## Delay x cue" in text
    assert "| 500ms | predictive | 7/8 |" in text
    assert "| completion_time_s @ 500ms | none | predictive |" in text  # pairwise, per delay
    assert "delay x cue, completion_time_s" not in text  # not listed again among subsets
    assert pd.read_csv(files["cells.csv"]).shape == (4, 8)
