"""What the questionnaire asks: statements each AR class a participant saw is rated on, 1 to 7.

A study gives its own (``[[questionnaire]]`` tables in the study file, or a file of them named
by ``questionnaire_file``), for instance the items its ethics board approved; the default is the
original study's three (docs/explanation/study.md §4: sense of presence, embodiment and ease of
the task, rated per AR class).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from arteleop.analysis.data import ITEM_ID
from arteleop.errors import StudyDefinitionError

if TYPE_CHECKING:
    from arteleop.study.definition import StudyConfig

MAX_ITEMS = 20
"""At most this many items: each is asked for every AR class shown, on one page."""


@dataclass(frozen=True)
class QuestionnaireItem:
    """One statement the participant rates, 1 to 7, for each AR class it saw.

    Attributes:
        id: How questionnaire.csv and the analysis name it
            (:data:`~arteleop.analysis.data.ITEM_ID`).
        text: The statement as the page shows it.
        low: What 1 means, shown beside it.
        high: What 7 means.
    """

    id: str
    text: str
    low: str = "not at all"
    high: str = "very much"

    def __post_init__(self) -> None:
        if not ITEM_ID.fullmatch(self.id):
            raise StudyDefinitionError(
                f"questionnaire.id = {self.id!r}: expected lower-case letters, digits and _, a "
                "letter first, at most 32 (it names the item in questionnaire.csv)."
            )
        for key in ("text", "low", "high"):
            value = getattr(self, key)
            if not value.strip() or not value.isprintable():
                raise StudyDefinitionError(
                    f"questionnaire.{key} = {value!r} (item {self.id!r}): expected one line of "
                    "printable text."
                )


ORIGINAL_QUESTIONNAIRE = (
    QuestionnaireItem("presence", "I felt present at the robot's place"),
    QuestionnaireItem("embodiment", "The robot arm felt like my own arm"),
    QuestionnaireItem("ease", "The task was easy to do"),
)
"""The original study's items, in its order."""


def check_items(items: tuple[QuestionnaireItem, ...]) -> None:
    """Refuses no item, more than :data:`MAX_ITEMS`, or an id given twice."""
    if not 1 <= len(items) <= MAX_ITEMS:
        raise StudyDefinitionError(
            f"questionnaire: {len(items)} items; expected 1 to {MAX_ITEMS} [[questionnaire]] "
            "tables (remove the key for the original study's three)."
        )
    ids = [item.id for item in items]
    for k, item_id in enumerate(ids):
        if item_id in ids[:k]:
            raise StudyDefinitionError(
                f"questionnaire.id = {item_id!r}: item {k + 1} repeats item "
                f"{ids.index(item_id) + 1}; each item needs an id of its own."
            )


def modelled_items(study: StudyConfig) -> list[str]:
    """The ids of the study's items that the simulated participant answers: the original's, asked
    in the original's words (an item that only shares an id answers nothing of the model's)."""
    return [item.id for item in study.questionnaire if item in ORIGINAL_QUESTIONNAIRE]
