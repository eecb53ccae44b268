"""A study served to people in their browser (``arteleop study serve``), one at a time.

Each person takes the next planned participant's place (:mod:`arteleop.study.session`) and goes
through the pages: information and consent, the questions about them, how to drive the robot,
the practice trials, the experimental trials in their counterbalanced order, the
questionnaire, the end. A trial runs in real time through the same loop as a simulated one,
driven by the gizmo, the step buttons and the Grip slider
(:class:`~arteleop.ar_features.live_input.LiveInput`), under its condition's AR layers and
network delay, its timer from motion onset; it starts when the person presses Start. A pointing
study (:class:`~arteleop.study.pointing_session.ServedPointingRun`) has the same pages without
practice and questionnaire, its trials ending at the person's selection.

One browser tab controls the session, the first to connect; another sees the robot's view and
"a session is in progress". Served with links (:attr:`ViewConfig.links`), a browser connects
only through the session's participant's own link (:meth:`ServedRun.token`): any other address
gets nothing, and a session's link stops working when the next participant's session begins;
an ended session's tab keeps its last page until the next participant's tab (or the
experimenter's) connects. The experimenter's link (:attr:`StudyServer.observer_link`) sees the
robot session after session and never controls.

When the controlling tab goes (closed, reloaded, the connection lost) during a trial, the
attempt is recorded as interrupted and the trial runs again from its start once a tab is back;
between trials nothing is lost, and the next tab carries on where the session was. A server
stopped and started again on the folder carries on the same way.
"""

from __future__ import annotations

import contextlib
import logging
import math
import statistics
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import replace

from arteleop.ar_features import OperatorView, ViewConfig, modality_cues
from arteleop.ar_features.page_frames import frames_drawn, read_in_background
from arteleop.ar_features.view import drew_a_frame
from arteleop.errors import ArteleopError, RunFolderError
from arteleop.lifetime import Closeable
from arteleop.operator import HandTarget, live_source
from arteleop.scene import HeadCameraConfig, RemoteSite
from arteleop.study.demographics import GENDERS, HANDEDNESS, Demographics, SessionInputError
from arteleop.study.plan import TrialSpec
from arteleop.study.questionnaire import classes_shown
from arteleop.study.session import BrowserCheck, ServedRun
from arteleop.study.session_tabs import SessionStopped, SessionTabs
from arteleop.study.session_words import (
    AGREE,
    AR_CLASS_TEXT,
    CANNOT_SAVE,
    SESSION_OVER,
    TRY_IT,
    consent_text,
    instructions_text,
)
from arteleop.teleop import (
    TrialProgress,
    run_trial,
    site_frame,
    view_assets,
)

ROUND_TRIPS = 3
"""Frames asked of the browser after each trial: their median is its display round trip."""
ROUND_TRIP_TIMEOUT_S = 5.0
"""A frame not back by then: the round trip is not known (a tab in the background draws none)."""


STARVED = (
    "participant %s, trial %s: the page drew %.1f frames a second, fewer than the %.1f clouds "
    "it was sent: the person saw the robot in jumps (a browser drawing without a GPU?). Ask "
    "them to close other tabs and turn on their browser's hardware acceleration, or serve a "
    "smaller image (--width-px, --height-px); browser.csv has each trial's figures"
)
"""The console's line for a page that could not show the stream it was sent."""

_log = logging.getLogger(__name__)


class SessionInterrupted(ArteleopError):
    """The controlling tab went during a trial: the attempt is recorded, the trial repeated."""


TUTORIAL_S = 600.0
"""The longest the robot runs on the page that says how to drive it (s)."""


class _TutorialOver(Exception):
    """The person went on from the page that says how to drive the robot."""


class StudyServer(Closeable):
    """Serves a :class:`ServedRun` to people until every session is over or :meth:`stop`.

    Args:
        run: The served run (its lock held by the caller).
        view: Where the page is served; with ``links``, each session by its participant's link.
        camera: The head camera of every trial (its registration stays the study's).
        on_link: Told each session's participant and link as the session begins (with links).
    """

    def __init__(
        self,
        run: ServedRun,
        view: ViewConfig,
        camera: HeadCameraConfig | None = None,
        on_link: Callable[[str, str], None] = lambda participant, url: None,
    ) -> None:
        self.run = run
        self._on_link = on_link
        self._observer: str | None = None
        self._site = run.site if camera is None else run.site.with_camera(camera)
        with RemoteSite(self._site.base) as site:
            # The layers are the trial's condition: no panel to switch them.
            self.view = OperatorView(replace(view, layer_panel=False), view_assets(site))
            rest = site.observe()
            self._rest_gripper_m, self._T_base_camera = rest.gripper_m, rest.camera.T_base_camera
            # The robot's view, plain: no AR layers, the depth aids if the study has them.
            self.view.show(site_frame(site, modality_cues("none"), False, run.study.depth_aids))
        self._target = HandTarget(self._rest_gripper_m)
        if self.view.gate is not None:
            self._observer = run.observer_token()
        self.tabs = SessionTabs(self.view, self._target, self._rest_gripper_m,
                                self._T_base_camera, self._observer)  # fmt: skip
        """The browsers' tabs: which controls the session, and what it is shown."""

    @property
    def url(self) -> str:
        return self.view.url

    @property
    def observer_link(self) -> str | None:
        """With links, the address of the experimenter's read-only view of every session."""
        return None if self._observer is None else self.view.link(self._observer)

    def serve(self) -> bool:
        """Session after session until every planned participant is done (True) or
        :meth:`stop` (False)."""
        try:
            while (person := self.run.current()) is not None:
                self._session(person.id)
        except SessionStopped:
            return False
        except RunFolderError:  # the disk is full or not writable: say so on the page too
            self.tabs.show(lambda p: p.message(*CANNOT_SAVE))
            self.view.deliver()
            raise
        self.run.finish_if_done()
        self.tabs.show(lambda p: p.message("Thank you", "Every session of this study is done. The "
                                       "researcher can close this page."))  # fmt: skip
        return True

    def stop(self) -> None:
        self.tabs.stop()

    def close(self) -> None:
        self.stop()
        self.view.deliver()  # the last page, "every session is done", stays on the tabs
        self.view.close()

    # The session, on the serving thread: each step shows a page, then waits for its answer.

    def _session(self, participant: str) -> None:
        run = self.run
        if (gate := self.view.gate) is not None:
            token = run.token(participant)
            self.tabs.begin_session(token)
            gate.allow({token, self._observer})
            self._on_link(participant, self.view.link(token))
        if not run.consented(participant):
            text = consent_text(run.study)
            self.tabs.show(lambda p: p.consent(text, AGREE, lambda: self.tabs.act("agree")))
            self.tabs.wait("agree")
            self._ask_demographics(participant)
        if not run.instructed(participant):
            self._tutorial(participant)
        while pending := run.pending(participant):
            self._trial(pending[0])
        if not run.answered(participant):
            classes = [(c, AR_CLASS_TEXT[c]) for c in classes_shown(run.study)]
            items = [(i.id, i.text, (i.low, i.high)) for i in run.study.questionnaire]
            self.tabs.show(
                lambda p: p.questionnaire(classes, items, lambda r: self.tabs.act("rate", r))
            )
            run.answer(participant, self._wait_for_ratings(classes, items))
        if self.view.gate is not None:  # the next participant comes by their own link
            self.tabs.show(lambda p: p.message("Thank you", f"{SESSION_OVER} You can close this "
                                           "page."))  # fmt: skip
            self.tabs.release()
        elif run.current() is not None:
            self.tabs.show(lambda p: p.message("Thank you", f"{SESSION_OVER} Please tell the "
                                           "researcher.",
                                           "Next participant (researcher)",
                                           lambda: self.tabs.act("next")))  # fmt: skip
            self.tabs.wait("next")

    def _wait_for_ratings(
        self, classes: list[tuple[str, str]], items: list[tuple[str, str, tuple[str, str]]]
    ) -> Mapping[tuple[str, str], int]:
        """The questionnaire's ratings once every item has one; until then the page names the
        first without."""
        while True:
            ratings = self.tabs.wait("rate")
            unrated = ((c, i) for c in classes for i in items if not ratings.get((c[0], i[0])))
            first = next(unrated, None)
            if first is None:
                return ratings
            (_, class_text), (_, item_text, _) = first
            message = f'"{item_text}", under "{class_text}": choose a rating, 1 to 7.'
            self.tabs.on_pages(lambda p, message=message: p.error(message))

    def _ask_demographics(self, participant: str) -> None:
        self.tabs.show(
            lambda p: p.demographics(lambda f: self.tabs.act("about", f), GENDERS, HANDEDNESS)
        )
        while True:
            form = self.tabs.wait("about")
            try:
                answers = Demographics.from_form(form)
            except SessionInputError as err:
                self.tabs.on_pages(lambda p, message=str(err): p.error(message))
                continue
            self.run.consent(participant, answers)
            return

    def _tutorial(self, participant: str) -> None:
        """How to drive the robot, with the robot to drive: the first trial's scene, condition
        and delay, recorded nowhere, until the person goes on (or its time is up), so that the
        lag is felt before the practice (before, the gizmo moved and the robot did not)."""
        text = f"{instructions_text(self.run.study)}\n\n{TRY_IT}"
        gone_on = threading.Event()

        def go_on() -> None:
            gone_on.set()
            self.tabs.act("next")

        self.tabs.show(lambda p: p.message("How to drive the robot", text, "Continue", go_on),
                   driving=True)  # fmt: skip

        def tick(status: TrialProgress) -> None:
            if gone_on.is_set() or self.tabs.stopped.is_set():
                raise _TutorialOver

        pending = self.run.pending(participant)
        # A try that ends (the bowl placed, or its time up) begins again from the start.
        while pending and not (gone_on.is_set() or self.tabs.stopped.is_set()):
            config = replace(self.run.trial_config(pending[0], self._site), realtime=True,
                             render_camera=True, timeout_s=TUTORIAL_S)  # fmt: skip
            with RemoteSite(config.site) as site:
                cues = modality_cues(pending[0].modality)
                self.view.show(site_frame(site, cues, True, config.depth_aids))
                if (live := self.tabs.live) is not None:
                    live.reset()
                source = live_source(self._target, config.controller.mapping, config.seed)
                self._pace_controller()
                try:
                    with contextlib.suppress(_TutorialOver):
                        run_trial(source, config, site, self.view, tick)
                finally:
                    self.view.pace(None)
        self.tabs.wait("next")

    def _pace_controller(self) -> None:
        """Send the cloud at the pace the controlling tab's connection carries."""
        controller = self.tabs.controller
        self.view.pace(None if controller is None else controller.client_id)

    def _trial(self, spec: TrialSpec) -> None:
        trials = self.run.trials_of(spec.participant)
        k, n = trials.index(spec) + 1, len(trials)
        heading = f"Trial {k} of {n}"
        text = self.run.trial_text(spec)
        config = replace(self.run.trial_config(spec, self._site),
                         realtime=True, render_camera=True)  # fmt: skip
        with RemoteSite(config.site) as site:
            # The scene as the trial will begin, its layers on, while the person gets ready.
            cues = modality_cues(spec.modality)
            self.view.show_still(site_frame(site, cues, True, config.depth_aids))
            if (live := self.tabs.live) is not None:  # the gizmo where the last trial left it
                live.reset()
            self.tabs.show(
                lambda p: p.trial(heading, text, lambda: self.tabs.act("start")), driving=True
            )
            self.tabs.wait("start")
            if (live := self.tabs.live) is not None:  # a tab may go meanwhile
                live.reset()
            self.tabs.lost.clear()
            cloud = self.view.cloud
            sent = (cloud.frames_drawn, cloud.payload_bytes, cloud.frames_held)
            self._pace_controller()
            tab = self.tabs.controller
            drawn = [None if tab is None else read_in_background(tab)]  # the page's own count
            start = time.perf_counter()
            self.tabs.trial_running.set()
            try:
                source = live_source(self._target, config.controller.mapping, config.seed)
                result = run_trial(source, config, site, self.view, self._tick)
            except SessionInterrupted:
                self.run.keep_interrupted(spec)
                return
            finally:
                self.tabs.trial_running.clear()
                drawn.append(None if tab is None else read_in_background(tab))
                pacer, latency_s = self.view.pacer, None
                if pacer is not None:
                    latency_s = pacer.take_latency_s()
                self.view.pace(None)
        wall_s = time.perf_counter() - start
        frames, payload = cloud.frames_drawn - sent[0], cloud.payload_bytes - sent[1]
        stream = {"cloud_frames": frames, "cloud_kbytes": payload / 1e3,
                  "cloud_mbit_s": payload * 8 / 1e6 / max(wall_s, 1e-9),
                  "cloud_frames_held": cloud.frames_held - sent[2],
                  "cloud_fps": frames / max(wall_s, 1e-9),
                  "link_latency_s": math.nan if latency_s is None else latency_s}  # fmt: skip
        self.view.settle()  # the scene the trial ended on, whole beside its outcome
        result_text = self.run.keep_result(spec, result, wall_s)
        devices = live.take_devices() if (live := self.tabs.live) is not None else ""
        self.tabs.show(
            lambda p: p.message(heading, result_text, "Next", lambda: self.tabs.act("next"))
        )
        # While the person reads the outcome: a silent page's count is waited for up to 5 s.
        page_frames, page_fps = frames_drawn(*drawn)
        if page_fps < stream["cloud_fps"]:  # False for NaN: a count not read says nothing
            _log.warning(STARVED, spec.participant, spec.trial_index, page_fps, stream["cloud_fps"])
        check = replace(self._check_browser(), input_device=devices, page_frames=page_frames,
                        page_fps=page_fps, **stream)  # fmt: skip
        self.run.keep_browser(spec, check)
        self.tabs.wait("next")

    def _check_browser(self) -> BrowserCheck:
        """The controlling browser's display round trip (NaN if it did not answer, or without
        a tab, or once the server is stopping) and scene size (0 without a tab)."""
        client = self.tabs.controller
        if client is None:
            return BrowserCheck(math.nan, 0, 0)
        times = []
        for _ in range(ROUND_TRIPS):
            if self.tabs.stopped.is_set():
                break
            begun = time.perf_counter()
            if not drew_a_frame(client, ROUND_TRIP_TIMEOUT_S):
                break
            times.append(time.perf_counter() - begun)
        round_trip_s = round(statistics.median(times), 4) if len(times) == ROUND_TRIPS else math.nan
        camera = client.camera
        return BrowserCheck(round_trip_s, camera.image_width, camera.image_height)

    def _tick(self, status: TrialProgress) -> None:
        if self.tabs.lost.is_set() or self.tabs.stopped.is_set():
            raise SessionInterrupted("the controlling tab went during the trial")
        self.tabs.on_pages(lambda p: p.running(status.elapsed_s, status.state))
        if (live := self.tabs.live) is not None:
            live.show_reach(status.reachable)
