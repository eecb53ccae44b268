"""The task monitor's reading of grasps and releases, tick by tick, on hand-made site states."""

import numpy as np
from scipy.spatial.transform import Rotation

from arteleop.scene import BowlTracker, CameraGeometry, HeadCameraConfig, SiteState, Workspace
from arteleop.teleop import Outcome, TaskMonitor

WS = Workspace()
HELD, EMPTY = 0.88, 1.0
"""Measured closures: the fingers on the bowl's wall, and on nothing."""


def _state(height_m: float, closure: float, pads: bool, tilt_deg: float = 0.0) -> SiteState:
    """The bowl over its start, its bottom face's centre ``height_m`` over the table, tilted
    about x; ``pads``: both finger pads touch it."""
    T_base_bowl = np.eye(4)
    T_base_bowl[:3, :3] = Rotation.from_euler("x", tilt_deg, degrees=True).as_matrix()
    T_base_bowl[:3, 3] = [*WS.start_xy_m, WS.table_top_z_m + height_m]
    return SiteState(
        time_s=0.0, arm_q_rad=np.zeros(7), gripper_closure=closure, pads_touch_bowl=(pads, pads),
        T_base_bowl=T_base_bowl, bowl_speed_m_s=0.0,
        camera=CameraGeometry(HeadCameraConfig(), np.eye(4)), links={},
    )  # fmt: skip


def _monitor(*ticks: tuple[bool, SiteState]) -> TaskMonitor:
    """A monitor fed ``(gripper closed, state)`` control ticks, 10 ms apart."""
    monitor = TaskMonitor(WS, BowlTracker(WS.bowl))
    for k, (closed, state) in enumerate(ticks):
        monitor.control(0.01 * k, 0.1, closed, state)
    return monitor


def test_a_bowl_that_drops_out_of_the_closed_gripper_is_not_released_by_opening_it() -> None:
    """The fingers close on nothing while the bowl is in the air: it dropped (the default
    study's runs on 2dcb559 ended 10 such trials as successes, the bowl 6-38 cm off the target,
    when the participant opened its empty hand to reach for it again)."""
    monitor = _monitor(
        (True, _state(0.0, HELD, pads=True)),  # closed on the wall, on the table: not yet
        (True, _state(0.03, HELD, pads=True)),  # lifted in both pads: grasped
        (True, _state(0.02, EMPTY, pads=False)),  # falling, the fingers shut on nothing
        (True, _state(0.0, EMPTY, pads=False)),  # back on the table
        (False, _state(0.0, 0.5, pads=False)),  # the empty hand opens to reach again
    )
    assert not monitor.grasped and not monitor.released and monitor.grasp_attempts == 1
    assert monitor.operator_stopped() is Outcome.NOT_GRASPED


def test_a_bowl_set_down_is_released_even_if_the_fingers_slid_off_it_first() -> None:
    """Set down with the gripper closed, the fingers slide off the wall as the hand rises, and
    the closed, empty hand then pokes the bowl and tilts it: the opening is the release (a fix
    reverted in d1e9d44 turned such placements into timeouts)."""
    monitor = _monitor(
        (True, _state(0.03, HELD, pads=True)),
        (True, _state(0.0, HELD, pads=True)),  # set down, still held
        (True, _state(0.0, EMPTY, pads=False)),  # the fingers slid off the wall
        (True, _state(0.015, 0.99, pads=True, tilt_deg=20.0)),  # the empty hand tilts it
        (False, _state(0.0, 0.5, pads=False)),
    )
    assert monitor.released


def test_a_bowl_tilted_on_the_table_by_the_fingers_is_not_grasped() -> None:
    """Tilted 20 degrees on its foot's edge, the bowl's centre is 15 mm up but it has not left
    the table (in seed 2's run on 2dcb559 the fingers tilting it counted as a grasp and their
    opening as the release: a success with the bowl never moved, 44 cm off the target)."""
    tilted = _state(0.015, 0.2, pads=True, tilt_deg=20.0)
    assert tilted.bowl_m[2] > WS.table_top_z_m + 0.01
    monitor = _monitor((True, tilted), (True, tilted), (False, _state(0.0, 0.0, pads=False)))
    assert not monitor.grasped and not monitor.released


def test_a_bowl_that_tilts_as_it_slips_out_is_dropped_though_its_edge_is_low() -> None:
    """Lifted barely past the grasp's threshold, the bowl tilts as it slips out: when the
    fingers shut, its low edge is 8 mm over the table, its centre 41 mm (the delay example's P07,
    trial 8, on eb52e90: scored a success 23 cm off the target when the empty hand opened)."""
    tilt_deg = 30.0
    low = _state(0.0, EMPTY, pads=False, tilt_deg=tilt_deg)
    edge_m = WS.bowl.lowest_z_m(low.T_base_bowl) - WS.table_top_z_m  # below the table: negative
    monitor = _monitor(
        (True, _state(0.0, HELD, pads=True)),
        (True, _state(0.012, HELD, pads=True)),  # 12 mm up, level: grasped
        (True, _state(0.008 - edge_m, 0.963, pads=False, tilt_deg=tilt_deg)),  # edge 8 mm up
        (True, _state(0.0, EMPTY, pads=False)),  # on the table
        (False, _state(0.0, 0.5, pads=False)),  # the empty hand opens
    )
    assert monitor.grasp_attempts == 1 and not monitor.released


def test_a_bowl_caught_again_by_the_closed_fingers_is_released_when_they_open() -> None:
    """Set down too fast, the bowl slips out 3 cm above the table, and the fingers, still
    closed, catch its wall again with it leaning on the table: it is in the hand, and their
    opening is the release (seed 3's P15, trial 1, at 3879203: a timeout). Fingers that only
    poke it when shut (as in the second test) or never touch it again (the first) catch
    nothing."""
    slipped = (
        (True, _state(0.03, HELD, pads=True)),  # lifted: grasped
        (True, _state(0.03, EMPTY, pads=False)),  # slipped out 3 cm over the table
    )
    caught = _monitor(
        *slipped,
        (True, _state(0.015, 0.83, pads=True, tilt_deg=20.0)),  # caught, leaning on the table
        (False, _state(0.0, 0.5, pads=False)),
    )
    assert caught.released and caught.grasp_attempts == 1
    poked = _monitor(
        *slipped,
        (True, _state(0.015, 0.99, pads=True, tilt_deg=20.0)),  # the shut fingers poke it
        (False, _state(0.0, 0.5, pads=False)),
    )
    assert not poked.released
    reopened = _monitor(
        *slipped,
        (False, _state(0.0, 0.5, pads=False)),  # the hand opens: the closure is over
        (True, _state(0.0, 0.83, pads=True)),  # closed on it on the table: not lifted
        (False, _state(0.0, 0.5, pads=False)),
    )
    assert not reopened.released and reopened.grasp_attempts == 2
