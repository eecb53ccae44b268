"""Every trial of a study, planned before any runs: who, which condition (modality and network),
where, with which seed.

The plan is a pure function of the definition, so a resumed or parallel run plans the same
trials, and each trial's seed depends only on the study's seed and the trial's place.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from arteleop.errors import StudyDefinitionError
from arteleop.study.cohort import participants
from arteleop.study.counterbalancing import participant_orders
from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec

FAMILIARIZATION = "familiarization"
EXPERIMENTAL = "experimental"
MIN_PRACTICE_GAP_M = 0.20
"""Practice start and target are at least this far apart (m): a reach worth practising."""
MAX_DRAWS = 10_000

Accept = Callable[[tuple[float, float], tuple[float, float]], "str | None"]
"""Says why a (start, target) pair of points (base frame, m) cannot be used, or None."""


@dataclass(frozen=True)
class TrialSpec:
    """One planned trial.

    Attributes:
        participant: The participant's id.
        participant_index: The participant's place in the study (0-based), for seeds.
        phase: ``familiarization`` or ``experimental``.
        trial_index: The trial's place in the participant's session (1, 2, ...).
        modality: The AR modality.
        position: Experimental: the modality's place in the participant's order (1..n);
            practice: the practice trial's number.
        seed: The trial's seed (operator, wearable, network, depth noise).
        start_xy_m: Where the bowl starts (base frame, m).
        target_xy_m: Where it must go (base frame, m).
        timeout_s: Simulated time after which the trial ends as a timeout (s).
        round_trip_ms: The network's round-trip delay (ms), half each way.
        jitter_ms: SD of each one-way delay (ms).
        loss: Chance that an operator sample is lost.
    """

    participant: str
    participant_index: int
    phase: str
    trial_index: int
    modality: str
    position: int
    seed: int
    start_xy_m: tuple[float, float]
    target_xy_m: tuple[float, float]
    timeout_s: float
    round_trip_ms: float = 0.0
    jitter_ms: float = 0.0
    loss: float = 0.0

    @property
    def key(self) -> tuple[str, int]:
        """(participant, trial_index): names the trial in every file."""
        return self.participant, self.trial_index


def trial_seed(study_seed: int, participant_index: int, trial_index: int) -> int:
    """A trial's seed: independent streams per trial, whatever runs before or beside it."""
    sequence = np.random.SeedSequence([study_seed, participant_index, trial_index])
    return int(sequence.generate_state(1)[0])


def condition_orders(config: StudyConfig, n_people: int) -> list[tuple[int, ...]]:
    """Each participant's order of the conditions (indices into
    :attr:`StudyConfig.planned_conditions`), by the study's order scheme."""
    names = config.condition_names
    if config.order == "listed":
        listed = [tuple(names.index(m) for m in o) for o in config.orders]
        return [listed[k % len(listed)] for k in range(n_people)]
    return participant_orders(config.order, len(names), n_people, config.seed)


def plan_study(
    config: StudyConfig, practice_points: PracticePoints | None = None
) -> list[TrialSpec]:
    """Every trial of the study, participant by participant, in session order.

    ``practice_points`` draws the familiarisation start and target; needed when the
    definition has practice trials.
    """
    people = participants(config)
    orders = condition_orders(config, len(people))
    plan: list[TrialSpec] = []
    for k, (person, order) in enumerate(zip(people, orders, strict=True)):
        plan += _session(config, k, person, order, practice_points)
    return plan


def _session(
    config: StudyConfig,
    k: int,
    person: ParticipantSpec,
    order: tuple[int, ...],
    practice_points: PracticePoints | None,
) -> list[TrialSpec]:
    fam = config.familiarization
    trials = []
    rng = np.random.default_rng([config.seed, 3, k])
    for i in range(fam.trials):
        if practice_points is None:
            raise StudyDefinitionError("familiarization.trials > 0 needs practice points to draw.")
        start, target = practice_points.draw(rng)
        trials.append(
            TrialSpec(
                participant=person.id,
                participant_index=k,
                phase=FAMILIARIZATION,
                trial_index=i + 1,
                modality=fam.modality,
                position=i + 1,
                seed=trial_seed(config.seed, k, i + 1),
                start_xy_m=start,
                target_xy_m=target,
                timeout_s=fam.timeout_s,
                round_trip_ms=0.0 if config.conditions else 2 * config.delay_ms,
            )
        )
    conditions = config.planned_conditions
    for position, c in enumerate(order, start=1):
        index = fam.trials + position
        condition = conditions[c]
        trials.append(
            TrialSpec(
                participant=person.id,
                participant_index=k,
                phase=EXPERIMENTAL,
                trial_index=index,
                modality=condition.modality,
                position=position,
                seed=trial_seed(config.seed, k, index),
                start_xy_m=config.start_xy_m,
                target_xy_m=config.target_xy_m,
                timeout_s=config.timeout_s,
                round_trip_ms=condition.round_trip_ms,
                jitter_ms=condition.jitter_ms,
                loss=condition.loss,
            )
        )
    return trials


class PracticePoints:
    """Draws practice start and target points uniformly on the table, keeping those the arm
    can grasp from above at all four sides of the rim and that lie at least
    :data:`MIN_PRACTICE_GAP_M` apart.

    Args:
        accept: Says why a (start, target) pair cannot be used, or None if it can
            (:meth:`arteleop.study.StudySite.problem` gives the site's own checks).
        lower_xy_m, upper_xy_m: The box to draw the bowl's centre in (base frame, m).
    """

    def __init__(
        self,
        accept: Accept,
        lower_xy_m: tuple[float, float],
        upper_xy_m: tuple[float, float],
    ) -> None:
        self._accept = accept
        self._lower, self._upper = np.asarray(lower_xy_m), np.asarray(upper_xy_m)

    def draw(self, rng: np.random.Generator) -> tuple[tuple[float, float], tuple[float, float]]:
        for _ in range(MAX_DRAWS):
            a, b = (np.round(rng.uniform(self._lower, self._upper), 4) for _ in range(2))
            start, target = (float(a[0]), float(a[1])), (float(b[0]), float(b[1]))
            if np.hypot(*(a - b)) < MIN_PRACTICE_GAP_M:
                continue
            if self._accept(start, target) is None:
                return start, target
        raise StudyDefinitionError(
            f"No practice start and target in {MAX_DRAWS} draws: the table area the arm "
            "reaches from above is too small; move the table closer to the robot."
        )
