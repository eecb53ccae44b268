"""The five AR modalities of the study (docs/study.md §3) as sets of AR layers."""

from __future__ import annotations

from dataclasses import dataclass

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
    """

    ghost: bool = False
    beam: bool = False
    distance_bar: bool = False
    grip_bar: bool = False
    target_mesh: bool = False

    def shows(self, cue: str | None) -> bool:
        """Whether the layer switched by ``cue`` (an attribute's name) is on; None: always."""
        return cue is None or bool(getattr(self, cue))


MODALITIES: dict[str, ArCues] = {
    "none": ArCues(),
    "manipulation": ArCues(beam=True, distance_bar=True, grip_bar=True),
    "embodiment": ArCues(ghost=True),
    "task": ArCues(target_mesh=True),
    "full": ArCues(ghost=True, beam=True, distance_bar=True, grip_bar=True, target_mesh=True),
}


def modality_cues(name: str) -> ArCues:
    """The AR layers of a modality; raises with the valid names for an unknown one."""
    if name not in MODALITIES:
        raise ConfigurationError(f"Unknown modality '{name}'. Valid modalities: {list(MODALITIES)}")
    return MODALITIES[name]
