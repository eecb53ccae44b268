"""A pointing study's report: its tables as CSV and report.md (:mod:`.pointing`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.output import whole_folder
from arteleop.analysis.pointing import (
    cell_medians,
    fitts_fits,
    lag_effect,
    lag_models,
    person_cells,
)


def write_pointing_report(source: Path, trials: pd.DataFrame, out_dir: Path) -> dict[str, Path]:
    """Write people.csv (per lag, participant and cell), cells.csv (medians over people),
    fits.csv (the Fitts fit per lag), lags.csv (each lag against the first, and the lag
    models) and report.md into ``out_dir``, whole or not at all; returns the files by name."""
    people = person_cells(trials)
    cells = cell_medians(people)
    fits = fitts_fits(cells)
    lags = sorted(trials["round_trip_ms"].unique())
    effects = pd.DataFrame(
        [(lag, *lag_effect(people, lag, lags[0])) for lag in lags],
        columns=["round_trip_ms", "mt_ratio", "ratio_low", "ratio_high", "people"],
    )
    models = lag_models(cells) if cells["round_trip_ms"].nunique() > 1 else {}
    tables = {"people.csv": people, "cells.csv": cells, "fits.csv": fits, "lags.csv": effects}
    with whole_folder(out_dir) as partial:
        for name, table in tables.items():
            table.to_csv(partial / name, index=False, float_format="%.6g")
        text = _markdown(source, trials, cells, fits, effects, models)
        (partial / "report.md").write_text(text, encoding="utf-8")
    return {name: out_dir / name for name in [*tables, "report.md"]}


def _markdown(
    source: Path,
    trials: pd.DataFrame,
    cells: pd.DataFrame,
    fits: pd.DataFrame,
    effects: pd.DataFrame,
    models: dict[str, dict[str, float]],
) -> str:
    selected = int(trials["movement_time_s"].notna().sum())
    lines = [
        "# Pointing (ISO 9241-9)",
        "",
        f"{source}: {len(trials)} trials of {trials['participant'].nunique()} participants, "
        f"{selected} with a selection. Per participant, lag and cell: the median movement time, "
        "W_e = 4.133 SD of the selections along the task axis, ID_e = log2(D_e / W_e + 1); per "
        "cell the medians over participants (docs/reference/data-format.md, pointing.csv).",
        "",
    ]
    for lag, here in cells.groupby("round_trip_ms", sort=True):
        lines += [
            f"## Lag {lag:g} ms (round trip)",
            "",
            "| D (m) | W (mm) | ID (bits) | W_e (mm) | ID_e (bits) | MT (s) | throughput "
            "(bits/s) | errors | people | timeouts |",
            "| ---: " * 10 + "|",
        ]
        for c in here.itertuples():
            lines.append(
                f"| {c.distance_m:g} | {1000 * c.width_m:.0f} | {c.id_bits:.2f} "
                f"| {1000 * c.we_m:.1f} | {c.id_e_bits:.2f} | {c.mt_s:.2f} "
                f"| {c.throughput_bits_s:.2f} | {100 * c.error_rate:.0f} % | {c.people} "
                f"| {c.timeouts} |"
            )
        fit = fits[fits["round_trip_ms"] == lag]
        if not fit.empty:
            f = fit.iloc[0]
            lines += ["", f"MT = {f.a_s_effective:.2f} s + {f.b_s_per_bit_effective:.2f} s/bit x "
                      f"ID_e, R^2 = {f.r2_effective:.2f} (nominal ID: {f.a_s_nominal:.2f} s + "
                      f"{f.b_s_per_bit_nominal:.2f} s/bit, R^2 = {f.r2_nominal:.2f})"]  # fmt: skip
        lines.append("")
    if len(effects) > 1:
        base = effects["round_trip_ms"].iloc[0]
        lines += [
            f"## Each lag against {base:g} ms",
            "",
            "Movement time, participant by participant (the mean log ratio over the cells both "
            "have), as the geometric mean over participants with its 95 % t-interval.",
            "",
            "| lag (ms) | MT ratio (95 % CI) | participants |",
            "| ---: | --- | ---: |",
        ]
        for e in effects.iloc[1:].itertuples():
            ratio = "-" if np.isnan(e.mt_ratio) else (
                f"x {e.mt_ratio:.2f} ({e.ratio_low:.2f}-{e.ratio_high:.2f})")  # fmt: skip
            lines.append(f"| {e.round_trip_ms:g} | {ratio} | {e.people} |")
        lines.append("")
    for name, m in models.items():
        lines.append(
            f"{name} lag model (MacKenzie & Ware 1993): a = {m['a_s']:.2f} s, b = "
            f"{m['b_s_per_bit']:.2f} s/bit, c = {m['c']:.2f}, R^2 = {m['r2']:.3f}  "
        )
    return "\n".join(lines).rstrip() + "\n"
