"""The robot-side controller on plain data: no PyBullet, no site.

The loop is closed kinematically: the arm is wherever the last joint command put it, and the
encoders and the gripper's pose come from pinocchio's forward kinematics.
"""

import numpy as np
from scipy.spatial.transform import Rotation

from arteleop.operator import (
    ImuErrorConfig,
    RecordingInfo,
    WearableConfig,
    minimum_jerk,
    record_hand_motion,
)
from arteleop.robot import (
    GRIPPER_FRAME,
    REST_POSE,
    RIGHT_ARM_JOINTS,
    ArmCommand,
    BaxterDescription,
    BaxterKinematics,
)
from arteleop.scene import CameraGeometry, HeadCameraConfig, SiteState, Workspace
from arteleop.teleop import (
    ControllerConfig,
    ControllerState,
    LoopClock,
    LoopRates,
    TeleopController,
)


def _state(kin: BaxterKinematics, t: float, q: np.ndarray, closure: float) -> SiteState:
    T = kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)), GRIPPER_FRAME)
    return SiteState(
        time_s=t, arm_q_rad=q, gripper_closure=closure, pads_touch_bowl=(False, False),
        T_base_bowl=np.eye(4), bowl_speed_m_s=0.0,
        camera=CameraGeometry(HeadCameraConfig(), np.eye(4)), links={GRIPPER_FRAME: T},
    )  # fmt: skip


def test_the_controller_engages_and_the_gripper_follows_the_mapped_hand(
    description: BaxterDescription,
) -> None:
    kin = BaxterKinematics(description.urdf_path)
    rest = np.array(REST_POSE.right)
    rest_gripper = kin.frame_transform(REST_POSE.as_dict(), GRIPPER_FRAME)[:3, 3]
    config = ControllerConfig()
    hand_rest = rest_gripper - np.array(config.mapping.offset_m)  # maps onto the resting gripper
    hand_far = hand_rest + [0.10, 0.05, -0.12]
    t = np.arange(0.0, 1.5, 0.01)
    path = np.vstack(
        [np.repeat(hand_rest[None], 100, 0), minimum_jerk(hand_rest, hand_far, 1.5, t),
         np.repeat(hand_far[None], 250, 0)]
    )  # fmt: skip
    grip = np.r_[np.zeros(300), np.ones(len(path) - 300)]
    synth = record_hand_motion(
        path, Rotation.from_euler("y", np.full((len(path), 1), 0.4)), grip,
        RecordingInfo(rate_hz=100.0), WearableConfig(errors=ImuErrorConfig.ideal()),
        np.random.default_rng(0),
    )  # fmt: skip
    rec = synth.recording
    rates = LoopRates()
    ctrl = TeleopController(
        description.urdf_path, kin.limits(RIGHT_ARM_JOINTS), rest, rec.info,
        rates, Workspace().table_box(), config,
    )  # fmt: skip
    q, closure, clock = rest.copy(), 0.0, LoopClock(rates)
    states, engaged_at = [], None
    for i, sample_t in enumerate(rec.time_s - rec.time_s[0]):
        while True:  # run the clock up to this control tick and apply the physics ticks
            tick = clock.next()
            if tick.physics and (command := ctrl.physics_tick()) is not None:
                q = command.q_rad
            if tick.control:
                break
        ctrl.receive(sample_t, rec.sensor_quat_wxyz[i], float(rec.grip[i]))
        command = ctrl.control_tick(_state(kin, tick.time_s, q, closure))
        states.append(ctrl.state)
        if command is not None:
            assert isinstance(command, ArmCommand) and command.q_rad is None
            closure = command.gripper_closure
        if engaged_at is None and ctrl.engaged:
            engaged_at = tick.time_s
    calibration_s = rec.info.calibration.hold_s
    assert states[0] is ControllerState.CALIBRATING
    assert ControllerState.WAITING in states
    assert engaged_at is not None and calibration_s < engaged_at < calibration_s + 3.0
    # Engaged, the arm went where the hand maps: the gripper over the far point, 1:1.
    gripper = kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)), GRIPPER_FRAME)
    expected = np.array(config.mapping.offset_m) + hand_far
    assert np.linalg.norm(gripper[:3, 3] - expected) < 0.005
    assert gripper[:3, 2] @ [0.0, 0.0, -1.0] > 0.99  # pointing down
    assert closure == 1.0  # the pinch closed the gripper
    assert ctrl.last_ik is not None and ctrl.last_ik.reachable
