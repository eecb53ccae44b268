"""The range checks shared by the configuration dataclasses."""

import math
from dataclasses import dataclass

import pytest

from arteleop.checks import Bounds, check_fields
from arteleop.errors import ConfigurationError, StudyDefinitionError


@dataclass(frozen=True)
class _Config:
    gain: float = 1.0
    share: float = 0.5


@pytest.mark.parametrize(
    ("bounds", "value", "admitted"),
    [
        (Bounds(0, above=True), 0.0, False),
        (Bounds(0, above=True), 1e-12, True),
        (Bounds(0), 0.0, True),
        (Bounds(0), -1e-12, False),
        (Bounds(0.5, 0.999), 0.999, True),
        (Bounds(0.5, 0.999), 0.9991, False),
        (Bounds(0), math.inf, False),
        (Bounds(), math.nan, False),
        (Bounds(), -math.inf, False),
    ],
)
def test_bounds_admit_finite_values_within_them(bounds: Bounds, value: float, admitted: bool):
    assert bounds.admits(value) is admitted


@pytest.mark.parametrize(
    ("bounds", "said"),
    [
        (Bounds(0, above=True), "> 0"),
        (Bounds(0), ">= 0"),
        (Bounds(0.5, 0.999, "a probability"), "0.5-0.999 (a probability)"),
        (Bounds(0, 1), "0-1"),
        (Bounds(0, 0.5, "rad", above=True), "> 0 and <= 0.5 (rad)"),  # 0 is not admitted
        (Bounds(0.01, 100.0, text="a cutoff of 0.01-100 Hz"), "a cutoff of 0.01-100 Hz"),
    ],
)
def test_bounds_say_what_they_admit(bounds: Bounds, said: str):
    assert str(bounds) == said


def test_the_first_field_out_of_bounds_is_named_with_its_value_and_range():
    bounds = {"gain": Bounds(0, above=True), "share": Bounds(0, 1, "a share")}
    check_fields(_Config(), bounds)
    with pytest.raises(ConfigurationError) as err:
        check_fields(_Config(gain=math.inf, share=2.0), bounds)
    assert str(err.value) == "_Config.gain = inf: expected > 0."
    with pytest.raises(StudyDefinitionError) as err:
        check_fields(_Config(share=2.0), bounds, StudyDefinitionError)
    assert str(err.value) == "_Config.share = 2.0: expected 0-1 (a share)."
