"""A study definition: who takes part, under which modalities, in which order, on which task.

Each TOML table maps one-to-one onto a frozen dataclass: the top level onto
:class:`StudyConfig`, ``[familiarization]`` onto :class:`FamiliarizationConfig`, ``[cohort]``
onto :class:`~arteleop.study.participants.CohortConfig` and each ``[[participants]]`` onto
:class:`~arteleop.study.participants.ParticipantSpec` (who takes part has a module of its own),
``[operator]`` onto the simulated participants' :class:`~arteleop.operator.TraitDistribution` and
``[hand_filter]`` onto the robot side's :class:`~arteleop.teleop.HandFilterConfig`. The defaults
mirror the original study (docs/explanation/study.md §4) and the operator model's frozen constants
(docs/explanation/operator-model.md).
"""

from __future__ import annotations

import math
from dataclasses import MISSING, dataclass, field, fields
from typing import Any

from arteleop.analysis.data import network_label
from arteleop.ar_features import LAYER_NAMES, MODALITIES, STUDY_MODALITIES, modality_cues
from arteleop.errors import ConfigurationError, StudyDefinitionError
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.traits import TraitDistribution
from arteleop.scene.camera_config import HeadCameraConfig
from arteleop.study.participants import CohortConfig, ParticipantSpec
from arteleop.study.pointing_design import MOST_PEOPLE, PointingDesign
from arteleop.study.questionnaire_items import (
    ORIGINAL_QUESTIONNAIRE,
    QuestionnaireItem,
    check_items,
)
from arteleop.study.study_constants import check_study_constants
from arteleop.teleop.hand_filter import HandFilterConfig
from arteleop.teleop.trial_task import POINTING, trial_task

MODALITY_NAMES: tuple[str, ...] = STUDY_MODALITIES
"""The original study's modalities, in its order: the default conditions."""
ORDER_SCHEMES: tuple[str, ...] = ("williams", "cyclic", "random", "listed")


@dataclass(frozen=True)
class FamiliarizationConfig:
    """Practice before the experimental trials (docs/explanation/study.md §4): start and target
    drawn at random inside the table area the arm reaches from above, under ``modality``.

    Attributes:
        trials: Practice trials per participant (the original: 3-4).
        modality: The AR modality of practice (the original: none).
        timeout_s: Simulated time after which a practice trial ends (s).
    """

    trials: int = 3
    modality: str = "none"
    timeout_s: float = 120.0

    def __post_init__(self) -> None:
        if self.trials < 0:
            raise StudyDefinitionError(f"familiarization.trials = {self.trials}: expected >= 0.")
        if not _is_cue_set(self.modality):
            raise StudyDefinitionError(
                f"familiarization.modality = {self.modality!r}; expected one of "
                f"{', '.join(MODALITIES)}, or layers joined by '+'."
            )
        _check_timeout("familiarization.timeout_s", self.timeout_s)


@dataclass(frozen=True)
class ConditionSpec:
    """One condition of a study: a set of AR layers shown over a network profile.

    Attributes:
        cues: What the display shows: modalities and AR layers, their layers together (``[]``
            none, ``["embodiment"]``, ``["ghost", "predictive_ghost"]``).
        round_trip_ms: Round-trip delay between operator and robot (ms): half of it each way,
            operator samples to the robot and camera frames back.
        jitter_ms: Standard deviation of each one-way delay (ms).
        loss: Chance that an operator sample is lost on its way, in [0, 1).
    """

    cues: tuple[str, ...] = ()
    round_trip_ms: float = 0.0
    jitter_ms: float = 0.0
    loss: float = 0.0

    def __post_init__(self) -> None:
        bad = [c for c in self.cues if c not in MODALITIES and c not in LAYER_NAMES]
        if bad:
            raise StudyDefinitionError(
                f"conditions.cues = {list(self.cues)}: unknown {bad[0]!r}; expected modalities "
                f"({', '.join(MODALITIES)}) or AR layers ({', '.join(LAYER_NAMES)})."
            )
        for key in ("round_trip_ms", "jitter_ms"):
            value = getattr(self, key)
            if not (math.isfinite(value) and value >= 0):
                raise StudyDefinitionError(f"conditions.{key} = {value}: expected 0 ms or more.")
        if not (math.isfinite(self.loss) and 0 <= self.loss < 1):
            raise StudyDefinitionError(
                f"conditions.loss = {self.loss}: expected a probability in [0, 1)."
            )

    @property
    def modality(self) -> str:
        """The cue set's label, as ``trials.csv`` records it (:attr:`ArCues.label`)."""
        return modality_cues("+".join(self.cues) or "none").label

    @property
    def name(self) -> str:
        """The condition's name: its cue set and network profile (``predictive@500ms``)."""
        return f"{self.modality}@{network_label(self.round_trip_ms, self.jitter_ms, self.loss)}"


@dataclass(frozen=True)
class StudyConfig:
    """A within-subject study of AR modalities on one task.

    Attributes:
        name: A name for the report.
        task: What every trial asks and how it is scored: ``"pick-and-place"`` (the original
            study's), ``"pointing"`` (a Fitts study under lag: ``pointing``, and the lags as
            ``conditions``), or a task of one's own as ``"package.module:NAME"``
            (:func:`~arteleop.teleop.trial_task`, docs/guides/extending.md).
        consent: The information and consent page shown to people (``arteleop study serve``),
            in Markdown (the study file's ``consent``, or the file its ``consent_file`` names);
            empty: the built-in page, which says this study's trials and timeout
            (:func:`arteleop.study.session_words.consent_text`).
        questionnaire: The statements each AR class a participant saw is rated on, 1-7, after
            the last trial (``[[questionnaire]]`` tables, or ``questionnaire_file``): the
            original study's three by default. Simulated participants answer the original's
            items only.
        instructions: The page on how to drive the robot, shown once before the first trial,
            in Markdown (the study file's ``instructions``, or the file its
            ``instructions_file`` names); empty: the built-in page
            (:func:`arteleop.study.session_words.instructions_text`).
        seed: Seed of everything random in the study: the cohort, the orders, the practice
            positions and every trial (each trial's seed derives from it and the trial's place).
        modalities: The conditions, in the order the order schemes number them: modalities
            (or AR layers joined by ``+``), all under ``delay_ms``.
        order: ``williams`` (a balanced Latin square: each condition follows each other equally
            often; for an odd count, 2n sequences), ``cyclic`` (n rotations), ``random``
            (a seeded permutation per participant) or ``listed`` (the sequences in ``orders``).
            Participant k takes sequence k modulo the count, so full balance needs a multiple
            of it.
        orders: With ``order = "listed"``, the sequences of modality names, each naming every
            modality once (e.g. a published study's own square).
        trials_per_modality: Experimental trials per modality: 1, as in the original and as
            the data format records.
        timeout_s: Simulated time after which an experimental trial ends as a timeout (s).
        delay_ms: One-way network delay between operator and robot (ms), in every trial.
        depth_aids: The display draws the depth aids in every trial, practice included
            (:attr:`~arteleop.ar_features.DisplayFrame.depth_aids`: a line from the gripper
            down to the table, a ring at its foot, the gripper's height in numbers), for every
            participant, simulated or real: what a flat screen lacks against the original's
            head-mounted display. Off by default, as in the original; the simulated participant
            judges them too (docs/explanation/operator-model.md).
        conditions: Instead of ``modalities`` and ``delay_ms``: the conditions, each a set of
            AR layers over a network profile (``[[conditions]]`` tables), e.g. delay crossed
            with cues; numbered in this order by the order schemes. Practice runs without
            delay.
        camera_offset_mm, camera_offset_deg: A mis-registered head camera in every trial: the
            pose the system uses for it is the true one moved by this translation (mm) and
            rotation vector (deg), in the camera's frame (``HeadCameraConfig``'s
            ``registration_offset_*``), so the point cloud and the tracked bowl sit off the
            ghost and the target by that much. Zero: a perfect registration.
        camera_pose: The camera's pose as the system has it registered, instead of the
            offsets: ``T_base_camera``, 4 rows of 4 numbers (m), e.g. a calibration's. In a
            study file, ``camera_graph = "calibration.json"`` takes it from the graph file that
            ``arteleop calibrate`` writes (a path relative to the study file). Empty: the true
            pose moved by the offsets.
        start_xy_m: Where the bowl starts in every experimental trial (base frame, m).
        target_xy_m: Where the bowl must go (base frame, m).
        familiarization: Practice trials.
        cohort: The simulated cohort, used when ``participants`` is empty.
        participants: Named participants; empty draws the cohort.
        operator: Where the simulated participants' lasting traits come from (their accuracy
            criterion, confidence, urgency, glance, expertise's effects); each participant's are
            drawn from it, the study's seed and their id.
        operator_params: The simulated participants' constants, the same for every person
            (:class:`~arteleop.operator.OperatorParams`, docs/explanation/operator-model.md):
            the model's by default. A study file changes one (``[operator_params]``, its
            plain numbers only) to see how far an answer rests on it, the constant at half and
            at twice its value: a sensitivity run, not another model.
        hand_filter: The 1€ filter on the operator's reconstructed hand, in every trial.
        pointing: With ``task = "pointing"``: the targets' distances and widths and the
            repetitions of each cell under each lag (the conditions, met in blocks).
    """

    name: str = "arteleop default study"
    task: str = "pick-and-place"
    consent: str = ""
    instructions: str = ""
    questionnaire: tuple[QuestionnaireItem, ...] = ORIGINAL_QUESTIONNAIRE
    seed: int = 0
    modalities: tuple[str, ...] = MODALITY_NAMES
    order: str = "williams"
    orders: tuple[tuple[str, ...], ...] = ()
    trials_per_modality: int = 1
    timeout_s: float = 120.0
    delay_ms: float = 0.0
    depth_aids: bool = False
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    camera_pose: tuple[tuple[float, ...], ...] = ()
    start_xy_m: tuple[float, float] = (0.68, -0.45)
    target_xy_m: tuple[float, float] = (0.68, -0.10)
    familiarization: FamiliarizationConfig = field(default_factory=FamiliarizationConfig)
    cohort: CohortConfig = field(default_factory=CohortConfig)
    participants: tuple[ParticipantSpec, ...] = ()
    operator: TraitDistribution = field(default_factory=TraitDistribution)
    operator_params: OperatorParams = field(default_factory=OperatorParams)
    hand_filter: HandFilterConfig = field(default_factory=HandFilterConfig)
    conditions: tuple[ConditionSpec, ...] = ()
    pointing: PointingDesign = field(default_factory=PointingDesign)

    def __post_init__(self) -> None:
        try:
            trial_task(self.task)
        except ConfigurationError as err:
            raise StudyDefinitionError(str(err)) from None
        if self.task == POINTING.name:
            _check_pointing(self)
        elif self.pointing != PointingDesign():
            raise StudyDefinitionError(
                f'pointing: the [pointing] table designs a pointing study; give task = "pointing" '
                f"with it (task is {self.task!r}), or remove the table."
            )
        if self.seed < 0:
            raise StudyDefinitionError(f"seed = {self.seed}: expected a whole number, 0 or more.")
        check_items(self.questionnaire)
        check_study_constants(self.operator_params)
        unknown = [m for m in self.modalities if not _is_cue_set(m)]
        if unknown or not self.modalities:
            raise StudyDefinitionError(
                f"modalities = {list(self.modalities)}: expected one or more of "
                f"{', '.join(MODALITIES)} (or AR layers joined by '+')."
            )
        if len(set(self.modalities)) != len(self.modalities):
            raise StudyDefinitionError(
                f"modalities = {list(self.modalities)}: each modality at most once."
            )
        if self.conditions:
            if self.modalities != MODALITY_NAMES or self.delay_ms:
                raise StudyDefinitionError(
                    "conditions: the [[conditions]] tables replace modalities and delay_ms; "
                    "give one or the other."
                )
            names = [c.name for c in self.conditions]
            for k, name in enumerate(names):
                if name in names[:k]:
                    raise StudyDefinitionError(
                        f"conditions: condition {k + 1} ({name}) repeats condition "
                        f"{names.index(name) + 1}; each condition at most once."
                    )
        if self.order not in ORDER_SCHEMES:
            raise StudyDefinitionError(
                f"order = {self.order!r}; expected one of {', '.join(ORDER_SCHEMES)}."
            )
        if (self.order == "listed") != bool(self.orders):
            raise StudyDefinitionError(
                f"orders = {[list(o) for o in self.orders]}: give sequences in orders exactly "
                f'when order = "listed" (order is {self.order!r}).'
            )
        names = self.condition_names
        for k, sequence in enumerate(self.orders):
            if sorted(sequence) != sorted(names):
                raise StudyDefinitionError(
                    f"orders = ...: sequence {k + 1}, {list(sequence)}, must name each of the "
                    f"{len(names)} conditions {list(names)} exactly once."
                )
        if self.trials_per_modality != 1:
            raise StudyDefinitionError(
                f"trials_per_modality = {self.trials_per_modality}: the study data format "
                "(docs/reference/data-format.md) holds one experimental trial per "
                "participant and modality, so 1 is the only value it can record."
            )
        _check_timeout("timeout_s", self.timeout_s)
        if not (math.isfinite(self.delay_ms) and 0 <= self.delay_ms < 500 * self.timeout_s):
            raise StudyDefinitionError(
                f"delay_ms = {self.delay_ms}: expected 0 ms or more, with a round trip shorter "
                f"than timeout_s ({self.timeout_s} s)."
            )
        for key, limit, unit in (("camera_offset_mm", 500, "mm"), ("camera_offset_deg", 45, "deg")):
            value = getattr(self, key)
            if (
                len(value) != 3
                or not all(math.isfinite(v) for v in value)
                or math.hypot(*value) > limit
            ):
                raise StudyDefinitionError(
                    f"{key} = {list(value)}: expected three numbers ({unit}, camera frame) whose "
                    f"length is at most {limit} {unit}."
                )
        if self.camera_pose:
            try:
                HeadCameraConfig(**self.camera_registration())
            except ConfigurationError:
                raise StudyDefinitionError(
                    f"camera_pose = {[list(row) for row in self.camera_pose]}: expected 4 rows of "
                    "4 numbers, a rigid transform (m), and no camera_offset_mm or "
                    "camera_offset_deg beside it."
                ) from None
        ids = [p.id for p in self.participants]
        twice = sorted({i for i in ids if ids.count(i) > 1})
        if twice:
            raise StudyDefinitionError(
                f"participants: the id {twice[0]!r} is used more than once; ids must be unique."
            )

    @property
    def planned_conditions(self) -> tuple[ConditionSpec, ...]:
        """The conditions in order: the ``[[conditions]]``, or each modality under
        ``delay_ms`` each way."""
        if self.conditions:
            return self.conditions
        return tuple(ConditionSpec((m,), round_trip_ms=2 * self.delay_ms) for m in self.modalities)

    @property
    def condition_names(self) -> tuple[str, ...]:
        """What ``orders`` names the conditions by: the modalities, or the conditions' names."""
        if self.conditions:
            return tuple(c.name for c in self.conditions)
        return self.modalities

    def camera_registration(self) -> dict[str, Any]:
        """The head camera's registration, as :class:`~arteleop.scene.HeadCameraConfig`'s
        fields."""
        return {
            "registration_offset_mm": self.camera_offset_mm,
            "registration_offset_deg": self.camera_offset_deg,
            "registered_pose": self.camera_pose or None,
        }


POINTING_UNUSED = ("questionnaire", "modalities", "trials_per_modality", "timeout_s", "delay_ms",
                   "camera_offset_mm", "camera_offset_deg", "camera_pose", "start_xy_m",
                   "target_xy_m", "familiarization", "hand_filter")  # fmt: skip
"""The keys of a pick-and-place study that a pointing study's trials do not read."""
_SCALARS = ("trials_per_modality", "timeout_s", "delay_ms", "start_xy_m", "target_xy_m",
            "camera_offset_mm", "camera_offset_deg", "modalities")  # fmt: skip
"""Of those, the keys whose value a message can quote in a line."""


def _check_pointing(study: StudyConfig) -> None:
    """A pointing study's lags are its conditions, which differ in round trip alone."""
    if not study.conditions:
        raise StudyDefinitionError(
            'task = "pointing": give its lags as [[conditions]] tables, one round_trip_ms each '
            "(cues = [] for all), e.g. round_trip_ms = 0 and round_trip_ms = 225."
        )
    timeout_ms = 1000 * study.pointing.timeout_s
    for k, condition in enumerate(study.conditions):
        if condition.cues or condition.jitter_ms or condition.loss:
            raise StudyDefinitionError(
                f"conditions: condition {k + 1} ({condition.name}): a pointing study's conditions "
                "are lags; give cues = [], jitter_ms = 0 and loss = 0, and round_trip_ms."
            )
        if condition.round_trip_ms >= timeout_ms:
            raise StudyDefinitionError(
                f"conditions: condition {k + 1}: round_trip_ms = {condition.round_trip_ms:g}: "
                f"expected less than pointing.timeout_s ({timeout_ms:g} ms), or every trial "
                "times out."
            )
    for f in fields(study):
        if f.name in POINTING_UNUSED:
            default = f.default_factory() if f.default is MISSING else f.default  # type: ignore[misc]
            if getattr(study, f.name) != default:
                value = getattr(study, f.name)
                value = list(value) if isinstance(value, tuple) else value
                given = f"{f.name} = {value!r}" if f.name in _SCALARS else f.name
                raise StudyDefinitionError(
                    f"{given}: a pointing study does not use it (its trials are the [pointing] "
                    "table's, without practice, on the default camera and hand filter, and it is "
                    "not served to people); remove it."
                )
    given = (f"participants: {len(study.participants)} listed" if study.participants
             else f"cohort.size = {study.cohort.size}")  # fmt: skip
    if (len(study.participants) or study.cohort.size) > MOST_PEOPLE:
        raise StudyDefinitionError(
            f"{given}: a pointing study takes at most {MOST_PEOPLE} participants (each one's "
            "trials have 10000 seeds of their own)."
        )


def _is_cue_set(label: str) -> bool:
    try:
        modality_cues(label)
    except ConfigurationError:
        return False
    return True


def _check_timeout(name: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0):
        raise StudyDefinitionError(f"{name} = {value}: expected a positive time (s).")
