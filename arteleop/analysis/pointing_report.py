"""A pointing study's report: its tables as CSV and report.md (:mod:`.pointing`); or several
pointing tables side by side (a lab's people and simulated participants of the same design)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.data import AnalysisInputError
from arteleop.analysis.output import whole_folder
from arteleop.analysis.pointing import (
    cell_medians,
    fitts_fits,
    lag_effect,
    lag_models,
    person_cells,
)


def pointing_tables(trials: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """One pointing table's analysis as its report's files: people.csv (per lag, participant and
    cell), cells.csv (medians over people), fits.csv (the Fitts fit per lag) and lags.csv (each
    lag against the first)."""
    people = person_cells(trials)
    cells = cell_medians(people)
    lags = sorted(trials["round_trip_ms"].unique())
    effects = pd.DataFrame(
        [(lag, *lag_effect(people, lag, lags[0])) for lag in lags],
        columns=["round_trip_ms", "mt_ratio", "ratio_low", "ratio_high", "people"],
    )
    return {"people.csv": people, "cells.csv": cells, "fits.csv": fitts_fits(cells),
            "lags.csv": effects}  # fmt: skip


def write_pointing_report(source: Path, trials: pd.DataFrame, out_dir: Path) -> dict[str, Path]:
    """Write people.csv (per lag, participant and cell), cells.csv (medians over people),
    fits.csv (the Fitts fit per lag), lags.csv (each lag against the first, and the lag
    models) and report.md into ``out_dir``, whole or not at all; returns the files by name."""
    tables = pointing_tables(trials)
    cells, fits, effects = tables["cells.csv"], tables["fits.csv"], tables["lags.csv"]
    models = lag_models(cells) if cells["round_trip_ms"].nunique() > 1 else {}
    if cells.empty:
        raise AnalysisInputError(
            f"{source}: no participant has two selections in any cell; an effective width needs "
            "a spread of selections (repeat each cell)"
        )
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
        f"{source}: {_counted(trials)}, {selected} with a selection. Per participant, lag and "
        "cell: the median movement time, W_e = 4.133 SD of the selections along the task axis, "
        "ID_e = log2(D_e / W_e + 1); per cell the medians over participants "
        "(docs/reference/data-format.md, pointing.csv).",
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
                f"| {_shown(1000 * c.we_m, '.1f')} | {_shown(c.id_e_bits, '.2f')} | {c.mt_s:.2f} "
                f"| {_shown(c.throughput_bits_s, '.2f')} | {100 * c.error_rate:.0f} % "
                f"| {c.people} | {c.timeouts} |"
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


def source_name(source: Path) -> str:
    """How a comparison names a pointing table: its folder's name for ``pointing.csv``, else
    the file's stem."""
    source = Path(source).resolve()
    return source.parent.name if source.name == "pointing.csv" else source.stem


def write_pointing_comparison(
    sources: list[Path], tables: list[pd.DataFrame], out_dir: Path
) -> dict[str, Path]:
    """Several pointing tables side by side, each analysed alone (:func:`write_pointing_report`'s
    tables, a ``source`` column first): cells.csv, fits.csv, lags.csv and report.md, with each
    lag's cells and fits of every source in one table; whole or not at all."""
    names = [source_name(s) for s in sources]
    parts: dict[str, list[pd.DataFrame]] = {"cells.csv": [], "fits.csv": [], "lags.csv": []}
    for name, trials in zip(names, tables, strict=True):
        for key, table in pointing_tables(trials).items():
            if key in parts:
                parts[key].append(table.assign(source=name)[["source", *table.columns]])
    joined = {key: pd.concat(frames, ignore_index=True) for key, frames in parts.items()}
    if joined["cells.csv"].empty:
        raise AnalysisInputError(
            "no participant of any source has two selections in any cell; an effective width "
            "needs a spread of selections (repeat each cell)"
        )
    with whole_folder(out_dir) as partial:
        for key, table in joined.items():
            table.to_csv(partial / key, index=False, float_format="%.6g")
        (partial / "report.md").write_text(_comparison(names, tables, joined), encoding="utf-8")
    return {name: out_dir / name for name in [*joined, "report.md"]}


def _counted(trials: pd.DataFrame) -> str:
    """How many trials of how many participants ``trials`` holds, in words."""
    people = trials["participant"].nunique()
    return (f"{len(trials)} trial{'s' * (len(trials) != 1)} of {people} "
            f"participant{'s' * (people != 1)}")  # fmt: skip


def _comparison(
    names: list[str], tables: list[pd.DataFrame], joined: dict[str, pd.DataFrame]
) -> str:
    cells, fits, lags = joined["cells.csv"], joined["fits.csv"], joined["lags.csv"]
    lines = ["# Pointing (ISO 9241-9), side by side", ""]
    for name, trials in zip(names, tables, strict=True):
        lines.append(f"- **{name}**: {_counted(trials)}")
    lines += ["", "Each source analysed alone, as `arteleop analyze` analyses one; per cell the "
              "medians over its participants.", ""]  # fmt: skip
    for lag in sorted(cells["round_trip_ms"].unique()):
        here = cells[cells["round_trip_ms"] == lag]
        lines += [
            f"## Lag {lag:g} ms (round trip)",
            "",
            "| D (m) | W (mm) | ID (bits) | "
            + " | ".join(f"{n}: MT (s) | {n}: errors" for n in names)
            + " |",
            "| ---: | ---: | ---: | " + "---: | ---: | " * len(names),
        ]
        for (d, w), cell in here.groupby(["distance_m", "width_m"], sort=True):
            by_source = cell.set_index("source")
            values = []
            for n in names:
                if n in by_source.index:
                    c = by_source.loc[n]
                    values.append(f"{c.mt_s:.2f} | {100 * c.error_rate:.0f} %")
                else:
                    values.append("- | -")
            lines.append(f"| {d:g} | {1000 * w:.0f} | {np.log2(d / w + 1):.2f} | "
                         + " | ".join(values) + " |")  # fmt: skip
        lines.append("")
        for f in fits[fits["round_trip_ms"] == lag].itertuples():
            lines.append(f"{f.source}: MT = {f.a_s_effective:.2f} s + "
                         f"{f.b_s_per_bit_effective:.2f} s/bit x ID_e, R^2 = "
                         f"{f.r2_effective:.2f}  ")  # fmt: skip
        lines.append("")
    later = lags[lags["round_trip_ms"] > lags.groupby("source")["round_trip_ms"].transform("min")]
    if not later.empty:
        lines += ["## Each lag against the source's first", "",
                  "| source | lag (ms) | MT ratio (95 % CI) | participants |",
                  "| --- | ---: | --- | ---: |"]  # fmt: skip
        for e in later.itertuples():
            ratio = "-" if np.isnan(e.mt_ratio) else (
                f"x {e.mt_ratio:.2f} ({e.ratio_low:.2f}-{e.ratio_high:.2f})")  # fmt: skip
            lines.append(f"| {e.source} | {e.round_trip_ms:g} | {ratio} | {e.people} |")
    return "\n".join(lines).rstrip() + "\n"


def _shown(value: float, spec: str) -> str:
    """A number as a table shows it; "-" where there is none (selections all alike, or
    short of the start, have no ID_e)."""
    return "-" if np.isnan(value) else format(value, spec)
