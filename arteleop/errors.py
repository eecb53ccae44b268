"""The exceptions arteleop raises. Every one derives from :class:`ArteleopError`."""

from __future__ import annotations


class ArteleopError(Exception):
    """Root of every error arteleop raises on purpose."""


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
