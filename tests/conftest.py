"""Shared fixtures. The robot description is generated once per session into a temporary cache,
so the tests also exercise mesh decimation and URDF rewriting from a clean state."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import pytest

from arteleop.robot import BaxterDescription, BaxterDescriptionConfig, load_baxter_description
from arteleop.scene import RemoteSite, SiteConfig
from tests.helpers import unavailable


@pytest.fixture(scope="session")
def description_config(tmp_path_factory: pytest.TempPathFactory) -> BaxterDescriptionConfig:
    return BaxterDescriptionConfig(cache_dir=Path(tmp_path_factory.mktemp("arteleop-cache")))


@pytest.fixture(scope="session")
def description(description_config: BaxterDescriptionConfig) -> BaxterDescription:
    return load_baxter_description(description_config)


@pytest.fixture(scope="session")
def site_config(description_config: BaxterDescriptionConfig) -> SiteConfig:
    return SiteConfig(robot=description_config)


@pytest.fixture(scope="session")
def gl_site_config(site_config: SiteConfig) -> SiteConfig:
    """The site with the OpenGL head camera; skipped where no EGL context opens, but on CI
    (which installs Mesa's EGL), where that fails."""
    from arteleop.scene.gl_renderer import RendererUnavailableError, gl_context

    try:
        gl_context()
    except RendererUnavailableError as err:
        unavailable(err)
    return replace(site_config, camera=replace(site_config.camera, renderer="gl"))


@pytest.fixture
def site(site_config: SiteConfig) -> Iterator[RemoteSite]:
    with RemoteSite(site_config) as s:
        yield s


@pytest.fixture
def noiseless_site(site_config: SiteConfig) -> Iterator[RemoteSite]:
    from arteleop.scene import DepthNoiseConfig

    camera = replace(site_config.camera, noise=DepthNoiseConfig(enabled=False, quantize=False))
    with RemoteSite(replace(site_config, camera=camera)) as s:
        yield s


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Under ``--dist loadgroup`` a file's tests go to one worker, as under ``loadfile`` (its
    shared set-ups run once), and the files marked ``xdist_group("chromium")`` go to one
    worker in turn: two headless Chromiums drawing WebGL in software beside two servers made a
    2-core CI machine miss the browser tests' timeouts."""
    for item in items:
        if item.get_closest_marker("xdist_group") is None:
            item.add_marker(pytest.mark.xdist_group(item.nodeid.partition("::")[0]))
