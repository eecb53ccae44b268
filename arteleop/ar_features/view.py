"""The operator's display: a viser web scene of the head camera's point cloud.

The scene's world frame is Baxter's ``base`` frame (z up), so the cloud is drawn where the robot
saw it and AR layers given in the base frame line up with it. The view takes plain arrays; it
knows nothing of the simulator.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import viser
from numpy.typing import ArrayLike

from arteleop.errors import ConfigurationError
from arteleop.lifetime import Closeable

CLOUD_NODE = "/camera/cloud"


@dataclass(frozen=True)
class ViewConfig:
    """Where the web scene is served and how the cloud is drawn.

    Attributes:
        host: Interface to bind. The default serves this machine only; give ``0.0.0.0`` to let
            other machines (the operator's headset or laptop) connect.
        port: TCP port; if it is taken viser tries the next ones, and 0 picks any free port.
            :attr:`OperatorView.url` tells which one was bound.
        point_size_m: Diameter of a drawn point (m). A 320x240 cloud of the table at about 1.2 m
            has a point every 4 mm.
    """

    host: str = "127.0.0.1"
    port: int = 8080
    point_size_m: float = 0.004

    def __post_init__(self) -> None:
        if not 0 <= self.port <= 65535:
            raise ConfigurationError(f"ViewConfig.port={self.port} is not a TCP port (0..65535)")
        if self.point_size_m <= 0:
            raise ConfigurationError(f"ViewConfig.point_size_m={self.point_size_m} must be > 0")


class OperatorView(Closeable):
    """A running viser server showing the latest point cloud; a context manager."""

    def __init__(self, config: ViewConfig | None = None) -> None:
        self.config = config = config or ViewConfig()
        self.server = viser.ViserServer(host=config.host, port=config.port, verbose=False)
        self.updates = 0
        """Clouds shown so far."""

    @property
    def url(self) -> str:
        """Address to open in a browser."""
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    def show_cloud(self, points_m: ArrayLike, colors: ArrayLike) -> None:
        """Replace the drawn cloud: points (N, 3) in the base frame (m), colours (N, 3) uint8.

        Returns once the update is handed to the server's sender, which delivers it to every
        connected browser.
        """
        points = np.asarray(points_m, dtype=np.float32)
        rgb = np.asarray(colors, dtype=np.uint8)
        if points.ndim != 2 or points.shape[1] != 3 or rgb.shape != points.shape:
            raise ValueError(
                f"show_cloud needs points (N, 3) and colours (N, 3); got {points.shape} and "
                f"{rgb.shape}"
            )
        self.server.scene.add_point_cloud(
            CLOUD_NODE, points, rgb, point_size=self.config.point_size_m, precision="float32"
        )
        self.server.flush()
        self.updates += 1

    def close(self) -> None:
        """Stop the server."""
        self.server.stop()
