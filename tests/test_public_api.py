import importlib

import pytest

PACKAGES = ["arteleop.analysis", "arteleop.operator", "arteleop.robot", "arteleop.scene"]


@pytest.mark.parametrize("name", PACKAGES)
def test_every_name_in_all_exists(name: str) -> None:
    module = importlib.import_module(name)
    assert module.__all__ == sorted(module.__all__, key=lambda s: (not s.isupper(), s))
    for attr in module.__all__:
        assert hasattr(module, attr), f"{name}.__all__ lists {attr} but it is missing"
