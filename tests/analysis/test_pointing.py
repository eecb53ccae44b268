"""A pointing study's ISO 9241-9 analysis against values worked out by hand."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from arteleop.analysis import AnalysisInputError
from arteleop.analysis.pointing import (
    EFFECTIVE_WIDTH_SD,
    POINTING_COLUMNS,
    cell_medians,
    fitts_fits,
    lag_effect,
    lag_models,
    load_pointing,
    person_cells,
)
from arteleop.cli import main

SPREAD_M = 0.004
"""Each cell's selections land at -s, 0 and +s along the axis: their SD (ddof 1) is s."""
A_S, B_S = 0.2, 0.3
"""MT = a + b ID_e without lag, to the bit; under 300 ms every time is half as long again."""


def _table() -> pd.DataFrame:
    rows = []
    we = EFFECTIVE_WIDTH_SD * SPREAD_M
    for person in ("P1", "P2"):
        for lag, factor in ((0.0, 1.0), (300.0, 1.5)):
            for d in (0.1, 0.2, 0.4):
                mt = factor * (A_S + B_S * np.log2(d / we + 1))
                for k, along in enumerate((-SPREAD_M, 0.0, SPREAD_M)):
                    rows.append((person, lag, d, 0.02, mt, along, 0.001, float(k != 0)))
                rows.append((person, lag, d, 0.02, np.nan, np.nan, np.nan, np.nan))  # a timeout
    return pd.DataFrame(rows, columns=list(POINTING_COLUMNS))


def test_effective_width_id_and_errors_per_person_and_cell() -> None:
    people = person_cells(_table())
    assert len(people) == 2 * 2 * 3
    assert (people["n"] == 3).all() and (people["timeouts"] == 1).all()
    np.testing.assert_allclose(people["we_m"], EFFECTIVE_WIDTH_SD * SPREAD_M, rtol=1e-12)
    np.testing.assert_allclose(people["de_m"], people["distance_m"], atol=1e-15)
    np.testing.assert_allclose(people["error_rate"], 1 / 3)
    np.testing.assert_allclose(people["throughput_bits_s"], people["id_e_bits"] / people["mt_s"])


def test_the_fitts_line_the_lag_ratio_and_the_lag_models() -> None:
    people = person_cells(_table())
    cells = cell_medians(people)
    fits = fitts_fits(cells).set_index("round_trip_ms")
    assert fits.loc[0.0, "a_s_effective"] == pytest.approx(A_S, abs=1e-9)
    assert fits.loc[0.0, "b_s_per_bit_effective"] == pytest.approx(B_S, abs=1e-9)
    assert fits.loc[0.0, "r2_effective"] == pytest.approx(1.0)
    assert fits.loc[300.0, "b_s_per_bit_effective"] == pytest.approx(1.5 * B_S, abs=1e-9)
    ratio, low, high, n = lag_effect(people, 300.0, 0.0)
    assert (ratio, low, high, n) == (pytest.approx(1.5), pytest.approx(1.5), pytest.approx(1.5), 2)
    # Time scaled by the lag: the multiplicative model (lag x ID) fits better than the additive.
    models = lag_models(cells)
    assert models["multiplicative"]["r2"] > models["additive"]["r2"]


def test_analyze_reads_a_pointing_table_and_writes_its_report(tmp_path: Path, capsys) -> None:
    table = tmp_path / "pointing.csv"
    _table().to_csv(table, index=False)
    assert main(["analyze", str(table), "--out", str(tmp_path / "report")]) == 0
    report = (tmp_path / "report" / "report.md").read_text()
    assert "MT = 0.20 s + 0.30 s/bit x ID_e, R^2 = 1.00" in report
    assert "| 300 | x 1.50 (1.50-1.50) | 2 |" in report
    assert "analysed 48 pointing trials of 2 participants under 2 lags" in capsys.readouterr().out
    cells = pd.read_csv(tmp_path / "report" / "cells.csv")
    assert len(cells) == 6 and (cells["people"] == 2).all()
    one = _table()
    one[one["participant"] == one["participant"].iloc[0]].to_csv(table, index=False)
    assert main(["analyze", str(table), "--out", str(tmp_path / "one")]) == 0
    assert ": 24 trials of 1 participant, " in (tmp_path / "one" / "report.md").read_text()


@pytest.mark.parametrize(
    ("column", "value", "message"),
    [
        ("hit", 2.0, "column hit: '2.0'; expected 0 (a miss) or 1 (a hit)"),
        ("width_m", 0.0, "column width_m: '0.0'; expected a width above 0 m"),
        ("along_m", 0.001, "column along_m: '0.001'; expected a value exactly where "
                           "movement_time_s has one (a selection)"),
    ],
)  # fmt: skip
def test_a_bad_value_is_named_by_line_and_column(
    tmp_path: Path, column: str, value: float, message: str
) -> None:
    table = _table()
    table.loc[3, column] = value  # the first cell's timeout, on line 5
    path = tmp_path / "pointing.csv"
    table.to_csv(path, index=False)
    with pytest.raises(AnalysisInputError) as err:
        load_pointing(path)
    assert str(err.value) == f"{path}, line 5, {message}"


def test_a_labs_people_and_simulated_ones_side_by_side(tmp_path: Path, capsys) -> None:
    people, simulated = tmp_path / "people.csv", tmp_path / "simulated.csv"
    _table().to_csv(people, index=False)
    slower = _table()
    slower["movement_time_s"] *= 1.2
    slower.to_csv(simulated, index=False)
    assert main(["analyze", str(people), str(simulated), "--out", str(tmp_path / "both")]) == 0
    report = (tmp_path / "both" / "report.md").read_text()
    assert "- **people**: 48 trials of 2 participants\n" in report
    assert "people: MT = 0.20 s + 0.30 s/bit x ID_e, R^2 = 1.00" in report
    assert "simulated: MT = 0.24 s + 0.36 s/bit x ID_e, R^2 = 1.00" in report
    fits = pd.read_csv(tmp_path / "both" / "fits.csv")
    assert list(fits["source"]) == ["people", "people", "simulated", "simulated"]
    capsys.readouterr()
    # The same trials twice would count one cohort as two.
    copy = tmp_path / "copy.csv"
    copy.write_bytes(people.read_bytes())
    assert main(["analyze", str(people), str(copy), "--out", str(tmp_path / "twice")]) == 2
    assert f"{copy} holds the same trials as {people}" in capsys.readouterr().err
    run = tmp_path / "run"
    run.mkdir()
    (run / "trials.csv").write_text("participant\n")
    assert main(["analyze", str(people), str(run), "--out", str(tmp_path / "mixed")]) == 2
    assert "is a pointing study's table, and the others are not" in capsys.readouterr().err


def test_degenerate_cells_have_no_id_and_a_table_without_spread_is_refused(tmp_path: Path) -> None:
    """Selections all alike (W_e 0) or short of the start (D_e <= 0) give no ID_e, and the fit
    leaves them out; no cell with two selections is a message. A lab's extra columns and a
    quoted header are read."""
    table = _table()
    first = table.index[:3]  # P1's first cell without lag: every selection at its centre
    table.loc[first, "along_m"] = 0.0
    people = person_cells(table)
    degenerate = people.iloc[0]
    assert degenerate["we_m"] == 0.0 and np.isnan(degenerate["id_e_bits"])
    fits = fitts_fits(cell_medians(people)).set_index("round_trip_ms")
    assert fits.loc[0.0, "b_s_per_bit_effective"] == pytest.approx(B_S, abs=1e-9)  # P2's cell
    path = tmp_path / "pointing.csv"
    table.assign(block=1).to_csv(path, index=False, quoting=1)  # quoted, with a block column
    assert len(load_pointing(path)) == len(table)
    timeouts = table.assign(movement_time_s=np.nan, along_m=np.nan, across_m=np.nan, hit=np.nan)
    timeouts.to_csv(path, index=False)
    assert main(["analyze", str(path), "--out", str(tmp_path / "none")]) == 2
