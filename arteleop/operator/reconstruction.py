"""Moved in 0.3 to :mod:`arteleop.teleop.reconstruction` (the robot side): its names are
found here, with a warning, through 0.3."""

from arteleop.moved import moved_names

__getattr__ = moved_names(
    "arteleop.operator.reconstruction",
    dict.fromkeys(
        ("HandSample", "HandTrajectory", "SampleStatus", "StreamingReconstructor", "reconstruct"),
        "arteleop.teleop.reconstruction",
    ),
    until="0.3",
)
