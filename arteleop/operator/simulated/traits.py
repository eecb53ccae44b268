"""A simulated person's lasting traits: drawn once from stated distributions, kept across all of
that person's trials (docs/explanation/operator-model.md gives each one's source).

Nothing here depends on the display's AR layers: the traits are the person's, the same under
every display.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, replace

import numpy as np

from arteleop.checks import Bounds, check_fields


@dataclass(frozen=True)
class Expertise:
    """Weekly hours bucket (1: < 1 h, 2: 2-5 h, 3: > 5 h) for AR/VR and for video games."""

    avr_hours: int = 1
    games_hours: int = 1

    @property
    def avr_expert(self) -> bool:
        return self.avr_hours >= 2

    @property
    def games_expert(self) -> bool:
        return self.games_hours >= 2

    @property
    def expert(self) -> bool:
        return self.avr_expert or self.games_expert


@dataclass(frozen=True)
class OperatorTraits:
    """One person's traits; the defaults are the median novice.

    Attributes:
        confidence: How sure the person must be that an error is within its criterion to stop
            correcting (probability).
        grasp_criterion_scale: The person's grasp criterion as a share of the gripper's
            clearance around the bowl's wall (the task's tolerance).
        placement_criterion_m: How close to the target (m, in the table's plane) the person
            holds good enough.
        urgency_s: Effort after which the person's criterion has doubled (s): the longer a
            phase takes, the less it asks.
        glance_s: Time per glance while looking (s): a look averages its glances' errors.
        movement_time_factor: Scales every submovement's duration (below 1: faster, and by the
            speed-accuracy trade-off less accurate).
        depth_factor: Scales the SD of depth judged from the point cloud.
        depth_scale: How the person sees a depth interval in the rendered scene (1: true;
            below 1 compressed). A lasting error the person does not know of.
        bias_seed: Seeds the person's lasting proprioceptive biases, one per judgement (a
            judgement of the display lasts only through ``depth_scale``).
    """

    confidence: float = 0.95
    grasp_criterion_scale: float = 1.0
    placement_criterion_m: float = 0.010
    urgency_s: float = 8.0
    glance_s: float = 0.1
    movement_time_factor: float = 1.0
    depth_factor: float = 1.0
    depth_scale: float = 1.0
    bias_seed: int = 0

    def __post_init__(self) -> None:
        check_fields(self, {
            "confidence": Bounds(0.5, 0.999, "a probability"),
            "grasp_criterion_scale": Bounds(0.1, 3.0, "a share of the clearance"),
            "placement_criterion_m": Bounds(0.001, 0.1, "m"),
            "urgency_s": Bounds(0.5, 120.0, "s"),
            "glance_s": Bounds(0.02, 1.0, "s"),
            "movement_time_factor": Bounds(0.25, 4.0, "a factor"),
            "depth_factor": Bounds(0.1, 3.0, "a factor"),
            "depth_scale": Bounds(0.5, 2.0, "a factor on depth intervals"),
        })  # fmt: skip


@dataclass(frozen=True)
class TraitDistribution:
    """Where a cohort's traits come from: each a lognormal about a median (``*_sd``: SD of the
    log), or, for the confidence, the miss rate ``1 - confidence``.

    Attributes:
        miss_rate: Median of ``1 - confidence``.
        miss_rate_sd: Its log SD.
        grasp_criterion_sd: Log SD of ``grasp_criterion_scale`` (median 1).
        placement_criterion_m: Median placement criterion (m).
        placement_criterion_sd: Its log SD.
        urgency_s: Median urgency (s).
        urgency_sd: Its log SD.
        glance_s: Median glance (s).
        glance_sd: Its log SD.
        avr_depth_factor: ``depth_factor`` of an AR/VR expert.
        depth_scale_sd: Log SD of ``depth_scale`` (median 1).
        games_speed_factor: Movement-time factor of a video-game expert (on their own one).
    """

    miss_rate: float = 0.05
    miss_rate_sd: float = 0.5
    grasp_criterion_sd: float = 0.2
    placement_criterion_m: float = 0.010
    placement_criterion_sd: float = 0.3
    urgency_s: float = 8.0
    urgency_sd: float = 0.3
    glance_s: float = 0.1
    glance_sd: float = 0.2
    avr_depth_factor: float = 0.8
    depth_scale_sd: float = 0.15
    games_speed_factor: float = 0.88

    def __post_init__(self) -> None:
        log_sd = Bounds(0.0, 1.0, "the SD of a log")
        check_fields(self, {
            "miss_rate": Bounds(0.005, 0.2, "a probability: 1 - the confidence"),
            "placement_criterion_m": Bounds(0.002, 0.05, "m"),
            "urgency_s": Bounds(1.0, 60.0, "s"),
            "glance_s": Bounds(0.05, 0.3, "s"),
            "avr_depth_factor": Bounds(0.1, 3.0, "a factor"),
            "games_speed_factor": Bounds(0.25, 4.0, "a factor"),
            **dict.fromkeys(("miss_rate_sd", "grasp_criterion_sd", "placement_criterion_sd",
                             "urgency_sd", "glance_sd", "depth_scale_sd"), log_sd),
        })  # fmt: skip

    def draw(
        self, seed: int, person: str, expertise: Expertise, movement_time_factor: float = 1.0
    ) -> OperatorTraits:
        """The traits of ``person`` (an id) in a study seeded ``seed``: the same person gets the
        same traits in every trial, whatever else the study draws."""
        rng = np.random.default_rng([seed, zlib.crc32(person.encode()), 23])

        def lognormal(median: float, sd: float, low: float, high: float) -> float:
            return float(np.clip(median * np.exp(rng.normal(0.0, sd)), low, high))

        speed = movement_time_factor * (self.games_speed_factor if expertise.games_expert else 1)
        return OperatorTraits(
            confidence=1.0 - lognormal(self.miss_rate, self.miss_rate_sd, 0.005, 0.2),
            grasp_criterion_scale=lognormal(1.0, self.grasp_criterion_sd, 0.3, 2.0),
            placement_criterion_m=lognormal(
                self.placement_criterion_m, self.placement_criterion_sd, 0.002, 0.05
            ),
            urgency_s=lognormal(self.urgency_s, self.urgency_sd, 1.0, 60.0),
            glance_s=lognormal(self.glance_s, self.glance_sd, 0.05, 0.3),
            movement_time_factor=float(np.clip(speed, 0.25, 4.0)),
            depth_factor=self.avr_depth_factor if expertise.avr_expert else 1.0,
            bias_seed=int(rng.integers(2**31)),
            depth_scale=lognormal(1.0, self.depth_scale_sd, 0.5, 2.0),
        )

    def typical(self, expertise: Expertise | None = None) -> OperatorTraits:
        """The median person of the distribution (with ``expertise``'s effects)."""
        e = expertise or Expertise()
        return replace(
            OperatorTraits(),
            movement_time_factor=self.games_speed_factor if e.games_expert else 1.0,
            depth_factor=self.avr_depth_factor if e.avr_expert else 1.0,
        )
