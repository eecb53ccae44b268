"""Who takes part in a study: participants named in its file, or a cohort of simulated ones
drawn from its seed (the study file's ``[[participants]]`` and ``[cohort]`` tables)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from arteleop.errors import StudyDefinitionError


@dataclass(frozen=True)
class ParticipantSpec:
    """One named participant (a real lab's, or a chosen simulated one).

    Attributes:
        id: Participant id, as written in every file (letters, digits, ``-`` and ``_``).
        avr_hours: Weekly AR/VR hours bucket: 1 = under 2 h, 2 = 2-5 h, 3 = over 5 h.
        games_hours: Weekly video-game hours bucket, same buckets.
        avr_experience: AR/VR experience, Likert 1-7.
        games_experience: Video-game experience, Likert 1-7.
        age: Age (years).
        gender: As the participant gives it.
        movement_time_factor: The participant's own speed, for a simulated participant: a
            factor on every submovement's duration (below 1: faster), and so, through the
            endpoint scatter's growth with speed (:class:`~arteleop.operator.MovementScatter`),
            on its accuracy. See :class:`CohortConfig` for how a cohort draws it; the simulated
            participant's other traits come from the study's seed and the id
            (docs/explanation/operator-model.md).
    """

    id: str
    avr_hours: int = 1
    games_hours: int = 1
    avr_experience: int = 4
    games_experience: int = 4
    age: int = 30
    gender: str = ""
    movement_time_factor: float = 1.0

    def __post_init__(self) -> None:
        if not self.id or not all(ch.isalnum() or ch in "-_" for ch in self.id):
            raise StudyDefinitionError(
                f"participant id {self.id!r}: use letters, digits, '-' and '_' only "
                "(it names a folder of the run)."
            )
        for name in ("avr_hours", "games_hours"):
            if getattr(self, name) not in (1, 2, 3):
                raise StudyDefinitionError(
                    f"participant {self.id}: {name} = {getattr(self, name)!r}; "
                    "expected a bucket 1, 2 or 3."
                )
        for name in ("avr_experience", "games_experience"):
            if getattr(self, name) not in range(1, 8):
                raise StudyDefinitionError(
                    f"participant {self.id}: {name} = {getattr(self, name)!r}; "
                    "expected a Likert score 1-7."
                )
        factor = self.movement_time_factor
        if not (math.isfinite(factor) and 0.25 <= factor <= 4.0):
            raise StudyDefinitionError(
                f"participant {self.id}: movement_time_factor = {factor!r}; expected 0.25-4."
            )


MAX_COHORT = 10_000
"""The most participants one run takes (its plan is held in memory, its trials in one folder)."""


@dataclass(frozen=True)
class CohortConfig:
    """A simulated cohort, drawn from the study's seed when no participants are listed.

    The defaults are the original study's 22 participants (docs/explanation/study.md §4): 7 AR/VR
    experts and 7 gamers (at least 2 h a week), 4 of them both.

    Attributes:
        size: Number of participants.
        avr_experts: Participants with AR/VR hours bucket >= 2.
        games_experts: Participants with video-game hours bucket >= 2.
        both_experts: Of those, how many are both.
        movement_time_sd: SD of the log of each participant's movement-time factor
            (:attr:`ParticipantSpec.movement_time_factor`), lognormal around 1. Movement times
            of healthy adults in the same pointing task vary by a coefficient of variation of
            about 0.2 between people (MacKenzie, HCI 1992, per-subject Fitts fits).
        id_prefix: Ids are this prefix and a two-digit number: P01, P02, ...
    """

    size: int = 22
    avr_experts: int = 7
    games_experts: int = 7
    both_experts: int = 4
    movement_time_sd: float = 0.2
    id_prefix: str = "P"

    def __post_init__(self) -> None:
        if self.size < 1:
            raise StudyDefinitionError(f"cohort.size = {self.size}: expected 1 or more.")
        if self.size > MAX_COHORT:
            raise StudyDefinitionError(
                f"cohort.size = {self.size}: expected at most {MAX_COHORT} participants. A run "
                "plans every trial before the first runs and keeps them in one folder: run a "
                "larger cohort as several runs with other seeds and pool them with 'arteleop "
                "analyze RUN1 RUN2 ...'."
            )
        only = self.avr_experts + self.games_experts - self.both_experts
        if not (
            0 <= self.both_experts <= min(self.avr_experts, self.games_experts)
            and only <= self.size
        ):
            raise StudyDefinitionError(
                f"cohort: {self.avr_experts} AR/VR experts and {self.games_experts} gamers, "
                f"{self.both_experts} of them both, do not fit {self.size} participants: "
                "both_experts must not exceed either count, and avr_experts + games_experts - "
                "both_experts must not exceed size."
            )
        if not (math.isfinite(self.movement_time_sd) and 0 <= self.movement_time_sd <= 1):
            raise StudyDefinitionError(
                f"cohort.movement_time_sd = {self.movement_time_sd}: expected 0-1."
            )
