"""End to end on a synthetic run folder with known effects."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from arteleop.analysis import AnalysisOptions, analyse, load_study, write_report
from arteleop.cli import main
from tests.analysis.make_study import make_run


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_run(tmp_path_factory.mktemp("run"), seed=3)


@pytest.fixture(scope="module")
def report(run: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("report")
    study = load_study(run)
    write_report(study, analyse(study), AnalysisOptions(), out)
    return out


def test_tests_csv_has_the_documented_columns_and_rows(report: Path) -> None:
    tests = pd.read_csv(report / "tests.csv", keep_default_na=False)
    assert list(tests.columns)[:12] == [
        "subset", "measure", "group_a", "group_b", "test", "n_a", "n_b", "statistic", "p_value",
        "effect_size", "effect_size_kind", "stars",
    ]  # fmt: skip
    main_rows = tests[
        (tests["subset"] == "all") & ~tests["measure"].str.startswith("questionnaire")
    ]
    assert len(main_rows) == 6 * (10 + 1)  # time, error, 4 smoothness x (10 pairs + ANOVA)
    assert set(tests["subset"]) >= {
        "all",
        "avr_expert",
        "avr_novice",
        "games_expert",
        "games_novice",
        "experts_vs_novices:avr",
    }
    assert {f"questionnaire:{i}" for i in ("presence", "embodiment", "ease")} <= set(
        tests["measure"]
    )
    assert set(tests["test"]) <= {"ttest", "mannwhitneyu", "anova", ""}


def test_known_effects_are_found(report: Path) -> None:
    tests = pd.read_csv(report / "tests.csv", keep_default_na=False)
    row = tests[
        (tests.subset == "all")
        & (tests.measure == "completion_time_s")
        & (tests.group_a == "none")
        & (tests.group_b == "full")
    ].iloc[0]
    assert row["stars"] == "**"
    assert (row["n_a"], row["n_b"]) == (22, 21)  # everyone; full lost a timed-out trial
    err = tests[
        (tests.subset == "all")
        & (tests.measure == "placement_error_m")
        & (tests.group_a == "none")
        & (tests.group_b == "full")
    ].iloc[0]
    assert err["stars"] == "**"
    jerk = tests[
        (tests.subset == "all")
        & (tests.measure == "normalized_jerk_xy")
        & (tests.group_a == "none")
        & (tests.group_b == "embodiment")
    ].iloc[0]
    assert jerk["stars"] == "**"  # the embodiment trajectories carry the least tremor
    order = pd.read_csv(report / "order_effect.csv")
    assert (order["p_value"] > 0.01).all()  # no order effect was built in


def test_test_choice_follows_normality(report: Path) -> None:
    tests = pd.read_csv(report / "tests.csv", keep_default_na=False)
    norm = pd.read_csv(report / "normality.csv")
    # An empty verdict (a constant group, e.g. one submovement in every trial) is not normal.
    normal = {(r.measure, r.group): str(r.normal) == "True"
              for r in norm[norm.subset == "all"].itertuples()}  # fmt: skip
    for r in tests[
        (tests.subset == "all")
        & tests.group_b.isin(["none", "manipulation", "embodiment", "task", "full"])
    ].itertuples():
        both = normal[(r.measure, r.group_a)] and normal[(r.measure, r.group_b)]
        assert r.test == ("ttest" if both else "mannwhitneyu")


def test_report_and_figures(report: Path) -> None:
    text = (report / "report.md").read_text()
    assert "Mann-Whitney U test" in text and "Lilliefors" in text
    assert "Method `untrimmed` (the default): every participant." in text
    assert "timeout: 1" in text  # the failed trial is counted, not analysed
    assert "computed from trajectory files for 109 trial(s)" in text
    for name in (
        "boxplot_completion_time_s.png",
        "boxplot_normalized_jerk_xy.png",
        "questionnaire.png",
        "expertise_avr_completion_time_s.png",
        "trajectories_xy.png",
    ):
        assert (report / "figures" / name).stat().st_size > 10_000


def test_descriptives(report: Path, run: Path) -> None:
    desc = pd.read_csv(report / "descriptives.csv")
    full = desc[(desc.measure == "completion_time_s") & (desc.modality == "full")].iloc[0]
    assert full["n_total"] == 21 and full["n"] == 21  # one full-AR trial timed out
    trials = pd.read_csv(run / "trials.csv")
    v = trials[
        (trials.phase == "experimental")
        & (trials.outcome == "success")
        & (trials.modality == "full")
    ]["completion_time_s"].sort_values()
    assert full["mean"] == pytest.approx(v.mean())


def test_the_thesis_method_drops_each_groups_extremes_first(run: Path) -> None:
    """--method thesis: per modality the largest and smallest values go (22 -> 20; 21 -> 19
    for full, which lost a timed-out trial), per modality and expertise group too, and the
    rest is tested by Lilliefors' choice; the report says what its error rate is."""
    study = load_study(run / "trials.csv")
    study = type(study)(study.trials.assign(trajectory_file=""), load_study(run).participants,
                        None, study.base_dir, study.trials_path)  # fmt: skip
    options = AnalysisOptions(method="thesis")
    result = analyse(study, options)
    tests = result.tests.set_index(["subset", "measure", "group_a", "group_b"])
    row = tests.loc[("all", "completion_time_s", "none", "full")]
    assert (row["n_a"], row["n_b"], row["test"]) == (20, 19, "ttest")
    trials = result.trials[result.trials.modality.isin(["none", "full"])]
    kept = {m: np.sort(g["completion_time_s"].to_numpy())[1:-1]
            for m, g in trials.groupby("modality")}  # fmt: skip
    assert row["p_value"] == pytest.approx(stats.ttest_ind(kept["none"], kept["full"]).pvalue)
    experts = tests.loc["avr_expert"].query("measure == 'completion_time_s'")
    assert experts["n_a"].max() == 5  # 7 experts, less the extremes
    desc = result.descriptives.set_index(["measure", "modality"])
    assert desc.loc[("completion_time_s", "full"), ["n_total", "n"]].tolist() == [21, 19]


def test_the_yuen_method_tests_trimmed_means(run: Path) -> None:
    """--method yuen: Yuen's test on everyone (scipy's trimmed ttest_ind), paired: the trimmed
    differences; ratings stay on Lilliefors' choice."""
    study = load_study(run)
    study = type(study)(study.trials.assign(trajectory_file=""), study.participants,
                        study.questionnaire, study.base_dir, study.trials_path)  # fmt: skip
    for paired, name in ((False, "yuen"), (True, "trimmed_paired")):
        tests = analyse(study, AnalysisOptions(method="yuen", paired=paired)).tests
        main_tests = tests[(tests.subset == "all") & (tests.test != "anova")
                           & ~tests.measure.str.startswith("questionnaire")]  # fmt: skip
        assert set(main_tests["test"]) == {name}
        between = tests[tests.subset.str.startswith("experts_vs_novices")]
        assert set(between["test"]) == {"yuen"}  # other people: never paired
        ratings = tests[tests.measure.str.startswith("questionnaire")]
        assert set(ratings["test"]) <= {"ttest", "mannwhitneyu", "paired_ttest", "wilcoxon"}
    row = main_tests.set_index(["measure", "group_a", "group_b"]).loc[
        ("completion_time_s", "none", "full")]  # fmt: skip
    assert row["n_a"] == 21 and row["stars"] == "**"  # the pairs full's timeout left


def test_missing_parts_are_skipped_with_a_note(run: Path, tmp_path: Path) -> None:
    study = load_study(run / "trials.csv")  # no participants, no questionnaire
    trials = study.trials.assign(normalized_jerk_xy=np.nan, trajectory_file="")
    result = analyse(type(study)(trials, None, None, study.base_dir, study.trials_path))
    assert any("Expertise analysis skipped" in n for n in result.notes)
    assert any("Smoothness skipped" in n for n in result.notes)
    assert set(result.tests["measure"]) == {"completion_time_s", "placement_error_m"}


def test_a_study_with_nothing_to_compare_has_a_report_without_tests(
    run: Path, tmp_path: Path
) -> None:
    """No trial placed and no questionnaire (a pilot whose trials all ran out of time): the
    report is written, its tests table with its columns and no row."""
    study = load_study(run / "trials.csv")
    trials = study.trials.assign(outcome="timeout", completion_time_s=np.nan,
                                 placement_error_m=np.nan)  # fmt: skip
    none = type(study)(trials, None, None, study.base_dir, study.trials_path)
    result = analyse(none)
    assert result.tests.empty and "p_value" in result.tests.columns
    write_report(none, result, AnalysisOptions(), tmp_path / "report")
    tests = pd.read_csv(tmp_path / "report" / "tests.csv")
    assert tests.empty and "p_value" in tests.columns


def test_options_paired_and_holm(run: Path) -> None:
    study = load_study(run)
    paired = analyse(study, AnalysisOptions(paired=True, holm=True))
    within = paired.tests[paired.tests.subset.isin(["all", "avr_expert", "games_novice"])]
    assert set(within["test"]) <= {"paired_ttest", "wilcoxon", "anova", ""}
    # Experts and novices are different people: that comparison stays unpaired.
    between = paired.tests[paired.tests.subset.str.startswith("experts_vs_novices")]
    assert set(between["test"]) <= {"ttest", "mannwhitneyu", ""}
    assert (paired.tests["note"] == "Holm-adjusted").any()
    assert within[within.test != "anova"]["n_a"].max() == 22  # untrimmed: every person paired


def test_same_input_same_files(run: Path, report: Path, tmp_path: Path) -> None:
    """The command, run again on the same files, writes what the module's report has."""
    assert main(["analyze", str(run), "--out", str(tmp_path / "again")]) == 0
    for name in ("tests.csv", "normality.csv", "descriptives.csv", "report.md"):
        a = (report / name).read_text().replace(str(report), "")
        b = (tmp_path / "again" / name).read_text().replace(str(tmp_path / "again"), "")
        assert a == b


def test_cli_reports_bad_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "trials.csv").write_text(
        "participant,phase,modality,position,outcome,completion_time_s,placement_error_m\nP1,experimental,vr,1,success,30,0.01\n"
    )
    assert main(["analyze", str(tmp_path / "trials.csv"), "--out", str(tmp_path / "r")]) == 2
    assert "line 2, column modality: unknown value 'vr'" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--no-trim"], "--no-trim is gone: the default, --method untrimmed, keeps everyone; "
                        "--method yuen compares 20 % trimmed means at their stated error rate."),
        (["--trim"], "--trim is gone: --method thesis is the thesis's trimming (it rejects a true "
                     "null about twice as often as p <= 0.05 says); the default, --method "
                     "untrimmed, keeps everyone."),
        (["--method", "thesis", "--paired"], "method 'thesis' compares modalities as "
         "independent groups, as the thesis did; paired tests go with method 'untrimmed' or "
         "'yuen'."),
    ],
)  # fmt: skip
def test_a_method_the_analysis_cannot_run_is_refused_and_nothing_written(
    run: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], message: str
) -> None:
    out = tmp_path / "r"
    for command in (["analyze"], ["study", "power"]):
        assert main([*command, str(run), "--out", str(out), *argv]) == 2
        assert capsys.readouterr().err == f"arteleop: error: {message}\n"
        assert not out.exists()
