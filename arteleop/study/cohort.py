"""The study's participants: the listed ones, or a simulated cohort drawn from the study's seed."""

from __future__ import annotations

import numpy as np

from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec

EXPERT_BUCKETS = (2, 3)
"""Weekly-hours buckets of an expert (at least two hours a week, docs/explanation/study.md §5)."""
MALE_FRACTION = 16 / 22
"""The original cohort: 16 men and 6 women (docs/explanation/study.md §4)."""
AGE_RANGE = (23, 40)
"""The original cohort's ages (years)."""


def participants(config: StudyConfig) -> tuple[ParticipantSpec, ...]:
    """The listed participants, or else the cohort of ``config.cohort`` drawn from its seed.

    A drawn participant is an expert of a kind with an hours bucket of 2 or 3 and a Likert
    experience of 5-7, a novice with bucket 1 and experience 1-4 (the questionnaire's scales,
    docs/explanation/study.md §4); the movement-time factor is lognormal around 1, with
    ``cohort.movement_time_sd``.
    """
    if config.participants:
        return config.participants
    c = config.cohort
    rng = np.random.default_rng([config.seed, 1])
    shuffled = [int(k) for k in rng.permutation(c.size)]
    both = set(shuffled[: c.both_experts])
    avr = both | set(shuffled[c.both_experts : c.avr_experts])
    gamers_end = c.avr_experts + c.games_experts - c.both_experts
    games = both | set(shuffled[c.avr_experts : gamers_end])
    people = []
    for k in range(c.size):
        avr_hours, avr_exp = _skill(rng, k in avr)
        games_hours, games_exp = _skill(rng, k in games)
        people.append(
            ParticipantSpec(
                id=f"{c.id_prefix}{k + 1:02d}",
                avr_hours=avr_hours,
                games_hours=games_hours,
                avr_experience=avr_exp,
                games_experience=games_exp,
                age=int(rng.integers(AGE_RANGE[0], AGE_RANGE[1] + 1)),
                gender="m" if rng.uniform() < MALE_FRACTION else "f",
                movement_time_factor=float(
                    np.clip(rng.lognormal(0.0, c.movement_time_sd), 0.25, 4.0)
                ),
            )
        )
    return tuple(people)


def _skill(rng: np.random.Generator, expert: bool) -> tuple[int, int]:
    """(hours bucket, Likert experience) of an expert or a novice."""
    if expert:
        return int(rng.choice(EXPERT_BUCKETS)), int(rng.integers(5, 8))
    return 1, int(rng.integers(1, 5))
