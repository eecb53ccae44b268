"""The remote site: Baxter, the table with its bowl and markers, and the head camera, in PyBullet.

The world frame of the simulation is Baxter's ``base`` frame. Every check that can fail because
of the configuration runs in the constructor, so a bad setting stops the program at start-up.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import pybullet as p
from numpy.typing import ArrayLike, NDArray
from scipy.spatial.transform import Rotation

from arteleop.errors import CameraConfigError, WorkspaceError
from arteleop.lifetime import Closeable
from arteleop.robot import (
    GRIPPER_FRAME,
    HEAD_PAN_JOINT,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
    ArmCommand,
    Baxter,
    BaxterKinematics,
    TopDownReach,
    load_baxter_description,
)
from arteleop.robot.bullet_client import KeptBulletClient
from arteleop.robot.native_output import native_stdout_silenced
from arteleop.scene.bodies import add_bowl, add_start_cross, add_table, add_target_circle
from arteleop.scene.bowl_sight import BowlSight
from arteleop.scene.bowl_tracking import BowlTrack
from arteleop.scene.camera import HeadCamera, RGBDFrame
from arteleop.scene.camera_geometry import colocation_errors, landmark_problem
from arteleop.scene.gl_renderer import resolve_renderer
from arteleop.scene.mark_sight import MARK_HIT_TOLERANCE_M, MarksSight, start_line_m, target_line_m
from arteleop.scene.render_process import RenderProcess
from arteleop.scene.render_world import RenderWorld, SceneState
from arteleop.scene.sight_rays import first_hits
from arteleop.scene.site_checks import gripper_gap_range_m, gripper_span_problem, reach_problem
from arteleop.scene.site_config import SiteConfig
from arteleop.scene.site_frames import BASE_FRAME, BOWL_FRAME, SiteFrames
from arteleop.scene.site_state import SiteState
from arteleop.transforms import (
    invert_transform,
    make_transform,
    pybullet_pose_to_transform,
)

MOVING_JOINTS = (*RIGHT_ARM_JOINTS, *RIGHT_FINGER_JOINTS)
"""The joints a trial moves: the camera redraws the links they carry, and the bowl, each frame
(:class:`RenderWorld`); the rest of the scene it draws once."""


class RemoteSite(Closeable):
    """A running simulation of the remote site; a context manager (or call :meth:`close`).

    Its surface is plain data: :meth:`observe` returns a :class:`SiteState`, :meth:`apply` takes
    an :class:`~arteleop.robot.ArmCommand`, :meth:`step` advances the physics and
    :meth:`capture` renders the head camera. PyBullet's client and body ids stay inside.

    Two PyBullet worlds: one is simulated; the head camera draws ``render_world``'s, into which
    :meth:`capture` first copies the moving state. A body added to one world only is simulated
    but not seen, or seen but not simulated.
    """

    def __init__(self, config: SiteConfig | None = None) -> None:
        self.config = config = config or SiteConfig()
        ws = config.workspace
        self.description = description = load_baxter_description(config.robot)
        self.kinematics = BaxterKinematics(description.urdf_path)
        problem = reach_problem(ws, TopDownReach.from_kinematics(self.kinematics),
                                config.reach_margin)  # fmt: skip
        if problem is not None:
            raise WorkspaceError(problem)

        with native_stdout_silenced():
            self._client = KeptBulletClient(connection_mode=p.DIRECT)
        try:
            self._client.setGravity(0.0, 0.0, -9.81)
            self._client.setTimeStep(1.0 / config.physics_rate_hz)
            self._client.setPhysicsEngineParameter(numSolverIterations=config.solver_iterations)
            with native_stdout_silenced():
                self.robot = Baxter(
                    self._client,
                    description,
                    config.gripper,
                    left_arm_rad=config.rest_pose.left,
                    freeze_idle_joints=config.freeze_idle_joints,
                )
            self.robot.reset(config.rest_pose)
            self.gripper_gap_range_m = gripper_gap_range_m(
                self.robot.gripper, config.rest_pose.gripper_closure
            )
            problem = gripper_span_problem(self.gripper_gap_range_m, ws.bowl.wall_thickness_m)
            if problem is not None:
                raise WorkspaceError(problem)
            # PyBullet body ids, for the segmentation masks of tests: name -> id.
            self._bodies = {
                "robot": self.robot.body_id,
                "table": add_table(self._client, ws),
                "start_marker": add_start_cross(self._client, ws),
                "target_marker": add_target_circle(self._client, ws),
                "bowl": add_bowl(self._client, ws, ws.bowl_start_xy_m),
            }
            self._bowl_id = self._bodies["bowl"]
            self.renderer = resolve_renderer(config.camera.renderer)
            """What draws the head camera here: ``"gl"`` or ``"tiny"``."""
            self.render_world = RenderWorld(
                self.robot.urdf_path, ws, tuple(self._bodies.values()), MOVING_JOINTS,
                self.renderer,
            )  # fmt: skip
            self.camera = HeadCamera(
                self.render_world.render,
                config.camera,
                self.robot.link_transform(config.camera.mount_link),
                config.seed,
            )
            problem = landmark_problem(self.camera.geometry, ws.camera_landmarks_m())
            if problem is not None:
                raise CameraConfigError(
                    f"{problem}. Adjust HeadCameraConfig.pitch_down_deg, yaw_deg or mount_xyz_m."
                )
        except BaseException:
            if hasattr(self, "render_world"):
                self.render_world.close()
            self._client.disconnect()
            raise
        self._sight = BowlSight(ws.bowl, config.bowl_sight)
        target_line = target_line_m(ws)
        self._target_points = len(target_line)
        self._mark_points_m = np.vstack([target_line, start_line_m(ws)])
        self.frames = SiteFrames(
            self.kinematics,
            ws,
            self.camera.registered.T_base_camera,
            {HEAD_PAN_JOINT: 0.0, **config.rest_pose.as_dict()},
        )
        """The remote system's frames: the point cloud, the tracked bowl and the AR layers are
        placed through it, with the camera's registration."""
        self._T_camera_base_true = invert_transform(self.camera.T_base_camera)
        self._steps = 0
        self._renderer: RenderProcess | None = None
        self._requested_s = 0.0

    # -- time -----------------------------------------------------------------------------------
    @property
    def time_s(self) -> float:
        """Simulated time since the site was built (s)."""
        return self._steps / self.config.physics_rate_hz

    def step(self, n: int = 1) -> None:
        """Advance the physics by ``n`` steps of ``1 / physics_rate_hz`` seconds."""
        for _ in range(n):
            self._client.stepSimulation()
        self._steps += n

    # -- state ----------------------------------------------------------------------------------
    def observe(self, links: Sequence[str] = (GRIPPER_FRAME,)) -> SiteState:
        """The site's state now (ground truth), with ``T_base_link`` of the named ``links``."""
        robot = self.robot
        velocity, _ = self._client.getBaseVelocity(self._bowl_id)
        return SiteState(
            time_s=self.time_s,
            arm_q_rad=robot.arm_positions(),
            gripper_closure=robot.gripper.closure(),
            pads_touch_bowl=robot.gripper.touching(self._bowl_id),
            T_base_bowl=self._bowl_transform(),
            bowl_speed_m_s=float(np.linalg.norm(velocity)),
            camera=self.camera.registered,
            links={name: robot.link_transform(name) for name in links},
        )

    def apply(self, command: ArmCommand) -> None:
        """Send a command to the arm's position control and to the gripper; the physics acts
        on it from the next :meth:`step`. Raises ``ArmCommandError`` for joint targets outside
        the limits."""
        if command.q_rad is not None:
            self.robot.command_arm(command.q_rad)
        if command.gripper_closure is not None:
            self.robot.gripper.command(command.gripper_closure)

    def _bowl_transform(self) -> NDArray[np.float64]:
        """``T_base_bowl``: ground-truth pose of the bowl frame (centre of its bottom face)."""
        pos, quat = self._client.getBasePositionAndOrientation(self._bowl_id)
        # PyBullet reports the centre of mass; shift back to the bowl's own frame.
        T = pybullet_pose_to_transform(pos, quat)
        T[:3, 3] -= T[:3, 2] * self.config.workspace.bowl.center_of_mass_height_m
        return T

    def reset(self) -> None:
        """Back to the start of a trial: the arm at rest, the gripper open, the bowl at rest where
        it starts, and the site's clock at 0 s."""
        self.robot.reset(self.config.rest_pose)
        self.place_bowl(self.config.workspace.bowl_start_xy_m)
        self._steps = 0
        self._requested_s = 0.0

    def place_bowl(
        self,
        xy_m: tuple[float, float],
        velocity_m_s: tuple[float, float, float] = (0.0, 0.0, 0.0),
        angular_velocity_rad_s: tuple[float, float, float] = (0.0, 0.0, 0.0),
        tilt_rad: tuple[float, float] = (0.0, 0.0),
    ) -> None:
        """Teleport the bowl onto the table with its bottom centre over ``xy_m``, at rest unless
        given the velocities of its centre of mass (m/s, rad/s, base frame); upright, or tilted
        by the rotation vector ``(tilt_rad[0], tilt_rad[1], 0)`` (rad, about the base's x and
        y axes) with its foot's lowest edge on the table, as a bowl left leaning is."""
        ws = self.config.workspace
        if not any(tilt_rad):
            com = [xy_m[0], xy_m[1], ws.table_top_z_m + ws.bowl.center_of_mass_height_m]
            quat_xyzw: Sequence[float] = (0.0, 0.0, 0.0, 1.0)
        else:
            tilt = Rotation.from_rotvec([tilt_rad[0], tilt_rad[1], 0.0])
            lean = float(np.hypot(*tilt_rad))
            bottom = np.array([*xy_m, ws.table_top_z_m + ws.bowl.bottom_radius_m * np.sin(lean)])
            com = (bottom + tilt.apply([0.0, 0.0, ws.bowl.center_of_mass_height_m])).tolist()
            quat_xyzw = tilt.as_quat().tolist()
        self._client.resetBasePositionAndOrientation(self._bowl_id, com, quat_xyzw)
        self._client.resetBaseVelocity(self._bowl_id, velocity_m_s, angular_velocity_rad_s)

    def pose(
        self, arm_q_rad: ArrayLike, gripper_closure: float, bowl_m: ArrayLike, time_s: float
    ) -> None:
        """Set the scene to a recorded state, without physics: the right arm's joints (rad, in
        ``RIGHT_ARM_JOINTS`` order), the gripper's closure, the bowl upright with its bottom
        centre at ``bowl_m`` (base frame, m), and the site's clock at ``time_s`` (s). For
        replays; a trial that steps on from here starts from rest."""
        q = np.asarray(arm_q_rad, dtype=np.float64)
        self.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q.tolist(), strict=True)))
        self.robot.gripper.reset(float(gripper_closure))
        com = np.asarray(bowl_m, dtype=np.float64) + [
            0.0, 0.0, self.config.workspace.bowl.center_of_mass_height_m
        ]  # fmt: skip
        self._client.resetBasePositionAndOrientation(self._bowl_id, com.tolist(), (0, 0, 0, 1))
        self._client.resetBaseVelocity(self._bowl_id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        self._steps = round(time_s * self.config.physics_rate_hz)

    def sight_bowl(self) -> BowlTrack:
        """What the bowl tracker would report now, from rays instead of a rendered frame
        (:class:`~arteleop.scene.BowlSight`): found when the camera sees enough of the bowl,
        at its true position."""
        T_base_bowl = self._bowl_transform()
        hits = first_hits(
            self._client, self.camera.geometry.position_m, self._sight.surface_points_m(T_base_bowl)
        )
        track = self._sight.look(T_base_bowl, self.camera.geometry, hits, self.time_s)
        if track.position_m is None:
            return track
        # Seen in the camera's frame, placed in the base frame through the registration.
        self.frames.set_bowl_seen(
            self._T_camera_base_true @ make_transform(np.eye(3), track.position_m)
        )
        return replace(track, position_m=self.frames.T(BASE_FRAME, BOWL_FRAME)[:3, 3])

    def sight_marks(self) -> MarksSight:
        """How much of each mark on the table the point cloud would draw now, from rays instead
        of a rendered frame (:mod:`~arteleop.scene.mark_sight`)."""
        points = self._mark_points_m
        seen = self.camera.geometry.sees_points(points)
        miss = np.linalg.norm(
            first_hits(self._client, self.camera.geometry.position_m, points) - points, axis=1
        )
        seen &= np.nan_to_num(miss, nan=np.inf) <= MARK_HIT_TOLERANCE_M
        n = self._target_points
        return MarksSight(float(seen[:n].mean()), float(seen[n:].mean()))

    @property
    def T_cloud_true(self) -> NDArray[np.float64] | None:
        """Where the point cloud, placed through :attr:`frames`, shows a point of the real
        scene (4x4, base frame): the camera's registration error; None when there is none.
        Simulation only: a real system cannot know it."""
        registered = self.frames.T_base_camera
        if np.array_equal(registered, self.camera.T_base_camera):
            return None
        return registered @ self._T_camera_base_true

    def colocation_errors(
        self, points_base_m: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """How far virtual objects drawn at (N, 3) base-frame points land from the real ones in
        the camera's view, the view placed through :attr:`frames`: (N,) in the image (px) and
        (N,) in space (m). Measured against the camera's true pose (only errors use it)."""
        camera = self.camera
        if np.array_equal(self.frames.T_base_camera, camera.T_base_camera):
            # A perfect registration (the default) draws each point where it is: no error, at
            # each camera tick, without projecting it twice.
            finite = np.isfinite(np.reshape(points_base_m, (-1, 3))).all(axis=1)
            zero = np.where(finite, 0.0, np.nan)
            return zero, zero.copy()
        return colocation_errors(
            camera.T_base_camera, self.frames.T_base_camera, camera.intrinsics, points_base_m
        )

    def capture(self, with_segmentation: bool = False) -> RGBDFrame:
        """One head-camera frame of the current state, stamped with :attr:`time_s`."""
        self.render_world.sync(self.scene_state())
        return self.camera.capture(self.time_s, with_segmentation)

    def scene_state(self) -> SceneState:
        """What the camera needs of the simulation's current state."""
        robot = self.robot
        names = list(robot.joint_index)
        pos, quat = self._client.getBasePositionAndOrientation(self._bowl_id)
        return SceneState(
            dict(zip(names, robot.joint_positions(names).tolist(), strict=True)),
            tuple(pos),
            tuple(quat),
        )

    # -- rendering on another core --------------------------------------------------------------
    def start_render_process(self) -> RenderProcess:
        """Start the render process now (it takes about two seconds) rather than on the first
        :meth:`request_frame`; returns the running one if it runs already."""
        if self._renderer is None:
            self._renderer = RenderProcess(
                self.robot.urdf_path, self.config.workspace, self.render_world.body_ids,
                MOVING_JOINTS, self.renderer,
            )  # fmt: skip
        return self._renderer

    def request_frame(self, stride: int = 1) -> None:
        """Start rendering the current state in a render process of its own, so the loop goes on
        while another core renders; collect the frame with :meth:`poll_frame`. One frame at a
        time; the process starts on the first request unless already started. The frame keeps
        every ``stride``-th row and column of the full-size image."""
        request = self.camera.request(stride=stride)
        self.start_render_process().submit(self.scene_state(), request)
        self._requested_s = self.time_s

    @property
    def frame_pending(self) -> bool:
        """A requested frame is still being rendered."""
        return self._renderer is not None and self._renderer.busy

    def poll_frame(self) -> RGBDFrame | None:
        """The requested frame if it is ready (stamped with the time it was requested)."""
        raw = self._renderer.poll() if self._renderer is not None else None
        return None if raw is None else self.camera.frame(raw, self._requested_s)

    # -- lifetime -------------------------------------------------------------------------------
    def close(self) -> None:
        """Disconnect both PyBullet worlds and stop the render process."""
        if self._renderer is not None:
            self._renderer.close()
        self.render_world.close()
        if self._client.isConnected():
            self._client.disconnect()
