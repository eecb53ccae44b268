"""A scripted participant: does a pick-and-place trial in a real browser from what the page
shows a person, through the keyboard and the page's controls.

It reads the distance bar's and the grip bar's labels and sees the bowl and the target circle
(:mod:`tests.instruments.screen_reading`), and drives with the keys (W A S D, E and Q step the
gripper, G grips) and the Step dropdown. No server-side shortcut, no page messages: what
it decides, a person at the screen could decide. Its way is a person's who cannot judge depth
and counts their steps (the step buttons' directions are at right angles: across the image,
into it on the table, and up):

- **Reach.** Three double steps, towards the bowl as the image shows it, and the distance
  label's numbers give the point they measure to (a least-squares fit): the nearest point of
  the bowl's grasp ring, on its near side. The bowl's width as seen, scaled by how far a step
  moved the label, gives the ring's size and middle. The fingers open across the image, so they
  close on the wall facing them across it. From afar that estimate can be a few centimetres
  off: the gripper goes outside that wall and above the ring, out of its way, and a few 1 cm
  steps there say where the wall is (the ring's distances from near by). Over the wall, down
  onto it, the open fingers straddling it; then a step at a time, kept when the number falls,
  and the gripper closes when the number is small.
- **Carry.** Lifted, the bowl is brought across the image over the target circle, lowered to
  just above the table and nudged until the two are one in the image (its middle judged from
  its edges away from the gripper), set down and let go.
"""

from __future__ import annotations

import base64
import re
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from operator import attrgetter
from pathlib import Path
from typing import Any, ClassVar

import cv2
import numpy as np
from numpy.typing import NDArray
from playwright.sync_api import TimeoutError as PlaywrightTimeout
from scipy.optimize import least_squares

from arteleop.ar_features.keys import GRIP_KEY, KEYS
from tests.instruments.browser import answer_questions, press_button, rate_every_item
from tests.instruments.screen_reading import (
    DISTANCE,
    Box,
    Spot,
    bowl_box,
    find_label,
    grip_percent,
    target_box,
)

STEPS_MM = {"5 cm": 50, "1 cm": 10}
"""The step buttons' sizes, as the Step dropdown names them (mm)."""
AXES = (("right", "left"), ("away", "nearer"), ("up", "down"))
"""The step buttons in opposite pairs along three directions at right angles."""
_OPPOSITE = {a: b for pair in AXES for a, b in (pair, pair[::-1])}
KEY = {name: code for code, name in KEYS.items() if code.startswith("Key")}
"""The letter key of each step button (:data:`arteleop.ar_features.keys.KEYS`)."""
PROBE_STEPS = 2
"""The first steps, to learn from the distance where the grasp point lies: 10 cm each way."""
RING_SHARE = 0.95
"""The grasp ring (the middle of the wall, below the rim) is about this share of the bowl's
width as seen."""
OUT_MM = 50
"""Outside the wall by this, to learn from near by where it is (mm): clear of it when the first
estimate is a few centimetres off."""
UP_MM = 40
"""Above the grasp ring by this, to learn where the wall is and to cross over it (mm): the rim
is 15 mm above the ring, the fingers' ends a little below the point the label measures from."""
LOCAL_PROBE_STEPS = 3
"""Steps of 1 cm each way to learn, near it, where the wall is."""
CLOSE_ENOUGH_MM = 15
"""Near enough to the grasp point to close the gripper on the rim (mm)."""
LOST_MM = 30
"""Arrived at the wall further than this from the grasp point, the estimate was wrong (mm): more
than the feel's 1 cm steps across and in height make up (69 mm, once in six runs)."""
MAX_FEELS = 10
"""Steps tried near the grasp point before closing the gripper wherever it is."""
FELT_MM = 3
"""A step that brings the number down by more than this is kept (mm): the readout jitters."""
SHORT_WAY_MM = 100
"""Further than this along an axis, the Step is changed to 5 cm for the way there (mm)."""
LIFT_STEPS = 2
"""Steps of 5 cm up with the bowl: clear of the table and of the target circle."""
CLICK_GAP_S = 0.1
"""After a press, before the next (s). viser's panel sends at most one update per 50 ms, the
latest (one throttled sender for the whole panel): twenty clicks by the script with no time
between moved the target twice. With the page's own time to take a key (about 0.4 s in a
browser drawing in software), presses come about two a second; a person taps up to five."""
ARRIVE_S = 0.5
"""The gripper has arrived this long after a press, or is about to (s)."""
READS = 2
"""Looks per reading: the tracked bowl's jitter moves the label by a few millimetres."""
STILL_MM = 10
"""Readings within this (mm) of each other show a gripper at rest."""
STILL_PX = 4
"""Where the bowl is seen, within this (px), shows it at rest."""
SETTLE_TIMEOUT_S = 20.0
"""A reading that never settles fails the trial: the page stopped showing what it should."""
CLEAR_STEPS = 3
"""Steps of 1 cm over the table the bowl is lined up at."""
OUTCOME = re.compile(r"Placed in|Not placed")
"""The start of the outcome the page shows after a trial."""
OUTCOME_WAIT_S = 10.0
"""The bowl let go, the outcome shows within this (s), unless the gripper hides the bowl."""
TRIAL_END_WAIT_S = 130.0
"""Out of the way, the outcome shows within this (s): the camera sees the bowl standing (or the
trial runs out of time, if its timeout is shorter)."""
LINE_UP_GOES = 3
"""Goes at lining the bowl up with the target, each from a fresh look: a first go on a step
misjudged by half overshoots, the second mends most of it, the third the rest."""
MOST_STEPS_A_GO = 10
"""Steps pressed at most before looking again (a person does not press 45 times blind): more
says the pixels a step were misread."""
MOVE_WAIT_S = 5.0
"""Steps pressed, the bowl is seen to move within this (s), or it was held back (a bowl that
moved half as far as expected, seen between frames, sent it 10 cm past the target)."""
QUESTIONNAIRE_RATING = "5"
"""Its answer to every item of the questionnaire (1-7)."""
PAGE_WAIT_S = 60.0
"""The next page shows within this (s): a trial's site is built meanwhile."""


def _decode(png: bytes) -> NDArray[np.uint8]:
    return cv2.cvtColor(cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR),
                        cv2.COLOR_BGR2RGB)  # fmt: skip


def _readings(
    seen: list[tuple[NDArray[np.float64], float]],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Where the gripper was (N, 3) and what was read there (N,), in mm."""
    return np.array([at for at, _ in seen]), np.array([read for _, read in seen])


@dataclass
class ScriptedParticipant:
    """Does a trial in ``tab`` (a playwright page on the participant's link, on the trial's
    page); ``log`` hears what it reads and does."""

    tab: Any
    log: Callable[[str], None] = lambda _: None
    step: str = "5 cm"
    presses: list[str] = field(default_factory=list)
    """Every input, in order: what the trial's outcome came from."""
    side: float = 1.0
    """The bowl's side the gripper holds, across the image: 1 its right, -1 its left."""
    _bowl_size: Box | None = None
    """The bowl as seen before it was touched."""
    _at_mm: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    """Where its steps have put the gripper's target, from where it was at Start (mm; along
    right, away and up)."""
    outcome: ClassVar[re.Pattern[str]] = OUTCOME
    """The start of the outcome the page shows after its trials."""

    def __post_init__(self) -> None:
        # The browser's own capture: playwright's element screenshot waits for the element to
        # stand still over animation frames, 4 s a look while the cloud streams.
        self._cdp = self.tab.context.new_cdp_session(self.tab)
        box = self.tab.locator("canvas").first.bounding_box()
        self._clip = {**box, "scale": 1}

    def look(self) -> NDArray[np.uint8]:
        """The scene's pixels as they are now (RGB)."""
        shot = self._cdp.send(
            "Page.captureScreenshot",
            {"format": "png", "optimizeForSpeed": True, "clip": self._clip},
        )
        return _decode(base64.b64decode(shot["data"]))

    def reading(self, read: Callable[[NDArray[np.uint8]], float | None], still: float) -> float:
        """What ``read`` finds on the screen once :data:`READS` looks in a row agree to within
        ``still``: their median."""
        end = time.monotonic() + SETTLE_TIMEOUT_S
        seen: list[float] = []
        while time.monotonic() < end:
            value = read(self.look())
            if value is not None:
                seen = [*seen[-(READS - 1) :], value]
                if len(seen) == READS and max(seen) - min(seen) <= still:
                    return statistics.median(seen)
        raise AssertionError(f"the readout never settled: {seen}")

    def click(self, element: Any) -> None:
        """The pointer straight at ``element``, where it is now (the panel's texts above it
        change their number of lines): a locator's click first waits for the page to stand
        still over animation frames, a second a click while the cloud streams."""
        box = element.bounding_box()
        self.tab.mouse.click(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        time.sleep(CLICK_GAP_S)

    def press(self, name: str, times: int = 1) -> None:
        """Step ``name`` (a step button's), ``times`` times, with its key, then give the arm
        time to get there."""
        for _ in range(times):
            self.tab.keyboard.press(KEY[name])
            time.sleep(CLICK_GAP_S)
            self.presses.append(name)
            for k, pair in enumerate(AXES):
                if name in pair:
                    self._at_mm[k] += STEPS_MM[self.step] * (1 if name == pair[0] else -1)
        if times:
            time.sleep(ARRIVE_S)

    def choose_step(self, label: str) -> None:
        """Pick the Step dropdown's ``label``."""
        if label != self.step:
            self.click(self.tab.get_by_role("combobox", name="Step"))
            self.click(self.tab.get_by_role("option", name=label, exact=True))
            self.step = label

    def go_by(self, offset_mm: NDArray[np.float64], order: tuple[int, ...] = (0, 1, 2)) -> None:
        """Step the target by ``offset_mm`` (right, away, up) as near as 1 cm steps can, the
        axes in ``order``."""
        # Big steps short of it, small ones the rest of the way: never past it and back, which
        # near the bowl could knock it. Changing the Step takes two clicks, the time of a few
        # presses: a short way is all small steps when they are chosen.
        offset_mm = np.asarray(offset_mm)
        short = self.step == "1 cm" and np.all(np.abs(offset_mm) < SHORT_WAY_MM)
        big = np.zeros(3, int) if short else np.fix(offset_mm / STEPS_MM["5 cm"]).astype(int)
        small = np.round((offset_mm - big * STEPS_MM["5 cm"]) / STEPS_MM["1 cm"])
        counts = {"5 cm": big, "1 cm": small.astype(int)}
        for label in STEPS_MM:
            for k in order:
                n = int(counts[label][k])
                if n:
                    self.choose_step(label)
                    self.press(AXES[k][0] if n > 0 else AXES[k][1], abs(n))

    def distance(self) -> float:
        """The distance label, read once the gripper stands (mm); where it was drawn goes to
        :attr:`label_at`."""
        spots: list[Spot] = []

        def read(rgb: NDArray[np.uint8]) -> float | None:
            found = find_label(rgb, DISTANCE)
            if found is not None:
                spots.append(found[1])
            return None if found is None else found[0]

        value = self.reading(read, STILL_MM)
        self.label_at = spots[-1]
        return value

    def reach(self, start: Spot, distance: float, bowl: Spot, bowl_wide_px: float) -> float:
        """To the grasp point on the bowl's wall that faces the gripper across the image, from
        ``distance`` read with the label at ``start`` and the bowl seen at ``bowl``,
        ``bowl_wide_px`` wide; the distance left (mm)."""
        # Towards the bowl as the image shows it (the label hangs beside the gripper), keeping
        # both in sight, and down, still above it.
        across = "left" if bowl.x_px < start.x_px else "right"
        probes = (across, "away" if bowl.y_px < start.y_px else "nearer", "down")
        seen = [(self._at_mm.copy(), distance)]
        self.choose_step("5 cm")
        for name in probes:
            self.press(name, PROBE_STEPS)
            seen.append((self._at_mm.copy(), self.distance()))
            if name == across:
                moved_px = abs(self.label_at.x_px - start.x_px)
                px_per_mm = moved_px / (PROBE_STEPS * STEPS_MM["5 cm"])
        self.log(f"probed {probes}: {[round(d) for _, d in seen]} mm")
        # The label measures to the nearest point of a level ring round the bowl's axis: from
        # afar, a point on its near side. The ring is about as wide as the bowl looks, measured
        # by how far a step moved the label. The fingers open across the image, so they close
        # on the wall facing them across it, beside the ring across the image and in line with
        # its middle.
        near = self._point(seen, seen[0][0] - [0.0, 0.0, seen[0][1]])
        radius = RING_SHARE * bowl_wide_px / 2 / px_per_mm
        inward = (near - self._at_mm)[:2] / np.linalg.norm((near - self._at_mm)[:2])
        centre = near + np.append(radius * inward, 0.0)
        self.side = side = 1.0 if across == "left" else -1.0
        # From afar the point the numbers give is a few centimetres off (it slides along the
        # ring as the gripper moves, and far readings pin it down poorly). Out of the wall's
        # way, beside it and above it, a few small steps say where the wall is from near by;
        # arrived there still far off, it goes back up and out and learns it again, once.
        for _ in range(2):
            centre = self._wall_from_near_by(centre, radius, side)
            wall = centre + [side * radius, 0.0, 0.0]
            # Over the wall, then down onto it: the open fingers straddle it (from the side,
            # the leading one pushes the bowl away).
            self.log(f"wall at {np.round(wall)} mm")
            self.go_by(wall + [0.0, 0.0, UP_MM] - self._at_mm, order=(2, 0, 1))
            self.go_by(wall - self._at_mm)
            distance = self.distance()
            self.log(f"now {distance:.0f} mm")
            if distance <= LOST_MM:
                break
            self.go_by(np.array([0.0, 0.0, UP_MM]), order=(2, 0, 1))
        # ...then as a person feels their way with the number: a step, kept if the number
        # falls, taken back if not, at the wall and in height, until it is small.
        self.choose_step("1 cm")
        tries = [("left" if side > 0 else "right"), "down", "up"]
        steps = 0
        while distance > CLOSE_ENOUGH_MM and steps < MAX_FEELS:
            for name in tries:
                self.press(name)
                steps += 1
                now = self.distance()
                if now < distance - FELT_MM:
                    distance = now
                    tries = [name, *(t for t in tries if t != name)]  # that way again first
                    break
                self.press(_OPPOSITE[name])
            else:
                break  # no step helps: as near as it gets
            self.log(f"felt {tries[0]}: {distance:.0f} mm")
        return distance

    def _wall_from_near_by(
        self, centre: NDArray[np.float64], radius: float, side: float
    ) -> NDArray[np.float64]:
        """The ring's middle (mm) learnt from beside the wall: out of its way, above it, a few
        1 cm steps from there, their readings fitted to the ring of ``radius`` nearest
        ``centre``."""
        out = [side * (radius + OUT_MM), 0.0, UP_MM]
        self.log(f"ring of {radius:.0f} mm round {np.round(centre)}: to {np.round(centre + out)}")
        # Across and along first, still above the bowl, then down: never through it.
        self.go_by(centre + out - self._at_mm, order=(0, 1, 2))
        seen = [(self._at_mm.copy(), self.distance())]
        self.choose_step("1 cm")
        for name in ("right" if side > 0 else "left", "away", "down", "nearer"):
            self.press(name, LOCAL_PROBE_STEPS * (2 if name == "nearer" else 1))
            seen.append((self._at_mm.copy(), self.distance()))
        self.log(f"beside it: {[round(d) for _, d in seen]} mm")
        return self._ring_centre(seen, centre, radius)

    @staticmethod
    def _point(
        seen: list[tuple[NDArray[np.float64], float]], guess: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """The point nearest ``guess`` whose distances from where the gripper was best match
        those read (mm)."""
        at, read = _readings(seen)
        fit = least_squares(lambda x: np.linalg.norm(at - x, axis=1) - read, guess)
        return np.asarray(fit.x)

    @staticmethod
    def _ring_centre(
        seen: list[tuple[NDArray[np.float64], float]],
        guess: NDArray[np.float64],
        radius: float,
    ) -> NDArray[np.float64]:
        """The middle, nearest ``guess``, of the level ring of ``radius`` whose distances from
        where the gripper was best match those read (mm): what the label measures to is the
        ring's nearest point. From one side the readings tell where the ring's near wall is,
        not its size, so the size is taken as seen."""
        at, read = _readings(seen)

        def residuals(c: NDArray[np.float64]) -> NDArray[np.float64]:
            out = np.linalg.norm(at[:, :2] - c[:2], axis=1) - radius
            return np.asarray(np.hypot(out, at[:, 2] - c[2]) - read)

        return np.asarray(least_squares(residuals, guess).x)

    def grip(self, closed: bool) -> None:
        """Close the gripper, or open it, with the grip's key (it closes an open gripper and
        opens a closed one)."""
        self.tab.keyboard.press(GRIP_KEY)
        self.presses.append("close" if closed else "open")
        time.sleep(ARRIVE_S)

    def bowl(self) -> Spot:
        """Where the bowl's middle is seen once it stands still: from its far edges, as the
        gripper at its near side hides some of it, by its size at the start."""
        boxes: list[Box] = []

        def left_px(rgb: NDArray[np.uint8]) -> float | None:
            box = bowl_box(rgb)
            if box is not None:
                boxes.append(box)
            return None if box is None else box.x_px - box.width_px / 2

        self.reading(left_px, STILL_PX)
        box, size = boxes[-1], self._bowl_size
        far = self.side * -1
        return Spot(
            box.x_px + far * (box.width_px - size.width_px) / 2,
            box.y_px - (box.height_px - size.height_px) / 2,
        )

    def line_up(self, target: Spot, axis: int, step: str, per_step_px: float = 0.0) -> float:
        """Step along ``axis`` (0 across the image, 1 into it) until the bowl's middle is as
        near ``target``'s in the image as such steps take it, looking again after each go; how
        far the bowl moves in the image a step (px): ``per_step_px``, or measured by a step."""
        self.choose_step(step)
        coordinate = attrgetter("x_px" if axis == 0 else "y_px")
        now = coordinate(self.bowl())
        if not per_step_px:
            self.press(AXES[axis][0])
            before, now = now, self._bowl_moved(coordinate, now, 4 * STILL_PX)
            per_step_px = now - before
        expected = per_step_px
        for _ in range(LINE_UP_GOES):
            n = round((coordinate(target) - now) / per_step_px) if abs(per_step_px) >= 1 else 0
            n = int(np.clip(n, -MOST_STEPS_A_GO, MOST_STEPS_A_GO))
            self.log(f"bowl {now:.0f} px, target {coordinate(target):.0f} px, "
                     f"{per_step_px:+.0f} px a step: {n:+d}")  # fmt: skip
            if not n:
                break
            self.press(AXES[axis][0] if n > 0 else AXES[axis][1], abs(n))
            before, now = now, self._bowl_moved(coordinate, now, n * per_step_px)
            # As the steps went, not as assumed (a bowl that turned in the fingers moves
            # otherwise), but from half to three times what was expected: a bowl that barely
            # moved (held back, or misread) read as 1 px a step sent it 45 cm in one go, and a
            # step into the image, estimated from the target's foreshortening, was seen 2.5
            # times as long as estimated (the bowl nearer the camera than the circle).
            seen = (now - before) / n
            if abs(now - before) >= abs(n) and 0.5 <= seen / expected <= 3.0:
                per_step_px = seen
        return per_step_px

    def _bowl_moved(
        self, coordinate: Callable[[Spot], float], before: float, expected_px: float
    ) -> float:
        """Where the bowl stands (``coordinate`` of :meth:`bowl`) once it has moved at least
        half of ``expected_px`` from ``before`` and then stands still (two looks within
        :data:`STILL_PX`), or after :data:`MOVE_WAIT_S`: on a busy machine the arm lags the
        presses and the page the arm, and two looks at a stale frame agree."""
        end = time.monotonic() + MOVE_WAIT_S
        now = coordinate(self.bowl())
        while abs(now - before) < abs(expected_px) / 2 and time.monotonic() < end:
            now = coordinate(self.bowl())
        # Then until it stands (two looks alike), as a person waits for the arm to settle: a
        # look while it still moved made the next go overshoot, or a step seem reversed.
        last = None
        while (last is None or abs(now - last) > STILL_PX) and time.monotonic() < end:
            last, now = now, coordinate(self.bowl())
        return now

    def do_trial(self) -> str:
        """Start, reach, grasp, carry, set down, let go; the outcome the page then shows, also
        when the trial ends before (its controls go with it)."""
        try:
            return self._do_trial()
        except (PlaywrightTimeout, AssertionError):
            ended = self.tab.get_by_text(self.outcome)
            if not ended.is_visible():
                raise
            return str(ended.inner_text())

    def _do_trial(self) -> str:
        # Looked at before Start, while the timer waits.
        rgb = self.look()
        target, found, bowl = target_box(rgb), find_label(rgb, DISTANCE), bowl_box(rgb)
        assert target and found and bowl, "the target, the gripper or the bowl is not to be seen"
        distance = self.distance()
        self.tab.get_by_role("button", name="Start", exact=True).click()
        # The robot follows once the page says so.
        self.tab.get_by_text("waiting for motion onset", exact=False).wait_for()
        self._bowl_size = bowl
        left = self.reach(self.label_at, distance, bowl, bowl.width_px)
        self.grip(closed=True)
        self.log(f"closed {left:.0f} mm from the grasp point: grip {grip_percent(self.look())} %")
        self.choose_step("5 cm")
        self.press("up", LIFT_STEPS)
        across_px = self.line_up(target, 0, "5 cm")
        # Down to just above the table, where the bowl is seen about where it will stand, still
        # clear of it: dragged on the table, it turns in the fingers.
        self.press("down", LIFT_STEPS - 1)
        self.choose_step("1 cm")
        self.press("down", STEPS_MM["5 cm"] // STEPS_MM["1 cm"] - CLEAR_STEPS)
        small = STEPS_MM["1 cm"] / STEPS_MM["5 cm"]
        self.line_up(target, 0, "1 cm", across_px * small)
        # A step away moves the bowl up the image by a step across, foreshortened as the round
        # target circle is into an ellipse.
        self.line_up(
            target, 1, "1 cm", -abs(across_px) * small * target.height_px / target.width_px
        )
        self.press("down", CLEAR_STEPS)
        self.grip(closed=False)
        outcome = self.tab.get_by_text(OUTCOME)
        try:
            outcome.wait_for(timeout=1000 * OUTCOME_WAIT_S)
        except PlaywrightTimeout:
            # Out of the camera's way: the bowl is scored once it is seen standing. Then until
            # the trial ends, placed or out of time.
            self.choose_step("5 cm")
            self.press("up", LIFT_STEPS)
            outcome.wait_for(timeout=1000 * TRIAL_END_WAIT_S)
        return outcome.inner_text()


@dataclass(frozen=True)
class TrialDone:
    """A trial as the scripted participant did it."""

    heading: str
    """The page's heading: ``Trial k of n``."""
    outcome: str
    """What the page said after it."""
    presses: tuple[str, ...]
    """Every input, in order."""


def take_part(
    tab: Any,
    log: Callable[[str], None] = lambda _: None,
    shots: Path | None = None,
    person: type[ScriptedParticipant] = ScriptedParticipant,
) -> list[TrialDone]:
    """A participant's whole session in ``tab``, from the consent page to the study's last
    page: consent, the start page's questions, the tutorial, every trial (practice ones too)
    done by a ``person``, the questionnaire if it comes. ``shots``: a folder for a screenshot
    of every page, named in order."""
    taken: list[str] = []

    def shot(name: str) -> None:
        taken.append(name)
        if shots is not None:
            tab.screenshot(path=str(shots / f"{len(taken):02d}-{name}.png"))

    def wait(text: str | re.Pattern[str]) -> Any:
        shown = tab.get_by_text(text).first
        shown.wait_for(timeout=1000 * PAGE_WAIT_S)
        return shown

    wait("Information and consent")
    shot("consent")
    tab.get_by_text("I have read the information above").click()
    press_button(tab, "Continue")
    wait("Age (years)")
    shot("questions")
    answer_questions(tab)
    wait("How to drive the robot")
    shot("tutorial")
    press_button(tab, "Continue")
    done: list[TrialDone] = []
    step, k, n = "5 cm", 1, 1
    while k <= n:
        heading = wait(re.compile(rf"^Trial {k} of \d+$")).inner_text()
        n = int(heading.split()[-1])
        shot(f"trial-{k}")
        scripted = person(tab, log=log, step=step)
        try:
            outcome = scripted.do_trial()
        except Exception:
            shot(f"stopped-{k}")  # what the page showed when the script gave up
            raise
        log(f"{heading}: {outcome}")
        shot(f"outcome-{k}")
        done.append(TrialDone(heading, outcome, tuple(scripted.presses)))
        step = scripted.step  # the Step dropdown keeps its choice from trial to trial
        press_button(tab, "Next")
        k += 1
    end = "Every session of this study is done"
    if wait(re.compile(f"^Questionnaire$|{end}")).inner_text() == "Questionnaire":
        rate_every_item(tab, QUESTIONNAIRE_RATING)
        shot("questionnaire")
        press_button(tab, "Submit")
    wait(end)
    shot("end")
    return done
