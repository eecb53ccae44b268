"""How many frames a participant's page drew during a trial, counted on the page.

The server knows what it sent a tab (the cloud's frames and bytes, :mod:`.link_pacer`), not what
the tab drew: a browser drawing the scene in software, without a GPU, may draw fewer frames a
second than the clouds it is sent, and its person then sees the robot late or in jumps, while
the socket's pings, answered by the browser's network stack, see no queue. So a short script on
the page (with an HTML element of the panel, as :mod:`.keys`' is) counts the page's animation
frames and keeps the count, with the page's clock, in its localStorage under the tab's own key,
which viser lets the server read (``ClientHandle.local_storage``), at a trial's start and end.
While a trial runs, viser draws the scene in every animation frame (it draws on demand, for
250 ms after each update, and the layers update at the camera's rate), so the count is the
frames the person was shown; a tab in the background counts none.
"""

from __future__ import annotations

import html
import math
import re
import threading
from concurrent.futures import Future
from dataclasses import dataclass

import viser

STORAGE_PREFIX = "viser-user:"
"""What viser 1.1 puts before a key its server reads from a page's localStorage (its client's
``LOCAL_STORAGE_PREFIX``); the page's script writes the key whole."""
READ_TIMEOUT_S = 5.0
"""A count not read by then is not known (a page too busy to answer, or gone; s)."""

_COUNT = re.compile(r"([0-9]{1,15}) ([0-9]{1,15}(?:\.[0-9]{1,6})?)")
"""A count as the script writes it: frames, a space, the page's clock (ms); ASCII digits only
(a regular expression's digit class takes any script's)."""

_SCRIPT = """
window.arteleopFramesKey = KEY;
if (!window.arteleopFrames) {
  window.arteleopFrames = 0;
  const count = (now) => {
    window.arteleopFrames += 1;
    try {
      localStorage.setItem(window.arteleopFramesKey, window.arteleopFrames + " " + now.toFixed(1));
    } catch (e) {}
    requestAnimationFrame(count);
  };
  requestAnimationFrame(count);
}
"""


def frames_key(client_id: int) -> str:
    """The key under which the tab of viser's ``client_id`` keeps its count."""
    return f"arteleop.frames.{client_id}"


def frame_counter_html(client_id: int) -> str:
    """The panel element that counts the page's frames for the tab of ``client_id``: an image
    that fails to load, whose error handler starts the count (once a page: a later one only
    renames its key, for a tab connected again)."""
    key = STORAGE_PREFIX + frames_key(client_id)
    script = _SCRIPT.replace("KEY", f'"{key}"')
    return f'<img alt="" src="data:," style="display: none" onerror="{html.escape(script)}">'


@dataclass(frozen=True)
class FrameCount:
    """A page's count of its animation frames, and its clock when it last counted one."""

    frames: int
    at_ms: float


def parse_count(value: object) -> FrameCount | None:
    """The count a page gave, None if it is not one: a page's reply is its own input."""
    found = _COUNT.fullmatch(value) if isinstance(value, str) else None
    return None if found is None else FrameCount(int(found[1]), float(found[2]))


def read_count(client: viser.ClientHandle, timeout_s: float = READ_TIMEOUT_S) -> FrameCount | None:
    """``client``'s count now; None if it did not answer within ``timeout_s`` (s), went, or
    gave something else."""
    try:
        value = client.local_storage.get_item(frames_key(client.client_id), timeout=timeout_s)
    # viser's for a tab gone or silent, and whatever a server stopping under the read raises:
    # a page's count is never worth stopping a server for.
    except Exception:
        return None
    return parse_count(value)


def frames_between(first: FrameCount | None, last: FrameCount | None) -> tuple[int | None, float]:
    """The frames a page drew from ``first`` to ``last`` and their rate (frames a second of
    the page's clock); (None, NaN) if either is not known or they are not in order (a page
    that reloaded between them counts again from 0)."""
    if first is None or last is None or last.frames < first.frames or last.at_ms <= first.at_ms:
        return None, math.nan
    frames = last.frames - first.frames
    return frames, 1000.0 * frames / (last.at_ms - first.at_ms)


def read_in_background(client: viser.ClientHandle) -> Future[FrameCount | None]:
    """:func:`read_count` of ``client`` on a thread of its own, not to hold up the caller (a
    busy page answers in up to :data:`READ_TIMEOUT_S`)."""
    future: Future[FrameCount | None] = Future()
    threading.Thread(target=lambda: future.set_result(read_count(client)), daemon=True).start()
    return future


def frames_drawn(
    first: Future[FrameCount | None] | None, last: Future[FrameCount | None] | None
) -> tuple[int | None, float]:
    """:func:`frames_between` the counts two background reads give, each waited for up to
    :data:`READ_TIMEOUT_S` (s); (None, NaN) for a read not made (None) or not back."""
    counts = []
    for future in (first, last):
        try:
            counts.append(None if future is None else future.result(READ_TIMEOUT_S))
        except TimeoutError:
            counts.append(None)
    return frames_between(*counts)
