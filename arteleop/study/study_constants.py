"""The simulated participant's constants a study may change (``[operator_params]``): the plain
numbers of :class:`~arteleop.operator.OperatorParams`, for a sensitivity run. A movement's
scatter, perception's constants and the outcomes seen stay the model's."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import replace
from typing import get_type_hints

from arteleop.errors import StudyDefinitionError
from arteleop.operator.simulated.params import OperatorParams

OPERATOR_PARAMS_KEYS = tuple(
    name for name, hint in get_type_hints(OperatorParams).items() if hint in (float, int)
)
"""The constants a study may change, by name."""


def check_study_constants(params: OperatorParams) -> None:
    """Refuse ``params`` that differ from the model's in more than :data:`OPERATOR_PARAMS_KEYS`:
    a run folder's study file could not say so."""
    model = OperatorParams()
    plain = {key: getattr(model, key) for key in OPERATOR_PARAMS_KEYS}
    if replace(params, **plain) != model:
        raise StudyDefinitionError(
            "operator_params: a study may change only the plain-number constants "
            f"({', '.join(OPERATOR_PARAMS_KEYS)}); a movement's scatter, perception's "
            "constants and the outcomes seen stay the model's."
        )


def refuse_unknown_constants(keys: Iterable[str], at: Callable[[str], str]) -> None:
    """Refuse a study file's ``[operator_params]`` key that is not one of
    :data:`OPERATOR_PARAMS_KEYS`; ``at(key)`` says where the file gives it."""
    for key in keys:
        if key not in OPERATOR_PARAMS_KEYS:
            raise StudyDefinitionError(
                f"{at(key)}: unknown key 'operator_params.{key}'. A study may change these of "
                f"the model's constants: {', '.join(OPERATOR_PARAMS_KEYS)}."
            )
