"""The display feed's real-time bookkeeping, with the render process's timing set by hand."""

from __future__ import annotations

from typing import Any

from arteleop.ar_features import MODALITIES, DisplayFrame
from arteleop.scene import HeadCameraConfig, RemoteSite, RGBDFrame, SiteConfig
from arteleop.teleop.display_feed import DisplayFeed
from arteleop.teleop.latency import LatencyAccount
from arteleop.teleop.timing import StageTimer


class _HandRenderedSite:
    """A real site whose render process finishes a frame only when :meth:`finish` says so."""

    def __init__(self, site: RemoteSite) -> None:
        self._site = site
        self._image: RGBDFrame = site.capture()
        self._pending = False
        self._done = False
        self.requested_s: list[float] = []

    def __getattr__(self, name: str) -> Any:
        return getattr(self._site, name)

    @property
    def frame_pending(self) -> bool:
        return self._pending

    def request_frame(self, stride: int = 1) -> None:
        assert not self._pending
        self._pending, self._done = True, False
        self.requested_s.append(self._site.time_s)

    def finish(self) -> None:
        self._done = True

    def poll_frame(self) -> RGBDFrame | None:
        if not (self._pending and self._done):
            return None
        self._pending = False
        return self._image


class _Shown:
    def __init__(self) -> None:
        self.times_s: list[float] = []

    def show(self, frame: DisplayFrame) -> None:
        self.times_s.append(frame.time_s)


def test_a_camera_tick_at_the_instant_of_an_owed_frame_waits_for_the_physics(
    site_config: SiteConfig,
) -> None:
    """The loop polls the renderer at each of its 1200 Hz of base ticks, four between two
    physics steps: the frame owed since the last camera tick starts at one of them, and a fast
    render is in before the camera tick that follows, at the same physics instant. That tick
    must not render the instant again (two frames with one time); it is owed until the physics
    moves on."""
    small = SiteConfig(robot=site_config.robot, camera=HeadCameraConfig(width_px=80, height_px=60))
    shown = _Shown()
    with RemoteSite(small) as real:
        site = _HandRenderedSite(real)
        feed = DisplayFeed(
            site, MODALITIES["none"], render=True, in_background=True,  # type: ignore[arg-type]
            return_delay_s=0.0, display=shown, timer=StageTimer(), latency=LatencyAccount(),
        )  # fmt: skip

        def camera_tick() -> None:
            feed.camera_tick(real.observe(), engaged=False, reachable=True,
                             applied_sample_time_s=0.0)  # fmt: skip

        def poll() -> None:
            feed.poll(engaged=False, reachable=True, applied_sample_time_s=0.0)
            feed.deliver(real.time_s)

        p0 = real.time_s
        camera_tick()  # renders P0
        real.step()
        camera_tick()  # P1 while P0 renders: owed
        assert feed.frames_skipped == 0 and site.requested_s == [p0]
        real.step()
        p2 = real.time_s
        site.finish()
        poll()  # a base tick at P2: P0 shown, the owed frame starts
        site.finish()
        poll()  # the next base tick: it is in
        camera_tick()  # still P2
        assert site.requested_s == [p0, p2]
        real.step()
        poll()  # P3: the owed frame starts now
        site.finish()
        poll()
    times = site.requested_s
    assert len(times) == 3 and times[0] < times[1] < times[2]
    assert shown.times_s == times
    assert feed.frames_skipped == 0
