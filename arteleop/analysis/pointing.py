"""A pointing study's analysis as ISO 9241-9 asks it (Soukoreff & MacKenzie, Int. J. Human-
Computer Studies 61, 2004), under added lag (MacKenzie & Ware, CHI 1993).

The input is one row per pointing trial (docs/reference/data-format.md, ``pointing.csv``): who,
under which round-trip lag, at which distance and width, and where the selection landed. Per
person, lag and cell (distance D, width W), with two selections or more: the movement time (the
median of the selected trials, where Soukoreff & MacKenzie take the mean: robust to the odd
trial a lab's people or the simulated participant leave long), the effective width
``W_e = 4.133 SD`` of the selections along the task axis and the effective distance ``D_e`` (D
plus their mean overshoot), ``ID_e = log2(D_e / W_e + 1)`` (bits), the throughput ``ID_e / MT``
(bits/s) and the error rate (selections outside the circle). Per lag and cell, the medians over
people (the error rate their mean); per lag, the Fitts fit of the medians on ``ID_e`` (and on
the nominal ``ID = log2(D / W + 1)``); over lags, each lag's movement time against the first
lag's, person by person, and MacKenzie & Ware's additive and multiplicative lag models.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.data import AnalysisInputError, read_table
from arteleop.analysis.statistics import mean_interval

EFFECTIVE_WIDTH_SD = 4.133
"""W_e in SDs of the selections along the task axis: the width that holds 96 % of a normal
scatter (Soukoreff & MacKenzie 2004)."""
POINTING_COLUMNS = ("participant", "round_trip_ms", "distance_m", "width_m", "movement_time_s",
                    "along_m", "across_m", "hit")  # fmt: skip
"""The columns of ``pointing.csv``; a trial with no selection leaves the last four empty."""
_NUMERIC = POINTING_COLUMNS[1:]


POINTING_FILE = "pointing.csv"
"""A pointing study's trials in a folder."""


def pointing_table_path(source: Path) -> Path | None:
    """The pointing table ``source`` is or holds: a folder with ``pointing.csv`` (and no
    trials.csv), or a CSV whose header names a pointing table's columns; else None."""
    source = Path(source)
    if source.is_dir():
        table = source / POINTING_FILE
        return table if table.is_file() and not (source / "trials.csv").exists() else None
    header = _header(source)
    return source if {"distance_m", "width_m", "round_trip_ms"} <= set(header) else None


def _header(path: Path) -> list[str]:
    """A CSV's column names (none if it cannot be read)."""
    try:
        with path.open(encoding="utf-8-sig", newline="") as f:
            return [c.strip() for c in next(csv.reader(f), [])]
    except (OSError, UnicodeDecodeError, csv.Error):
        return []


def load_pointing(path: Path) -> pd.DataFrame:
    """A pointing table (``pointing.csv``), checked: every column, distances and widths above 0,
    lags 0 or more, hits 0 or 1 and given exactly where a movement time is."""
    path = Path(path)
    if not path.is_file():
        raise AnalysisInputError(f"{path}: no such file; a pointing study's trials are a CSV")
    # A lab's table may hold more (a block, a trial number): those columns are not read.
    extra = tuple(c for c in _header(path) if c not in POINTING_COLUMNS)
    table = read_table(path, POINTING_COLUMNS + extra, POINTING_COLUMNS, _NUMERIC, {},
                       may_be_empty=POINTING_COLUMNS[4:])  # fmt: skip
    table = table[list(POINTING_COLUMNS)]
    if table.empty:
        raise AnalysisInputError(f"{path}: no trials below the header")
    checks = {
        "round_trip_ms": (table["round_trip_ms"] >= 0, "a round trip of 0 ms or more"),
        "distance_m": (table["distance_m"] > 0, "a distance above 0 m"),
        "width_m": (table["width_m"] > 0, "a width above 0 m"),
        "hit": (table["hit"].isin([0.0, 1.0]) | table["hit"].isna(), "0 (a miss) or 1 (a hit)"),
        "movement_time_s": (
            table["movement_time_s"].isna() | (table["movement_time_s"] > 0),
            "a time above 0 s, or empty for no selection",
        ),
    }
    selected = table["movement_time_s"].notna()
    for column in ("along_m", "across_m", "hit"):
        checks[f"{column} "] = (
            table[column].notna() == selected,
            "a value exactly where movement_time_s has one (a selection)",
        )
    for key, (ok, expected) in checks.items():
        bad = np.flatnonzero(~ok.to_numpy())
        if len(bad):
            column = key.strip()
            raise AnalysisInputError(
                f"{path}, line {bad[0] + 2}, column {column}: '{table[column].iloc[bad[0]]}'; "
                f"expected {expected}"
            )
    return table


PERSON_CELL_COLUMNS = ("round_trip_ms", "participant", "distance_m", "width_m", "n", "timeouts",
                       "id_bits", "mt_s", "we_m", "de_m", "id_e_bits", "throughput_bits_s",
                       "error_rate")  # fmt: skip
CELL_COLUMNS = ("round_trip_ms", "distance_m", "width_m", "people", "id_bits", "id_e_bits",
                "we_m", "mt_s", "throughput_bits_s", "error_rate", "timeouts")  # fmt: skip
FIT_COLUMNS = ("round_trip_ms", "a_s_effective", "b_s_per_bit_effective", "r2_effective",
               "a_s_nominal", "b_s_per_bit_nominal", "r2_nominal")  # fmt: skip


def person_cells(trials: pd.DataFrame) -> pd.DataFrame:
    """Per lag, participant and cell: the trials selected (``n``) and not (``timeouts``), the
    nominal ``id_bits``; with two selections or more, ``mt_s``, ``we_m``, ``de_m``,
    ``id_e_bits``, ``throughput_bits_s`` and ``error_rate`` (else NaN)."""
    keys = ["round_trip_ms", "participant", "distance_m", "width_m"]
    rows = []
    for (lag, person, d, w), cell in trials.groupby(keys, sort=True):
        done = cell[cell["movement_time_s"].notna()]
        entry = {"round_trip_ms": lag, "participant": person, "distance_m": d, "width_m": w,
                 "n": len(done), "timeouts": len(cell) - len(done),
                 "id_bits": float(np.log2(d / w + 1))}  # fmt: skip
        mt = we = de = id_e = error_rate = float("nan")
        if len(done) >= 2:
            along = done["along_m"].to_numpy()
            we = EFFECTIVE_WIDTH_SD * float(along.std(ddof=1))
            de = d + float(along.mean())
            # Selections all alike (W_e 0) or short of the start (D_e <= 0) give no ID_e.
            id_e = float(np.log2(de / we + 1)) if we > 0 and de > 0 else float("nan")
            mt = float(np.median(done["movement_time_s"].to_numpy()))
            error_rate = float(1 - np.mean(done["hit"].to_numpy()))
        entry.update(mt_s=mt, we_m=we, de_m=de, id_e_bits=id_e, throughput_bits_s=id_e / mt,
                     error_rate=error_rate)  # fmt: skip
        rows.append(entry)
    return pd.DataFrame(rows, columns=PERSON_CELL_COLUMNS)


def cell_medians(people: pd.DataFrame) -> pd.DataFrame:
    """Per lag and cell with a movement time of someone's: the people with one there (two
    selections or more), the nominal ID, the medians of their ``mt_s``, ``id_e_bits``,
    ``we_m`` and ``throughput_bits_s`` (of those with an ID_e), the mean of their error rates,
    and everyone's timeouts there."""
    rows = []
    keys = ["round_trip_ms", "distance_m", "width_m"]
    timeouts = people.groupby(keys)["timeouts"].sum()
    timed = people[people["mt_s"].notna()]
    for (lag, d, w), cell in timed.groupby(keys, sort=True):
        rows.append({
            "round_trip_ms": lag, "distance_m": d, "width_m": w, "people": len(cell),
            "id_bits": float(np.log2(d / w + 1)),
            "id_e_bits": _median(cell["id_e_bits"]),
            "we_m": _median(cell["we_m"]),
            "mt_s": float(np.median(cell["mt_s"].to_numpy())),
            "throughput_bits_s": _median(cell["throughput_bits_s"]),
            "error_rate": float(np.mean(cell["error_rate"].to_numpy())),
            "timeouts": int(timeouts[lag, d, w]),
        })  # fmt: skip
    return pd.DataFrame(rows, columns=CELL_COLUMNS)


def _median(values: pd.Series) -> float:
    """The median of the values there are (NaN: none)."""
    present = values.dropna().to_numpy()
    return float(np.median(present)) if len(present) else float("nan")


def fit_line(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """(a, b, R^2) of the least-squares line y = a + b x."""
    b, a = np.polyfit(x, y, 1)
    r2 = 1 - np.sum((y - a - b * x) ** 2) / np.sum((y - y.mean()) ** 2)
    return float(a), float(b), float(r2)


def fitts_fits(cells: pd.DataFrame) -> pd.DataFrame:
    """Per lag with three cells or more: ``MT = a + b ID_e`` and ``MT = a + b ID`` over its
    cells' medians (``a_s``, ``b_s_per_bit``, ``r2``, each ``_effective`` and ``_nominal``)."""
    rows = []
    for lag, here in cells[cells["id_e_bits"].notna()].groupby("round_trip_ms", sort=True):
        if len(here) < 3:
            continue
        mt = here["mt_s"].to_numpy()
        a, b, r2 = fit_line(here["id_e_bits"].to_numpy(), mt)
        a0, b0, r20 = fit_line(here["id_bits"].to_numpy(), mt)
        rows.append({"round_trip_ms": lag, "a_s_effective": a, "b_s_per_bit_effective": b,
                     "r2_effective": r2, "a_s_nominal": a0, "b_s_per_bit_nominal": b0,
                     "r2_nominal": r20})  # fmt: skip
    return pd.DataFrame(rows, columns=FIT_COLUMNS)


def lag_effect(people: pd.DataFrame, lag: float, base: float) -> tuple[float, float, float, int]:
    """Movement time under ``lag`` over ``base`` (ms), person by person (the mean of the log
    ratios over the cells both have), as the geometric mean over people with its 95 %
    t-interval, and the people counted."""
    logs = []
    timed = people[people["mt_s"].notna()]
    for _, mine in timed.groupby("participant", sort=True):
        mt = {(r.distance_m, r.width_m, r.round_trip_ms): r.mt_s for r in mine.itertuples()}
        cells = sorted({(d, w) for d, w, _ in mt})
        pairs = [np.log(mt[d, w, lag] / mt[d, w, base]) for d, w in cells
                 if (d, w, lag) in mt and (d, w, base) in mt]  # fmt: skip
        if pairs:
            logs.append(float(np.mean(pairs)))
    if len(logs) < 2:
        return float("nan"), float("nan"), float("nan"), len(logs)
    mean, low, high = np.exp(mean_interval(logs))
    return float(mean), float(low), float(high), len(logs)


def lag_models(cells: pd.DataFrame) -> dict[str, dict[str, float]]:
    """MacKenzie & Ware's models of the cells' median movement time, least squares: additive
    ``MT = a + b ID + c lag`` and multiplicative ``MT = a + b ID + c lag ID`` (lag in s); each
    model's ``a_s``, ``b_s_per_bit``, ``c`` and ``r2`` (none with fewer than four cells)."""
    if len(cells) < 4:
        return {}
    ids = cells["id_bits"].to_numpy()
    lag_s = cells["round_trip_ms"].to_numpy() / 1000
    mt = cells["mt_s"].to_numpy()
    designs = {
        "additive": np.column_stack([np.ones_like(ids), ids, lag_s]),
        "multiplicative": np.column_stack([np.ones_like(ids), ids, lag_s * ids]),
    }
    out = {}
    for name, X in designs.items():
        coef, *_ = np.linalg.lstsq(X, mt, rcond=None)
        r2 = 1 - np.sum((mt - X @ coef) ** 2) / np.sum((mt - mt.mean()) ** 2)
        out[name] = {"a_s": float(coef[0]), "b_s_per_bit": float(coef[1]), "c": float(coef[2]),
                     "r2": float(r2)}  # fmt: skip
    return out
