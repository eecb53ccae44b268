"""A printed marker drawn in the camera's scene: a textured square, visual only.

The scene needs only the printed square (:class:`PrintedSquare`), so ArUco markers, defined with
their detection in :mod:`arteleop.calibration.aruco`, and any other such print can be drawn.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Protocol

import cv2
import numpy as np
import pybullet as p
from numpy.typing import ArrayLike, NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.transforms import quat_wxyz_to_xyzw, transform_to_pose


class PrintedSquare(Protocol):
    """A square print: a black square of side ``side_m`` (m) in a white border of ``margin_m``
    (m), whose image (grey levels, square, uint8) covers both."""

    side_m: float
    margin_m: float

    def image(self) -> NDArray[np.uint8]: ...


class MarkerBody:
    """A marker drawn in a PyBullet world (visual only: it has no mass and no collision)."""

    def __init__(self, client: BulletClient, marker: PrintedSquare) -> None:
        self._client = client
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "marker.png"
            cv2.imwrite(str(path), cv2.cvtColor(marker.image(), cv2.COLOR_GRAY2RGB))
            texture = client.loadTexture(str(path))
        h = marker.side_m / 2 + marker.margin_m
        # TinyRenderer reads texture rows bottom-up: (u, v) = (0, 1) is the image's top left.
        shape = client.createVisualShape(
            p.GEOM_MESH,
            vertices=[[-h, h, 0.0], [h, h, 0.0], [h, -h, 0.0], [-h, -h, 0.0]],
            indices=[0, 2, 1, 0, 3, 2],
            uvs=[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
            normals=[[0.0, 0.0, 1.0]] * 4,
        )
        self.body_id = client.createMultiBody(0.0, -1, shape)
        client.changeVisualShape(self.body_id, -1, textureUniqueId=texture, rgbaColor=[1, 1, 1, 1])

    def place(self, T_base_marker: ArrayLike) -> None:
        """Put the marker's frame at ``T_base_marker`` (4x4, base frame, m)."""
        position, quat_wxyz = transform_to_pose(T_base_marker)
        self._client.resetBasePositionAndOrientation(
            self.body_id, position.tolist(), quat_wxyz_to_xyzw(quat_wxyz).tolist()
        )

    def remove(self) -> None:
        self._client.removeBody(self.body_id)
