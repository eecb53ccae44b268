"""The statistics' error rates: how often each method rejects a true null, and the power
engine's power against the analytic value, side by side.

Null datasets are built on a run folder's plan: its experimental trials, participants and
orders kept, every successful trial's completion time and placement error drawn anew from one
log-normal distribution per measure (the run's own log-SD), so that no modality changes either.
Each goes through ``load_study`` and ``analyse`` under each method and option, as
``arteleop analyze`` runs them; printed: the share of the ten modality pairs with p <= 0.05 per
measure, and with ``--holm`` the share of families with any rejection. Then the power engine
(``arteleop study power``) on a pool of 400 participants without an effect, and with a known
paired effect (d_z 0.6) against statsmodels' analytic power.

    python benchmarks/bench_error_rates.py RUN_DIR [--datasets 200] [--seed 0]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd
from statsmodels.stats.power import TTestPower

from arteleop.analysis import AnalysisOptions, analyse, load_study
from arteleop.analysis.data import MODALITIES
from arteleop.analysis.power import PowerOptions, make_pool, power

MEASURES = ("completion_time_s", "placement_error_m")
OPTIONS = {
    "thesis": AnalysisOptions(method="thesis"),
    "thesis --holm": AnalysisOptions(method="thesis", holm=True),
    "untrimmed (default)": AnalysisOptions(),
    "untrimmed --paired": AnalysisOptions(paired=True),
    "untrimmed --holm": AnalysisOptions(holm=True),
    "yuen": AnalysisOptions(method="yuen"),
    "yuen --paired": AnalysisOptions(method="yuen", paired=True),
}


def null_trials(trials: pd.DataFrame, rng: np.random.Generator) -> pd.DataFrame:
    """The run's experimental trials with each success's time and error drawn anew."""
    out = trials.copy()
    ok = out["outcome"] == "success"
    for m in MEASURES:
        logs = np.log(trials.loc[ok, m])
        out.loc[ok, m] = np.exp(rng.normal(logs.mean(), logs.std(), ok.sum()))
    return out


def through_analyse(run: Path, datasets: int, seed: int) -> pd.DataFrame:
    study = load_study(run)
    trials = study.trials[study.trials["phase"] == "experimental"]
    trials = trials.drop(columns=[c for c in trials if c.endswith("_xy")])  # no smoothness
    rng = np.random.default_rng(seed)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(datasets):
            folder = Path(tmp) / f"d{k}"
            folder.mkdir()
            null_trials(trials, rng).to_csv(folder / "trials.csv", index=False)
            if study.participants is not None:
                study.participants.to_csv(folder / "participants.csv", index=False)
            data = load_study(folder)
            for name, options in OPTIONS.items():
                tests = analyse(data, options).tests
                tests = tests[(tests["subset"] == "all") & tests["measure"].isin(MEASURES)
                              & (tests["test"] != "anova")]  # fmt: skip
                for m, part in tests.groupby("measure"):
                    rejections = part["p_value"] <= 0.05
                    rows.append({"options": name, "measure": m, "dataset": k,
                                 "rate": rejections.mean(), "any": rejections.any()})  # fmt: skip
    table = pd.DataFrame(rows)
    summary = table.groupby(["options", "measure"], sort=False).agg(
        pair_rate=("rate", "mean"), family_rate=("any", "mean")
    )
    return summary.unstack("measure")


def through_the_engine(seed: int) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    values = np.exp(rng.normal(0.0, 0.3, 400))
    effect = rng.normal(size=400)
    effect = (effect - effect.mean()) / effect.std()
    rows = []
    for k in range(400):
        for position, modality in enumerate(("none", "task", "full"), start=1):
            time_s = values[k] * 20.0
            if modality == "task":
                time_s = values[rng.integers(400)] * 20.0  # none's distribution, shuffled
            if modality == "full":
                time_s += -0.6 + effect[k]  # d_z 0.6: differences of unit SD
            rows.append({"participant": f"P{k:03d}", "phase": "experimental",
                         "modality": modality, "position": position, "outcome": "success",
                         "completion_time_s": time_s, "placement_error_m": 0.01})  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp:
        pd.DataFrame(rows).to_csv(Path(tmp) / "trials.csv", index=False)
        pool = make_pool([load_study(Path(tmp) / "trials.csv")], ["pool"])
    out = []
    for name, method, paired in (("thesis", "thesis", False), ("untrimmed", "untrimmed", False),
                                 ("untrimmed --paired", "untrimmed", True),
                                 ("yuen --paired", "yuen", True)):  # fmt: skip
        options = PowerOptions(sizes=(8, 12, 20), resamples=2000, method=method, paired=paired)
        table = pd.concat(power(pool, options), ignore_index=True)
        table = table[table["measure"] == "completion_time_s"]
        for _, r in table.iterrows():
            out.append({"options": name, "comparison": r["comparison"], "n": r["n"],
                        "rejects": r["power"]})  # fmt: skip
    frame = pd.DataFrame(out).pivot_table(index=["comparison", "options"], columns="n",
                                          values="rejects", sort=False)  # fmt: skip
    analytic = {n: TTestPower().power(effect_size=0.6, nobs=n, alpha=0.05) for n in (8, 12, 20)}
    frame.loc[("full vs none", "analytic (paired t)"), :] = [analytic[n] for n in frame.columns]
    return frame


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path, help="a run folder whose plan the null data keep")
    parser.add_argument("--datasets", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    assert set(MODALITIES) >= set(load_study(args.run).trials["modality"])
    print(f"## {args.datasets} null datasets on the plan of {args.run}, through analyse\n")
    print("pair_rate: share of the ten modality pairs with p <= 0.05; family_rate: share of "
          "datasets with any pair at p <= 0.05 (with --holm: the family-wise rate)\n")  # fmt: skip
    print(through_analyse(args.run, args.datasets, args.seed).round(3).to_string())
    print("\n## The power engine: 2000 resampled studies of a pool of 400\n")
    print("task vs none: no effect (rate should be 0.05); full vs none: a paired effect of "
          "d_z 0.6 (power should be the analytic one)\n")  # fmt: skip
    print(through_the_engine(args.seed).round(3).to_string())


if __name__ == "__main__":
    main()
