"""The operator's display: a viser web scene of the head camera's point cloud and AR layers.

The scene's world frame is Baxter's ``base`` frame (z up), so the cloud is drawn where the robot
saw it and AR layers given in the base frame line up with it. The view takes
:class:`DisplayFrame` s, plain data; it knows nothing of the simulator.
"""

from __future__ import annotations

from dataclasses import dataclass

import viser

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers import CloudLayer
from arteleop.errors import ConfigurationError
from arteleop.lifetime import Closeable


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
    """A running viser server that draws display frames, layer by layer; a context manager."""

    def __init__(self, config: ViewConfig | None = None) -> None:
        self.config = config = config or ViewConfig()
        self.server = viser.ViserServer(host=config.host, port=config.port, verbose=False)
        self.layers: list[Layer] = [CloudLayer(self.server.scene, config.point_size_m)]
        self.updates = 0
        """Frames shown so far."""

    @property
    def url(self) -> str:
        """Address to open in a browser."""
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    def show(self, frame: DisplayFrame) -> None:
        """Draw ``frame``: each layer its modality turns on, the others hidden.

        Returns once the update is handed to the server's sender, which delivers it to every
        connected browser.
        """
        for layer in self.layers:
            layer.draw(frame)
        self.server.flush()
        self.updates += 1

    def close(self) -> None:
        """Stop the server."""
        self.server.stop()
