"""The statistics at their stated error rate (issue 63): on data with no effect the default
analysis and the power engine reject a true null at alpha, Holm keeps the power engine's
family-wise rate at most alpha, and the power of a known effect is the analytic one from
n = 8 up. The thesis's procedure is checked to reject about twice as often, as its reports
say. (The power engine's tests are ``analyze``'s own, row by row: test_power.py.)"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from statsmodels.stats.power import TTestIndPower, TTestPower

from arteleop.analysis import analyse, load_study
from arteleop.analysis.data import MODALITIES
from arteleop.analysis.power import Pool, PowerOptions, make_pool, power, wilson
from arteleop.analysis.resampled_tests import (
    holm_reject,
    independent_p,
    paired_p,
    trimmed_paired_p,
    yuen_p,
)
from tests.analysis.make_study import make_run

ALPHA = 0.05
DATASETS = 150
"""Null datasets through ``analyse``, each of one pair of modalities, so that their tests are
independent: 300 tests (about 0.05 s a dataset)."""
POOL = 400
NULL_POOL = 4000
MEASURES = ("completion_time_s", "placement_error_m")
LOG_SD = {"completion_time_s": 0.3, "placement_error_m": 0.6}
"""Spread of log time and log error, about a default study's: times mildly skewed, errors
strongly."""


def _lognormal(rng: np.random.Generator, size: int) -> dict[str, np.ndarray]:
    return {m: np.exp(rng.normal(0.0, sd, size)) for m, sd in LOG_SD.items()}


# Through analyse: fresh null datasets ---------------------------------------------------------


@pytest.fixture(scope="module")
def null_tests(tmp_path_factory: pytest.TempPathFactory) -> pd.DataFrame:
    """The comparison of none with full by ``analyse`` (default options) in ``DATASETS``
    pilot studies of 8 participants (where the thesis's trimming errs most) whose every
    trial's time and error come from one distribution."""
    folder = make_run(tmp_path_factory.mktemp("null"), n=8, trajectories=False)
    template = load_study(folder)
    trials = template.trials[template.trials["modality"].isin(["none", "full"])]
    trials = trials.assign(outcome="success")
    rng = np.random.default_rng(63)
    out = []
    for k in range(DATASETS):
        study = type(template)(trials.assign(**_lognormal(rng, len(trials))), None, None,
                               template.base_dir, template.trials_path)  # fmt: skip
        tests = analyse(study).tests
        out.append(tests[tests["test"].isin(["ttest", "mannwhitneyu"])].assign(dataset=k))
    return pd.concat(out, ignore_index=True)


def test_the_default_analysis_rejects_a_true_null_at_alpha(null_tests: pd.DataFrame) -> None:
    """None against full rejects in 5 % of the null datasets' time and error tests, within
    three binomial standard errors (the thesis's procedure: 0.113 on these data); every
    participant is tested."""
    assert len(null_tests) == 2 * DATASETS and (null_tests["n_a"] == 8).all()
    rate = (null_tests["p_value"] <= ALPHA).mean()
    assert abs(rate - ALPHA) <= 3 * math.sqrt(ALPHA * (1 - ALPHA) / len(null_tests)), rate


# Through the power engine: resampling a pool without an effect --------------------------------


@pytest.fixture(scope="module")
def null_pool() -> Pool:
    """``NULL_POOL`` participants; every modality's values are the same values shuffled, so the
    pool holds no difference between modalities, and so many that the chance correlation of
    two shuffles (SD 1 / sqrt(NULL_POOL)) and the repeats of resampling with replacement move
    no rate visibly."""
    rng = np.random.default_rng(64)
    values = {m: np.column_stack([v[rng.permutation(NULL_POOL)] for _ in MODALITIES])
              for m, v in _lognormal(rng, NULL_POOL).items()}  # fmt: skip
    people = tuple(f"P{k:04d}" for k in range(NULL_POOL))
    return Pool(people, MODALITIES, ("0ms",) * len(MODALITIES), values)


ROBUST = [("untrimmed", False), ("untrimmed", True), ("yuen", False), ("yuen", True)]


@pytest.mark.parametrize(("method", "paired"), ROBUST)
def test_the_power_engine_rejects_a_true_null_at_alpha(null_pool: Pool, method: str, paired: bool):
    """At n = 8 and 20, each comparison with none rejects at alpha: the times' rate within its
    99.99 % Wilson interval (sixteen checks a test: all pass by chance 99.8 % of the time);
    the strongly skewed errors' never above it (Yuen's test is a little conservative there at
    n = 8)."""
    options = PowerOptions(sizes=(8, 20), resamples=2000, method=method, paired=paired)
    table = pd.concat(power(null_pool, options), ignore_index=True)
    low, high = wilson(table["rejections"].to_numpy(), 2000, confidence=0.9999)
    times = (table["measure"] == "completion_time_s").to_numpy()
    assert ((low <= ALPHA) & (ALPHA <= high))[times].all(), table[times]
    assert (low <= ALPHA)[~times].all(), table[~times]


@pytest.mark.parametrize(("method", "paired"), ROBUST)
def test_holm_keeps_the_power_engines_family_wise_rate(null_pool: Pool, method: str, paired: bool):
    """The ten pairs of one measure as one family, Holm-corrected: any rejection in at most
    alpha of 3,000 resampled studies of 12 (the Wilson interval's lower end)."""
    test = {("untrimmed", False): lambda a, b: independent_p(a, b, ALPHA),
            ("untrimmed", True): lambda a, b: paired_p(a, b, ALPHA),
            ("yuen", False): yuen_p,
            ("yuen", True): trimmed_paired_p}[(method, paired)]  # fmt: skip
    picks = np.random.default_rng(65).integers(0, NULL_POOL, size=(3000, 12))
    for measure in MEASURES:
        values = null_pool.values[measure][picks]
        p = np.column_stack([test(values[:, :, i], values[:, :, j])
                             for i in range(5) for j in range(i + 1, 5)])  # fmt: skip
        any_rejection = holm_reject(p, ALPHA).any(axis=1)
        low, _ = wilson(np.array(any_rejection.sum()), 3000)
        assert low <= ALPHA, (measure, any_rejection.mean())


def test_the_thesis_procedure_rejects_about_twice_as_often(null_pool: Pool) -> None:
    """What the thesis method's reports say of it: on data with no effect, 8-12 % of its tests
    reject at p <= 0.05 at 8 to 20 participants (the values left after dropping the extremes
    spread less than the sample)."""
    options = PowerOptions(sizes=(8, 20), resamples=2000, method="thesis")
    table = pd.concat(power(null_pool, options), ignore_index=True)
    rate = table.groupby("n")["rejections"].sum() / table.groupby("n")["resamples"].sum()
    assert rate.between(0.08, 0.125).all(), rate


# A known effect: the analytic power ------------------------------------------------------------


def _effect_pool(tmp_path: Path, effect: float, paired: bool):
    """Times of ``POOL`` participants under none and full: full is none shifted by ``effect``
    (SD units of the pool) per participant, plus normal noise, with ``paired``; otherwise an
    independent normal sample of its own. Each column is standardised exactly, so resampling
    the pool draws from distributions whose effect size is ``effect``."""
    rng = np.random.default_rng(66)

    def unit(x: np.ndarray) -> np.ndarray:
        return (x - x.mean()) / x.std()

    none = unit(rng.normal(size=POOL))
    full = (none if paired else 0.0) + effect + unit(rng.normal(size=POOL))
    rows = [{"participant": f"P{k:03d}", "phase": "experimental", "modality": m,
             "position": i + 1, "outcome": "success", "completion_time_s": 40.0 + v[k],
             "placement_error_m": 0.01} for i, (m, v) in enumerate((("none", none),
             ("full", full))) for k in range(POOL)]  # fmt: skip
    pd.DataFrame(rows).to_csv(tmp_path / "trials.csv", index=False)
    return make_pool([load_study(tmp_path / "trials.csv")], ["effect"])


@pytest.mark.parametrize("paired", [False, True])
def test_a_known_effects_power_is_the_analytic_one(tmp_path: Path, paired: bool) -> None:
    """The default method's power at n = 8 and 20 is statsmodels' for the t-test (paired: on
    differences of unit SD; independent: groups of unit SD), within the 99.9 % Wilson interval
    of 4,000 resampled studies."""
    effect = 0.6 if paired else 1.0
    pool = _effect_pool(tmp_path, -effect, paired)
    options = PowerOptions(sizes=(8, 20), resamples=4000, paired=paired)
    table = pd.concat(power(pool, options), ignore_index=True)
    table = table[table["measure"] == "completion_time_s"].set_index("n")
    for n in (8, 20):
        if paired:
            analytic = TTestPower().power(effect_size=effect, nobs=n, alpha=ALPHA)
        else:
            analytic = TTestIndPower().power(effect_size=effect, nobs1=n, alpha=ALPHA)
        low, high = wilson(np.array(table.loc[n, "rejections"]), 4000, confidence=0.999)
        assert low <= analytic <= high, (n, table.loc[n, "power"], analytic)
