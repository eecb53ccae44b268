"""What defines the simulated remote site: its workspace, camera, physics and robot settings."""

from __future__ import annotations

from dataclasses import dataclass, field

from arteleop.errors import ConfigurationError
from arteleop.robot import REST_POSE, ArmPose, BaxterDescriptionConfig, GripperConfig
from arteleop.scene.bowl_sight import BowlSightConfig
from arteleop.scene.camera_config import HeadCameraConfig
from arteleop.scene.workspace import Workspace


@dataclass(frozen=True)
class SiteConfig:
    """Everything that defines the simulated remote site.

    Attributes:
        workspace: Table, bowl and markers.
        camera: The head RGB-D camera.
        physics_rate_hz: Physics steps per simulated second (>= 240).
        solver_iterations: Iterations of PyBullet's constraint solver per step (its default,
            50). Fewer make a step cheaper, most of all while the pads hold the bowl, and change
            the grasp's dynamics: benchmarks/bench_physics.py compares outcomes and placement
            errors over the study's trials.
        reach_margin: Fraction of the arm's maximum reach kept free at start and target.
        robot: How the robot's URDF is prepared.
        gripper: Electric gripper settings.
        rest_pose: Arm pose before each trial.
        freeze_idle_joints: Simulate only the right arm and its fingers; the left arm (at
            ``rest_pose.left``) and the head become rigid, for about four times cheaper physics.
            False simulates every joint of the URDF (see :class:`arteleop.robot.Baxter`).
        seed: Seed of every random source of the site (depth noise).
        bowl_sight: The model of the bowl tracker for frames that are not rendered.
    """

    workspace: Workspace = field(default_factory=Workspace)
    camera: HeadCameraConfig = field(default_factory=HeadCameraConfig)
    physics_rate_hz: float = 240.0
    solver_iterations: int = 50
    reach_margin: float = 0.05
    robot: BaxterDescriptionConfig = field(default_factory=BaxterDescriptionConfig)
    gripper: GripperConfig = field(default_factory=GripperConfig)
    rest_pose: ArmPose = REST_POSE
    freeze_idle_joints: bool = True
    seed: int = 0
    bowl_sight: BowlSightConfig = field(default_factory=BowlSightConfig)

    def __post_init__(self) -> None:
        if self.physics_rate_hz < 240:
            raise ConfigurationError(
                f"physics_rate_hz={self.physics_rate_hz}: use at least 240 Hz for stable grasps"
            )
        if isinstance(self.solver_iterations, bool) or not (
            isinstance(self.solver_iterations, int) and self.solver_iterations >= 1
        ):
            raise ConfigurationError(
                f"solver_iterations={self.solver_iterations!r}: use a whole number >= 1 "
                "(PyBullet's default is 50)"
            )
        if not 0 <= self.reach_margin < 0.5:
            raise ConfigurationError(f"reach_margin={self.reach_margin} must be in [0, 0.5)")
