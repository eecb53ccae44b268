"""Keys for the gripper: the step buttons and the Grip slider from the keyboard, in place of the
view's own camera keys while the robot's controls are on the page.

viser 1.1 passes no key presses to the server (viser-project/viser#691), so a short script on
the page presses the panel's own controls: a key goes through the panel's one sender as a click
does, and the server sees a press of the button. The script comes with an HTML element of the
panel (viser renders it as the page's HTML, where an image's ``onerror`` runs); it listens once
per page, before the view's camera controls (the capture phase of the window), and takes a key
only while the step buttons are shown and no text field has the focus (a closed dropdown, such
as the Step's after a choice, is no text field): the view keeps its keys on every other page,
and a key held down steps once.
"""

from __future__ import annotations

import html
import json

KEYS: dict[str, str] = {
    "KeyW": "away",
    "ArrowUp": "away",
    "KeyS": "nearer",
    "ArrowDown": "nearer",
    "KeyA": "left",
    "ArrowLeft": "left",
    "KeyD": "right",
    "ArrowRight": "right",
    "KeyE": "up",
    "KeyQ": "down",
}
"""Each key (a ``KeyboardEvent.code``: its place on the keyboard, named as on a QWERTY one) and
the step button it presses: the view's own keys for moving its camera (W A S D, the arrows, E
up and Q down), given to the gripper."""
GRIP_KEY = "KeyG"
"""Closes the gripper (the Grip slider to its end) when it is open, opens it when closed."""
KEYS_TEXT = "Keys: W A S D or the arrows move, E up, Q down; G closes or opens the grip."
"""What the panel says of the keys."""

_SCRIPT = """
if (!window.arteleopKeys) {
  window.arteleopKeys = true;
  const steps = STEPS;
  const shown = (text) => [...document.querySelectorAll("button")].find(
    (b) => b.textContent.trim() === text && b.offsetParent !== null);
  const typing = (t) => t instanceof HTMLElement && (t.isContentEditable
    || t.tagName === "TEXTAREA" || t.tagName === "SELECT"
    || t.getAttribute("aria-expanded") === "true"
    || (t.tagName === "INPUT" && !t.readOnly && t.getAttribute("role") !== "combobox"));
  window.addEventListener("keydown", (e) => {
    const step = steps[e.code];
    if ((!step && e.code !== GRIP) || e.ctrlKey || e.metaKey || e.altKey) return;
    if (typing(e.target) || !shown(steps.KeyS)) return;
    e.preventDefault();
    e.stopPropagation();
    if (e.repeat) return;
    if (step) { shown(step).click(); return; }
    const slider = document.querySelector("[role=slider]");
    const closed = Number(slider.getAttribute("aria-valuenow")) >= 0.5;
    slider.dispatchEvent(new KeyboardEvent("keydown", {key: closed ? "Home" : "End",
                                                        bubbles: true}));
  }, true);
}
"""


def keys_html() -> str:
    """The panel element that says what the keys do and gives them to the gripper: a line of
    text and an image that fails to load, whose error handler adds the listener."""
    script = _SCRIPT.replace("STEPS", json.dumps(KEYS)).replace("GRIP", json.dumps(GRIP_KEY))
    return (
        f'<div style="font-size: 0.8em; opacity: 0.8">{html.escape(KEYS_TEXT)}</div>'
        f'<img alt="" src="data:," style="display: none" onerror="{html.escape(script)}">'
    )
