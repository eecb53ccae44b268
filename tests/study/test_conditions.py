"""Studies that cross network delay with AR cues: the conditions table, its plan and files."""

from __future__ import annotations

import itertools
from collections import Counter

import pandas as pd
import pytest

from arteleop.errors import StudyDefinitionError
from arteleop.study import StudyConfig, parse_study, plan_study, run_study, study_text
from arteleop.study.protocol import trial_config

DELAYS_MS = (0, 250, 500)
CUES = ("[]", '["embodiment"]', '["predictive"]')


def crossed(size: int, extra: str = "") -> str:
    """A 3 x 3 delay x cue design for ``size`` participants without practice."""
    text = f"[cohort]\nsize = {size}\navr_experts = 0\ngames_experts = 0\nboth_experts = 0\n"
    text += "\n[familiarization]\ntrials = 0\n" + extra
    for delay, cues in itertools.product(DELAYS_MS, CUES):
        text += f"\n[[conditions]]\ncues = {cues}\nround_trip_ms = {delay}\n"
    return text


@pytest.mark.parametrize("size", [9, 12, 18])
def test_a_williams_square_over_crossed_conditions_is_balanced(size: int) -> None:
    """Each condition at each position equally often, within 1, for any cohort size."""
    plan = plan_study(parse_study(crossed(size)))
    cells = Counter((s.modality, s.round_trip_ms, s.position) for s in plan)
    names = {(s.modality, s.round_trip_ms) for s in plan}
    assert len(names) == 9
    counts = [cells[(m, d, p)] for (m, d) in names for p in range(1, 10)]
    assert max(counts) - min(counts) <= 1, counts
    for person in {s.participant for s in plan}:  # each person meets each condition once
        own = [(s.modality, s.round_trip_ms) for s in plan if s.participant == person]
        assert sorted(own) == sorted(names)


def test_each_trial_runs_with_its_conditions_network_and_cues() -> None:
    text = crossed(2).replace("round_trip_ms = 500\n", "round_trip_ms = 500\njitter_ms = 20\n")
    text = text.replace('["predictive"]\nround_trip_ms = 250', '["ghost", "predictive_ghost"]\n'
                        "round_trip_ms = 250\nloss = 0.05")  # fmt: skip
    study = parse_study(text)
    spec = next(s for s in plan_study(study) if s.round_trip_ms == 250 and "+" in s.modality)
    assert spec.modality == "ghost+predictive_ghost" and spec.loss == 0.05

    class _Site:
        def site_config(self, spec, registration):
            from arteleop.scene import SiteConfig

            return SiteConfig()

    config = trial_config(study, _Site(), spec)  # type: ignore[arg-type]
    assert (config.network.delay_s, config.network.jitter_s) == (0.125, 0.0)
    assert config.network.loss_probability == 0.05
    jittered = next(s for s in plan_study(study) if s.round_trip_ms == 500)
    assert trial_config(study, _Site(), jittered).network.jitter_s == 0.02  # type: ignore[arg-type]
    assert parse_study(study_text(study)) == study  # the run folder's study.toml reads back


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (('cues = ["embodiment"]\nround_trip_ms = 250', 'cues = ["ghosts"]\nround_trip_ms = 250'),
         "s.toml line 27: conditions.cues = ['ghosts']: unknown 'ghosts'; expected modalities "
         "(none, manipulation, embodiment, task, full, predictive) or AR layers (ghost, beam, "
         "distance_bar, grip_bar, target_mesh, predictive_ghost)."),
        (("round_trip_ms = 500\n", "round_trip_ms = -500\n"),
         "s.toml line 36: conditions.round_trip_ms = -500.0: expected 0 ms or more."),
        (("round_trip_ms = 0\n", "round_trip_ms = 0\nloss = 1.0\n"),
         "s.toml line 13: conditions.loss = 1.0: expected a probability in [0, 1)."),
        (("round_trip_ms = 0\n", "round_trip_ms = 0\nloss = -0.1\n"),
         "s.toml line 13: conditions.loss = -0.1: expected a probability in [0, 1)."),
        (("[cohort]", 'modalities = ["none"]\n[cohort]'),
         "s.toml line 1: modalities and [[conditions]]: the conditions give each trial's cues "
         "and network; remove one or the other."),
        (("round_trip_ms = 500\n", "round_trip_ms = 500\ndelay = 3\n"),
         "s.toml line 37: unknown key 'conditions.delay'. Valid keys in [conditions]: cues, "
         "round_trip_ms, jitter_ms, loss."),
    ],
)  # fmt: skip
def test_bad_conditions_are_refused_naming_line_and_key(
    change: tuple[str, str], message: str
) -> None:
    text = crossed(3).replace(*change, 1)
    with pytest.raises(StudyDefinitionError) as err:
        parse_study(text, "s.toml")
    assert str(err.value) == message


def test_a_condition_given_twice_is_refused() -> None:
    text = crossed(3) + '\n[[conditions]]\ncues = ["none"]\nround_trip_ms = 0\n'
    with pytest.raises(StudyDefinitionError, match=r"condition 10 \(none@0ms\) repeats "
                       r"condition 1; each condition at most once"):  # fmt: skip
        parse_study(text, "s.toml")


def test_without_conditions_the_study_is_the_original() -> None:
    study = StudyConfig()
    assert [c.name for c in study.planned_conditions] == [
        f"{m}@0ms" for m in ("none", "manipulation", "embodiment", "task", "full")
    ]
    assert "[[conditions]]" not in study_text(study).replace("# [[conditions]]", "")


def test_a_crossed_study_runs_to_its_files_and_answers(tmp_path) -> None:
    """Two people, no cue and the predictive ghost under a 500 ms round trip: every file, the
    network in trials.csv, and the questionnaire, its header alone: neither condition draws an
    aid of the classes it asks about (the trials end at 8 s: what they are is not this
    test's)."""
    text = (
        "timeout_s = 8.0\n"
        "[cohort]\nsize = 2\navr_experts = 0\ngames_experts = 0\nboth_experts = 0\n"
        "[familiarization]\ntrials = 0\n"
        "[[conditions]]\ncues = []\nround_trip_ms = 0\n"
        '[[conditions]]\ncues = ["predictive"]\nround_trip_ms = 500\njitter_ms = 10\n'
    )
    run = run_study(parse_study(text), tmp_path / "run", workers=2)
    trials = pd.read_csv(run.folder / "trials.csv")
    cells = trials[["modality", "round_trip_ms", "jitter_ms"]].itertuples(index=False)
    assert sorted(map(tuple, cells)) == [
        ("none", 0.0, 0.0), ("none", 0.0, 0.0), ("predictive", 500.0, 10.0),
        ("predictive", 500.0, 10.0),
    ]  # fmt: skip
    answers = pd.read_csv(run.folder / "questionnaire.csv")
    assert answers.empty and list(answers.columns) == ["participant", "ar_class", "item", "score"]


def test_questionnaire_answers_come_from_the_trials_under_the_least_delay() -> None:
    from arteleop.study.questionnaire import simulated_answers

    rows = [("none", 0, 20.0), ("none", 500, 40.0), ("embodiment", 500, 50.0),
            ("embodiment", 0, 10.0)]  # fmt: skip
    trials = pd.DataFrame(
        [{"modality": m, "round_trip_ms": d, "jitter_ms": 0.0, "loss": 0.0, "outcome": "success",
          "completion_time_s": t, "placement_error_m": 0.01} for m, d, t in rows]
    )  # fmt: skip
    crossed_answers = simulated_answers("P01", (0, 4, 0), trials, 120.0)
    undelayed = trials[trials["round_trip_ms"] == 0]
    assert crossed_answers == simulated_answers("P01", (0, 4, 0), undelayed, 120.0)
    assert crossed_answers != simulated_answers(
        "P01", (0, 4, 0), trials[trials["round_trip_ms"] == 500], 120.0
    )
