"""The electric gripper, checked against the simulator: geometry, limits, and a real grasp."""

import numpy as np
import pytest

from arteleop.errors import ArmCommandError
from arteleop.robot import ArmCommand
from arteleop.scene import RemoteSite
from tests.helpers import ik_down, reach_down


def test_pad_gap_spans_the_stroke(site: RemoteSite) -> None:
    closed, opened = site.gripper_gap_range_m
    stroke = site.robot.gripper.stroke_m
    assert stroke == pytest.approx(0.020833)  # URDF finger joint travel
    # Both fingers move by the stroke; the finger slot leaves about 0.5 mm when closed.
    assert opened - closed == pytest.approx(2 * stroke, abs=1e-6)
    assert closed == pytest.approx(0.0045 - 2 * 0.002, abs=2e-4)


@pytest.mark.parametrize("closure", [-0.1, 1.5, float("nan")])
def test_closure_outside_0_1_is_refused(site: RemoteSite, closure: float) -> None:
    with pytest.raises(ArmCommandError, match=r"gripper closure must be in \[0, 1\]"):
        site.robot.gripper.command(closure)
    with pytest.raises(ArmCommandError, match=r"ArmCommand.gripper_closure must be in \[0, 1\]"):
        ArmCommand(gripper_closure=closure)


def test_closure_reading_follows_the_command(site: RemoteSite) -> None:
    g = site.robot.gripper
    g.command(0.5)
    site.step(240)
    assert g.closure() == pytest.approx(0.5, abs=0.02)
    assert g.commanded_closure == 0.5


def test_gripper_pinches_the_rim_and_lifts_the_bowl(site: RemoteSite) -> None:
    ws = site.config.workspace
    site.step(60)  # let the bowl settle
    bowl = site.observe().bowl_m
    # Fingers open along base y: straddle the wall on the bowl's +y side.
    grasp = bowl + ws.bowl.grasp_offset_m()
    assert reach_down(site, grasp) < 2e-3
    g = site.robot.gripper
    g.command(1.0)
    site.step(240)
    assert site.observe().pads_touch_bowl == (True, True)
    # Force-limited: the fingers stop on the wall instead of pushing through it.
    assert g.pad_gap_m() > ws.bowl.wall_thickness_m - 1e-3
    # Lift 10 cm through the arm's motors; the bowl must come along.
    for dz in np.linspace(0.005, 0.10, 20):
        site.apply(ArmCommand(q_rad=ik_down(site, grasp + [0.0, 0.0, dz])))
        site.step(24)
    site.step(240)
    state = site.observe()
    assert state.bowl_m[2] - bowl[2] > 0.08
    assert state.grasped
