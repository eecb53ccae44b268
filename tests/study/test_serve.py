"""A study served to people: the run folder's files, and a participant's path in a real browser."""

import csv
import json
import os
import queue
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from arteleop.ar_features.link_pacer import PING_TIMEOUT_S
from arteleop.errors import RunFolderError
from arteleop.scene import HeadCameraConfig
from arteleop.study import (
    CohortConfig,
    FamiliarizationConfig,
    StudyConfig,
    classes_shown,
    plan_study,
)
from arteleop.study.demographics import Demographics, SessionInputError
from arteleop.study.plan import EXPERIMENTAL
from arteleop.study.runner import resume_study
from arteleop.study.serve import StudyServer
from arteleop.study.session import (
    BROWSER_FILE,
    INTERRUPTED_FILE,
    LINKS_KEY_FILE,
    BrowserCheck,
    ServedRun,
    served_run,
)
from arteleop.study.session_words import AR_CLASS_TEXT, IN_PROGRESS, OBSERVING
from tests.helpers import serve_to
from tests.instruments.browser import (
    answer_questions,
    press_button,
    rate_every_item,
    text_field,
)
from tests.instruments.screen_reading import gizmo_red, of_hue
from tests.instruments.view_probe import admitted, refused, until

# One headless Chromium at a time in the suite: see tests/conftest.py.
pytestmark = pytest.mark.xdist_group("chromium")

STUDY = StudyConfig(
    name="served",
    # The first (P01's) without the ghost, whose meshes take software WebGL seconds to load.
    modalities=("task", "none"),
    # Time for a step button's press to land in the second trial on a busy machine (at 2 s a
    # fresh-clone CI run pressed it after the trial's end, and no device was recorded).
    timeout_s=5.0,
    familiarization=FamiliarizationConfig(trials=0),
    cohort=CohortConfig(size=2, avr_experts=0, games_experts=0, both_experts=0),
)
"""Two people, two trials of five seconds each, no practice."""
BUSY_ROUND_TRIP_S = 30.0
"""The longest a display round trip is waited for in this suite's real browser (s)."""
TUTORIAL_WAIT_S = 120.0
"""How long the tutorial's page may take to show and to draw (s)."""
ANSWERS = Demographics(31, "female", "right", 5, 2, 3, 1)


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def test_answers_out_of_range_are_refused_naming_the_question() -> None:
    form = {"age": "31", "gender": "male", "handedness": "left", "avr_experience": 4,
            "avr_hours": 1, "games_experience": 4, "games_hours": 3}  # fmt: skip
    assert Demographics.from_form(form) == Demographics(31, "male", "left", 4, 1, 4, 3)
    cases = {
        "age": ("17", "age 17: expected a whole number 18-99 (years)."),
        "gender": ("", "gender: choose one of the answers."),
        "games_hours": (0, "video games per week: choose one of the answers."),
        "avr_experience": (0, "AR/VR experience: choose one of the answers."),
    }
    for key, (value, message) in cases.items():
        with pytest.raises(SessionInputError) as err:
            Demographics.from_form({**form, key: value})
        assert str(err.value) == message
    for age in ("thirty", "²", "3①", "2_5"):  # '²' is a key of AZERTY keyboards
        with pytest.raises(SessionInputError, match=rf"^age '{age}': expected a whole number"):
            Demographics.from_form({**form, "age": age})
    assert Demographics.from_form({**form, "age": "３１"}).age == 31  # full-width digits
    with pytest.raises(SessionInputError, match=r"^avr_experience 8: expected a whole number 1-7"):
        Demographics(31, "male", "left", 8, 1, 4, 3)


def test_people_take_the_places_of_a_simulated_runs_plan(tmp_path: Path) -> None:
    """The same plan as ``study run``; consent, interrupted attempts and answers land in the
    files in plan order, and a run carries on where it was."""
    with served_run(tmp_path / "run", STUDY) as run:
        assert run.plan == plan_study(STUDY)
        assert json.loads((tmp_path / "run" / "manifest.json").read_text())["cohort"] == "real"
        assert run.current() is not None and run.current().id == "P01"
        run.consent("P02", ANSWERS)  # out of order: the file keeps plan order
        run.consent("P01", Demographics(40, "male", "left", 2, 1, 7, 3))
        first = run.pending("P01")[0]
        run.keep_interrupted(first)
        assert run.pending("P01")[0] == first, "an interrupted trial runs again"
        with pytest.raises(SessionInputError, match=r"^ease of task 0: expected a whole number"):
            run.answer("P01", {**dict.fromkeys(_pairs(), 4), ("task", "ease"): 0})
        run.answer("P01", dict.fromkeys(_pairs(), 6))
    people = _rows(tmp_path / "run" / "participants.csv")
    assert [(p["participant"], p["age"], p["source"]) for p in people] == [
        ("P01", "40", "real"),
        ("P02", "31", "real"),
    ]
    (interrupted,) = _rows(tmp_path / "run" / INTERRUPTED_FILE)
    assert (interrupted["participant"], interrupted["trial_index"]) == ("P01", "1")
    assert interrupted["outcome"] == "interrupted" and interrupted["modality"] == first.modality
    answers = _rows(tmp_path / "run" / "questionnaire.csv")
    # Of the aids the study draws only (task, none), whatever else the form holds.
    assert [(a["ar_class"], a["item"]) for a in answers] == [p for p in _pairs() if p[0] == "task"]
    assert {a["score"] for a in answers} == {"6"}
    with served_run(tmp_path / "run") as again:  # a restarted server: the same session
        assert again.consented("P01") and again.current().id == "P01"
        assert [s.key for s in again.pending("P01")] == [("P01", 1), ("P01", 2)]
        # Consented, no trial in: a restart showed "Trial 1" with no instructions.
        assert not again.instructed("P01")


def test_a_participants_link_is_their_own_and_survives_a_restart(tmp_path: Path) -> None:
    with served_run(tmp_path / "run", STUDY) as run:
        first, second, observer = run.token("P01"), run.token("P02"), run.observer_token()
    key = tmp_path / "run" / LINKS_KEY_FILE
    assert key.stat().st_mode & 0o777 == 0o600, "only its owner reads the key"
    tokens = (first, second, observer)
    assert len(set(tokens)) == 3 and all(re.fullmatch(r"[A-Za-z0-9_-]{22}", t) for t in tokens)
    with served_run(tmp_path / "run") as again:
        assert again.token("P01") == first and again.observer_token() == observer
    key.write_text("00" * 32)  # another key: every link changes
    with served_run(tmp_path / "run") as rekeyed:
        assert rekeyed.token("P01") != first
    for text in ("", "00" * 31, "zz" * 32):  # cut short, or not a key: refused when read
        key.write_text(text)
        with served_run(tmp_path / "run") as broken:
            with pytest.raises(RunFolderError, match=r"links.key: not a key of participants' "
                               r"links \(64 hex digits\)\. Delete it"):  # fmt: skip
                broken.token("P01")


def test_a_trial_run_again_after_a_restart_has_one_row_of_its_browser(tmp_path: Path) -> None:
    """The browser's row follows the trial's: a server stopped between them leaves the trial
    without one; a trial run again (its row lost to a kill) replaces its earlier row."""
    from arteleop.study.protocol import TrialRecord, trial_row
    from arteleop.teleop import TRACE_COLUMNS

    with served_run(tmp_path / "run", STUDY) as run:
        first, second = run.pending("P01")[:2]
        for spec in (first, second):
            run.keep(TrialRecord(spec, trial_row(spec, {"outcome": "timeout"}),
                                 {c: np.zeros(2) for c in TRACE_COLUMNS}, 2.0, 1.0))  # fmt: skip
        assert run.instructed("P01") and not run.instructed("P02")  # a trial of theirs is in
        run.keep_browser(first, BrowserCheck(0.5, 900, 800, "gizmo"))
        run.keep_browser(second, BrowserCheck(0.4, 900, 800))
        run.keep_browser(first, BrowserCheck(0.25, 900, 800, "buttons", 412, 9876.54, 3.21,
                                              37, 11.438, 0.08123, 203, 5.678))  # fmt: skip
    shown = _rows(tmp_path / "run" / BROWSER_FILE)
    assert [(b["trial_index"], b["display_round_trip_s"], b["input_device"]) for b in shown] == [
        ("2", "0.4", ""), ("1", "0.25", "buttons")
    ]  # fmt: skip
    assert [(b["cloud_frames"], b["cloud_kbytes"], b["cloud_mbit_s"]) for b in shown] == [
        ("0", "0.0", "0.0"), ("412", "9876.5", "3.21")
    ]  # fmt: skip
    assert [(b["cloud_frames_held"], b["cloud_fps"], b["link_latency_s"]) for b in shown] == [
        ("0", "0.0", ""), ("37", "11.44", "0.0812")
    ]  # fmt: skip
    assert [(b["page_frames"], b["page_fps"]) for b in shown] == [("", ""), ("203", "5.68")]


def test_a_served_run_is_not_resumed_as_a_simulated_one(tmp_path: Path) -> None:
    with served_run(tmp_path / "run", STUDY):
        pass
    with pytest.raises(RunFolderError, match="a study served to people: 'arteleop study serve"):
        resume_study(tmp_path / "run")
    with pytest.raises(RunFolderError, match="made from another definition: its key 'timeout_s'"):
        ServedRun.open(tmp_path / "run", replace(STUDY, timeout_s=7.0))


def test_the_server_loads_the_robots_model_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The run's planning and the server's trials share one model of the robot, whatever head
    camera the trials see through (the server once loaded a second)."""
    from arteleop.ar_features import ViewConfig
    from arteleop.study import sites

    loads: list[object] = []
    load = sites.load_baxter_description
    monkeypatch.setattr(sites, "load_baxter_description", lambda *a: loads.append(a) or load(*a))
    camera = HeadCameraConfig(width_px=320, height_px=240)
    with served_run(tmp_path / "run", STUDY) as run, StudyServer(run, ViewConfig(port=0), camera):
        assert len(loads) == 1
        T_default = run.site.camera.T_base_camera
        seen = run.site.with_camera(camera).camera
        assert (seen.config.width_px, seen.config.height_px) == (320, 240)
        np.testing.assert_array_equal(seen.T_base_camera, T_default)  # the same head
        assert run.site.camera.config.width_px != 320  # the run's own site untouched


def test_a_full_disk_is_said_on_the_participants_page_and_named_on_the_console(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The page was left dead: the server ended with the error, saying nothing to the person.
    from arteleop.ar_features import ViewConfig
    from arteleop.errors import RunFolderError
    from arteleop.study.session_words import CANNOT_SAVE

    camera = HeadCameraConfig(width_px=320, height_px=240)
    full = RunFolderError("Cannot add a row to run/trials.csv: No space left on device.")
    with served_run(tmp_path / "run", STUDY) as run, StudyServer(run, ViewConfig(port=0),
                                                                 camera) as server:  # fmt: skip

        def session(participant: str) -> None:
            raise full

        monkeypatch.setattr(server, "_session", session)
        with pytest.raises(RunFolderError) as err:
            server.serve()
        assert err.value is full  # the console names the file
        shown: list[tuple[str, ...]] = []

        class Pages:
            def message(self, *args: str) -> None:
                shown.append(args)

        server.tabs._page(Pages())  # what the participant's tab shows, now or once it connects
        assert shown == [CANNOT_SAVE]


def _pairs() -> list[tuple[str, str]]:
    return [(c, i) for c in ("embodiment", "manipulation", "task")
            for i in ("presence", "embodiment", "ease")]  # fmt: skip


SHOTS = Path(os.environ.get("ARTELEOP_SHOTS", "/tmp"))


def _green_pixels(shot: np.ndarray) -> int:
    """Pixels of the target mesh's green (and the gizmo's) in an RGB screenshot."""
    return int(of_hue(shot, (0, 255, 0)).sum())


def _gizmo_px(shot: np.ndarray) -> np.ndarray:
    """Where the gizmo's red handle is in an RGB screenshot (px)."""
    rows, cols = np.nonzero(gizmo_red(shot))
    assert len(rows) > 50, "the gizmo is not to be seen"
    return np.array([cols.mean(), rows.mean()])


def _take_part(
    browser, server: StudyServer, links: queue.Queue, greens: list[int], gizmos: list[np.ndarray]
) -> None:
    gate = server.view.gate
    assert refused(server.url, gate)  # the server's bare address: a socket sent nothing
    participant, link = links.get(timeout=60)
    assert participant == "P01"
    # The experimenter watches from the start, by their own link, in a small window: a third
    # tab drawing the scene in software WebGL at full size cost this test an eighth of its time.
    small = {"width": 480, "height": 300}
    experimenter = browser.open(server.observer_link, for_pictures=False, viewport=small)
    experimenter = experimenter.playwright
    experimenter.get_by_text(OBSERVING).wait_for()
    first_tab = browser.open(link, for_pictures=False)
    first = first_tab.playwright
    first.get_by_text("Information and consent").wait_for()
    first.get_by_text("Drive the robot").wait_for(state="hidden")  # nothing to drag yet
    greens.append(_green_pixels(first_tab.screenshot(SHOTS / "consent.png")))
    watching_tab = browser.open(link, for_pictures=False)
    watcher = watching_tab.playwright
    watcher.get_by_text(IN_PROGRESS).wait_for()
    first.get_by_text("I have read the information above").click()
    press_button(first, "Continue")
    text_field(first, "Age (years)").fill("17")
    press_button(first, "Continue")
    first.get_by_text("age 17: expected a whole number 18-99 (years).").wait_for()
    answer_questions(first)
    # The tutorial drives the robot in three tabs at once: on a busy two-core machine their
    # software WebGL held the page's checks up for 30-50 s.
    first.get_by_text("How to drive the robot").wait_for(timeout=TUTORIAL_WAIT_S * 1000)
    # The robot runs on this page, for the person to try (the gizmo moved, the robot did not).
    first.get_by_text("Try it now", exact=False).wait_for(timeout=TUTORIAL_WAIT_S * 1000)
    drawn = server.view.cloud.frames_drawn
    assert until(lambda: server.view.cloud.frames_drawn > drawn + 10, wait_s=TUTORIAL_WAIT_S)
    press_button(first, "Continue", TUTORIAL_WAIT_S)
    first.get_by_text("Trial 1 of 2").wait_for(timeout=TUTORIAL_WAIT_S * 1000)
    press_button(first, "Start")
    # Closed as soon as the trial shows it runs (its page's heading outlives it, on the outcome).
    first.get_by_text("the robot is taking your hand", exact=False).wait_for()
    first.close()
    for k in (1, 2):
        watcher.get_by_text(f"Trial {k} of 2").wait_for(timeout=30_000)
        watcher.get_by_text("Drive the robot").wait_for()
        before = watching_tab.screenshot(SHOTS / f"before-start-{k}.png")
        gizmos.append(_gizmo_px(before))
        if k == 1:  # the trial cut short, again, its scene shown as it will start
            greens.append(_green_pixels(before))
        press_button(watcher, "Start")
        # Driven by a step button: the device is recorded. Once the trial's status has
        # replaced the prompt, Start's reset is behind.
        watcher.get_by_text("press Start when ready", exact=False).wait_for(state="hidden")
        # Start goes once pressed, with the line asking for it.
        watcher.get_by_role("button", name="Start", exact=True).wait_for(state="hidden")
        watcher.get_by_text("when you are ready", exact=False).wait_for(state="hidden")
        # From the keyboard: focused (as Tab would), pressed with Space.
        watcher.get_by_role("button", name="down", exact=True).focus()
        watcher.keyboard.press("Space")
        watcher.get_by_text("Not placed: timeout.").wait_for(timeout=60_000)
        press_button(watcher, "Next")
    watcher.get_by_text("Questionnaire").wait_for(timeout=30_000)
    press_button(watcher, "Submit")  # nothing rated: refused, naming the first item
    watcher.get_by_text(
        f'"{STUDY.questionnaire[0].text}", under "{AR_CLASS_TEXT[classes_shown(STUDY)[0]]}": '
        "choose a rating, 1 to 7."
    ).wait_for()
    rate_every_item(watcher, "6")
    press_button(watcher, "Submit")
    watcher.get_by_text("You can close this page", exact=False).wait_for(timeout=30_000)
    participant, next_link = links.get(timeout=30)
    assert participant == "P02" and next_link != link
    # Through both tabs of P01's and into P02's session, the experimenter's tab stayed, read-only:
    # it never took over nor drove the robot.
    assert experimenter.get_by_text(OBSERVING).is_visible()
    for text in ("Drive the robot", "Information and consent", IN_PROGRESS):
        assert not experimenter.get_by_text(text).is_visible(), text

    # The next link admits its participant; P01's, no one now.
    def socket_url(address: str) -> str:
        return address.rpartition("=")[2].replace("ws://", "http://", 1)

    assert admitted(socket_url(next_link)) and refused(socket_url(link), gate)
    assert admitted(socket_url(server.observer_link))  # the experimenter's, session after session


def test_a_participant_goes_through_the_study_in_a_real_browser(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """By the participant's link (the server's bare address gets nothing; the experimenter's
    link is let in throughout): consent,
    questions (a wrong answer told), a trial cut short by closing the tab (a second tab, which
    had seen "in progress", takes over and the trial runs again, its scene and layers shown
    before Start), both trials each stepped once (the next trial's page shows the gizmo at
    rest again), the questionnaire, the end; then the next participant's link
    admits them, and the first link no one. The files hold what the person gave."""
    from tests.instruments.browser import VIEWPORT, chromium, require_chromium

    require_chromium()
    from arteleop.ar_features import ViewConfig

    # Software WebGL in three tabs beside the server and the suite's other worker: on a busy
    # two-core CI machine an 8x8 frame once took over the 5 s a person's browser is given.
    monkeypatch.setattr("arteleop.study.serve.ROUND_TRIP_TIMEOUT_S", BUSY_ROUND_TRIP_S)
    camera = HeadCameraConfig(width_px=320, height_px=240)
    greens: list[int] = []
    gizmos: list[np.ndarray] = []
    links: queue.Queue[tuple[str, str]] = queue.Queue()
    with (
        served_run(tmp_path / "run", STUDY) as run,
        StudyServer(
            run,
            ViewConfig(port=0, links=True),
            camera,
            lambda participant, url: links.put((participant, url)),
        ) as server,  # fmt: skip
    ):

        def participant() -> None:
            with chromium() as browser:
                _take_part(browser, server, links, greens, gizmos)

        serve_to(server, participant)
    # Before the first trial the robot's view without layers (the gizmo's green handles
    # only); before a trial under task AR, its target mesh.
    assert greens[0] < 1000 and greens[1] > 5000, greens
    # Each trial's page shows the gizmo at rest, not where the last trial's steps left it.
    assert np.linalg.norm(gizmos[1] - gizmos[0]) < 6.0, gizmos
    folder = tmp_path / "run"
    (person,) = _rows(folder / "participants.csv")
    assert person == {"participant": "P01", "age": "31", "gender": "female",
                      "handedness": "right", "avr_experience": "4", "avr_hours": "2",
                      "games_experience": "4", "games_hours": "1", "source": "real"}  # fmt: skip
    trials = _rows(folder / "trials.csv")
    planned = [s for s in plan_study(STUDY) if s.participant == "P01"]
    assert [(t["trial_index"], t["modality"], t["phase"], t["outcome"]) for t in trials] == [
        (str(s.trial_index), s.modality, EXPERIMENTAL, "timeout") for s in planned
    ]
    assert all((folder / t["trajectory_file"]).is_file() for t in trials)
    (cut,) = _rows(folder / INTERRUPTED_FILE)
    assert (cut["participant"], cut["trial_index"], cut["outcome"]) == ("P01", "1", "interrupted")
    answers = _rows(folder / "questionnaire.csv")
    assert len(answers) == 3 and {a["participant"] for a in answers} == {"P01"}
    assert {a["score"] for a in answers} == {"6"}  # as chosen on the page
    shown = _rows(folder / BROWSER_FILE)
    assert [(b["participant"], b["trial_index"], b["input_device"]) for b in shown] == [
        ("P01", "1", "buttons"), ("P01", "2", "buttons")
    ]  # fmt: skip
    for b in shown:  # the tab's scene beside the docked panel; a frame there and back
        assert 0 < float(b["display_round_trip_s"]) < BUSY_ROUND_TRIP_S, b
        # Its socket pinged during the trial, and the cloud sent at a rate the link carried.
        assert 0 < float(b["link_latency_s"]) < PING_TIMEOUT_S, b
        assert float(b["cloud_fps"]) > 0 and int(b["cloud_frames_held"]) >= 0, b
        # The page counted the frames it drew, and the server read its count.
        assert int(b["page_frames"]) > 0 and float(b["page_fps"]) > 0, b
        assert (
            600 < int(b["scene_width_px"]) < 1280
            and int(b["scene_height_px"]) == VIEWPORT["height"]
        ), b
