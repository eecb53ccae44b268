"""The frames a participant's page drew, as it counted them: what it wrote read back, anything
else a page could answer refused, and the rate over its own clock. The page's script in a real
browser is the served session's test's (``tests/study/test_serve.py``)."""

import html
import math
import time
from concurrent.futures import Future
from types import SimpleNamespace

import pytest

from arteleop.ar_features import page_frames
from arteleop.ar_features.page_frames import (
    STORAGE_PREFIX,
    FrameCount,
    frame_counter_html,
    frames_between,
    frames_drawn,
    parse_count,
    read_count,
    read_in_background,
)


def test_the_page_writes_its_count_under_the_key_the_server_reads() -> None:
    script = html.unescape(frame_counter_html(7).split('onerror="')[1])
    assert f'window.arteleopFramesKey = "{STORAGE_PREFIX}arteleop.frames.7";' in script
    asked = []

    def get_item(key: str, timeout: float) -> str:
        asked.append(key)
        return "1200 20480.5"

    client = SimpleNamespace(client_id=7, local_storage=SimpleNamespace(get_item=get_item))
    assert read_count(client) == FrameCount(1200, 20480.5)  # type: ignore[arg-type]
    assert asked == ["arteleop.frames.7"]  # viser puts its prefix before it


@pytest.mark.parametrize(
    "reply", [None, 12, "", "12", "12 ", "-3 100.0", "3 1e9", "3 100.0 7", "1" * 16 + " 1.0",
              "٣ 100.0", "3\n100.0", b"3 100.0"],
)  # fmt: skip
def test_what_is_not_a_count_counts_nothing(reply: object) -> None:
    assert parse_count(reply) is None


@pytest.mark.parametrize("raised", [TimeoutError, RuntimeError, KeyError])
def test_a_page_that_does_not_answer_counts_nothing(raised: type[Exception]) -> None:
    def get_item(key: str, timeout: float) -> str:
        raise raised("gone")

    client = SimpleNamespace(client_id=1, local_storage=SimpleNamespace(get_item=get_item))
    assert read_count(client) is None  # type: ignore[arg-type]


def test_the_rate_is_over_the_pages_clock() -> None:
    assert frames_between(FrameCount(100, 1000.0), FrameCount(250, 31000.0)) == (150, 5.0)
    for first, last in [
        (None, FrameCount(9, 1.0)),
        (FrameCount(9, 1.0), None),
        (FrameCount(500, 1000.0), FrameCount(20, 4000.0)),  # reloaded between: counts from 0
        (FrameCount(5, 1000.0), FrameCount(5, 1000.0)),
    ]:
        frames, fps = frames_between(first, last)
        assert frames is None and math.isnan(fps)


def test_reads_in_the_background_never_raise_nor_wait_past_their_time(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def get_item(key: str, timeout: float) -> str:
        return "40 1000.0" if key.endswith(".1") else "240 11000.0"

    first, last = (SimpleNamespace(client_id=k, local_storage=SimpleNamespace(get_item=get_item))
                   for k in (1, 2))  # fmt: skip
    both = read_in_background(first), read_in_background(last)  # type: ignore[arg-type]
    assert frames_drawn(*both) == (200, 20.0)
    frames, fps = frames_drawn(both[0], None)
    assert frames is None and math.isnan(fps)
    monkeypatch.setattr(page_frames, "READ_TIMEOUT_S", 0.2)
    never: Future[FrameCount | None] = Future()
    begun = time.perf_counter()
    done: Future[FrameCount | None] = Future()
    done.set_result(FrameCount(10, 2000.0))
    frames, fps = frames_drawn(never, done)
    assert frames is None and math.isnan(fps) and time.perf_counter() - begun < 1.0
