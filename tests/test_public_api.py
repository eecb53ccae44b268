import importlib
import subprocess
import sys
import warnings

import pytest

PACKAGES = [
    "arteleop.analysis",
    "arteleop.ar_features",
    "arteleop.calibration",
    "arteleop.frames",
    "arteleop.operator",
    "arteleop.operator.simulated",
    "arteleop.operator.wearable",
    "arteleop.robot",
    "arteleop.scene",
    "arteleop.study",
    "arteleop.teleop",
]


@pytest.mark.parametrize("name", PACKAGES)
def test_every_name_in_all_exists(name: str) -> None:
    module = importlib.import_module(name)
    assert module.__all__ == sorted(module.__all__, key=lambda s: (not s.isupper(), s))
    for attr in module.__all__:
        assert hasattr(module, attr), f"{name}.__all__ lists {attr} but it is missing"


def test_the_operator_package_loads_without_the_view_server() -> None:
    """`arteleop.operator` needs the display frame, not viser's server or its websockets; the
    loop's package loads the live application's server only when asked for it."""
    code = (
        "import sys, arteleop.operator, arteleop.ar_features, arteleop.teleop; "
        "print(sorted(m for m in ('viser', 'websockets') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_a_trial_loads_without_the_mesh_plotting_and_statistics_libraries() -> None:
    """What a trial needs starts in about 3 s; open3d (with dash and IPython), trimesh,
    matplotlib and statsmodels would add 4 s: they load where they are used."""
    heavy = ("open3d", "trimesh", "matplotlib", "statsmodels", "dash", "IPython")
    code = (
        "import sys, arteleop.scene, arteleop.teleop, arteleop.analysis; "
        f"print(sorted(m for m in {heavy!r} if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_the_analysis_knows_the_same_modalities_as_the_view() -> None:
    """analysis/ imports nothing else from arteleop, so it keeps its own list: the same one."""
    from arteleop.analysis.data import CUE_NAMES
    from arteleop.analysis.data import MODALITIES as ANALYSED
    from arteleop.ar_features import LAYER_NAMES, MODALITIES, STUDY_MODALITIES

    assert ANALYSED == STUDY_MODALITIES
    assert sorted(CUE_NAMES) == sorted([*MODALITIES, *LAYER_NAMES])


@pytest.mark.parametrize(
    ("old", "name", "home", "until"),
    [
        ("arteleop.operator", "reconstruct", "arteleop.teleop", "0.3"),
        ("arteleop.operator", "SensorMounting", "arteleop.teleop", "0.3"),
        ("arteleop.operator.reconstruction", "StreamingReconstructor",
         "arteleop.teleop.reconstruction", "0.3"),
        ("arteleop.operator.calibration", "calibrate_from_hold",
         "arteleop.teleop.sensor_calibration", "0.3"),
        ("arteleop.operator.recording", "load_recording",
         "arteleop.operator.wearable.recording_file", "0.3"),
        ("arteleop.operator", "TaskGeometry", "arteleop.operator.simulated.tasks", "0.3"),
        ("arteleop.ar_features", "ViewProbe", "tests.instruments.view_probe", "0.3"),
    ],
)  # fmt: skip
def test_a_name_that_moved_is_found_at_its_old_home_with_a_warning(
    old: str, name: str, home: str, until: str
) -> None:
    """Scripts written for the release before keep working, told where the name went."""
    with warnings.catch_warnings():  # a module that moved too warns of that (tested below)
        warnings.simplefilter("ignore", DeprecationWarning)
        module = importlib.import_module(old)
    new_name = {"TaskGeometry": "PickAndPlace"}.get(name, name)
    renamed = f" as {new_name}" if new_name != name else ""
    message = (
        f"{old}.{name} has moved: import it from {home}{renamed} ({old} re-exports it through "
        f"{until} only)"
    )
    with pytest.warns(DeprecationWarning) as caught:
        moved = getattr(module, name)
    assert [str(w.message) for w in caught] == [message]
    assert moved is getattr(importlib.import_module(home), new_name)
    with pytest.raises(AttributeError, match=f"module '{old}' has no attribute 'NoSuchName'"):
        module.NoSuchName  # noqa: B018


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("arteleop.operator.synthetic", "arteleop.operator.simulated.synthetic"),
        ("arteleop.operator.tasks.pointing", "arteleop.operator.simulated.tasks.pointing"),
        ("arteleop.operator.recording_file", "arteleop.operator.wearable.recording_file"),
    ],
)
def test_a_module_that_moved_is_found_at_its_old_name_with_a_warning(old: str, new: str) -> None:
    """The same module, not a second copy of it (its classes would then be other classes)."""
    for name in [n for n in sys.modules if n == old or old.startswith(n + ".")]:
        if name.startswith("arteleop.operator.") and name.count(".") > 1:
            sys.modules.pop(name)  # an alias a test before left: import it afresh
    with pytest.warns(DeprecationWarning) as caught:
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)
    assert module.__spec__.name == new  # its own, not the old name's: a reload runs its file
    assert str(caught[-1].message) == (
        f"the module {old} has moved to {new}: import it from there ({old} is found through "
        "0.4 only)"
    )


def test_the_version_is_the_one_pyproject_gives() -> None:
    import tomllib
    from pathlib import Path

    import arteleop

    pyproject = Path(__file__).resolve().parent.parent / "pyproject.toml"
    with pyproject.open("rb") as f:
        assert arteleop.__version__ == tomllib.load(f)["project"]["version"]


def test_the_names_that_moved_in_0_2_are_gone_from_the_scene_in_0_3() -> None:
    import arteleop.scene

    with pytest.raises(AttributeError, match="has no attribute 'TransformGraph'"):
        arteleop.scene.TransformGraph  # noqa: B018
