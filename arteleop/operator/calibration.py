"""Moved in 0.3 to :mod:`arteleop.teleop.sensor_calibration` (the robot side): its names are
found here, with a warning, through 0.3."""

from arteleop.moved import moved_names

__getattr__ = moved_names(
    "arteleop.operator.calibration",
    dict.fromkeys(
        ("MAX_POSTURE_SPREAD_DEG", "SensorMounting", "calibrate", "calibrate_from_hold"),
        "arteleop.teleop.sensor_calibration",
    ),
    until="0.3",
)
