"""A scripted participant for a served pointing study: does a trial in a real browser from what
the page shows a person, through the keyboard, as :mod:`tests.instruments.scripted_participant`
does a pick-and-place trial.

It needs the depth aids (the study's ``depth_aids``). It sees the start cross and the target
circle on the table, and where the gripper is over the table: the aids' ring, in the table's
plane, so that lining it up with a mark in the image lines them up on the table
(:mod:`tests.instruments.screen_reading`): a magenta circle, seen over the black marks and with
part of it under the gripper's fingers. Its way:

- **Down, once.** Two big steps towards the cross as the image shows it (onto the table: at
  rest the gripper is beyond its edge), then down until the height label reads about
  :data:`LOW_MM`, the gripper's fingers off most of the ring.
- **Steps in pixels.** A big step across and one into the image towards the cross, each seen in
  where the ring moved; then a big step up, clear of the bowl, which lies beside the way.
- **Over the cross, over the circle.** From a fresh look each go, the steps that bring the ring
  onto the mark (big ones, then 1 cm ones) until the next would be none, what a step is in
  pixels corrected after each by where the ring went; over the circle, down again for a last
  go; then the grip closes.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from tests.instruments.screen_reading import (
    Spot,
    circle_spot,
    cross_spot,
    find_label,
    foot_spot,
    gizmo_red,
)
from tests.instruments.scripted_participant import (
    STEPS_MM,
    STILL_MM,
    ScriptedParticipant,
)

OUTCOME = re.compile(r"Chosen in|No target counted")
"""The start of the outcome the page shows after a pointing trial."""
HEIGHT = r"height(-?\d+)mm"
"""The depth aids' label."""
LOW_MM = 35
"""The height it holds the gripper at, or up to 1 cm above, to see the aids' ring (mm): lower,
the gripper's dark fingers lie over the ring in the image (the trials held at 25-27 mm lost
it; those at 31-34 mm did not)."""
STILL_PX = 3.0
"""Two looks at the ring within this (px): the gripper stands."""
RING_WAIT_S = 10.0
"""The ring settles within this, or is taken as seen (s)."""
ON_MARK_PX = 8.0
"""The ring this near a mark's middle is on it (px): about 1 cm there, half the cross's reach
(:data:`~arteleop.teleop.task_monitor.START_RADIUS_M`)."""
MOST_MM_A_GO = 100
"""The longest way a go takes along each direction (mm): further off, the pixels a step learnt
elsewhere mislead more (a step into the image is shorter there), and the ring was not found
near where it should have been."""
GOES = 8
"""Goes at lining the ring up with a mark, each from a fresh look."""
OUTCOME_WAIT_S = 30.0
"""The grip closed, the outcome shows within this (s)."""


@dataclass
class ScriptedPointer(ScriptedParticipant):
    """Does a pointing trial in ``tab``, on the trial's page."""

    outcome: ClassVar[re.Pattern[str]] = OUTCOME
    _per_step_px: NDArray[np.float64] = field(default_factory=lambda: np.eye(2))
    """The ring's move in the image (columns: a big step right, one away; px)."""

    def _do_trial(self) -> str:
        before = self.look()
        cross, circle = cross_spot(before), circle_spot(before)
        rows, cols = np.nonzero(gizmo_red(before))
        assert cross and circle and len(rows), "the cross, the circle or the gizmo is not seen"
        self.tab.get_by_role("button", name="Start", exact=True).click()
        self.tab.get_by_text("waiting for motion onset", exact=False).wait_for()
        across = "left" if cross.x_px < cols.mean() else "right"
        into = "away" if cross.y_px < rows.mean() else "nearer"
        self.choose_step("5 cm")
        self.press(across, 2)
        self.press(into, 1)
        self._go_down()
        at = self._learn_steps(across, into)
        self.press("up")  # clear of the bowl
        at = self._ring(expected=at)
        for name, mark in (("cross", cross), ("circle", circle)):
            at = self._go_to(mark, at)
            self.log(f"over the {name}: ring {np.round(at)}, mark {mark}")
        self.choose_step("5 cm")
        self.press("down")
        at = self._go_to(circle, self._ring(expected=at))
        self.grip(closed=True)
        outcome = self.tab.get_by_text(OUTCOME)
        outcome.wait_for(timeout=1000 * OUTCOME_WAIT_S)
        return str(outcome.inner_text())

    def _go_down(self) -> None:
        """Down to about :data:`LOW_MM` over the table, by the height label."""

        def height() -> float:
            return self.reading(
                lambda rgb: (found := find_label(rgb, HEIGHT)) and found[0], STILL_MM
            )

        now = height()
        self.go_by(np.array([0.0, 0.0, -50 * np.floor((now - LOW_MM) / 50)]))
        now = height()
        self.go_by(np.array([0.0, 0.0, -10 * np.floor((now - LOW_MM) / 10)]))
        self.log(f"down from {now:.0f} mm to about {LOW_MM} mm")

    def _ring(self, expected: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Where the ring stands, once two looks agree within :data:`STILL_PX` (px). Not
        settled within :data:`RING_WAIT_S`, the median of what was seen; nothing seen,
        ``expected``, as a person trusts the steps they took."""
        end = time.monotonic() + RING_WAIT_S
        seen: list[NDArray[np.float64]] = []
        while time.monotonic() < end:
            ring = foot_spot(self.look())
            if ring is not None:
                now = np.array([ring.x_px, ring.y_px])
                if seen and np.linalg.norm(now - seen[-1]) <= STILL_PX:
                    return (now + seen[-1]) / 2
                seen.append(now)
        if seen:
            return np.median(seen[-5:], axis=0)
        if expected is not None:
            self.log(f"the ring is not seen: taken to be where the steps put it, {expected}")
            return expected
        raise AssertionError("the depth aids' ring is not seen")

    def _learn_steps(self, across: str, into: str) -> NDArray[np.float64]:
        """The image's pixels a big step right and one away, from a step ``across`` and one
        ``into`` the image, the gripper low; where the ring then is (px)."""
        self.choose_step("5 cm")
        at = self._ring()
        self.press(across)
        moved = self._ring(expected=at)
        self.press(into)
        seen = self._ring(expected=moved)
        signs = (1 if across == "right" else -1, 1 if into == "away" else -1)
        self._per_step_px = np.column_stack([signs[0] * (moved - at), signs[1] * (seen - moved)])
        self.log(f"a big step right and away: {np.round(self._per_step_px.T).tolist()} px")
        return seen

    def _go_to(self, mark: Spot, at: NDArray[np.float64]) -> NDArray[np.float64]:
        """Steps that bring the ring from ``at`` onto ``mark`` (px), a fresh look after each go;
        where it ends (px)."""
        goal = np.array([mark.x_px, mark.y_px])
        for _ in range(GOES):
            steps = np.linalg.solve(self._per_step_px, goal - at)
            offset_mm = STEPS_MM["1 cm"] * np.round(steps * STEPS_MM["5 cm"] / STEPS_MM["1 cm"])
            offset_mm = np.clip(offset_mm, -MOST_MM_A_GO, MOST_MM_A_GO)
            self.log(f"ring {np.round(at)}, mark {np.round(goal)}: {offset_mm} mm")
            if not offset_mm.any() or np.linalg.norm(goal - at) <= ON_MARK_PX:
                break
            self.go_by(np.array([*offset_mm, 0.0]))
            step = offset_mm / STEPS_MM["5 cm"]
            moved = self._ring(expected=at + self._per_step_px @ step)
            # Broyden's update: what a step is in pixels, corrected by where this go moved the
            # ring (a step learnt while the arm was still moving sent it astray, on a loaded
            # machine); a ring not seen moved as expected, and corrects nothing.
            missed_px = moved - at - self._per_step_px @ step
            self._per_step_px += np.outer(missed_px, step) / (step @ step)
            at = moved
        return at
