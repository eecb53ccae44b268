"""ArUco markers: the printed square and finding its pose in a camera image with OpenCV (its
drawn copy in the camera's scene is :class:`arteleop.scene.MarkerBody`).

Marker frame (OpenCV's): origin at the centre of the black square, x to the right and y up as
the marker is printed, z out of the printed face (towards a camera that sees it).
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.scene.camera_config import CameraIntrinsics
from arteleop.transforms import make_transform

_TEXTURE_PX = 64
"""Texture pixels per marker cell: enough that the drawn edges are the renderer's, not the
texture's."""


@dataclass(frozen=True)
class ArucoMarker:
    """A printed ArUco marker.

    Attributes:
        marker_id: Its id in the dictionary.
        side_m: Side of the black square (m), the size OpenCV's pose estimate needs.
        margin_m: White border around the black square (m); detection needs one.
        dictionary: An OpenCV predefined dictionary, e.g. ``DICT_4X4_50``.
    """

    marker_id: int = 7
    side_m: float = 0.15
    margin_m: float = 0.03
    dictionary: str = "DICT_4X4_50"

    def __post_init__(self) -> None:
        code = getattr(cv2.aruco, self.dictionary, None)
        if not self.dictionary.startswith("DICT_") or not isinstance(code, int):
            raise ConfigurationError(
                f"ArucoMarker.dictionary={self.dictionary!r} is not an OpenCV ArUco dictionary; "
                "use one such as 'DICT_4X4_50' or 'DICT_6X6_250'"
            )
        size = cv2.aruco.getPredefinedDictionary(code).bytesList.shape[0]
        if not 0 <= self.marker_id < size:
            raise ConfigurationError(
                f"ArucoMarker.marker_id={self.marker_id} is not in {self.dictionary}, whose ids "
                f"are 0..{size - 1}"
            )
        if not 0.01 <= self.side_m <= 1.0 or not 0 <= self.margin_m <= self.side_m:
            raise ConfigurationError(
                f"ArucoMarker needs 0.01 <= side_m <= 1 m and 0 <= margin_m <= side_m; got "
                f"side_m={self.side_m}, margin_m={self.margin_m}"
            )

    @property
    def opencv_dictionary(self) -> cv2.aruco.Dictionary:
        return cv2.aruco.getPredefinedDictionary(getattr(cv2.aruco, self.dictionary))

    @property
    def corners_m(self) -> NDArray[np.float64]:
        """The black square's corners in the marker frame (4, 3), in OpenCV's order: top left,
        top right, bottom right, bottom left."""
        h = self.side_m / 2
        return np.array([[-h, h, 0.0], [h, h, 0.0], [h, -h, 0.0], [-h, -h, 0.0]])

    def image(self) -> NDArray[np.uint8]:
        """The printed marker with its white border, grey levels (square, uint8)."""
        dictionary = self.opencv_dictionary
        cells = dictionary.markerSize + 2  # the code's cells and the black frame around them
        side_px = cells * _TEXTURE_PX
        square = cv2.aruco.generateImageMarker(dictionary, self.marker_id, side_px)
        border = round(self.margin_m / self.side_m * side_px)
        return cv2.copyMakeBorder(square, *[border] * 4, cv2.BORDER_CONSTANT, value=255)


@dataclass(frozen=True)
class MarkerObservation:
    """One marker found in one image.

    Attributes:
        T_camera_marker: The marker's pose in the camera's optical frame (4x4, m).
        corners_px: (4, 2) corners as detected (u right, v down), in :attr:`ArucoMarker.corners_m`'s
            order.
        reprojection_error_px: RMS distance between the detected corners and the corners
            projected from the estimated pose.
    """

    T_camera_marker: NDArray[np.float64]
    corners_px: NDArray[np.float64]
    reprojection_error_px: float


def detect_marker(
    rgb: NDArray[np.uint8], intrinsics: CameraIntrinsics, marker: ArucoMarker
) -> MarkerObservation | None:
    """Find ``marker`` in an RGB image and estimate its pose (OpenCV's ArUco detector with
    sub-pixel corners, then ``solvePnP`` for a square); None if it is not in the image."""
    parameters = cv2.aruco.DetectorParameters()
    parameters.cornerRefinementMethod = cv2.aruco.CORNER_REFINE_SUBPIX
    detector = cv2.aruco.ArucoDetector(marker.opencv_dictionary, parameters)
    corners, ids, _ = detector.detectMarkers(cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY))
    if ids is None or marker.marker_id not in ids.ravel():
        return None
    found = corners[list(ids.ravel()).index(marker.marker_id)].reshape(4, 2).astype(np.float64)
    ok, rvec, tvec = cv2.solvePnP(
        marker.corners_m, found, intrinsics.K, None, flags=cv2.SOLVEPNP_IPPE_SQUARE
    )
    if not ok:
        return None
    projected, _ = cv2.projectPoints(marker.corners_m, rvec, tvec, intrinsics.K, None)
    error = float(np.sqrt(np.mean(np.sum((projected.reshape(4, 2) - found) ** 2, axis=1))))
    T = make_transform(cv2.Rodrigues(rvec)[0], tvec.ravel())
    return MarkerObservation(T, found, error)
