"""A study served to people (``arteleop study serve``): its run folder and what a person adds.

The served run has the plan a simulated run of the same definition has: the same participant
ids, counterbalanced orders, practice points and network conditions. People take the planned
participants' places one after another, in plan order. Beside a simulated run's files it keeps:

- ``participants.csv``: a row for each person once they have consented, with their own answers
  to the demographic questions and ``source`` ``real``;
- ``questionnaire.csv``: their own ratings, never a simulated participant's;
- ``links.key``: where participants join by link (``study serve --links``), the key their
  links' tokens are made from: a participant's link stays the same across server restarts.
  Only this file makes links: it holds no data, and deleting it after the study ends them all;
- ``browser.csv``: for each trial in ``trials.csv``, what the participant's browser showed it
  with and what drove it (:class:`BrowserCheck`): the display's round trip and the scene's size,
  measured as the trial's outcome shows, and the input device (written after the trial's row: a
  server stopped in between leaves the trial without one);
- ``interrupted.csv``: each attempt of a trial that a closed tab, a lost connection or a reload
  cut short, with the columns of ``trials.csv`` and the outcome ``interrupted``. The trial is
  then run again from its start; ``trials.csv`` keeps the attempt that ended.

Every file is written whole (a temporary file renamed over it) or grows by whole rows, as a
simulated run's do; the server holds the folder's lock while it serves.
"""

from __future__ import annotations

import base64
import contextlib
import hashlib
import hmac
import math
import re
import secrets
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from arteleop.analysis.data import (
    PARTICIPANT_COLUMNS,
    QUESTIONNAIRE_COLUMNS,
    TRIAL_COLUMNS,
)
from arteleop.ar_features.links import TOKEN_BYTES
from arteleop.errors import RunFolderError
from arteleop.study.definition import StudyConfig
from arteleop.study.demographics import Demographics, check_whole
from arteleop.study.participants import ParticipantSpec
from arteleop.study.plan import FAMILIARIZATION, TrialSpec
from arteleop.study.protocol import TrialRecord, trial_config, trial_record, trial_row
from arteleop.study.questionnaire import classes_shown
from arteleop.study.run_folder import (
    PARTICIPANTS_FILE,
    QUESTIONNAIRE_FILE,
    REAL,
    RunFolder,
    csv_line,
    read_table,
    table_text,
    write_atomic,
)
from arteleop.study.run_lock import run_lock
from arteleop.study.run_opening import new_manifest, open_run, plan_run, utc_now
from arteleop.study.runner import check_new, make_folder
from arteleop.study.session_words import outcome_text
from arteleop.study.sites import StudySite
from arteleop.study.study_writing import study_text
from arteleop.teleop.trial_task import POINTING

if TYPE_CHECKING:
    from arteleop.teleop import TrialConfig, TrialResult

INTERRUPTED_FILE = "interrupted.csv"
BROWSER_FILE = "browser.csv"
BROWSER_COLUMNS = ("participant", "trial_index", "display_round_trip_s", "scene_width_px",
                   "scene_height_px", "input_device", "cloud_frames", "cloud_kbytes",
                   "cloud_mbit_s", "cloud_frames_held", "cloud_fps",
                   "link_latency_s", "page_frames", "page_fps")  # fmt: skip
LINKS_KEY_FILE = "links.key"
LINKS_KEY_BYTES = 32


@dataclass(frozen=True)
class BrowserCheck:
    """What a participant's browser showed a trial with, measured as the trial's outcome shows.

    Attributes:
        display_round_trip_s: A frame asked of the browser and sent back (viser's render
            request, the median of a few): the network both ways and one drawing of the scene,
            which a person's view lags by beyond the study's own delay; NaN if the browser
            did not answer.
        scene_width_px: The scene's width in the browser (px as the browser gives it).
        scene_height_px: Its height.
        input_device: What moved the gripper's target during the trial: ``gizmo``, ``buttons``
            or ``gizmo+buttons`` (:meth:`~arteleop.ar_features.live_input.LiveInput.take_devices`);
            empty if nothing did.
        cloud_frames: The camera frames whose cloud the view sent during the trial.
        cloud_kbytes: The point cloud's positions and colours it sent for them (kB, before
            compression): only what changed (:mod:`arteleop.ar_features.layers.cloud`).
        cloud_mbit_s: That over the trial's wall time (Mbit/s): the rate the participant's
            connection had to carry.
        cloud_frames_held: The camera frames whose cloud was not sent: the participant's
            connection was still carrying earlier ones
            (:class:`~arteleop.ar_features.link_pacer.LinkPacer`).
        cloud_fps: The clouds sent a second of the trial's wall time: the rate chosen for the
            participant's connection.
        link_latency_s: The median round trip of the pings to the participant's tab during
            the trial (s): the network both ways and what queued before them; NaN if none
            was answered.
        page_frames: The frames the participant's page drew during the trial, as it counted
            them (:mod:`arteleop.ar_features.page_frames`); None if its count was not read.
        page_fps: Those a second of the page's own clock; NaN if its count was not read.
            Below ``cloud_fps``, the page could not show every cloud it was sent.
    """

    display_round_trip_s: float
    scene_width_px: int
    scene_height_px: int
    input_device: str = ""
    cloud_frames: int = 0
    cloud_kbytes: float = 0.0
    cloud_mbit_s: float = 0.0
    cloud_frames_held: int = 0
    cloud_fps: float = 0.0
    link_latency_s: float = math.nan
    page_frames: int | None = None
    page_fps: float = math.nan


Ratings = Mapping[tuple[str, str], int]
"""A participant's questionnaire: (AR class, item) -> score 1-7, every pair answered."""


class ServedRun:
    """The run folder of a study served to people; see the module's docstring.

    Made by :meth:`create` or :meth:`open`; the caller holds the folder's lock throughout.
    """

    def __init__(
        self,
        folder: RunFolder,
        study: StudyConfig,
        plan: list[TrialSpec],
        people: list[ParticipantSpec],
        site: StudySite,
    ) -> None:
        self.folder = folder
        self.site = site
        """The site that planned the run, to build its trials' sites from."""
        self._key: bytes | None = None  # the links' key, read from the folder once
        self.study = study
        self.plan = plan
        self.people = people

    @classmethod
    def create(cls, study: StudyConfig, out: Path, site: StudySite | None = None) -> ServedRun:
        """A new served run of ``study`` in the new or empty folder ``out``, which exists,
        planned with ``site`` (a new one if none)."""
        folder = RunFolder(out)
        check_new(folder)
        site = site or StudySite()
        plan, people = plan_run(study, site)
        text = study_text(study)
        manifest = {**new_manifest(study, text, plan, len(people)), "cohort": REAL}
        folder.start(text, manifest, table_text(PARTICIPANT_COLUMNS, []))
        return cls(folder, study, plan, people, site)

    @classmethod
    def open(
        cls, out: Path, study: StudyConfig | None = None, site: StudySite | None = None
    ) -> ServedRun:
        """The served run in ``out``, to go on with its next participant, planned again with
        ``site`` (a new one if none); with ``study``, refused if the run was made from another
        definition."""
        folder = RunFolder(out)
        site = site or StudySite()
        if folder.is_run_folder() and folder.manifest().get("cohort") != REAL:
            raise RunFolderError(
                f"{folder.path} holds a simulated run: 'arteleop study resume {folder.path}' "
                "continues it; give 'study serve' a new folder."
            )
        return cls.reopen(folder, study, site)

    @classmethod
    def reopen(cls, folder: RunFolder, study: StudyConfig | None, site: StudySite) -> ServedRun:
        """The served run in ``folder``, checked (see :meth:`open`)."""
        study, plan, people, _ = open_run(folder, study, site)
        folder.done_rows(repair=True)  # a row a kill cut short is set aside now, and said
        return cls(folder, study, plan, people, site)

    def done_keys(self) -> set[tuple[str, int]]:
        """The trials that ended, by (participant, trial_index)."""
        return set(self.folder.done_rows())

    def trial_config(self, spec: TrialSpec, site: StudySite) -> TrialConfig:
        """The trial of ``spec`` on ``site`` (the study's, seen through the server's camera)."""
        return trial_config(self.study, site, spec)

    def trial_text(self, spec: TrialSpec) -> str:
        """What the trial's page says before Start."""
        kind = "practice trial" if spec.phase == FAMILIARIZATION else "trial"
        return f"This is a {kind}."

    def keep_result(self, spec: TrialSpec, result: TrialResult, wall_s: float) -> str:
        """The trial that ended with ``result`` after ``wall_s`` (s) kept; what its outcome
        page says."""
        record = trial_record(spec, result, wall_s)
        self.keep(record)
        row = record.row
        time_s, error_m = row["completion_time_s"], row["placement_error_m"]
        return outcome_text(str(row["outcome"]), time_s, error_m)  # type: ignore[arg-type]

    def current(self) -> ParticipantSpec | None:
        """The participant whose session is under way or next: the first, in plan order, with
        trials or answers missing; None when every session is over."""
        done = self.done_keys()
        answered = self._answered()
        for person in self.people:
            if any(spec.key not in done for spec in self.trials_of(person.id)):
                return person
            if person.id not in answered:
                return person
        return None

    def trials_of(self, participant: str) -> list[TrialSpec]:
        """The participant's planned trials, in session order."""
        return [spec for spec in self.plan if spec.participant == participant]

    def pending(self, participant: str) -> list[TrialSpec]:
        """The participant's trials not yet in ``trials.csv``, in session order."""
        done = self.done_keys()
        return [spec for spec in self.trials_of(participant) if spec.key not in done]

    def token(self, participant: str) -> str:
        """The token of ``participant``'s link: unguessable without the folder's key (made on
        first use, readable by its owner only), the same each time it is asked for."""
        return self._token(participant.encode())

    def observer_token(self) -> str:
        """The token of the experimenter's read-only view of every session, likewise (made from
        what no participant id can be)."""
        return self._token(b"\x00observer")

    def _token(self, message: bytes) -> str:
        digest = hmac.new(self._links_key(), message, hashlib.sha256).digest()
        return base64.urlsafe_b64encode(digest[:TOKEN_BYTES]).decode().rstrip("=")

    def _links_key(self) -> bytes:
        if self._key is None:
            self._key = self._read_links_key()
        return self._key

    def _read_links_key(self) -> bytes:
        path = self.folder.path / LINKS_KEY_FILE
        if not path.exists():
            # Whole or not at all (an empty key would make every link computable); another
            # server's, made first, is kept.
            key = secrets.token_hex(LINKS_KEY_BYTES) + "\n"
            write_atomic(path, key, private=True, exclusive=True)
        text = path.read_text(encoding="ascii", errors="replace").strip()
        if not re.fullmatch(f"[0-9a-f]{{{2 * LINKS_KEY_BYTES}}}", text):
            raise RunFolderError(
                f"{path}: not a key of participants' links ({2 * LINKS_KEY_BYTES} hex digits). "
                "Delete it to make a new one: every participant's link then changes."
            )
        return bytes.fromhex(text)

    def consented(self, participant: str) -> bool:
        return participant in self._participant_rows()

    def instructed(self, participant: str) -> bool:
        """Whether ``participant`` has been through the tutorial, as far as the files can say:
        a trial of theirs is in ``trials.csv``. A server restarted between the consent and the
        first trial's end shows the tutorial again, so that no trial runs without it."""
        return len(self.pending(participant)) < len(self.trials_of(participant))

    def consent(self, participant: str, answers: Demographics) -> None:
        """The participant has agreed and answered the questions before the trials."""
        rows = self._participant_rows()
        rows[participant] = [str(v) for v in answers.row(participant)]
        order = [p.id for p in self.people]
        ordered = [rows[pid] for pid in order if pid in rows]
        write_atomic(self.folder.path / PARTICIPANTS_FILE, table_text(PARTICIPANT_COLUMNS, ordered))

    def keep(self, record: TrialRecord) -> None:
        """A trial that ended, its outcome whatever it was."""
        self.folder.append_trial(record.row, record.trace)

    def keep_browser(self, spec: TrialSpec, browser: BrowserCheck) -> None:
        """What the browser showed the kept trial ``spec`` with (a row of a trial run again
        after a restart replaces its earlier one)."""
        key = (spec.participant, str(spec.trial_index))
        path = self.folder.path / BROWSER_FILE
        rows = read_table(path, None) if path.exists() else [list(BROWSER_COLUMNS)]
        if rows[0] != list(BROWSER_COLUMNS):
            read_table(path, BROWSER_COLUMNS)  # the header's message
        kept = [row for row in rows[1:] if tuple(row[:2]) != key]
        check = (browser.display_round_trip_s, browser.scene_width_px, browser.scene_height_px,
                 browser.input_device, browser.cloud_frames, round(browser.cloud_kbytes, 1),
                 round(browser.cloud_mbit_s, 2), browser.cloud_frames_held,
                 round(browser.cloud_fps, 2), round(browser.link_latency_s, 4),
                 browser.page_frames, round(browser.page_fps, 2))  # fmt: skip
        write_atomic(path, table_text(BROWSER_COLUMNS, [*kept, (*key, *check)]))

    def keep_interrupted(self, spec: TrialSpec) -> None:
        """An attempt at ``spec`` cut short before it ended: recorded, to be run again."""
        row = trial_row(spec, {"outcome": "interrupted"})
        row["trajectory_file"] = ""  # an attempt cut short keeps no trajectory
        self._add_interrupted(TRIAL_COLUMNS, [row.get(c) for c in TRIAL_COLUMNS])

    def _add_interrupted(self, columns: tuple[str, ...], row: list[object]) -> None:
        """``row`` added to ``interrupted.csv``, begun with ``columns`` if new."""
        path = self.folder.path / INTERRUPTED_FILE
        old = path.read_text(encoding="utf-8") if path.exists() else csv_line(columns)
        write_atomic(path, old + csv_line(row))

    def answered(self, participant: str) -> bool:
        return participant in self._answered()

    def answer(self, participant: str, ratings: Ratings) -> None:
        """The participant's questionnaire, every item of every AR class the study's conditions
        draw (:func:`classes_shown`) rated 1-7."""
        rows = []
        for ar_class in classes_shown(self.study):
            for item in (i.id for i in self.study.questionnaire):
                score = ratings.get((ar_class, item))
                check_whole(f"{item} of {ar_class}", score, 1, 7, "on the 1-7 scale")
                rows.append((participant, ar_class, item, score))
        path = self.folder.path / QUESTIONNAIRE_FILE
        kept = [row for row in self._rows(path, QUESTIONNAIRE_COLUMNS) if row[0] != participant]
        order = [p.id for p in self.people]
        every = sorted([*kept, *rows], key=lambda row: order.index(str(row[0])))
        write_atomic(path, table_text(QUESTIONNAIRE_COLUMNS, every))

    def finish_if_done(self) -> bool:
        """When every session is over: ``trials.csv`` in plan order and the manifest's
        ``finished``; whether it was."""
        if self.current() is not None:
            return False
        self._put_in_order()
        manifest = self.folder.manifest()
        if not manifest.get("finished"):
            manifest["finished"] = utc_now()
            self.folder.write_manifest(manifest)
        return True

    def _put_in_order(self) -> None:
        """Every trial is in: its table in plan order."""
        self.folder.finish([spec.key for spec in self.plan])

    def _participant_rows(self) -> dict[str, list[str]]:
        path = self.folder.path / PARTICIPANTS_FILE
        return {row[0]: row for row in self._rows(path, PARTICIPANT_COLUMNS)}

    @staticmethod
    def _rows(path: Path, columns: tuple[str, ...]) -> list[list[str]]:
        """A table's rows below its header; none before the file is written."""
        return read_table(path, columns)[1:] if path.exists() else []

    def _answered(self) -> set[str]:
        if not classes_shown(self.study):  # no AR drawn: nothing to ask
            return {person.id for person in self.people}
        path = self.folder.path / QUESTIONNAIRE_FILE
        return {row[0] for row in self._rows(path, QUESTIONNAIRE_COLUMNS)}


@contextlib.contextmanager
def served_run(out: Path, study: StudyConfig | None = None) -> Iterator[ServedRun]:
    """The served run in ``out``, its lock held: carried on where ``out`` holds one (made from
    ``study`` when given), else begun in the new or empty folder from ``study`` (the default
    study when none)."""
    folder = RunFolder(out)
    if folder.is_run_folder():
        with run_lock(folder.path):
            yield _served_kind(folder.manifest().get("task")).open(out, study)
        return
    check_new(folder)
    make_folder(folder)
    study = study or StudyConfig()
    with run_lock(folder.path):
        yield _served_kind(study.task).create(study, out)


def _served_kind(task: object) -> type[ServedRun]:
    """The served run of a study whose task is called ``task``."""
    if task != POINTING.name:
        return ServedRun
    from arteleop.study.pointing_session import ServedPointingRun

    return ServedPointingRun
