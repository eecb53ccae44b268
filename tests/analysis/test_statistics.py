"""Statistics against scipy/statsmodels directly and against closed-form values."""

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats
from statsmodels.stats.diagnostic import lilliefors

from arteleop.analysis import (
    AnalysisOptions,
    cohens_d,
    compare_independent,
    compare_paired,
    holm,
    normality,
    order_effect,
    pairwise,
    stars,
    trim_extremes,
)
from arteleop.analysis.errors import AnalysisInputError
from arteleop.analysis.statistics import (
    TestResult,
    compare_trimmed_differences,
    compare_yuen,
    winsorized_scale,
)


def test_trimming_drops_the_max_and_min_participant_per_group() -> None:
    df = pd.DataFrame(
        {
            "participant": list("abcdeabcde"),
            "modality": ["x"] * 5 + ["y"] * 5,
            "v": [5, 1, 3, 9, 4, 2, 8, 6, 7, 0],
        }
    )
    kept = trim_extremes(df, "v", ["modality"])
    assert sorted(kept[kept.modality == "x"].participant) == ["a", "c", "e"]  # 9 (d) and 1 (b) out
    assert sorted(kept[kept.modality == "y"].participant) == ["a", "c", "d"]  # 8 (b) and 0 (e) out


def test_normality_is_statsmodels_lilliefors() -> None:
    x = np.random.default_rng(0).normal(size=20)
    stat, p, normal = normality(x)
    assert (stat, p) == pytest.approx(lilliefors(x, dist="norm", pvalmethod="table"))
    assert normal is True
    assert normality(np.array([1.0, 2.0, 3.0]))[2] is None  # too few for the table


def test_student_t_when_normal() -> None:
    a, b = np.array([1.0, 2.0, 3.0, 4.0, 5.0]), np.array([3.0, 4.0, 5.0, 6.0, 7.0])
    name, stat, p, d, kind = compare_independent(a, b, normal=True)
    ref = stats.ttest_ind(a, b)
    assert (name, kind) == ("ttest", "cohen_d")
    assert (stat, p) == pytest.approx((ref.statistic, ref.pvalue))
    assert d == pytest.approx(-2.0 / math.sqrt(2.5))  # mean difference / pooled SD
    assert cohens_d(a, b) == pytest.approx(d)


def test_mann_whitney_uses_the_continuity_corrected_normal_approximation() -> None:
    a = np.array([1.1, 2.3, 2.9, 4.2, 5.0, 6.1, 7.4, 8.8, 9.3, 10.5])
    b = np.array([3.2, 4.4, 5.9, 6.6, 7.9, 8.1, 9.9, 11.2, 12.7, 13.3])
    name, u, p, r, kind = compare_independent(a, b, normal=False)
    n1, n2 = len(a), len(b)
    u_ref = sum((x > y) + 0.5 * (x == y) for x in a for y in b)
    z = (u_ref - n1 * n2 / 2 + 0.5) / math.sqrt(n1 * n2 * (n1 + n2 + 1) / 12)  # no ties
    assert (name, kind) == ("mannwhitneyu", "rank_biserial")
    assert u == u_ref
    assert p == pytest.approx(2 * stats.norm.sf(abs(z)))
    assert r == pytest.approx(2 * u_ref / (n1 * n2) - 1)
    # MATLAB's ranksum reports the rank sum W of sample a: W = U + n1 (n1 + 1) / 2.
    assert stats.rankdata(np.concatenate([a, b]))[:n1].sum() == pytest.approx(u + n1 * (n1 + 1) / 2)


def test_fully_separated_samples_have_rank_biserial_one() -> None:
    _, _, _, r, _ = compare_independent(np.arange(10.0) + 100, np.arange(10.0), normal=False)
    assert r == 1.0


def test_paired_tests() -> None:
    rng = np.random.default_rng(1)
    a = rng.normal(10, 1, 12)
    b = a - 0.5 + rng.normal(0, 0.2, 12)
    name, t, p, dz, _ = compare_paired(a, b, normal=True)
    ref = stats.ttest_rel(a, b)
    assert name == "paired_ttest" and (t, p) == pytest.approx((ref.statistic, ref.pvalue))
    assert dz == pytest.approx(np.mean(a - b) / np.std(a - b, ddof=1))
    name, _, _, r, kind = compare_paired(a + 5, a, normal=False)
    assert (name, kind, r) == ("wilcoxon", "rank_biserial", 1.0)  # every difference positive


def test_holm_matches_hand_computation() -> None:
    rows = [
        TestResult("all", "m", "a", "b", "ttest", 5, 5, 0.0, p, 0.0, "", stars(p))
        for p in (0.01, 0.04, 0.03)
    ]
    rows.append(
        TestResult("all", "m", "a", "c", "", 1, 1, math.nan, math.nan, math.nan, "", "", "too few")
    )
    out = holm(rows)
    # Sorted 0.01, 0.03, 0.04 -> 3 * 0.01, max(2 * 0.03, 0.03), max(1 * 0.04, 0.06).
    assert [r.p_value for r in out[:3]] == pytest.approx([0.03, 0.06, 0.06])
    assert [r.stars for r in out[:3]] == ["*", "", ""]
    assert math.isnan(out[3].p_value)


def test_anova_matches_sums_of_squares() -> None:
    df = pd.DataFrame({"position": [1, 1, 1, 2, 2, 2, 3, 3, 3], "v": [1.0, 2, 3, 2, 3, 4, 6, 7, 8]})
    row, summary = order_effect(df, "v")
    # Group means 2, 3, 7; grand mean 4; SSB = 3 * (4 + 1 + 9) = 42, SSW = 6; F = (42/2) / (6/6).
    assert row.statistic == pytest.approx(21.0)
    assert row.p_value == pytest.approx(stats.f.sf(21.0, 2, 6))
    assert summary["eta_squared"] == pytest.approx(42 / 48)


def test_too_few_values_give_an_empty_p_and_a_reason() -> None:
    df = pd.DataFrame(
        {
            "participant": ["a", "b", "c", "d"],
            "modality": ["none", "none", "full", "full"],
            "v": [1.0, 2.0, 3.0, 4.0],
        }
    )
    rows, _ = pairwise(df, "v", "modality", ("none", "full"), "all", AnalysisOptions())
    assert math.isnan(rows[0].p_value)
    assert rows[0].note == "too few values (2 and 2, need 3 each)"


@pytest.mark.parametrize(
    ("p", "expected"), [(0.0099, "**"), (0.01, "*"), (0.05, "*"), (0.0501, ""), (math.nan, "")]
)
def test_stars(p: float, expected: str) -> None:
    assert stars(p) == expected


def test_the_trimmed_differences_test_by_hand() -> None:
    """d = 1..9, 30: 20 % of 10 is 2 from each end; trimmed mean of 3..8 = 5.5; winsorized
    3,3,3,4,5,6,7,8,8,8: sum of squares 42.5, so s_w^2 = 42.5 / 9; h = 6:
    SE^2 = 9 s_w^2 / (6 x 5) = 42.5 / 30, t = 5.5 / sqrt(42.5 / 30) on 5 degrees of freedom."""
    d = np.array([1.0, 2, 3, 4, 5, 6, 7, 8, 9, 30])
    name, t, p, dz, kind = compare_trimmed_differences(d + 2.0, np.full(10, 2.0))
    assert (name, kind) == ("trimmed_paired", "robust_dz")
    assert t == pytest.approx(5.5 / math.sqrt(42.5 / 30))
    assert p == pytest.approx(2 * stats.t.sf(5.5 / math.sqrt(42.5 / 30), 5))
    assert dz == pytest.approx(0.6419398 * 5.5 / math.sqrt(42.5 / 9), rel=1e-6)
    # The outlier 30 weighs as an 8: the plain paired t-test is much weaker here.
    assert p < stats.ttest_1samp(d, 0.0).pvalue / 2


def test_yuens_test_is_scipys_with_the_robust_d() -> None:
    a = np.array([1.0, 2, 3, 4, 5, 6, 7, 8, 9, 30])
    b = np.array([4.0, 5, 6, 7, 8, 9, 10, 11, 12, 13])
    name, t, p, d, kind = compare_yuen(a, b)
    ref = stats.ttest_ind(a, b, equal_var=False, trim=0.2)
    assert (name, kind) == ("yuen", "robust_d")
    assert (t, p) == pytest.approx((ref.statistic, ref.pvalue))
    # Trimmed means 5.5 and 8.5; winsorized variances both 42.5 / 9 (b: 6,6,6,7,...,11,11,11).
    assert d == pytest.approx(0.6419398 * -3.0 / math.sqrt((42.5 + 42.5) / 18), rel=1e-6)


def test_the_robust_d_scale_is_algina_keselman_penfields() -> None:
    assert winsorized_scale(0.2) == pytest.approx(0.642, abs=5e-4)  # their published constant
    x = stats.norm.ppf((np.arange(200_000) + 0.5) / 200_000)  # a unit normal, by its quantiles
    w = np.clip(x, *np.quantile(x, [0.1, 0.9]))
    assert winsorized_scale(0.1) == pytest.approx(w.std(), rel=1e-3)


@pytest.mark.parametrize(
    ("method", "paired", "message"),
    [
        ("trimmed", False, "method 'trimmed': expected one of untrimmed, yuen, thesis"),
        ("thesis", True, "method 'thesis' compares modalities as independent groups, as the "
                         "thesis did; paired tests go with method 'untrimmed' or 'yuen'"),
    ],
)  # fmt: skip
def test_a_method_that_does_not_exist_is_refused(method: str, paired: bool, message: str) -> None:
    with pytest.raises(AnalysisInputError) as err:
        AnalysisOptions(method=method, paired=paired)
    assert str(err.value) == message


def test_values_that_do_not_vary_after_trimming_get_no_p_and_say_why() -> None:
    df = pd.DataFrame({"participant": list("abcdeabcde"), "modality": ["none"] * 5 + ["full"] * 5,
                       "v": [1.0, 1, 1, 1, 9, 1, 1, 1, 1, 2]})  # fmt: skip
    (row,), _ = pairwise(df, "v", "modality", ("none", "full"), "all",
                         AnalysisOptions(method="yuen"))  # fmt: skip
    assert (row.test, row.stars) == ("yuen", "") and math.isnan(row.p_value)
    assert row.note == "no p: the values compared do not vary (after trimming)"


@pytest.mark.parametrize(("shift", "want_p"), [(1.0, 0.0), (0.0, math.nan)])
def test_differences_without_spread_are_certain_or_untestable_as_in_yuens(
    shift: float, want_p: float
) -> None:
    # Every participant 1 slower: Yuen's test (scipy's) says p 0 for a like difference between
    # groups; the paired test and its vectorised copy in the power engine must agree with it.
    from arteleop.analysis.resampled_tests import trimmed_paired_p

    a = np.array([3.0, 5, 8, 9, 14])
    _, _, p, _, _ = compare_trimmed_differences(a + shift, a)
    assert p == pytest.approx(want_p, nan_ok=True)
    assert trimmed_paired_p((a + shift)[None, :], a[None, :])[0] == pytest.approx(
        want_p, nan_ok=True
    )
    groups = stats.ttest_ind(np.ones(5) + shift, np.ones(5), equal_var=False, trim=0.2).pvalue
    assert groups == pytest.approx(want_p, nan_ok=True)
