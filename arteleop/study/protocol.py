"""One trial of the protocol (docs/explanation/study.md §1), run for one planned trial.

The arm starts at the rest pose; the completion timer starts at motion onset (the hand's speed
crosses ``START_SPEED_M_S``) and stops at the first camera frame, after the release, in which
the tracker finds the bowl at rest (:mod:`arteleop.teleop.task_monitor`). A failure is an
outcome with its reason and is kept like any other trial.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import SimulationError
from arteleop.operator import Expertise, OperatorTraits
from arteleop.scene import RemoteSite
from arteleop.study.carry import Carried
from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec
from arteleop.study.plan import TrialSpec
from arteleop.study.sites import StudySite
from arteleop.teleop import (
    ControllerConfig,
    NetworkConfig,
    Outcome,
    TrialConfig,
    TrialResult,
    run_trial,
    trial_operator,
)


@dataclass(frozen=True)
class TrialRecord:
    """What a study keeps of one trial.

    Attributes:
        spec: The planned trial.
        row: Its row of ``trials.csv`` (docs/reference/data-format.md), by column name.
        trace: Its trajectory file's columns (:data:`~arteleop.teleop.TRACE_COLUMNS`).
        duration_s: Simulated time of the trial (s).
        wall_s: Wall-clock time it took, site included (s); kept out of the files, which must
            not depend on the machine.
    """

    spec: TrialSpec
    row: dict[str, object]
    trace: dict[str, NDArray[np.float64]]
    duration_s: float
    wall_s: float


def trajectory_file(spec: TrialSpec) -> str:
    """The trial's trajectory file, relative to the run folder."""
    return f"trajectories/{spec.participant}/{spec.trial_index}.csv"


def operator_traits(study: StudyConfig, person: ParticipantSpec) -> OperatorTraits:
    """The participant's lasting traits, drawn from the study's seed and the participant's id
    (the same in each of their trials), with their expertise and movement-time factor."""
    expertise = Expertise(avr_hours=person.avr_hours, games_hours=person.games_hours)
    return study.operator.draw(study.seed, person.id, expertise, person.movement_time_factor)


def trial_config(study: StudyConfig, site: StudySite, spec: TrialSpec) -> TrialConfig:
    """The headless trial of a planned trial."""
    return TrialConfig(
        modality=spec.modality,
        seed=spec.seed,
        timeout_s=spec.timeout_s,
        network=NetworkConfig(
            delay_s=spec.round_trip_ms / 2000,
            jitter_s=spec.jitter_ms / 1000,
            loss_probability=spec.loss,
        ),
        controller=ControllerConfig(hand_filter=study.hand_filter),
        site=site.site_config(spec, study.camera_registration()),
        record_trace=True,
        depth_aids=study.depth_aids,
        task=study.task,
    )


def run_planned_trial(
    study: StudyConfig,
    site: StudySite,
    person: ParticipantSpec,
    spec: TrialSpec,
    brought: Carried | None = None,
) -> TrialRecord:
    """Run one planned trial with the participant's synthetic operator, who brings to it what
    it carried from its last trial (None for its first: the lag it knows from practice on the
    system, ``familiar_lag_s``, and no outcome seen); at the end it sees whether it missed
    (:meth:`~arteleop.operator.SyntheticOperator.saw_miss`: a bowl let go on the table is judged
    on the display; a trial that ended before, in time or with the bowl dropped, is a miss it
    knows)."""
    config = trial_config(study, site, spec)
    params = study.operator_params
    if brought is not None:
        params = replace(params, familiar_lag_s=brought.lag_s, seen_outcomes=brought.outcomes)
    start = time.perf_counter()
    with RemoteSite(config.site) as remote:
        source = trial_operator(
            remote,
            config,
            params=params,
            traits=operator_traits(study, person),
        )
        result = run_trial(source, config, remote)
    operator, frame = source.operator, result.final_frame
    # Let go on the table, the bowl is judged where the display shows it (the tracker that lost
    # it is the system's failure, not one the person sees); any other failure it knows.
    looks = result.outcome in (Outcome.SUCCESS, Outcome.TRACKING_LOST) and frame is not None
    missed = operator.saw_miss(frame) if looks else result.outcome is not Outcome.SUCCESS
    return trial_record(spec, result, time.perf_counter() - start, operator.lag_s, missed)


def trial_record(
    spec: TrialSpec,
    result: TrialResult,
    wall_s: float,
    believed_lag_s: float = float("nan"),
    saw_miss: bool | None = None,
) -> TrialRecord:
    """What a study keeps of a planned trial's result, whoever the participant was; a synthetic
    one's ``believed_lag_s`` (s) at the trial's end and whether it ``saw_miss``, NaN and None
    (empty) for a person."""
    if result.trace is None:
        raise SimulationError("The trial recorded no trace although its config asked for one.")
    seen = {
        "believed_lag_s": believed_lag_s,
        "saw_miss": None if saw_miss is None else int(saw_miss),
    }
    row = trial_row(spec, {**result.to_row(), **seen})
    return TrialRecord(spec, row, result.trace, result.duration_s, wall_s)


def trial_row(spec: TrialSpec, measured: dict[str, object]) -> dict[str, object]:
    """A planned trial's row of ``trials.csv``: the plan's columns around what was measured
    (:meth:`~arteleop.teleop.TrialResult.to_row`'s columns, the operator's belief of the lag and
    whether it saw a miss; absent ones stay empty)."""
    return {
        "participant": spec.participant,
        "phase": spec.phase,
        "trial_index": spec.trial_index,
        "position": spec.position,
        "modality": spec.modality,
        "seed": spec.seed,
        **measured,
        "round_trip_ms": spec.round_trip_ms,
        "jitter_ms": spec.jitter_ms,
        "loss": spec.loss,
        "trajectory_file": trajectory_file(spec),
    }
