"""The exceptions arteleop raises. Every one derives from :class:`ArteleopError`."""

from __future__ import annotations


class ArteleopError(Exception):
    """Root of every error arteleop raises on purpose."""


class BlasKernelWarning(UserWarning):
    """numpy was loaded before arteleop with another BLAS kernel than the one arteleop pins:
    seeded trials will differ from those of other machines (:mod:`arteleop.blas_kernel`)."""


class NumpyLoopsWarning(UserWarning):
    """numpy was loaded before arteleop with its AVX-512 math loops on: seeded trials may differ
    from those of other machines (:mod:`arteleop.numpy_loops`)."""


class RobotDataNotFoundError(ArteleopError):
    """The robot description (URDF, meshes) could not be found in the installed packages."""


class ConfigurationError(ArteleopError, ValueError):
    """A configuration value is invalid; the message names the field, the value and the range."""


class WorkspaceError(ConfigurationError):
    """The workspace cannot be used with this robot (out of reach, bowl the gripper can't span)."""


class CameraConfigError(ConfigurationError):
    """The camera configuration cannot work (for example, the camera does not see the table)."""


class RecordingError(ArteleopError):
    """A wearable recording is invalid. The message names the file, the line and the value."""


class ArmCommandError(ArteleopError):
    """A command the arm cannot take: the wrong shape, not finite, or outside the joint limits."""


class TrajectoryError(ArteleopError):
    """The trajectory generator could not plan a motion to the IK's target."""


class DisplayFrameError(ArteleopError):
    """What the loop handed the display is malformed (shapes, values)."""


class SimulationError(ArteleopError):
    """The simulator's state is not what arteleop built (e.g. the two PyBullet worlds differ)."""


class StudyDefinitionError(ConfigurationError):
    """A study definition is invalid: the message names the key (and, from a file, its line)."""


class RunFolderError(ArteleopError):
    """A run folder cannot be created, resumed or written: the message names the file."""


class FrameGraphError(ArteleopError):
    """A transform graph cannot answer or be built: no path between two frames, a malformed
    transform or covariance, or a graph file whose edge is corrupt (the message names it)."""


class CalibrationError(ArteleopError):
    """A calibration cannot be solved: the marker was not seen, or the poses were too few or too
    similar. The message says how many were usable and what is needed."""


class ReportWriteError(ArteleopError):
    """A report could not be written (a full disk, permissions): nothing of it was kept."""
