"""The study's statistics: three methods of comparing two conditions, as
docs/guides/analysing-data.md describes.

- ``untrimmed`` (the default): every participant; Lilliefors' test decides between Student's
  t-test (both groups normal) and the Mann-Whitney U test (two-sided, normal approximation with
  continuity correction, as MATLAB's ``ranksum`` for samples this size); paired: the paired
  t-test when the differences are normal, else Wilcoxon's signed-rank test.
- ``yuen``: robust to outliers at its stated error rate: Yuen's (1974) test of 20 % trimmed
  means, whose standard error comes from the winsorized variance, so the trimming is accounted
  for; paired: the same trimmed-mean test on the paired differences (Tukey & McLaughlin 1963).
- ``thesis``: the original study's procedure (docs/explanation/study.md §5), kept to reproduce it:
  per group the largest and the smallest value are dropped, then the untrimmed method's tests treat
  the rest as an ordinary sample. Its standard error is too small, so it rejects a true null about
  twice as often as p <= 0.05 says (0.08-0.12 in our checks, the more the fewer participants).

Options: paired tests for the within-subject design, Holm correction within each family
(subset x measure). Every p-value comes with an effect size: Cohen's d (pooled SD; d_z for
paired tests), Algina, Keselman & Penfield's robust d with Yuen's test, or the rank-biserial
correlation.
"""

from __future__ import annotations

import gc
import itertools
import math
import warnings
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np
import pandas as pd
from numpy.typing import NDArray
from scipy import stats
from statsmodels.stats.diagnostic import lilliefors
from statsmodels.stats.multitest import multipletests

from arteleop.analysis.errors import AnalysisInputError

MIN_NORMALITY_N = 4  # Lilliefors' table starts at n = 4
MIN_TEST_N = 3
NO_SPREAD = "no p: the values compared do not vary (after trimming)"
METHODS = ("untrimmed", "yuen", "thesis")
"""How two conditions are compared (the module's docstring says what each does)."""
YUEN_TRIM = 0.2
"""The share trimmed from each end by the ``yuen`` method: Wilcox's (2012, *Introduction to
Robust Estimation and Hypothesis Testing*, 3rd ed.) recommended 20 %, efficient under
normality and resistant to heavy tails."""


@dataclass(frozen=True)
class AnalysisOptions:
    """How to run the statistics.

    Attributes:
        method: How two conditions are compared: ``untrimmed``, ``yuen`` or ``thesis`` (see
            :data:`METHODS` and the module's docstring).
        paired: Within-subject tests between modalities (not with ``thesis``, which compared
            them as independent groups).
        holm: Holm-correct the p-values of each family of pairwise tests.
        alpha: Significance level for the normality decision (and the star for p <= alpha).
    """

    method: str = "untrimmed"
    paired: bool = False
    holm: bool = False
    alpha: float = 0.05

    def __post_init__(self) -> None:
        check_method(self.method, self.paired)
        if not (np.isfinite(self.alpha) and 0 < self.alpha < 1):
            raise AnalysisInputError(f"alpha = {self.alpha}: expected a level between 0 and 1")

    @property
    def drops_extremes(self) -> bool:
        """Whether each group loses its largest and smallest value first (the thesis)."""
        return self.method == "thesis"


def check_method(method: str, paired: bool) -> None:
    """Refuse an unknown method, and the thesis's trimming with paired tests."""
    if method not in METHODS:
        raise AnalysisInputError(f"method {method!r}: expected one of {', '.join(METHODS)}")
    if method == "thesis" and paired:
        raise AnalysisInputError(
            "method 'thesis' compares modalities as independent groups, as the thesis did; "
            "paired tests go with method 'untrimmed' or 'yuen'"
        )


@dataclass(frozen=True)
class TestResult:
    """One row of tests.csv."""

    __test__ = False  # not a pytest test class, despite the name
    subset: str
    measure: str
    group_a: str
    group_b: str
    test: str
    n_a: int
    n_b: int
    statistic: float
    p_value: float
    effect_size: float
    effect_size_kind: str
    stars: str
    note: str = ""


@dataclass(frozen=True)
class NormalityResult:
    """One row of normality.csv."""

    subset: str
    measure: str
    group: str
    n: int
    statistic: float
    p_value: float
    normal: bool | None
    note: str = ""


def stars(p: float, alpha: float = 0.05) -> str:
    """'**' for p < 0.01, '*' for p <= alpha, '' otherwise (and for missing p)."""
    if not np.isfinite(p):
        return ""
    return "**" if p < 0.01 else "*" if p <= alpha else ""


def trim_extremes(df: pd.DataFrame, value: str, by: Sequence[str]) -> pd.DataFrame:
    """Drop, within each group of ``by``, the row with the largest and the smallest ``value``."""
    kept = []
    for _, group in df.dropna(subset=[value]).groupby(list(by), sort=False):
        if len(group) <= 2:
            continue
        order = group[value].to_numpy().argsort(kind="stable")
        kept.append(group.iloc[np.sort(order[1:-1])])
    return pd.concat(kept) if kept else df.iloc[0:0]


def normality(values: NDArray[np.float64], alpha: float = 0.05) -> tuple[float, float, bool | None]:
    """Lilliefors test: (statistic, p, normal?). ``normal`` is None when n < 4."""
    x = np.asarray(values, dtype=np.float64)
    if len(x) < MIN_NORMALITY_N or np.ptp(x) == 0:
        return math.nan, math.nan, None
    stat, p = lilliefors(x, dist="norm", pvalmethod="table")
    return float(stat), float(p), bool(p > alpha)


def cohens_d(a: NDArray[np.float64], b: NDArray[np.float64]) -> float:
    """(mean a - mean b) / pooled standard deviation (ddof = 1)."""
    na, nb = len(a), len(b)
    pooled = np.sqrt(((na - 1) * np.var(a, ddof=1) + (nb - 1) * np.var(b, ddof=1)) / (na + nb - 2))
    return float((np.mean(a) - np.mean(b)) / pooled) if pooled > 0 else math.nan


def rank_biserial(u_a: float, na: int, nb: int) -> float:
    """Rank-biserial correlation from the U of sample a: positive when a tends to be larger."""
    return float(2.0 * u_a / (na * nb) - 1.0)


def compare_independent(
    a: NDArray[np.float64], b: NDArray[np.float64], normal: bool
) -> tuple[str, float, float, float, str]:
    """(test, statistic, p, effect size, effect kind) for two independent samples."""
    if normal:
        res = stats.ttest_ind(a, b, equal_var=True)
        return "ttest", float(res.statistic), float(res.pvalue), cohens_d(a, b), "cohen_d"
    res = stats.mannwhitneyu(
        a, b, alternative="two-sided", method="asymptotic", use_continuity=True
    )
    u = float(res.statistic)
    return "mannwhitneyu", u, float(res.pvalue), rank_biserial(u, len(a), len(b)), "rank_biserial"


def compare_paired(
    a: NDArray[np.float64], b: NDArray[np.float64], normal: bool
) -> tuple[str, float, float, float, str]:
    """(test, statistic, p, effect size, effect kind) for paired samples (a[i] with b[i])."""
    d = a - b
    if normal:
        res = stats.ttest_rel(a, b)
        sd = np.std(d, ddof=1)
        return (
            "paired_ttest",
            float(res.statistic),
            float(res.pvalue),
            float(np.mean(d) / sd),
            "cohen_dz",
        )
    res = stats.wilcoxon(a, b, zero_method="wilcox", correction=True, method="approx")
    nz = d[d != 0]
    ranks = stats.rankdata(np.abs(nz))
    t_plus, t_minus = ranks[nz > 0].sum(), ranks[nz < 0].sum()
    r = (t_plus - t_minus) / (t_plus + t_minus) if len(nz) else math.nan
    return "wilcoxon", float(res.statistic), float(res.pvalue), float(r), "rank_biserial"


def winsorized_scale(trim: float = YUEN_TRIM) -> float:
    """The winsorized standard deviation of a unit normal at ``trim`` (0.642 at 20 %):
    Algina, Keselman & Penfield (2005) divide by it to put the robust d on Cohen's scale."""
    z = stats.norm.ppf(1.0 - trim)
    inner = (1.0 - 2.0 * trim) - 2.0 * z * stats.norm.pdf(z)  # E[x^2; |x| < z]
    return math.sqrt(inner + 2.0 * trim * z * z)


def _winsorized(x: NDArray[np.float64], trim: float) -> tuple[float, float, int]:
    """(trimmed mean, winsorized variance (ddof 1), values left after trimming)."""
    v = np.sort(x)
    n = len(v)
    g = int(n * trim)
    w = np.clip(v, v[g], v[n - g - 1])
    return float(np.mean(v[g : n - g])), float(np.var(w, ddof=1)), n - 2 * g


def compare_yuen(
    a: NDArray[np.float64], b: NDArray[np.float64], trim: float = YUEN_TRIM
) -> tuple[str, float, float, float, str]:
    """Yuen's test of trimmed means (scipy's ``ttest_ind(..., trim=, equal_var=False)``), with
    the robust d of Algina, Keselman & Penfield (2005): the trimmed means' difference over
    the pooled winsorized SD, rescaled by :func:`winsorized_scale`."""
    with warnings.catch_warnings():  # no spread after trimming: p 0, or NaN if no difference
        warnings.simplefilter("ignore", RuntimeWarning)
        res = stats.ttest_ind(a, b, equal_var=False, trim=trim)
    (ma, va, _), (mb, vb, _) = _winsorized(a, trim), _winsorized(b, trim)
    na, nb = len(a), len(b)
    pooled = math.sqrt(((na - 1) * va + (nb - 1) * vb) / (na + nb - 2))
    d = winsorized_scale(trim) * (ma - mb) / pooled if pooled > 0 else math.nan
    return "yuen", float(res.statistic), float(res.pvalue), d, "robust_d"


def compare_trimmed_differences(
    a: NDArray[np.float64], b: NDArray[np.float64], trim: float = YUEN_TRIM
) -> tuple[str, float, float, float, str]:
    """The paired differences' trimmed mean against 0 (Tukey & McLaughlin 1963): the
    differences are trimmed, not each condition; squared standard error (n - 1) s_w^2 /
    (h (h - 1)) as in Yuen's test (s_w^2 the winsorized variance, h the values kept), h - 1
    degrees of freedom; effect: the robust d_z."""
    d = a - b
    mean, var_w, h = _winsorized(d, trim)
    if var_w == 0:  # as scipy's Yuen: a difference without spread is certain, none is no p
        t = math.copysign(math.inf, mean) if mean != 0 else math.nan
        return "trimmed_paired", t, 0.0 if mean != 0 else math.nan, math.nan, "robust_dz"
    t = mean / math.sqrt((len(d) - 1) * var_w / (h * (h - 1)))
    p = 2.0 * float(stats.t.sf(abs(t), h - 1))
    dz = winsorized_scale(trim) * mean / math.sqrt(var_w)
    return "trimmed_paired", t, p, dz, "robust_dz"


def compare(
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    options: AnalysisOptions,
    normal: bool | None = None,
) -> tuple[str, float, float, float, str]:
    """(test, statistic, p, effect size, effect kind) of ``a`` against ``b`` by ``options``'
    method; paired (a[i] with b[i]) if ``options.paired``. ``normal``: whether both groups
    passed Lilliefors, where the caller knows (independent groups)."""
    if options.method == "yuen":
        return (compare_trimmed_differences if options.paired else compare_yuen)(a, b)
    if options.paired:
        return compare_paired(a, b, bool(normality(a - b, options.alpha)[2]))
    if normal is None:
        normal = normality(a, options.alpha)[2] and normality(b, options.alpha)[2]
    return compare_independent(a, b, bool(normal))


def untested(subset: str, measure: str, a: str, b: str, n_a: int, n_b: int, why: str) -> TestResult:
    """A row for a comparison that could not run: empty test, statistic and p, and the reason."""
    return TestResult(
        subset, measure, a, b, "", n_a, n_b, math.nan, math.nan, math.nan, "", "", why
    )


def tested(
    subset: str,
    measure: str,
    a_name: str,
    b_name: str,
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    result: tuple[str, float, float, float, str],
    options: AnalysisOptions,
) -> TestResult:
    """The row of a comparison that ran: ``result`` from :func:`compare` of ``a`` and ``b``."""
    name, stat, p, effect, kind = result
    note = "" if np.isfinite(p) else NO_SPREAD
    return TestResult(
        subset, measure, a_name, b_name, name, len(a), len(b), stat, p, effect, kind,
        stars(p, options.alpha), note,
    )  # fmt: skip


def pairwise(
    df: pd.DataFrame,
    value: str,
    group_col: str,
    groups: Sequence[str],
    subset: str,
    options: AnalysisOptions,
    measure: str | None = None,
) -> tuple[list[TestResult], list[NormalityResult]]:
    """All pairwise comparisons of ``value`` between ``groups`` of ``group_col``, by
    :func:`compare`.

    ``df`` must already have lost its extremes for the thesis's method. Paired tests pair rows
    by participant.
    """
    measure = measure or value
    present = dict(iter(df.dropna(subset=[value]).groupby(group_col, sort=False)))
    data = {g: present.get(g, df.iloc[0:0]) for g in groups}
    norm_rows = []
    normal: dict[str, bool | None] = {}
    for g in groups:
        stat, p, is_normal = normality(data[g][value].to_numpy(), options.alpha)
        normal[g] = is_normal
        note = (
            ""
            if is_normal is not None
            else f"n={len(data[g])} is too few for Lilliefors (need {MIN_NORMALITY_N})"
        )
        norm_rows.append(
            NormalityResult(subset, measure, g, len(data[g]), stat, p, is_normal, note)
        )
    rows: list[TestResult] = []
    for ga, gb in itertools.combinations(groups, 2):
        a_df, b_df = data[ga], data[gb]
        if options.paired:
            both = a_df.merge(b_df, on="participant", suffixes=("_a", "_b"))
            a, b = both[f"{value}_a"].to_numpy(), both[f"{value}_b"].to_numpy()
            short = f"too few pairs ({len(a)}, need {MIN_TEST_N})"
        else:
            a, b = a_df[value].to_numpy(), b_df[value].to_numpy()
            short = f"too few values ({len(a)} and {len(b)}, need {MIN_TEST_N} each)"
        if min(len(a), len(b)) < MIN_TEST_N:
            rows.append(untested(subset, measure, ga, gb, len(a), len(b), short))
            continue
        both_normal = bool(normal[ga] and normal[gb])
        rows.append(
            tested(subset, measure, ga, gb, a, b, compare(a, b, options, both_normal), options)
        )
    if options.holm:
        rows = holm(rows, options.alpha)
    return rows, norm_rows


def holm_test(p_values: Sequence[float], alpha: float = 0.05) -> tuple[NDArray, NDArray]:
    """Holm's step-down test of one family (statsmodels' ``multipletests``): which p-values
    reject at family-wise ``alpha``, and the adjusted p-values."""
    # statsmodels' Holm ends with a full garbage collection (0.15: half of an analysis's time);
    # frozen, the objects that exist already are not walked again. Not where a caller froze
    # objects of its own: unfreezing would release theirs too.
    freeze = gc.get_freeze_count() == 0
    if freeze:
        gc.freeze()
    try:
        reject, adjusted, _, _ = multipletests(p_values, alpha=alpha, method="holm")
    finally:
        if freeze:
            gc.unfreeze()
    return reject, adjusted


def holm(rows: list[TestResult], alpha: float = 0.05) -> list[TestResult]:
    """Holm-adjust the p-values of one family of tests (rows without p stay as they are)."""
    idx = [i for i, r in enumerate(rows) if np.isfinite(r.p_value)]
    if not idx:
        return rows
    adjusted = holm_test([rows[i].p_value for i in idx], alpha)[1]
    out = list(rows)
    for i, p in zip(idx, adjusted, strict=True):
        r = asdict(rows[i]) | {
            "p_value": float(p),
            "stars": stars(float(p), alpha),
            "note": "Holm-adjusted",
        }
        out[i] = TestResult(**r)
    return out


def mean_interval(values: NDArray[np.float64] | Sequence[float]) -> tuple[float, float, float]:
    """The mean of ``values`` and its 95 % t-interval (two values or more)."""
    mean = float(np.mean(values))
    half = float(stats.t.ppf(0.975, len(values) - 1) * stats.sem(values))
    return mean, mean - half, mean + half
