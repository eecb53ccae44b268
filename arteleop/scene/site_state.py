"""What can be observed of the remote site at one instant: plain data, no simulator handle."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np
from numpy.typing import NDArray

from arteleop.arrays import frozen_array
from arteleop.errors import ConfigurationError
from arteleop.robot.joints import GRIPPER_FRAME
from arteleop.scene.camera_geometry import CameraGeometry


@dataclass(frozen=True)
class SiteState:
    """The remote site at one instant, as the simulator knows it (ground truth), base frame.

    The robot-side controller reads its encoders from here; the loop builds the display from
    here; nothing else of the simulation leaves :class:`~arteleop.scene.RemoteSite`.

    Attributes:
        time_s: Simulated time (s).
        arm_q_rad: (7,) right-arm joint positions in ``RIGHT_ARM_JOINTS`` order (rad).
        gripper_closure: Measured gripper closure, 0 (open) .. 1 (closed).
        pads_touch_bowl: Whether the (left, right) finger pad touches the bowl.
        T_base_bowl: (4, 4) pose of the bowl's frame (centre of its bottom face).
        bowl_speed_m_s: Linear speed of the bowl's centre of mass (m/s).
        camera: The head camera's pose, as the remote system has it registered (the true pose
            unless ``HeadCameraConfig.registration_offset_*`` says otherwise), and field of view.
        links: ``T_base_link`` (4, 4) of each link asked for in ``RemoteSite.observe``.
    """

    time_s: float
    arm_q_rad: NDArray[np.float64]
    gripper_closure: float
    pads_touch_bowl: tuple[bool, bool]
    T_base_bowl: NDArray[np.float64]
    bowl_speed_m_s: float
    camera: CameraGeometry
    links: Mapping[str, NDArray[np.float64]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "arm_q_rad", frozen_array(self.arm_q_rad))
        object.__setattr__(self, "T_base_bowl", frozen_array(self.T_base_bowl))
        links = {name: frozen_array(T) for name, T in self.links.items()}
        object.__setattr__(self, "links", MappingProxyType(links))

    def link(self, name: str) -> NDArray[np.float64]:
        """``T_base_link`` of an observed link."""
        if name not in self.links:
            raise ConfigurationError(
                f"Link '{name}' was not observed; observed links: {sorted(self.links)}. Ask "
                "RemoteSite.observe(links=...) for it."
            )
        return self.links[name]

    @property
    def gripper_m(self) -> NDArray[np.float64]:
        """Position of the gripper's tool frame (m); needs ``GRIPPER_FRAME`` observed."""
        return self.link(GRIPPER_FRAME)[:3, 3]

    @property
    def bowl_m(self) -> NDArray[np.float64]:
        """Position of the bowl's frame, the centre of its bottom face (m)."""
        return self.T_base_bowl[:3, 3]

    @property
    def grasped(self) -> bool:
        """Both finger pads touch the bowl."""
        return all(self.pads_touch_bowl)
