"""The operator's display: a viser web scene of the head camera's point cloud and AR layers.

The scene's world frame is Baxter's ``base`` frame (z up), so the cloud is drawn where the robot
saw it and AR layers given in the base frame line up with it. The view takes
:class:`DisplayFrame` s, plain data; it knows nothing of the simulator.
"""

from __future__ import annotations

import contextlib
import io
import ipaddress
import logging
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import viser
from numpy.typing import NDArray

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.client_errors import quiet_client_errors
from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.host import check_host
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers import (
    BeamLayer,
    CloudLayer,
    DepthAidsLayer,
    DistanceBarLayer,
    GhostLayer,
    GripBarLayer,
    PredictiveGhostLayer,
    TargetLayer,
)
from arteleop.ar_features.link_pacer import LinkPacer
from arteleop.ar_features.links import LinkGate, check_public_url, link_url
from arteleop.ar_features.modalities import ArCues
from arteleop.ar_features.panel import ModalityPanel
from arteleop.errors import ConfigurationError
from arteleop.lifetime import Closeable
from arteleop.transforms import sight_is_vertical

DELIVERY_TIMEOUT_S = 5.0
"""Longest wait for the tabs to confirm they have what was shown (s): a tab in the background
draws nothing."""


@dataclass(frozen=True)
class ViewConfig:
    """Where the web scene is served and how the cloud is drawn.

    Attributes:
        host: Interface to bind. The default serves this machine only; give ``0.0.0.0`` to let
            other machines (the operator's headset or laptop) connect.
        port: TCP port; if it is taken viser tries the next ones, and 0 picks any free port.
            :attr:`OperatorView.url` tells which one was bound.
        point_overlap: A drawn point's width as a share of its pixel's footprint at its distance
            (above 1: neighbours overlap a little, so no gaps show between them).
        vertical_fov_deg: The head camera's vertical field of view (the Kinect's 57 deg
            horizontal over 640x480 pixels gives 44.3 deg); the browser camera's is wider by
            the image's margin.
        horizontal_fov_deg: The head camera's horizontal field of view: a browser whose scene
            is narrower than the camera's 4:3 widens its vertical field until the whole
            camera image fits beside the docked panel.
        image_margin: The share of the camera image's width and height shown beyond each of
            its edges (0-0.5), empty of the cloud: what is drawn just outside the image stays in
            view (the gripper at rest lies a few pixels past its right edge, and its gizmo and
            ghost beyond).
        layer_panel: A panel to switch the AR layers live; off where the layers are a
            study's condition, not the viewer's choice (``arteleop study serve``).
        links: Admit only browsers that open a link with an allowed token
            (:attr:`OperatorView.gate`); none until tokens are allowed.
        public_url: The address browsers reach the view at through a reverse proxy or a
            tunnel (``https://study.example.org``), which links and :attr:`OperatorView.url`
            name instead of this machine's; None: this machine's address.
    """

    host: str = "127.0.0.1"
    port: int = 8080
    point_overlap: float = 1.25
    vertical_fov_deg: float = 44.3
    horizontal_fov_deg: float = 57.0
    image_margin: float = 0.1
    layer_panel: bool = True
    links: bool = False
    public_url: str | None = None

    def fitting_fov_rad(self, aspect: float) -> float:
        """The vertical field of view (rad) that shows the whole camera image and its margin in
        a scene of ``aspect`` (width over height)."""
        widen = 1 + 2 * self.image_margin
        half_v = np.tan(np.radians(self.vertical_fov_deg) / 2) * widen
        half_h = np.tan(np.radians(self.horizontal_fov_deg) / 2) * widen
        return float(2 * np.arctan(max(half_v, half_h / aspect)))

    @property
    def half_fov_tan(self) -> tuple[float, float]:
        """The tangents of the head camera's half fields of view, horizontal and vertical."""
        return (
            float(np.tan(np.radians(self.horizontal_fov_deg) / 2)),
            float(np.tan(np.radians(self.vertical_fov_deg) / 2)),
        )

    @property
    def image_aspect(self) -> float:
        """The camera image's width over its height."""
        horizontal, vertical = self.half_fov_tan
        return horizontal / vertical

    def __post_init__(self) -> None:
        if self.public_url is not None:
            object.__setattr__(self, "public_url", check_public_url(self.public_url))
        if not 0 <= self.port <= 65535:
            raise ConfigurationError(f"ViewConfig.port={self.port} is not a TCP port (0..65535)")
        if not (math.isfinite(self.image_margin) and 0 <= self.image_margin <= 0.5):
            raise ConfigurationError(
                f"ViewConfig.image_margin={self.image_margin}: expected 0-0.5 (a share of the "
                "camera image's width and height)."
            )
        if not (math.isfinite(self.point_overlap) and 0.5 <= self.point_overlap <= 4):
            raise ConfigurationError(
                f"ViewConfig.point_overlap={self.point_overlap}: expected 0.5-4 (a share of a "
                "point's footprint)."
            )


_log = logging.getLogger(__name__)


def _wake_senders(server: viser.ViserServer) -> None:
    """Wake each of ``server``'s senders (the broadcast's, each browser's) from its own event
    loop: one may wait on an event set from another thread (:meth:`OperatorView._send`). A
    sender woken for nothing sends an empty window. viser's internals, as 1.1.1 has them (it is
    pinned); absent, nothing is done."""
    websock = getattr(server, "_websock_server", None)
    clients = getattr(websock, "_client_state_from_id", {})
    buffers = [getattr(websock, "_broadcast_buffer", None)]
    buffers += [getattr(state, "message_buffer", None) for state in list(clients.values())]
    for buffer in buffers:
        event, loop = getattr(buffer, "message_event", None), getattr(buffer, "event_loop", None)
        if event is None or loop is None:
            continue

        def wake(event: Any = event) -> None:
            event.clear()
            event.set()

        with contextlib.suppress(RuntimeError):  # a loop already closed has no sender to wake
            loop.call_soon_threadsafe(wake)


class OperatorView(Closeable):
    """A running viser server that draws display frames, layer by layer; a context manager.

    With ``assets`` it draws every AR layer (ghost, beam, distance and grip bars, target) over
    the point cloud; without, the point cloud alone. A panel switches the modality, or single
    layers, live: the choice overrides the frames' own cues (:attr:`cues`) until the panel is
    set back to follow the trial. The browser's camera starts at the head camera's pose, looking
    where it looks (egocentric, as the original HMD view); "Egocentric view" returns there.
    """

    def __init__(self, config: ViewConfig | None = None, assets: ViewAssets | None = None) -> None:
        self.config = config = config or ViewConfig()
        self.host = check_host(config.host)
        """Whether only this machine can connect, and where to open the view."""
        # viser prints its own banner whatever ``verbose`` says; the caller prints the address.
        quiet_client_errors()  # a browser's bad message is its own: one line, no traceback
        with contextlib.redirect_stdout(io.StringIO()):
            self.server = server = viser.ViserServer(
                host=config.host, port=config.port, verbose=False
            )
        # Before anything is drawn: a browser without a link must never be sent the scene.
        self.gate = LinkGate(server) if config.links else None
        server.scene.set_up_direction("+z")  # Baxter's base frame
        server.gui.configure_theme(show_logo=False, show_share_button=False)
        # Docked beside the scene, the panel hides none of the camera image (floating, it
        # covered the right arm at rest and the bowl's start).
        server.gui.main_panel.dock_right()
        self.cloud = CloudLayer(server, config.point_overlap, config.half_fov_tan)
        """The point cloud's layer: what it has sent."""
        self.layers: list[Layer] = [
            self.cloud,
            DepthAidsLayer(server.scene),
        ]
        if assets is not None:
            self.layers += [
                GhostLayer(server, assets),
                PredictiveGhostLayer(server, assets),
                TargetLayer(server.scene, assets),
                BeamLayer(server.scene),
                DistanceBarLayer(server.scene),
                GripBarLayer(server.scene),
            ]
        cues = [layer.cue for layer in self.layers if layer.cue]
        self._panel = ModalityPanel(server.gui, cues) if config.layer_panel else None
        self._T_base_camera: NDArray[np.float64] | None = None
        server.gui.add_button("Egocentric view").on_click(lambda _: self._egocentric(True))
        server.on_client_connect(self._follow_shape)
        self.updates = 0
        """Frames shown so far."""
        self.races = 0
        """Layers' draws cut short by viser's sender racing its event loop (see :meth:`show`)."""
        self.pacer: LinkPacer | None = None
        """The pace of the tab the cloud is sent at, if one is paced (:meth:`pace`)."""
        self._least_s: dict[int, float] = {}  # each paced tab's least round trip (s)

    def pace(self, client_id: int | None) -> None:
        """Send the cloud at the pace the tab ``client_id``'s connection carries
        (:class:`LinkPacer`), or, with None, at every frame. The other tabs get the same
        frames, or fewer (viser drops a tile's update a newer one replaces). A tab paced again
        starts from the least round trip it was measured at before."""
        if (pacer := self.pacer) is not None:
            pacer.close()
            self._least_s[pacer.client_id] = pacer.rule.least_s
        self.pacer = None
        if client_id is not None:
            least_s = self._least_s.get(client_id, math.inf)
            self.pacer = LinkPacer(self.server, client_id, least_s)
        self.cloud.interval = 1

    @property
    def url(self) -> str:
        """Address to open in a browser: the public URL if given, else an address of this
        machine (for 0.0.0.0 one that other machines can reach)."""
        if self.config.public_url is not None:
            return self.config.public_url
        address = self.host.addresses[0]
        host = f"[{address}]" if ":" in address else address  # an IPv6 address, as URLs write it
        return f"http://{host}:{self.server.get_port()}"

    def link(self, token: str) -> str:
        """The address that admits a browser with ``token`` (see :attr:`ViewConfig.links`)."""
        return link_url(self.url, token)

    def notices(self) -> list[str]:
        """What the user should know about where the view is served, one line each."""
        out = []
        if self.config.port and self.server.get_port() != self.config.port:
            out.append(f"port {self.config.port} is taken; serving on {self.server.get_port()}")
        if not self.host.loopback:
            address = self.host.addresses[0]
            who = "anyone on that network" + (" with a link" if self.gate else "")
            out.append(
                f"warning: the view is served on {self.config.host}: {who} can see it and drive "
                "the robot"
            )
            if self.config.public_url is None and ipaddress.ip_address(address).is_loopback:
                out.append(
                    "warning: no network interface other machines can reach is up, so the "
                    f"address printed, {address}, opens only on this machine: bring a network "
                    "up, or give study serve a --public-url (a tunnel's, say)"
                )
        return out

    @property
    def cues(self) -> ArCues | None:
        """The layers the panel chose, or None while the frames' own cues are drawn."""
        return None if self._panel is None else self._panel.cues

    def show(self, frame: DisplayFrame) -> None:
        """Draw ``frame``: each layer its modality turns on, the others hidden.

        Returns once the update is handed to the server's sender, which delivers it to every
        connected browser.
        """
        if self._T_base_camera is None:
            self._T_base_camera = frame.T_base_camera
            self._egocentric(move_clients=True)
        if (pacer := self.pacer) is not None:  # another thread may stop pacing meanwhile
            self.cloud.interval = pacer.interval
        if (cues := self.cues) is not None:
            frame = replace(frame, cues=cues)
        elif (panel := self._panel) is not None:
            self._send(lambda: panel.follow(frame.cues))
        for layer in self.layers:
            self._send(lambda layer=layer: layer.draw(frame))  # type: ignore[misc]
        self.server.flush()
        self.updates += 1

    def show_still(self, frame: DisplayFrame) -> None:
        """:meth:`show` a frame that no other follows soon (the scene while a person gets
        ready), then :meth:`settle`."""
        self.show(frame)
        self.settle()

    def settle(self) -> None:
        """Send now every change of the cloud the latest frame shown still differs by
        (:meth:`CloudLayer.settle`): frames stream the small ones over the next frames, and
        after the last there are none."""
        self._send(self.cloud.settle)
        self.server.flush()

    def _send(self, draw: Callable[[], None]) -> None:
        """``draw``, whose messages viser sends. viser 1.1.1 sets its asyncio.Event from the
        sending thread (this one), racing the event loop's waiters: the message is buffered
        when "deque mutated during iteration" is raised, but the sender may be left waiting on
        an event already set, so it is woken again from its own loop. Raised, the race ended a
        served study (once in some ten suite runs under load); now it is counted and logged,
        and the frame drawn on."""
        try:
            draw()
        except RuntimeError as err:
            if "deque mutated during iteration" not in str(err):
                raise
            self.races += 1
            _log.warning("viser's sender raced its event loop (%d so far); frame drawn on",
                         self.races)  # fmt: skip
            _wake_senders(self.server)

    def _egocentric(self, move_clients: bool) -> None:
        """The initial camera (and, if asked, every connected browser's) at the head camera."""
        if self._T_base_camera is None:
            return
        T = self._T_base_camera
        eye, forward = T[:3, 3], T[:3, 2]  # optical frame: z forward, y down
        # The world's vertical, not the camera's: orbiting then turns about it instead of
        # rolling the view; Baxter's head camera does not roll, so the view starts as its image.
        up = -T[:3, 1] if sight_is_vertical(T) else np.array([0.0, 0.0, 1.0])
        cameras = [self.server.initial_camera]
        if move_clients:
            cameras += [client.camera for client in self.server.get_clients().values()]
        for camera in cameras:
            camera.position = eye
            camera.look_at = eye + forward
            camera.up = up
            camera.fov = self.config.fitting_fov_rad(self.config.image_aspect)
        for camera in cameras[1:]:
            self._fit(camera)

    def _follow_shape(self, client: viser.ClientHandle) -> None:
        """Keep a browser's field fitted to its scene's shape, which the page sets after it
        connects (the panel docks) and whenever the window is resized."""
        self._fit(client.camera)
        client.camera.on_update(self._fit)

    def _fit(self, camera: viser.CameraHandle) -> None:
        """Widen a browser's field until the whole camera image fits its scene, which the
        docked panel makes narrower than the camera's 4:3."""
        fov = self.config.fitting_fov_rad(camera.aspect)
        # Only a change: setting it sends the browser a camera update, which calls this again.
        if not math.isclose(camera.fov, fov, rel_tol=1e-9):
            camera.fov = fov

    def deliver(self, timeout_s: float = DELIVERY_TIMEOUT_S) -> None:
        """Return once every connected tab has received what was shown so far: a server about
        to stop had cut off the last page still in its buffer. viser sends in order, so a frame
        asked for now comes back after it. Tabs that draw nothing (in the background) or go
        are waited for at most ``timeout_s`` in all (s)."""
        self.server.flush()
        deadline = time.monotonic() + timeout_s
        for client in list(self.server.get_clients().values()):
            left_s = deadline - time.monotonic()
            if left_s <= 0:
                return
            drew_a_frame(client, left_s)

    def close(self) -> None:
        """Stop the server."""
        self.pace(None)
        with contextlib.redirect_stdout(io.StringIO()):  # its "Server stopped"
            self.server.stop()


def drew_a_frame(client: viser.ClientHandle, timeout_s: float) -> bool:
    """Whether ``client`` drew a small frame asked of it now within ``timeout_s`` (s): viser
    sends in order, so the frame also shows that everything sent before has arrived. False if
    the tab went, draws nothing (in the background) or answered with something other than an
    image: a client's reply is its own input and never stops the server."""
    try:
        client.get_render(8, 8, timeout=timeout_s)
    # Gone, not drawing, or a reply that is not an image (one that is not even bytes fails
    # viser's own check with a TypeError).
    except (RuntimeError, TimeoutError, TypeError):
        return False
    return True
