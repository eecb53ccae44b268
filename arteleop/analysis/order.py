"""The order effect (docs/explanation/study.md §5): does a measure change with a trial's place in
the participant's sequence? A one-way ANOVA over the positions, with eta squared, as the thesis
tested it."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd
from numpy.typing import NDArray
from scipy import stats

from arteleop.analysis.statistics import TestResult, stars, untested


def order_effect(df: pd.DataFrame, value: str, subset: str = "all") -> tuple[TestResult, dict]:
    """One-way ANOVA of ``value`` over trial position 1..5."""
    groups = [g[value].dropna().to_numpy() for _, g in df.groupby("position")]
    groups = [g for g in groups if len(g)]
    n = sum(len(g) for g in groups)
    summary = {"measure": value, "k": len(groups), "n": n}
    if len(groups) < 2 or n - len(groups) < 1:
        summary |= {
            "F": math.nan,
            "p_value": math.nan,
            "df_between": math.nan,
            "df_within": math.nan,
        }
        return untested(
            subset, value, "position", "", n, len(groups), "too few positions or trials"
        ), summary
    res = stats.f_oneway(*groups)
    eta2 = _eta_squared(groups)
    summary |= {
        "F": float(res.statistic),
        "p_value": float(res.pvalue),
        "df_between": len(groups) - 1,
        "df_within": n - len(groups),
        "eta_squared": eta2,
    }
    row = TestResult(
        subset,
        value,
        "position",
        "",
        "anova",
        n,
        len(groups),
        float(res.statistic),
        float(res.pvalue),
        eta2,
        "eta_squared",
        stars(float(res.pvalue)),
    )
    return row, summary


def _eta_squared(groups: Sequence[NDArray[np.float64]]) -> float:
    allv = np.concatenate(groups)
    ss_between = sum(len(g) * (np.mean(g) - np.mean(allv)) ** 2 for g in groups)
    ss_total = float(np.sum((allv - np.mean(allv)) ** 2))
    return float(ss_between / ss_total) if ss_total > 0 else math.nan
