"""Power by resampling: the vectorised tests are analyze's own, row by row; the same seed gives
the same files; bad input writes nothing. (Error rates and analytic power: test_error_rates.)"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from statsmodels.stats.anova import AnovaRM

from arteleop.analysis import load_study
from arteleop.analysis.power import PowerOptions, make_pool, power
from arteleop.analysis.resampled_tests import (
    holm_reject,
    independent_p,
    lilliefors_normal,
    paired_p,
    rm_anova_p,
    trim,
    trimmed_paired_p,
    yuen_p,
)
from arteleop.analysis.statistics import (
    compare_independent,
    compare_paired,
    compare_trimmed_differences,
    compare_yuen,
    holm_test,
    normality,
)
from arteleop.cli import main

RNG = np.random.default_rng(45)


def _rows(rows: int, n: int, ties: bool) -> np.ndarray:
    """Rows with NaNs (failed trials) and, with ``ties``, repeated values (resampled people)."""
    x = RNG.normal(10.0, 2.0, (rows, n))
    x[RNG.random((rows, n)) < 0.1] = np.nan
    if ties:
        x = np.round(x, 0)
    x[::7] = RNG.exponential(3.0, (len(x[::7]), n))  # some far from normal
    return x


@pytest.mark.parametrize("ties", [False, True])
def test_the_vectorised_tests_are_analyzes_own_row_by_row(ties: bool) -> None:
    a, b = _rows(300, 9, ties), _rows(300, 9, ties) + 0.8
    got_paired, got_independent = paired_p(a, b, 0.05), independent_p(a, b, 0.05)
    got_yuen, got_trimmed = yuen_p(a, b), trimmed_paired_p(a, b)
    normal = lilliefors_normal(a, 0.05)
    for r in range(len(a)):
        both = ~np.isnan(a[r]) & ~np.isnan(b[r])
        x, y = a[r][both], b[r][both]
        want = compare_paired(x, y, bool(normality(x - y)[2]))[2] if both.sum() >= 3 else np.nan
        assert got_paired[r] == pytest.approx(want, rel=1e-9, nan_ok=True), r
        want = compare_trimmed_differences(x, y)[2] if both.sum() >= 3 else np.nan
        assert got_trimmed[r] == pytest.approx(want, rel=1e-9, nan_ok=True), r
        xa, xb = a[r][~np.isnan(a[r])], b[r][~np.isnan(b[r])]
        both_normal = bool(normality(xa)[2] and normality(xb)[2])
        want = compare_independent(xa, xb, both_normal)[2]
        assert got_independent[r] == pytest.approx(want, rel=1e-9), r
        assert got_yuen[r] == pytest.approx(compare_yuen(xa, xb)[2], rel=1e-9, nan_ok=True), r
        assert normal[r] == bool(normality(xa)[2]), r


def test_trimming_and_holm_are_analyzes_own() -> None:
    from arteleop.analysis.statistics import trim_extremes

    x = _rows(50, 7, ties=True)
    got = trim(x)
    for r in range(len(x)):
        frame = pd.DataFrame({"v": x[r], "g": 0})
        kept = trim_extremes(frame, "v", ["g"]).index
        assert set(np.flatnonzero(~np.isnan(got[r]))) == set(kept), r
    p = RNG.uniform(0, 0.1, (40, 4))
    p[::5, 2] = np.nan
    reject = holm_reject(p, 0.05)
    for r in range(len(p)):
        ok = ~np.isnan(p[r])
        assert (reject[r][ok] == holm_test(p[r][ok], 0.05)[0]).all(), r  # statsmodels
        assert not reject[r][~ok].any()


def test_the_vectorised_anova_is_anovarms() -> None:
    y = RNG.normal(0, 1, (5, 8, 2, 3)) + np.array([0, 0.8])[:, None] + np.array([0, 0.3, 1])
    y[1, 2, 0, 1] = np.nan  # a participant without every cell: left out
    got = rm_anova_p(y)
    for r in range(len(y)):
        keep = ~np.isnan(y[r]).any(axis=(1, 2))
        rows = [{"s": s, "a": a, "b": b, "y": y[r, s, a, b]} for s in np.flatnonzero(keep)
                for a in range(2) for b in range(3)]  # fmt: skip
        table = AnovaRM(pd.DataFrame(rows), "y", "s", within=["a", "b"]).fit().anova_table
        for effect, term in (("cue", "a"), ("delay", "b"), ("cue x delay", "a:b")):
            assert got[effect][r] == pytest.approx(table.loc[term, "Pr > F"], rel=1e-9)


def _pool_folder(root: Path, effects: dict[str, float], people: int = 300) -> Path:
    """trials.csv of ``people`` participants, one trial per condition: the time of a condition
    is none's plus its effect (s) plus unit normal noise, so the paired differences are normal
    with effect size ``effect`` (d_z), centred exactly on it."""
    root.mkdir(parents=True)
    base = RNG.normal(40.0, 5.0, people)
    rows = []
    for cond, (name, effect) in enumerate({"none": 0.0, **effects}.items(), start=1):
        noise = RNG.normal(0.0, 1.0, people)
        noise = (noise - noise.mean()) / noise.std(ddof=1) if name != "none" else noise * 0
        for k in range(people):
            rows.append({"participant": f"P{k:03d}", "phase": "experimental",
                         "modality": name, "position": cond, "outcome": "success",
                         "completion_time_s": base[k] + effect + noise[k],
                         "placement_error_m": 0.01})  # fmt: skip
    pd.DataFrame(rows).to_csv(root / "trials.csv", index=False)
    return root


def _power(folder: Path, options: PowerOptions) -> pd.DataFrame:
    pool = make_pool([load_study(folder)], [str(folder)])
    table = pd.concat(power(pool, options), ignore_index=True)
    return table[table["measure"] == "completion_time_s"]


def test_with_holm_each_comparison_with_the_reference_is_reported(tmp_path: Path) -> None:
    effects = {"manipulation": 0.0, "embodiment": 0.0, "task": 0.0, "full": -2.0}
    folder = _pool_folder(tmp_path / "pool", effects, people=40)
    table = _power(folder, PowerOptions(sizes=(12,), resamples=200, paired=True, holm=True))
    assert set(table["comparison"]) == {f"{c} vs none" for c in effects}
    assert table.set_index("comparison").loc["full vs none", "power"] > 0.9


def test_the_same_seed_gives_the_same_files(tmp_path: Path, capsys) -> None:
    folder = _pool_folder(tmp_path / "pool", {"full": -0.5}, people=30)
    args = ["study", "power", str(folder), "--n", "5:15:5", "--resamples", "200", "--quiet"]
    assert main([*args, "--out", str(tmp_path / "a")]) == 0
    assert main([*args, "--out", str(tmp_path / "b")]) == 0
    for name in ("power.csv", "power.md"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    assert "pool: 30 participants from 1 source(s); 3 of 3 sizes x 200 resamples" in (
        capsys.readouterr().out
    )


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--n", "2:10:2"], "sample sizes [2, 4, 6, 8, 10]: each must be 3 or more (a test needs "
                            "3 values)."),
        (["--n", "ten"], "--n ten: give first:last:step (such as 8:40:4) or a list (such as "
                         "10,20,40) of whole numbers, 3 or more."),
        (["--alpha", "1.5"], "alpha = 1.5: expected a level between 0 and 1."),
        (["--compare", "wizard"], "compare 'wizard': no such condition in the pool; its "
                                  "conditions: none, full"),
    ],
)  # fmt: skip
def test_bad_input_is_refused_and_nothing_written(
    tmp_path: Path, capsys, extra: list[str], message: str
) -> None:
    folder = _pool_folder(tmp_path / "pool", {"full": -0.5}, people=10)
    out = tmp_path / "out"
    assert main(["study", "power", str(folder), "--out", str(out), *extra]) == 2
    assert capsys.readouterr().err == f"arteleop: error: {message}\n"
    assert not out.exists()


def test_a_pool_without_the_columns_the_tests_need_is_refused(tmp_path: Path, capsys) -> None:
    (tmp_path / "pool").mkdir()
    (tmp_path / "pool" / "trials.csv").write_text(
        "participant,phase,modality\nP01,experimental,none\n"
    )
    out = tmp_path / "out"
    assert main(["study", "power", str(tmp_path / "pool"), "--out", str(out)]) == 2
    assert "missing required column(s) position, outcome, completion_time_s" in (
        capsys.readouterr().err
    )
    assert not out.exists()


@pytest.mark.parametrize(("people", "said"), [(3, "3 participant(s)"), (0, "no participant")])
def test_a_pool_too_small_to_resample_is_refused(
    tmp_path: Path, capsys, people: int, said: str
) -> None:
    # One participant read as power 1.000 at every n; no success wrote empty files.
    folder = _pool_folder(tmp_path / "pool", {"full": -0.5}, people=5)
    trials = pd.read_csv(folder / "trials.csv")
    trials.loc[trials["participant"] >= f"P{people:03d}", "outcome"] = "timeout"
    trials.to_csv(folder / "trials.csv", index=False)
    out = tmp_path / "out"
    assert main(["study", "power", str(folder), "--out", str(out), "--quiet"]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: {folder}: {said} with a successful experimental trial; power needs "
        "at least 4 to resample (from fewer too few different studies can be drawn, and one "
        "person's groups have no spread: power would read 1 at every n). Add participants, or "
        "--simulate N simulated ones of the first run folder's design\n"
    )
    assert not out.exists()


def test_simulated_participants_of_the_design_join_the_pool(tmp_path: Path, capsys) -> None:
    """--simulate runs participants of the first run folder's design as a run folder of their
    own (the study runner), another seed than the pilot's, and resamples them with it."""
    from arteleop.study import CohortConfig, FamiliarizationConfig, StudyConfig, run_study

    tiny = StudyConfig(seed=3, modalities=("none", "full"), timeout_s=1.0,
                       familiarization=FamiliarizationConfig(trials=0),
                       cohort=CohortConfig(size=4, avr_experts=0, games_experts=0,
                                           both_experts=0))  # fmt: skip
    run_study(tiny, tmp_path / "pilot", workers=1)
    # Trials of 1 s time out; the pilot's are read as placed, so that the pool can be resampled.
    trials = pd.read_csv(tmp_path / "pilot" / "trials.csv")
    trials["outcome"] = "success"
    trials["completion_time_s"] = RNG.uniform(20.0, 40.0, len(trials))
    trials["placement_error_m"] = RNG.uniform(0.005, 0.03, len(trials))
    trials.to_csv(tmp_path / "pilot" / "trials.csv", index=False)
    out = tmp_path / "power"
    args = ["study", "power", str(tmp_path / "pilot"), "--out", str(out), "--simulate", "3",
            "--n", "3:4:1", "--resamples", "20", "--workers", "1", "--quiet"]  # fmt: skip
    assert main(args) == 0
    assert "pool: 7 participants from 2 source(s)" in capsys.readouterr().out
    simulated = tmp_path / "power-simulated-run"
    assert pd.read_csv(simulated / "participants.csv")["participant"].tolist() == [
        "P01",
        "P02",
        "P03",
    ]
    assert "seed = 1000" in (simulated / "study.toml").read_text()
    assert "(simulated)" in (out / "power.md").read_text()
    # Again: the simulated run is in the way until --force, which makes the same files anew.
    first = {p.name: p.read_bytes() for p in (simulated / "trials.csv", out / "power.csv")}
    shutil.rmtree(out)
    assert main(args) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: --simulate: {simulated} holds the simulated participants of an "
        "earlier power analysis; give --force to simulate them anew there, or another --out.\n"
    )
    assert main([*args, "--force"]) == 0
    assert first == {p.name: p.read_bytes() for p in (simulated / "trials.csv", out / "power.csv")}
    (simulated / "participants.csv").write_text("participant,source\nS01,real\n")
    assert main([*args, "--force"]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: --simulate: {simulated} is in the way and is not a run of simulated "
        "participants; move it, or give another --out (--force replaces only what power "
        "wrote).\n"
    )


def test_a_crossed_delay_design_gets_the_anovas_power(tmp_path: Path) -> None:
    from tests.analysis.test_delay import write_crossed

    write_crossed(tmp_path / "trials.csv", interaction=True)
    pool = make_pool([load_study(tmp_path / "trials.csv")], ["crossed"])
    assert pool.conditions == ("none@0ms", "predictive@0ms", "none@500ms", "predictive@500ms")
    options = PowerOptions(sizes=(6,), resamples=200, paired=True)
    table = pd.concat(power(pool, options), ignore_index=True).set_index(["comparison", "measure"])
    assert table.loc[("predictive@500ms vs none@500ms", "completion_time_s"), "power"] > 0.5
    assert table.loc[("ANOVA cue x delay", "completion_time_s"), "power"] > 0.5
    assert ("ANOVA cue", "placement_error_m") in table.index
