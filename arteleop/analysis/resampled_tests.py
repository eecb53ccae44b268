"""The tests of ``arteleop analyze``, run on many resampled studies at once: each row of an
array is one study's values (NaN: none), and every function returns one result per row, equal
to what :mod:`arteleop.analysis.statistics` gives that row. Rows with the same number of values
are tested together by scipy's own functions (``axis=1``)."""

from __future__ import annotations

import warnings

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from arteleop.analysis.statistics import MIN_NORMALITY_N, MIN_TEST_N, YUEN_TRIM

Array = NDArray[np.float64]


def _compact(x: Array) -> dict[int, tuple[NDArray[np.intp], Array]]:
    """Rows of ``x`` grouped by how many values (not NaN) they hold: count -> (row indices,
    those rows' values, sorted ascending, NaN dropped)."""
    counts = np.sum(~np.isnan(x), axis=1)
    ordered = np.sort(x, axis=1)  # NaN last
    return {int(k): (rows := np.flatnonzero(counts == k), ordered[rows, :k])
            for k in np.unique(counts)}  # fmt: skip


def lilliefors_normal(x: Array, alpha: float) -> NDArray[np.bool_]:
    """Per row, whether Lilliefors' test (statsmodels' table) keeps normality at ``alpha``, as
    :func:`~arteleop.analysis.statistics.normality` decides; False where it cannot be run (fewer
    than 4 values, or all equal)."""
    from statsmodels.stats._lilliefors import get_lilliefors_table

    table = get_lilliefors_table(dist="norm")
    normal = np.zeros(len(x), dtype=bool)
    for k, (rows, v) in _compact(x).items():
        if k < MIN_NORMALITY_N:
            continue
        spread = np.ptp(v, axis=1) > 0
        rows, v = rows[spread], v[spread]
        if not len(rows):
            continue
        z = (v - v.mean(axis=1, keepdims=True)) / v.std(axis=1, ddof=1, keepdims=True)
        cdf = stats.norm.cdf(z)
        i = np.arange(1, k + 1)
        d = np.maximum((i / k - cdf).max(axis=1), (cdf - (i - 1) / k).max(axis=1))
        normal[rows] = np.asarray(table.prob(d, k), dtype=np.float64) > alpha
    return normal


def trim(x: Array) -> Array:
    """Per row, the largest and the smallest value set aside (NaN), as
    :func:`~arteleop.analysis.statistics.trim_extremes` does; rows of 2 values or fewer lose
    all."""
    out = x.copy()
    counts = np.sum(~np.isnan(x), axis=1)
    order = np.argsort(np.where(np.isnan(x), np.inf, x), axis=1, kind="stable")
    rows = np.arange(len(x))
    out[rows, order[:, 0]] = np.nan
    out[rows, order[rows, np.maximum(counts - 1, 0)]] = np.nan
    out[counts <= 2] = np.nan
    return out


def paired_p(a: Array, b: Array, alpha: float) -> Array:
    """Per row, the p of :func:`~arteleop.analysis.statistics.compare_paired` on the pairs
    of ``a`` and ``b`` (rows, n; NaN: no value): the paired t-test where the differences pass
    Lilliefors, else Wilcoxon's signed-rank test; NaN with fewer than 3 pairs."""
    d = a - b
    k = np.sum(~np.isnan(d), axis=1)
    p = np.full(len(d), np.nan)
    normal = lilliefors_normal(d, alpha)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nansum(d, axis=1) / k
        sd = np.sqrt(np.nansum((d - mean[:, None]) ** 2, axis=1) / (k - 1))
        t = mean / (sd / np.sqrt(k))
    tested = k >= MIN_TEST_N
    use_t = tested & normal
    p[use_t] = 2 * stats.t.sf(np.abs(t[use_t]), k[use_t] - 1)
    rank = tested & ~normal
    if rank.any():
        # Missing pairs count as zero differences, which Wilcoxon's own method drops.
        with np.errstate(invalid="ignore", divide="ignore"):  # all-zero rows: p is NaN
            res = stats.wilcoxon(np.nan_to_num(d[rank]), axis=1, zero_method="wilcox",
                                 correction=True, method="approx")  # fmt: skip
        p[rank] = res.pvalue
    return p


def independent_p(a: Array, b: Array, alpha: float) -> Array:
    """Per row, the p of :func:`~arteleop.analysis.statistics.compare_independent`: Student's
    t-test where both groups pass Lilliefors, else Mann-Whitney's U (asymptotic, continuity
    corrected); NaN with fewer than 3 values in a group."""
    ka, kb = np.sum(~np.isnan(a), axis=1), np.sum(~np.isnan(b), axis=1)
    p = np.full(len(a), np.nan)
    normal = lilliefors_normal(a, alpha) & lilliefors_normal(b, alpha)
    tested = (ka >= MIN_TEST_N) & (kb >= MIN_TEST_N)
    with np.errstate(invalid="ignore", divide="ignore"):
        ma, mb = np.nansum(a, axis=1) / ka, np.nansum(b, axis=1) / kb
        ssa = np.nansum((a - ma[:, None]) ** 2, axis=1)
        ssb = np.nansum((b - mb[:, None]) ** 2, axis=1)
        df = ka + kb - 2
        t = (ma - mb) / np.sqrt((ssa + ssb) / df * (1 / ka + 1 / kb))
    use_t = tested & normal
    p[use_t] = 2 * stats.t.sf(np.abs(t[use_t]), df[use_t])
    rank = np.flatnonzero(tested & ~normal)
    for (na, nb), group in _by_counts(rank, ka[rank], kb[rank]).items():
        va, vb = np.sort(a[group], axis=1)[:, :na], np.sort(b[group], axis=1)[:, :nb]
        res = stats.mannwhitneyu(va, vb, axis=1, alternative="two-sided",
                                 method="asymptotic", use_continuity=True)  # fmt: skip
        p[group] = res.pvalue
    return p


def yuen_p(a: Array, b: Array) -> Array:
    """Per row, the p of :func:`~arteleop.analysis.statistics.compare_yuen` (scipy's trimmed
    ``ttest_ind``); NaN with fewer than 3 values in a group."""
    ka, kb = np.sum(~np.isnan(a), axis=1), np.sum(~np.isnan(b), axis=1)
    p = np.full(len(a), np.nan)
    tested = np.flatnonzero((ka >= MIN_TEST_N) & (kb >= MIN_TEST_N))
    for (na, nb), group in _by_counts(tested, ka[tested], kb[tested]).items():
        va, vb = np.sort(a[group], axis=1)[:, :na], np.sort(b[group], axis=1)[:, :nb]
        with warnings.catch_warnings():  # no spread left after trimming: p is NaN
            warnings.simplefilter("ignore", RuntimeWarning)
            p[group] = stats.ttest_ind(va, vb, axis=1, equal_var=False, trim=YUEN_TRIM).pvalue
    return p


def trimmed_paired_p(a: Array, b: Array) -> Array:
    """Per row, the p of :func:`~arteleop.analysis.statistics.compare_trimmed_differences`:
    the paired differences' 20 % trimmed mean against 0; NaN with fewer than 3 pairs."""
    p = np.full(len(a), np.nan)
    for k, (rows, d) in _compact(a - b).items():
        if k < MIN_TEST_N:
            continue
        g = int(k * YUEN_TRIM)
        h = k - 2 * g
        mean = d[:, g : k - g].mean(axis=1)
        w = np.clip(d, d[:, [g]], d[:, [k - g - 1]])
        var_w = w.var(axis=1, ddof=1)
        with np.errstate(invalid="ignore", divide="ignore"):  # no spread: t is +-inf or NaN
            t = mean / np.sqrt((k - 1) * var_w / (h * (h - 1)))
        p[rows] = 2 * stats.t.sf(np.abs(t), h - 1)  # p 0 at +-inf, NaN at 0/0, as in analyse
    return p


def _by_counts(rows: NDArray[np.intp], ka: NDArray, kb: NDArray) -> dict[tuple, NDArray]:
    keys = list(zip(ka.tolist(), kb.tolist(), strict=True))
    out: dict[tuple, list[int]] = {}
    for row, key in zip(rows.tolist(), keys, strict=True):
        out.setdefault(key, []).append(row)
    return {key: np.array(group) for key, group in out.items()}


def holm_reject(p: Array, alpha: float) -> NDArray[np.bool_]:
    """Holm's step-down test over the columns of ``p`` (rows, tests), row by row: which tests
    reject at family-wise ``alpha``; a NaN p neither rejects nor counts."""
    m = np.sum(~np.isnan(p), axis=1, keepdims=True)
    order = np.argsort(np.where(np.isnan(p), np.inf, p), axis=1)
    ranked = np.take_along_axis(p, order, axis=1)
    steps = np.arange(p.shape[1])[None, :]
    with np.errstate(invalid="ignore", divide="ignore"):
        passes = ranked <= alpha / (m - steps)
    passes &= ~np.isnan(ranked)
    kept = np.cumprod(passes, axis=1).astype(bool)  # step down: stop at the first failure
    reject = np.zeros_like(kept)
    np.put_along_axis(reject, order, kept, axis=1)
    return reject


def rm_anova_p(y: Array) -> dict[str, Array]:
    """The two-way repeated-measures ANOVA's p per effect, for each row of ``y`` (rows,
    participants, a, b); participants with a NaN cell are left out, as ``AnovaRM`` needs (the
    analysis does the same); NaN with fewer than 2 complete participants."""
    complete = ~np.isnan(y).any(axis=(2, 3))
    counts = complete.sum(axis=1)
    out = {e: np.full(len(y), np.nan) for e in ("cue", "delay", "cue x delay")}
    _, _, a, b = y.shape
    for n in np.unique(counts):
        if n < 2:
            continue
        rows = np.flatnonzero(counts == n)
        v = np.stack([y[r][complete[r]] for r in rows])  # (rows, n, a, b)
        m = v.mean(axis=(1, 2, 3), keepdims=True)
        ms, ma, mb = v.mean(axis=(2, 3), keepdims=True), v.mean(axis=(1, 3), keepdims=True), \
            v.mean(axis=(1, 2), keepdims=True)  # fmt: skip
        msa, msb, mab = v.mean(axis=3, keepdims=True), v.mean(axis=2, keepdims=True), \
            v.mean(axis=1, keepdims=True)  # fmt: skip
        ss = {
            "cue": n * b * ((ma - m) ** 2).sum(axis=(1, 2, 3)),
            "cue_err": b * ((msa - ms - ma + m) ** 2).sum(axis=(1, 2, 3)),
            "delay": n * a * ((mb - m) ** 2).sum(axis=(1, 2, 3)),
            "delay_err": a * ((msb - ms - mb + m) ** 2).sum(axis=(1, 2, 3)),
            "cue x delay": n * ((mab - ma - mb + m) ** 2).sum(axis=(1, 2, 3)),
            "cue x delay_err": ((v - mab - msa - msb + ma + mb + ms - m) ** 2).sum(axis=(1, 2, 3)),
        }
        dfs = {"cue": (a - 1,), "delay": (b - 1,), "cue x delay": (a - 1, b - 1)}
        for effect, parts in dfs.items():
            df1 = float(np.prod(parts))
            df2 = df1 * (n - 1)
            with np.errstate(invalid="ignore", divide="ignore"):
                f = (ss[effect] / df1) / (ss[f"{effect}_err"] / df2)
            out[effect][rows] = stats.f.sf(f, df1, df2)
    return out
