"""A participant's pages in the browser: consent, questions, trials, questionnaire, the end.

One page at a time, in the side panel of one browser tab (a viser client's GUI), beside the
robot's view. The pages only show and collect: what an answer means and where it goes is the
study server's (:mod:`arteleop.study.serve`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import viser

CHOOSE = "(choose)"
"""A dropdown's first entry: no answer yet."""
HOURS = ("under 2 h", "2-5 h", "over 5 h")
"""The weekly-hours buckets 1, 2 and 3. The original asked "under one hour" for the first, which
left one to two hours without an answer; its experts' cut (two hours) is kept."""
RATINGS = tuple(str(k) for k in range(1, 8))
"""A 1-7 rating's answers, before :func:`_scale` labels its ends. A dropdown, not a slider: a
slider starts at an answer (its middle), which a participant can send without reading it."""

PRESS_START = "Press **Start** when you are ready."
"""The line that asks for Start; it goes with the button."""

Form = Mapping[str, object]
"""A page's answers by question key, as the browser gave them."""


class SessionPages:
    """The pages of one tab; each call replaces the page shown."""

    def __init__(self, gui: viser.GuiApi) -> None:
        self._gui = gui
        self._page: viser.GuiFolderHandle | None = None
        self._error: viser.GuiMarkdownHandle | None = None
        self._status: viser.GuiMarkdownHandle | None = None

    def message(
        self,
        title: str,
        text: str,
        button: str | None = None,
        on_click: Callable[[], None] | None = None,
    ) -> None:
        """A page of text, and a button if given."""
        with self._new(title):
            self._gui.add_markdown(text)
            if button is not None and on_click is not None:
                self._button(button, on_click)

    def consent(self, text: str, agree: str, on_agree: Callable[[], None]) -> None:
        """The information and consent text; continuing needs the box ticked."""
        with self._new("Information and consent"):
            self._gui.add_markdown(text)
            box = self._gui.add_checkbox(agree, False)
            self._error = self._gui.add_markdown("")

            def go() -> None:
                if box.value:
                    on_agree()
                else:
                    self.error("Tick the box to agree, or close this page to leave.")

            self._button("Continue", go)

    def demographics(self, on_submit: Callable[[Form], None], genders: Sequence[str],
                     handedness: Sequence[str]) -> None:  # fmt: skip
        """The questions before the trials; ``on_submit`` gets the answers by key
        (``age`` as typed; experience 1-7; hours as 1-3; 0 unanswered)."""
        with self._new("About you"):
            age = self._gui.add_text("Age (years)", "")
            gender = self._gui.add_dropdown("Gender", (CHOOSE, *genders))
            hand = self._gui.add_dropdown("Handedness", (CHOOSE, *handedness))
            avr = self._rating("AR/VR experience", EXPERIENCE)
            avr_hours = self._gui.add_dropdown("AR/VR per week", (CHOOSE, *HOURS))
            games = self._rating("Video-game experience", EXPERIENCE)
            games_hours = self._gui.add_dropdown("Video games per week", (CHOOSE, *HOURS))
            self._error = self._gui.add_markdown("")

            def submit() -> None:
                on_submit({
                    "age": age.value.strip(),
                    "gender": "" if gender.value == CHOOSE else gender.value,
                    "handedness": "" if hand.value == CHOOSE else hand.value,
                    "avr_experience": _rated(avr.value),
                    "avr_hours": _bucket(avr_hours.value),
                    "games_experience": _rated(games.value),
                    "games_hours": _bucket(games_hours.value),
                })  # fmt: skip

            self._button("Continue", submit)

    def trial(self, heading: str, text: str, on_start: Callable[[], None]) -> None:
        """Before and during a trial: what it is (``text``), its timer and state, and Start,
        which goes once pressed, with the line that asks for it."""
        with self._new(heading):
            intro = self._gui.add_markdown(f"{text} {PRESS_START}")
            # Markdown wraps: a read-only text field cut long states off at the panel's edge.
            self._status = self._gui.add_markdown(_status(0.0, "press Start when ready"))
            start = self._gui.add_button("Start")

            def started(_: object) -> None:
                start.remove()
                intro.content = text
                on_start()

            start.on_click(started)

    def running(self, elapsed_s: float, state: str) -> None:
        """The trial's timer (s) and state, on its page."""
        text = _status(elapsed_s, state)
        if self._status is not None and self._status.content != text:  # a change is a message
            self._status.content = text

    def questionnaire(
        self,
        classes: Sequence[tuple[str, str]],
        items: Sequence[tuple[str, str, tuple[str, str]]],
        on_submit: Callable[[Mapping[tuple[str, str], int]], None],
    ) -> None:
        """A 1-7 rating of each item for each class: ``classes`` are (key, what the participant
        reads), ``items`` (key, what the participant reads, what 1 and 7 mean); ``on_submit``
        gets the ratings, 0 where none was chosen."""
        with self._new("Questionnaire"):
            self._gui.add_markdown("Rate each kind of display aid you saw, from 1 to 7.")
            ratings = {}
            for class_key, class_text in classes:
                self._gui.add_markdown(f"**{class_text}**")
                for item_key, item_text, ends in items:
                    ratings[class_key, item_key] = self._rating(item_text, ends)
            self._error = self._gui.add_markdown("")
            self._button(
                "Submit", lambda: on_submit({k: _rated(r.value) for k, r in ratings.items()})
            )

    def error(self, text: str) -> None:
        """What is wrong with the page's answers, shown on it."""
        if self._error is not None:
            self._error.content = f"**{text}**" if text else ""

    def _new(self, title: str) -> viser.GuiFolderHandle:
        if self._page is not None:
            self._page.remove()
        self._error = self._status = None
        self._page = self._gui.add_folder(title, order=-1.0)
        return self._page

    def _rating(self, label: str, ends: tuple[str, str]) -> viser.GuiDropdownHandle[str]:
        """A 1-7 rating whose ends read ``ends`` (1 and 7), unanswered until chosen."""
        return self._gui.add_dropdown(label, (CHOOSE, *_scale(ends)))

    def _button(self, label: str, on_click: Callable[[], None]) -> None:
        self._gui.add_button(label).on_click(lambda _: on_click())


def _status(elapsed_s: float, state: str) -> str:
    return f"**Timer** {elapsed_s:.1f} s: {state}"


EXPERIENCE = ("none", "a great deal")
"""The experience scales' ends."""


def _scale(ends: tuple[str, str]) -> tuple[str, ...]:
    """The 1-7 options, the first and the last with what they mean: "1 (none)", ..."""
    return (f"1 ({ends[0]})", *RATINGS[1:-1], f"7 ({ends[1]})")


def _rated(value: str) -> int:
    """The rating an option stands for (its leading digit); 0 for none chosen."""
    head = value.split(" ", 1)[0]
    return int(head) if head in RATINGS else 0


def _bucket(value: str) -> int:
    return HOURS.index(value) + 1 if value in HOURS else 0
