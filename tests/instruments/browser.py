"""Pictures of the operator's view: headless Chromium, driven by playwright, on the page.

Needs playwright (the ``test`` extra) and a system Chromium (Debian: ``apt-get install
chromium``); playwright never downloads a browser of its own here.
"""

from __future__ import annotations

import shutil
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import cv2
import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ArteleopError

VIEWPORT = {"width": 1280, "height": 800}
LLVMPIPE = ["--use-angle=gl-egl", "--ignore-gpu-blocklist", "--enable-unsafe-swiftshader"]
"""WebGL without a GPU: Mesa's llvmpipe through ANGLE's GL ES backend, which Chromium blocks by
default; SwiftShader where Mesa's drivers are missing. A still viser page cost a quarter of the
processor SwiftShader's did, and a page drew a third more frames
(benchmarks/bench_browser_gl.py)."""
SWIFTSHADER = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
"""Chromium's own software WebGL."""
# Background networking off: this machine has no network.
CHROMIUM_ARGS = [
    "--no-sandbox", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--no-first-run",
]  # fmt: skip


class BrowserError(ArteleopError):
    """No browser to take the picture with, or the page never settled."""


def chromium_path() -> str:
    """The system's Chromium."""
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        raise BrowserError(
            "Chromium is not installed: install it with 'apt-get install chromium' (Debian)."
        )
    return path


def require_chromium() -> None:
    """Skip the calling test without Chromium; fail it under CI, which installs it."""
    from tests.helpers import unavailable

    try:
        chromium_path()
    except BrowserError as err:
        unavailable(err)


class Page:
    """One browser tab on a view; screenshots once the drawing has settled."""

    def __init__(self, page: object) -> None:
        self._page = page

    @property
    def playwright(self) -> Any:
        """The tab's playwright page, to click and type on."""
        return self._page

    def close(self) -> None:
        """Close the tab: its viser client goes."""
        self._page.close()  # type: ignore[attr-defined]

    def scene_size_px(self) -> tuple[float, float]:
        """The 3D scene's width and height on the page (CSS pixels): the page beside the
        docked panel."""
        size = self._page.evaluate(  # type: ignore[attr-defined]
            "() => { const r = document.querySelector('canvas').getBoundingClientRect();"
            " return [r.width, r.height]; }"
        )
        return float(size[0]), float(size[1])

    def shows(self, text: str) -> bool:
        """Whether an element labelled ``text`` is visible inside the tab's viewport."""
        found = self._page.get_by_text(text, exact=True).first  # type: ignore[attr-defined]
        if not found.is_visible():
            return False
        box = found.bounding_box()
        size = self._page.viewport_size  # type: ignore[attr-defined]
        return (
            box is not None
            and box["x"] >= 0 and box["y"] >= 0
            and box["x"] + box["width"] <= size["width"]
            and box["y"] + box["height"] <= size["height"]
        )  # fmt: skip

    def screenshot(self, path: Path, timeout_s: float = 60.0) -> NDArray[np.uint8]:
        """The tab's pixels (H, W, 3) RGB, once two shots half a second apart are equal."""
        previous = None
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            time.sleep(0.5)
            self._page.screenshot(path=str(path))  # type: ignore[attr-defined]
            shot = cv2.cvtColor(cv2.imread(str(path)), cv2.COLOR_BGR2RGB)
            if previous is not None and np.array_equal(shot, previous):
                return shot
            previous = shot
        raise BrowserError(f"The view's page never stopped changing in {timeout_s} s.")


class Browser:
    """A headless Chromium; each :meth:`open` is a tab of its own (a viser client)."""

    def __init__(self, browser: object) -> None:
        self._browser = browser

    def open(
        self, url: str, for_pictures: bool = True, viewport: dict[str, int] = VIEWPORT
    ) -> Page:
        """A new tab on ``url`` of ``viewport``'s size (CSS px); ``for_pictures``: once the
        software-WebGL notice, which covers a corner of the scene, has come and been
        dismissed."""
        page = self._browser.new_page(viewport=viewport)  # type: ignore[attr-defined]
        page.goto(url)
        if for_pictures:
            notice = page.get_by_text("Software WebGL rendering detected")
            notice.wait_for(timeout=15_000)
            page.locator(".mantine-Notification-root button").first.click()
        return Page(page)

    @contextmanager
    def tab(self, url: str) -> Iterator[Page]:
        """:meth:`open`, closed on leaving."""
        page = self.open(url)
        try:
            yield page
        finally:
            page.close()


@contextmanager
def chromium(webgl: list[str] = LLVMPIPE) -> Iterator[Browser]:
    """Headless Chromium drawing WebGL as ``webgl`` says, closed on leaving."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        args = [*webgl, *CHROMIUM_ARGS]
        browser = pw.chromium.launch(executable_path=chromium_path(), args=args)
        try:
            yield Browser(browser)
        finally:
            browser.close()


@contextmanager
def browser_page(url: str) -> Iterator[Page]:
    """A headless Chromium tab on ``url``, the software-WebGL notice dismissed."""
    with chromium() as browser:
        yield browser.open(url)


def text_field(tab: Any, label: str) -> Any:
    """A text input of ``tab`` by its label (viser's text inputs are not linked to their
    labels)."""
    row = f"//label[text()='{label}']/ancestor::div[contains(@class,'mantine-Flex-root')][1]"
    return tab.locator(f"xpath={row}//input").first


def press_button(tab: Any, name: str, timeout_s: float = 60.0) -> None:
    """Click the button of ``tab`` named ``name``."""
    tab.get_by_role("button", name=name, exact=True).click(timeout=timeout_s * 1000)


CHOICES = {"Gender": "female", "Handedness": "right", "AR/VR experience": "4",
           "AR/VR per week": "2-5 h", "Video-game experience": "4",
           "Video games per week": "under 2 h"}  # fmt: skip
"""A participant's answers to the start page's dropdowns."""


def choose(tab: Any, choices: dict[str, str] = CHOICES) -> None:
    """Pick each dropdown's option: ``choices`` maps a dropdown's label to the option."""
    for label, option in choices.items():
        tab.get_by_role("combobox", name=label).click()
        tab.get_by_role("option", name=option, exact=True).click()


def answer_questions(tab: Any, age: str = "31", choices: dict[str, str] = CHOICES) -> None:
    """Answer the start page's questions (``age`` in years, the dropdowns' ``choices``) and go
    on."""
    text_field(tab, "Age (years)").fill(age)
    choose(tab, choices)
    press_button(tab, "Continue")


def rate_every_item(tab: Any, rating: str) -> None:
    """Choose ``rating`` (1-7) in every dropdown the questionnaire shows, by clicks."""
    boxes = tab.get_by_role("combobox")
    for k in range(boxes.count()):
        boxes.nth(k).click()
        tab.get_by_role("option", name=rating, exact=True).click()
