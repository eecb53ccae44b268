"""How a simulated participant answers the post-study questionnaire (docs/explanation/study.md §4).

For each AR class (embodiment, manipulation, task: the modality that shows that class alone)
and each item (presence, embodiment, ease), on the 1-7 Likert scale:

    score = clip(round(4 + leniency + effect + noise), 1, 7)

- ``leniency`` ~ N(0, LENIENCY_SD): a rater's own offset, the same for all their answers.
- ``noise`` ~ N(0, ANSWER_SD): each answer's own scatter.
- ``effect`` comes from what the participant lived through, never from the class's name:
  - ease: ``EASE_GAIN * tanh(ln(T_none / T_class))``, the participant's own completion time
    without AR against with the class (a failed trial counts as its timeout): a class that
    made them faster is rated easier.
  - presence: ``PRESENCE_GAIN * tanh(ln(E_none / E_class))`` with the placement errors (a
    failed trial: ``FAILED_ERROR_M``): cues that put the bowl where it belongs make the remote
    scene feel more present.
  - embodiment: ``EMBODIMENT_GAIN`` when the class draws the robot's own body (the ghost layer),
    else 0: the sense of embodiment needs a body to own.

The gains are Likert points, chosen so that a class that halves the time moves ease by about
1.5 points: in the original study the ratings spread over most of the scale
(docs/explanation/study.md §4). In a study that crosses delay with cues, a participant's answers
come from their trials under the least delay (the questionnaire asks about the cues, not the
network). Only the classes the study's conditions draw are asked about (:func:`classes_shown`),
of a simulated participant as of a person. Real answers replace these with
``arteleop study answer``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd

from arteleop.analysis.data import AR_CLASSES, NETWORK_COLUMNS
from arteleop.analysis.data import QUESTIONNAIRE_ITEMS as ITEMS
from arteleop.ar_features import LAYER_NAMES, modality_cues
from arteleop.study.definition import StudyConfig

LENIENCY_SD = 0.7
ANSWER_SD = 0.8
EASE_GAIN = 2.0
PRESENCE_GAIN = 1.5
EMBODIMENT_GAIN = 1.5
FAILED_ERROR_M = 0.10
"""Placement error a failed trial counts as (m): the largest the original study saw."""


def classes_shown(study: StudyConfig) -> tuple[str, ...]:
    """The AR classes (:data:`AR_CLASSES`) of which some layer is drawn in a condition of
    ``study``: what its questionnaire asks about. Practice is left out: its aids are not
    compared."""
    drawn = [modality_cues(c.modality) for c in study.planned_conditions]
    return tuple(
        ar_class
        for ar_class in AR_CLASSES
        if any(
            getattr(modality_cues(ar_class), layer) and getattr(cues, layer)
            for cues in drawn
            for layer in LAYER_NAMES
        )
    )


def simulated_answers(
    participant: str,
    seed: Sequence[int],
    experimental: pd.DataFrame,
    timeout_s: float,
    classes: Sequence[str] = AR_CLASSES,
    items: Sequence[str] = ITEMS,
) -> list[tuple[str, str, str, int]]:
    """(participant, ar_class, item, score) rows for one participant, from their experimental
    trials (``modality``, ``outcome``, ``completion_time_s``, ``placement_error_m``), for the
    AR classes in ``classes`` and the items in ``items`` of the original study's (each answer
    the same whichever others are asked; the model answers no other item)."""
    rng = np.random.default_rng(seed)
    network = [c for c in NETWORK_COLUMNS if c in experimental]
    least_delay = experimental.sort_values(network, kind="stable").drop_duplicates("modality")
    by_modality = least_delay.set_index("modality")
    leniency = rng.normal(0.0, LENIENCY_SD)
    rows = []
    for ar_class in AR_CLASSES:
        effects = {
            "presence": PRESENCE_GAIN * _ratio(by_modality, ar_class, "placement_error_m",
                                               FAILED_ERROR_M),
            "embodiment": EMBODIMENT_GAIN if modality_cues(ar_class).ghost else 0.0,
            "ease": EASE_GAIN * _ratio(by_modality, ar_class, "completion_time_s", timeout_s),
        }  # fmt: skip
        for item in ITEMS:
            raw = 4.0 + leniency + effects[item] + rng.normal(0.0, ANSWER_SD)
            if ar_class in classes and item in items:
                rows.append((participant, ar_class, item, int(np.clip(round(raw), 1, 7))))
    return rows


def _ratio(by_modality: pd.DataFrame, ar_class: str, column: str, failed: float) -> float:
    """tanh(ln(value without AR / value with the class)); 0 when either trial is missing."""
    if "none" not in by_modality.index or ar_class not in by_modality.index:
        return 0.0
    values = []
    for modality in ("none", ar_class):
        row = by_modality.loc[modality]
        value = float(row[column]) if row["outcome"] == "success" else failed
        values.append(max(value, 1e-3) if math.isfinite(value) else failed)
    return math.tanh(math.log(values[0] / values[1]))
