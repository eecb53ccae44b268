"""The cloud goes to a tab at the pace its connection carries, measured by pinging it."""

from __future__ import annotations

import time

import numpy as np
import pytest

from arteleop.ar_features import OperatorView, ViewConfig
from arteleop.ar_features.link_pacer import (
    MAX_INTERVAL,
    QUEUE_HIGH_S,
    QUEUE_LOW_S,
    QueueRule,
    next_interval,
)
from tests.ar_features.frames import CAMERA_M, display_frame
from tests.instruments.throttle import Throttle
from tests.instruments.view_probe import ViewProbe, until


@pytest.mark.parametrize(
    ("interval", "queue_s", "then"),
    [
        (1, QUEUE_HIGH_S + 0.01, 2),
        (4, 5.0, MAX_INTERVAL),
        (MAX_INTERVAL, 5.0, MAX_INTERVAL),
        (3, (QUEUE_LOW_S + QUEUE_HIGH_S) / 2, 3),
        (3, QUEUE_LOW_S - 0.01, 2),
        (1, 0.0, 1),
    ],
)
def test_a_queue_doubles_the_interval_and_none_shortens_it_by_one(
    interval: int, queue_s: float, then: int
) -> None:
    assert next_interval(interval, queue_s) == then


def test_a_ping_awaited_raises_the_interval_once_for_each_doubling_of_its_wait() -> None:
    rule = QueueRule()
    rule.sent()
    rule.waiting(0.15)  # no round trip known yet: all of the wait may be a queue
    assert rule.interval == 1
    rule.waiting(0.25)
    assert rule.interval == 2
    rule.waiting(0.3)  # the same doubling of the wait: no more
    assert rule.interval == 2
    rule.waiting(0.85)  # past 0.4 and 0.8 s
    assert rule.interval == 8
    rule.answered(0.9)  # counted while it waited, not again
    assert (rule.interval, rule.least_s) == (8, 0.9)
    # The next pings come back without a queue beyond the least: one frame more each.
    for interval in (7, 6):
        rule.sent()
        rule.answered(0.92)
        assert rule.interval == interval
    # A round trip known from before: only the wait beyond it is a queue.
    known = QueueRule(least_s=0.1)
    known.sent()
    known.waiting(0.25)
    assert known.interval == 1
    known.waiting(0.35)
    assert known.interval == 2


def test_a_tab_behind_a_slow_link_is_sent_fewer_clouds() -> None:
    # Every frame a new cloud of 9,000 points in front of the camera (81 kB): 10 frames a
    # second, 6.5 Mbit/s, to a tab behind a link of 1 Mbit/s.
    rng = np.random.default_rng(0)
    n = 9_000
    with OperatorView(ViewConfig(port=0)) as view:
        with (
            Throttle(view.server.get_port(), 1.0) as link,
            ViewProbe(f"http://127.0.0.1:{link.port}", render_reply=b"") as tab,
        ):
            assert until(lambda: len(view.server.get_clients()) == 1)
            (client_id,) = view.server.get_clients()
            view.pace(client_id)
            intervals = []
            for _ in range(30):
                rays = rng.uniform(-0.3, 0.3, (n, 2))
                points = CAMERA_M + np.column_stack([rays, np.ones(n)]) * rng.uniform(1, 2, (n, 1))
                colors = rng.integers(0, 256, (n, 3), dtype=np.uint8)
                view.show(display_frame(cloud_points_m=points.astype(np.float32),
                                        cloud_colors=colors, cloud_spacing_rad=0.004))  # fmt: skip
                intervals.append(view.cloud.interval)
                time.sleep(0.1)
            pacer = view.pacer
            assert pacer is not None
            # A ping sent behind the queue comes back late; on a busy machine the ones answered
            # by the last frame may all have gone before the queue grew.
            answered: list[float] = []

            def late_ping() -> bool:
                answered.append(pacer.take_latency_s() or 0.0)
                return max(answered) > QUEUE_HIGH_S

            queued = until(late_ping, wait_s=20.0)
        assert len(tab.messages()) > 0
    # Its queue grew: the clouds went every few frames, the most the pacer allows by the end.
    assert max(intervals) == MAX_INTERVAL and view.cloud.frames_held >= 15
    assert view.cloud.frames_drawn + view.cloud.frames_held == 30
    assert queued, f"no ping's round trip over {QUEUE_HIGH_S} s: {max(answered):.3f} s"
    # A tab no longer paced gets every frame.
    view.pace(None)
    assert view.cloud.interval == 1 and view.pacer is None
