"""The AR modalities as sets of AR layers: the five of the original study
(docs/explanation/study.md §3) and the predictive ghost, and any other set of layers named by a
cue-set label."""

from __future__ import annotations

from dataclasses import dataclass, fields

from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class ArCues:
    """Which AR layers the operator's display shows.

    Attributes:
        ghost: Embodiment: the robot model animated by the joint states.
        beam: Manipulation: red beam from the gripper to the bowl's closest grasp point.
        distance_bar: Manipulation: green bar, gripper-to-grasp-point distance.
        grip_bar: Manipulation: blue bar, gripper closure.
        target_mesh: Task: green mesh of the bowl at its target pose.
        predictive_ghost: Delay: the robot model where the commands already sent will put it,
            ahead of the delayed view (:class:`~arteleop.ar_features.PredictedArm`).
    """

    ghost: bool = False
    beam: bool = False
    distance_bar: bool = False
    grip_bar: bool = False
    target_mesh: bool = False
    predictive_ghost: bool = False

    def shows(self, cue: str | None) -> bool:
        """Whether the layer switched by ``cue`` (an attribute's name) is on; None: always."""
        return cue is None or bool(getattr(self, cue))

    @property
    def label(self) -> str:
        """The set's name: a preset's where it is one, else its layers joined by ``+``."""
        for name, cues in MODALITIES.items():
            if cues == self:
                return name
        return "+".join(name for name in LAYER_NAMES if getattr(self, name))


LAYER_NAMES: tuple[str, ...] = tuple(f.name for f in fields(ArCues))
"""The AR layers, as :class:`ArCues` names them."""

MODALITIES: dict[str, ArCues] = {
    "none": ArCues(),
    "manipulation": ArCues(beam=True, distance_bar=True, grip_bar=True),
    "embodiment": ArCues(ghost=True),
    "task": ArCues(target_mesh=True),
    "full": ArCues(ghost=True, beam=True, distance_bar=True, grip_bar=True, target_mesh=True),
    "predictive": ArCues(predictive_ghost=True),
}

STUDY_MODALITIES: tuple[str, ...] = ("none", "manipulation", "embodiment", "task", "full")
"""The original study's five modalities, in its order."""


def modality_cues(name: str) -> ArCues:
    """The AR layers of a cue-set label: a modality (``embodiment``), or modalities and layers
    joined by ``+`` (``ghost+predictive_ghost``, ``task+predictive``); raises with the valid
    names for an unknown one."""
    if name in MODALITIES:
        return MODALITIES[name]
    on: set[str] = set()
    for part in name.split("+"):
        if part in MODALITIES:
            on |= {n for n in LAYER_NAMES if getattr(MODALITIES[part], n)}
        elif part in LAYER_NAMES:
            on.add(part)
        else:
            raise ConfigurationError(
                f"Unknown modality '{name}'. Valid modalities: {list(MODALITIES)}; or AR layers "
                f"and modalities joined by '+' (layers: {', '.join(LAYER_NAMES)})"
            )
    return ArCues(**dict.fromkeys(on, True))
