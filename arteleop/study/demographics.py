"""A participant's answers to the questions before the trials, as the served page takes them:
each checked before use, a bad one a :class:`SessionInputError` naming the question."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from arteleop.errors import ArteleopError
from arteleop.study.run_folder import REAL

GENDERS = ("female", "male", "diverse", "prefer not to say")
HANDEDNESS = ("right", "left", "both")
AGE_RANGE = (18, 99)
"""Ages a participant may give (years): adults, as an ethics board asks by default."""


class SessionInputError(ArteleopError):
    """A participant's answer is out of its range; the message names the question."""


@dataclass(frozen=True)
class Demographics:
    """A participant's answers to the questions before the trials (docs/explanation/study.md §4).

    Attributes:
        age: Years.
        gender: One of :data:`GENDERS`.
        handedness: One of :data:`HANDEDNESS`.
        avr_experience: Experience with AR/VR, Likert 1-7.
        avr_hours: Weekly AR/VR hours: 1 = under 2 h, 2 = 2-5 h, 3 = over 5 h.
        games_experience: Experience with video games, Likert 1-7.
        games_hours: Weekly video-game hours, the same buckets.
    """

    age: int
    gender: str
    handedness: str
    avr_experience: int
    avr_hours: int
    games_experience: int
    games_hours: int

    def __post_init__(self) -> None:
        check_whole("age", self.age, *AGE_RANGE, "years")
        _choice("gender", self.gender, GENDERS)
        _choice("handedness", self.handedness, HANDEDNESS)
        for name in ("avr_experience", "games_experience"):
            check_whole(name, getattr(self, name), 1, 7, "on the 1-7 scale")
        for name in ("avr_hours", "games_hours"):
            check_whole(name, getattr(self, name), 1, 3, "a weekly-hours bucket")

    @classmethod
    def from_form(cls, form: Mapping[str, object]) -> Demographics:
        """The answers as the page gave them (``age`` as typed, an unanswered choice empty or
        0); :class:`SessionInputError` names the first question to answer again."""
        age = str(form.get("age", "")).strip()
        # isdecimal, not isdigit: '²' and '③' are digits that int() refuses.
        check_whole("age", int(age) if age.isdecimal() else age, *AGE_RANGE, "years")
        for key, label in (("gender", "gender"), ("handedness", "handedness"),
                           ("avr_experience", "AR/VR experience"),
                           ("avr_hours", "AR/VR per week"),
                           ("games_experience", "video-game experience"),
                           ("games_hours", "video games per week")):  # fmt: skip
            if form.get(key) in ("", 0, None):
                raise SessionInputError(f"{label}: choose one of the answers.")
        keys = ("gender", "handedness", "avr_experience", "avr_hours", "games_experience",
                "games_hours")  # fmt: skip
        return cls(int(age), **{key: form[key] for key in keys})  # type: ignore[arg-type]

    def row(self, participant: str) -> tuple[object, ...]:
        """The participant's row of ``participants.csv``."""
        return (participant, self.age, self.gender, self.handedness, self.avr_experience,
                self.avr_hours, self.games_experience, self.games_hours, REAL)  # fmt: skip


def check_whole(name: str, value: object, low: int, high: int, unit: str) -> None:
    """Refuse ``value`` unless a whole number ``low``-``high`` (``unit`` says of what), with a
    :class:`SessionInputError` naming the question ``name``."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise SessionInputError(f"{name} {value!r}: expected a whole number {low}-{high} ({unit}).")


def _choice(name: str, value: object, options: tuple[str, ...]) -> None:
    if value not in options:
        raise SessionInputError(f"{name} {value!r}: expected one of {', '.join(options)}.")
