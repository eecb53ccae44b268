"""The live application: the simulation in real time, served to the browser, trial after trial.

The operator is a synthetic participant (a new seeded trial after each one), a recording (replayed
again on "Start trial"), or a person driving the gripper's target with a gizmo and a grip slider.
The view's trial panel shows the trial's state; its buttons reset the robot to rest and start a
trial.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from arteleop.ar_features import OperatorView, ViewConfig, modality_cues
from arteleop.ar_features.live_input import LiveInput
from arteleop.ar_features.trial_panel import TrialPanel
from arteleop.errors import ArteleopError
from arteleop.lifetime import Closeable
from arteleop.operator import (
    HandTarget,
    OperatorSource,
    RecordingSource,
    check_operator,
    live_source,
    load_recording,
)
from arteleop.scene import RemoteSite
from arteleop.teleop.display_feed import site_frame, view_assets
from arteleop.teleop.loop import run_trial, trial_operator
from arteleop.teleop.trial import TrialConfig, TrialProgress, TrialResult


class TrialInterrupted(ArteleopError):
    """The trial was stopped from the panel."""


READY = "press Start trial when ready"
"""The state shown before a person's first trial."""
AT_REST = "at the rest pose: press Start trial"
"""The state shown after a reset."""


@dataclass(frozen=True)
class TeleopAppConfig:
    """The live application's settings.

    Attributes:
        operator: ``synthetic``, ``live`` (gizmo and grip slider) or a recording's CSV path.
        trial: The trials' settings; ``seed`` is the first synthetic trial's, each next trial
            takes the next seed. Real time and rendering are always on.
        view: Where the view is served.
        pause_s: Synthetic trials: the pause between one trial's end and the next (s).
    """

    operator: str = "synthetic"
    trial: TrialConfig = field(default_factory=TrialConfig)
    view: ViewConfig = field(default_factory=ViewConfig)
    pause_s: float = 3.0

    def __post_init__(self) -> None:
        check_operator(self.operator, live=True)


class TeleopApp(Closeable):
    """Runs trials until :meth:`stop` (or Ctrl-C); see the module's docstring. A context
    manager: closing it stops the view's server (the caller owns the site)."""

    def __init__(self, config: TeleopAppConfig, site: RemoteSite) -> None:
        self.config = config
        self.site = site
        trial = replace(config.trial, realtime=True, render_camera=True)
        self._trial = trial
        self.view = OperatorView(config.view, view_assets(site))
        self.panel = TrialPanel(self.view.server.gui)
        rest = site.observe()
        self._rest_gripper_m = rest.gripper_m
        self._target: HandTarget | None = None
        self._live: LiveInput | None = None
        if config.operator == "live":
            self._target = HandTarget(self._rest_gripper_m)
            grip = trial.controller.grip
            self._live = LiveInput(
                self.view.server, self._rest_gripper_m, self._target.set,
                grip.close_at, grip.open_at, rest.camera.T_base_camera,
            )  # fmt: skip
        self._recording = (
            load_recording(Path(config.operator))
            if config.operator not in ("synthetic", "live")
            else None
        )
        self._start = threading.Event()
        self._interrupt = threading.Event()
        self._stopped = threading.Event()
        self.panel.on_start(self.start_trial)
        self.panel.on_reset(self.reset)
        self.results: list[TrialResult] = []

    def run(self, on_trial: Callable[[TrialResult], None] | None = None) -> None:
        """Trial after trial until :meth:`stop`; ``on_trial`` hears each trial's result."""
        seed = self._trial.seed
        if self._live is None:
            self._start.set()  # a simulated or recorded operator's first trial starts at once
        else:  # a person starts when ready, the page open
            self._show_rest()
            self.panel.finished(READY, "")
        while not self._stopped.is_set():
            if not self._start.wait(timeout=0.1):
                continue
            self._start.clear()
            self._interrupt.clear()
            self.site.reset()
            if self._live is not None:
                self._live.reset()
            config = replace(self._trial, seed=seed)
            try:
                result = run_trial(self._source(config), config, self.site, self.view, self._tick)
            except TrialInterrupted:
                self.site.reset()
                if self._live is not None:
                    self._live.reset()
                self._show_rest()  # not "at the rest pose" over the stopped trial's last frame
                self.panel.finished(AT_REST, "")
                continue
            self.results.append(result)
            self.panel.finished(*trial_summary(result))
            if on_trial is not None:
                on_trial(result)
            if self.config.operator == "synthetic":  # the next participant, after a pause
                seed += 1
                self._start.wait(timeout=self.config.pause_s)
                self._start.set()

    def start_trial(self) -> None:
        """Start a trial now, unless one is running (the "Start trial" button)."""
        self._start.set()

    def reset(self) -> None:
        """Stop the running trial and wait at the rest pose for "Start trial" (the "Reset to
        rest pose" button)."""
        self._start.clear()
        self._interrupt.set()

    def close(self) -> None:
        self.stop()
        self.view.close()

    def stop(self) -> None:
        """End the run after the current control tick."""
        self._stopped.set()
        self._interrupt.set()

    def _show_rest(self) -> None:
        """The robot at rest on the view, the trial's layers on."""
        cues = modality_cues(self._trial.modality)
        self.view.show_still(site_frame(self.site, cues, True, self._trial.depth_aids))

    def _source(self, config: TrialConfig) -> OperatorSource:
        mapping = config.controller.mapping
        if self._target is not None:
            return live_source(self._target, mapping, config.seed)
        if self._recording is not None:
            return RecordingSource(self._recording)
        return trial_operator(self.site, config)

    def _tick(self, status: TrialProgress) -> None:
        if self._interrupt.is_set():
            raise TrialInterrupted("stopped from the panel")
        self.panel.show(self._trial.modality, status.elapsed_s, status.state)
        if self._live is not None:
            self._live.show_reach(status.reachable)


def trial_summary(result: TrialResult) -> tuple[str, str]:
    """The panel's state and result lines for a finished trial."""
    if result.placed:
        return (
            "placed",
            f"seed {result.seed}: {result.completion_time_s:.1f} s, "
            f"{result.placement_error_m * 1000:.0f} mm from the target",
        )
    reason = result.outcome.value.replace("_", " ")
    return f"failed: {reason}", f"seed {result.seed}: {reason} after {result.duration_s:.0f} s"
