"""Differential inverse kinematics of the right arm with mink.

Tasks: a frame task on the gripper (``right_gripper``) and a low-weight posture task that keeps the
arm near a natural pose and resolves the arm's redundancy. Limits: joint positions (the URDF's,
the elbow kept off straight: ``IKConfig.elbow_min_bend_rad``), joint velocities (the URDF's), and
collision avoidance between forearm/wrist/gripper and the table.

Each call to :meth:`ArmIK.step` integrates one QP solution over ``dt`` seconds, so the joint motion
per step never exceeds the velocity limits: a far target is approached over several control ticks
instead of jumping, and an unreachable one leaves the gripper at the nearest pose it can reach.
"""

from __future__ import annotations

from ctypes import c_int
from dataclasses import dataclass
from pathlib import Path

import daqp
import mink
import numpy as np
import qpsolvers
from mink.solve_ik import build_ik
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import ConfigurationError
from arteleop.robot.ik_limits import HingeConfigurationLimit, KeptVelocityLimit
from arteleop.robot.joints import GRIPPER_FRAME, RIGHT_ARM_JOINTS, JointLimits
from arteleop.robot.mujoco_model import (
    ARM_COLLISION_BODIES,
    TABLE_BODY,
    body_geoms,
    build_arm_model,
)

_DAMPING = 1e-6
"""Levenberg-Marquardt damping of every task (mink's ``damping``): keeps the QP's Hessian
positive definite where a task's Jacobian loses rank."""


@dataclass(frozen=True)
class IKConfig:
    """Weights, limits and tolerances of the IK.

    Attributes:
        position_cost: Frame-task weight on position errors (per metre).
        orientation_cost: Frame-task weight on orientation errors (per radian); lower than the
            position's because the bowl is symmetric and the position matters most.
        posture_cost: Posture-task weight (per radian); small, it resolves redundancy. At 1e-3
            the elbow drifted up into the head camera's view over a long teleoperated motion.
        lm_damping: Levenberg-Marquardt damping of the frame task, scaled by the task error:
            it settles the arm at the nearest pose when the target is out of reach (with 1e-3
            a wrist joint chattered on its limit) and leaves reachable targets unaffected.
        solver: QP solver for mink (``daqp``: fast dense active-set).
        collision_margin_m: Clearance kept between the arm's geoms and the table.
        collision_detection_m: Distance at which collision avoidance starts acting.
        unreachable_tolerance_m: Position error above which a target that a step no longer
            brings nearer (the task's error, weighted as its cost weighs it) is flagged
            unreachable.
        elbow_min_bend_rad: The elbow (``right_e1``) is kept bent at least this much (rad).
            Baxter's own limit, -0.05, lets it straighten, and a straight elbow is a
            singularity: bending it moves the wrist across the arm, not towards the shoulder, so
            no step brings a nearer target closer, and the arm stays stretched. In seed 3's P09,
            practice trial 1 (3879203), the hand drove the gripper to the edge of the reach,
            the elbow straightened, and the arm stayed there, 17 cm from every target after it,
            for the trial's last 90 s. Of 0.1, 0.2 and 0.3 rad, 0.1 still held the arm there
            and 0.2 freed it (that trial's IK targets replayed); it costs 4 mm of the
            shoulder-to-wrist distance (0.741 against 0.745 m). At or below -0.05 the joint's
            own limit holds.
    """

    position_cost: float = 1.0
    orientation_cost: float = 0.5
    posture_cost: float = 1e-2
    lm_damping: float = 1.0
    solver: str = "daqp"
    collision_margin_m: float = 0.01
    collision_detection_m: float = 0.05
    unreachable_tolerance_m: float = 0.005
    elbow_min_bend_rad: float = 0.2

    def __post_init__(self) -> None:
        for name in (
            "position_cost",
            "orientation_cost",
            "posture_cost",
            "unreachable_tolerance_m",
        ):
            if getattr(self, name) < 0:
                raise ConfigurationError(f"IKConfig.{name} must be >= 0, got {getattr(self, name)}")


@dataclass(frozen=True)
class IKResult:
    """Outcome of an IK step or solve.

    Attributes:
        q_rad: (7,) joint positions in ``RIGHT_ARM_JOINTS`` order.
        position_error_m: Distance between the gripper frame and the target.
        orientation_error_rad: Angle between the gripper frame's and the target's orientation.
        reachable: False when the target is out of reach (the arm stopped short of it).
        iterations: QP solves used.
    """

    q_rad: NDArray[np.float64]
    position_error_m: float
    orientation_error_rad: float
    reachable: bool
    iterations: int


class ArmIK:
    """mink IK for Baxter's right arm on a MuJoCo model of the same URDF."""

    def __init__(
        self,
        urdf_path: Path,
        limits: JointLimits,
        posture_rad: ArrayLike,
        table_center_m: ArrayLike | None = None,
        table_half_extents_m: ArrayLike | None = None,
        config: IKConfig | None = None,
    ) -> None:
        self.config = c = config or IKConfig()
        self.model = build_arm_model(urdf_path, table_center_m, table_half_extents_m)
        names = [self.model.joint(i).name for i in range(self.model.njnt)]
        if tuple(names) != RIGHT_ARM_JOINTS:
            raise ConfigurationError(
                f"MuJoCo arm model has joints {names}, expected {RIGHT_ARM_JOINTS}"
            )
        self.configuration = mink.Configuration(self.model)
        self.frame_task = mink.FrameTask(
            GRIPPER_FRAME, "body", position_cost=c.position_cost,
            orientation_cost=c.orientation_cost, lm_damping=c.lm_damping,
        )  # fmt: skip
        self.posture_task = mink.PostureTask(self.model, cost=c.posture_cost)
        self.posture_task.set_target(np.asarray(posture_rad, dtype=np.float64))
        self.tasks = [self.frame_task, self.posture_task]
        if limits.names != RIGHT_ARM_JOINTS:
            raise ConfigurationError(f"limits are for {limits.names}, expected {RIGHT_ARM_JOINTS}")
        velocities = dict(zip(RIGHT_ARM_JOINTS, limits.velocity.tolist(), strict=True))
        joints = HingeConfigurationLimit(self.model)
        elbow = int(self.model.joint("right_e1").qposadr[0])
        if not c.elbow_min_bend_rad < joints.upper[elbow]:
            raise ConfigurationError(
                f"IKConfig.elbow_min_bend_rad={c.elbow_min_bend_rad}: expected an angle below the "
                f"elbow's upper limit, {joints.upper[elbow]:.3f} rad"
            )
        joints.lower[elbow] = max(joints.lower[elbow], c.elbow_min_bend_rad)
        self.limits: list[mink.Limit] = [joints, KeptVelocityLimit(self.model, velocities)]
        if table_center_m is not None:
            arm = body_geoms(self.model, ARM_COLLISION_BODIES)
            table = body_geoms(self.model, (TABLE_BODY,))
            self.limits.append(
                mink.CollisionAvoidanceLimit(
                    self.model, [(arm, table)],
                    minimum_distance_from_collisions=c.collision_margin_m,
                    collision_detection_distance=c.collision_detection_m,
                )
            )  # fmt: skip
        self._gripper_body = self.model.body(GRIPPER_FRAME).id
        # The QP's arrays, kept across ticks (see _velocity): 6 frame-task rows and nv posture
        # rows; each limit's rows, whose count does not change (mink's collision limit always
        # gives one per geom pair, with an infinite bound for pairs out of range).
        nv = self.model.nv
        self._eye = np.eye(nv)
        self._W, self._e = np.empty((6 + nv, nv)), np.empty(6 + nv)
        m = sum(
            limit.compute_qp_inequalities(self.configuration, 0.01).h.size for limit in self.limits
        )
        self._G, self._h = np.empty((m, nv)), np.empty(m)
        self._h_lower, self._bound_types = np.full(m, -1e30), np.zeros(m, dtype=c_int)
        self._last_error = np.inf
        self._target = np.eye(4)

    def set_target(self, T_base_gripper: ArrayLike) -> None:
        """Target pose of the gripper frame in the base frame (4x4)."""
        self._target = np.array(T_base_gripper, dtype=np.float64)
        self.frame_task.set_target(mink.SE3.from_matrix(self._target))
        # A step stalls if it does not bring the gripper nearer this target than it is now.
        self._last_error = self._task_error(self.gripper_transform())[0]

    def gripper_transform(self) -> NDArray[np.float64]:
        """``T_base_gripper`` at the IK's current configuration."""
        # MuJoCo's own pose of the body (``Configuration.update`` ran its kinematics), without
        # mink's SE3 round trip through a quaternion: 8 us instead of 26 us, once per tick.
        data, body = self.configuration.data, self._gripper_body
        T = np.eye(4)
        T[:3, :3] = data.xmat[body].reshape(3, 3)
        T[:3, 3] = data.xpos[body]
        return T

    def reset(self, q_rad: ArrayLike) -> None:
        """Restart from joint positions ``q_rad`` (e.g. the measured state). Steps from joints
        beyond a position limit, the elbow straighter than ``IKConfig.elbow_min_bend_rad``
        among them, may find no solution: the limit then asks more of a step than the velocity
        limit allows (mink's limits, as here). The controller restarts it as it engages, from
        the arm at rest."""
        self.configuration.update(np.asarray(q_rad, dtype=np.float64))
        self._last_error = np.inf

    def step(self, dt: float, iterations: int = 1) -> IKResult:
        """Integrate ``iterations`` QP solutions of duration ``dt`` towards the target."""
        for _ in range(iterations):
            velocity = self._velocity(dt)
            self.configuration.integrate_inplace(velocity, dt)
        return self._result(iterations, float(np.linalg.norm(velocity)))

    def solve(
        self, dt: float = 0.05, max_iterations: int = 300, tolerance_m: float = 1e-4
    ) -> IKResult:
        """Iterate to convergence: for offline use (benchmarks, reach checks).

        Once the posture-weighted solution stalls, it is refined with the posture task almost
        off, so the posture only picks the branch and does not bias the answer.
        """
        cost = self.config.posture_cost
        _, iterations = self._iterate(dt, max_iterations // 2, tolerance_m)
        self.posture_task.set_cost(cost * 1e-3)
        try:
            refined, more = self._iterate(dt, max_iterations - iterations, tolerance_m)
        finally:
            self.posture_task.set_cost(cost)
        return IKResult(
            refined.q_rad,
            refined.position_error_m,
            refined.orientation_error_rad,
            refined.reachable,
            iterations + more,
        )

    def _iterate(self, dt: float, max_iterations: int, tolerance_m: float) -> tuple[IKResult, int]:
        result = self.step(dt)
        for i in range(2, max_iterations + 1):
            previous = result.position_error_m
            result = self.step(dt)
            converged = (
                result.position_error_m < tolerance_m and result.orientation_error_rad < 1e-3
            )
            if converged or abs(previous - result.position_error_m) < 1e-9:
                return result, i
        return result, max_iterations

    def _velocity(self, dt: float) -> NDArray[np.float64]:
        """mink's QP of this tick, solved: the joint velocity (rad/s).

        With daqp, the QP is assembled here as mink's ``build_ik`` assembles it, with the same
        operations in the same order, into arrays kept across ticks: mink rebuilds the posture
        task's constant rows and re-checks every matrix through qpsolvers at each tick, which
        cost more than daqp's solve of these seven unknowns. The rows go to daqp without
        qpsolvers' wrapper (inequalities only, no bounds or equalities). The joints are the
        same to the bit (tests compare them with mink's ``build_ik`` and ``solve_ik``).
        """
        if self.config.solver != "daqp":
            problem = build_ik(self.configuration, self.tasks, dt, _DAMPING, self.limits)
            solution = qpsolvers.solve_problem(problem, solver=self.config.solver)
            if not solution.found:
                raise mink.NoSolutionFound(self.config.solver)
            return solution.x / dt
        H, c = self._objective()
        G, h = self._G, self._h
        row = 0
        for limit in self.limits:
            rows = limit.compute_qp_inequalities(self.configuration, dt)
            n = rows.h.size
            G[row : row + n] = rows.G
            h[row : row + n] = rows.h
            row += n
        x, _, exitflag, _ = daqp.solve(H, c, G, h, self._h_lower, self._bound_types)
        if exitflag <= 0:
            raise mink.NoSolutionFound(self.config.solver)
        return x / dt

    def _objective(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(H, c)`` of the frame and posture tasks, as mink's ``_compute_qp_objective``
        stacks their weighted residuals: ``H = W^T W`` plus the damping on the diagonal,
        ``c = -e^T W``."""
        configuration, posture, W, e = self.configuration, self.posture_task, self._W, self._e
        W[:6], e[:6], mu_frame = self.frame_task.compute_qp_residual(configuration)
        # The posture task's Jacobian is the identity and, for hinge joints, its error is
        # q - q*, which is what mj_differentiatePos gives mink.
        W[6:] = posture.cost[:, None] * self._eye
        e[6:] = posture.cost * (-posture.gain * (configuration.q - posture.target_q))
        mu_posture = posture.lm_damping * float(e[6:] @ e[6:])
        H = W.T @ W
        c = -(e @ W)
        H.flat[:: H.shape[0] + 1] += _DAMPING + (mu_frame + mu_posture)
        return H, c

    def _task_error(self, T: NDArray[np.float64]) -> tuple[float, float, float]:
        """The frame task's error at the gripper pose ``T``, weighted as its cost weighs it,
        and its position (m) and orientation (rad) errors."""
        pos_err = float(np.linalg.norm(T[:3, 3] - self._target[:3, 3]))
        cos = (np.trace(T[:3, :3].T @ self._target[:3, :3]) - 1.0) / 2.0
        rot_err = float(np.arccos(np.clip(cos, -1.0, 1.0)))
        c = self.config
        return (
            float(np.hypot(c.position_cost * pos_err, c.orientation_cost * rot_err)),
            pos_err,
            rot_err,
        )

    def _result(self, iterations: int, speed: float) -> IKResult:
        # Stalled: the step did not bring the task nearer its target, as the QP weighs it. By
        # the position alone, the wrist turning to the hand's orientation as the robot engaged
        # (the position's error growing for half a second) was flagged out of reach.
        error, pos_err, rot_err = self._task_error(self.gripper_transform())
        stalled = speed < 1e-3 or error >= self._last_error - 1e-6
        reachable = not (pos_err > self.config.unreachable_tolerance_m and stalled)
        self._last_error = error
        return IKResult(self.configuration.q.copy(), pos_err, rot_err, reachable, iterations)
