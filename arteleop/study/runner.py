"""Run a study: plan it, run its trials through an executor, keep every trial as it ends.

Each trial has its own site and seed; a participant's trials run one after the other, each
bringing what the participant carried from the one before (its belief of the display's lag, as
a person adapts to a delay over many trials, and the misses it has seen), and participants run
side by side on any worker: a process per core by default, or any
:class:`concurrent.futures.Executor`, such as a Dask cluster's
(``distributed.Client(...).get_executor()``; docs/guides/running-a-study.md shows Ray's
equivalent). Whatever the order, the finished folder's CSVs are the same bytes.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import pandas as pd

from arteleop import files
from arteleop.analysis.data import PARTICIPANT_COLUMNS, QUESTIONNAIRE_COLUMNS
from arteleop.errors import RunFolderError
from arteleop.study.carry import Carried, carried_after, line_carried, row_carried
from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec
from arteleop.study.plan import EXPERIMENTAL, TrialSpec
from arteleop.study.protocol import TrialRecord, run_planned_trial
from arteleop.study.questionnaire import classes_shown, simulated_answers
from arteleop.study.questionnaire_items import modelled_items
from arteleop.study.run_folder import (
    REAL,
    STUDY_FILE,
    RunFolder,
    table_text,
)
from arteleop.study.run_lock import LOCK_FILE, run_lock
from arteleop.study.run_opening import (
    arithmetic_notes,
    new_manifest,
    open_run,
    plan_run,
    record_resume,
    require_run_folder,
    utc_now,
)
from arteleop.study.sites import StudySite
from arteleop.study.study_writing import study_text
from arteleop.study.worker_pool import worker_pool
from arteleop.teleop.trial_task import POINTING


class Done(Protocol):
    """What progress is told of: a trial (:class:`TrialSpec`), or a pointing study's block
    (its last trial)."""

    @property
    def participant(self) -> str: ...

    @property
    def trial_index(self) -> int: ...


Progress = Callable[[Done, int, int], None]
"""Called after each trial (or block) is written: (it, trials done, trials in the plan)."""


@dataclass(frozen=True)
class StudyRun:
    """A finished run.

    Attributes:
        folder: The run folder.
        trials: trials.csv as a table (a pointing study's: pointing.csv).
        ran: Trials run by this call (the rest were in the folder already).
        speed: (simulated s, wall s) of each trial run by this call, for benchmarks.
        notes: What the run set aside or repaired in the folder, to tell the user.
        task: The study's task (``task`` in the study file): what ``trials`` holds.
    """

    folder: Path
    trials: pd.DataFrame
    ran: int
    speed: list[tuple[float, float]]
    notes: tuple[str, ...] = ()
    task: str = "pick-and-place"


class RunComplete(RunFolderError):
    """``resume`` found every planned trial in the folder: nothing to do."""


def run_study(
    study: StudyConfig,
    out: Path,
    workers: int | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
) -> StudyRun:
    """Start a run of ``study`` in the new folder ``out`` and run it to the end.

    Args:
        workers: Processes for the trials when no ``executor`` is given; default one per core;
            1 runs them in this process (a pointing study's blocks, each in a process of its
            own: :mod:`arteleop.study.pointing_run`).
        executor: Runs the trials (any :class:`concurrent.futures.Executor`).
        progress: Told of each trial written.
    """
    if study.task == POINTING.name:
        from arteleop.study.pointing_run import run_pointing_study  # it imports this module

        return run_pointing_study(study, out, workers, executor, progress)
    folder = RunFolder(out)
    check_new(folder)
    site = StudySite()
    plan, people = plan_run(study, site)
    text = study_text(study)
    manifest = new_manifest(study, text, plan, len(people))
    make_folder(folder)
    with run_lock(folder.path):
        check_new(folder)  # again, holding the lock: another run may have begun meanwhile
        folder.start(text, manifest, participants_text(people))
        return _execute(study, site, folder, plan, people, workers, executor, progress)


def make_folder(folder: RunFolder) -> None:
    """Create the run folder (and its parents), or say why it cannot be."""
    try:
        folder.path.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise RunFolderError(f"Cannot create {folder.path}: {err.strerror or err}.") from err


def check_new(folder: RunFolder) -> None:
    """Refuse a folder that holds anything but a lock or a start that a kill cut short."""
    if folder.path.exists() and not folder.path.is_dir():
        raise RunFolderError(f"--out {folder.path}: a file, not a folder; give a new folder.")
    if folder.path.exists() and not _begun_only(folder):
        if folder.is_run_folder():
            raise RunFolderError(
                f"{folder.path} already holds a run: {folder.carry_on()} continues it; give "
                "--out a new folder for a new run."
            )
        raise RunFolderError(
            f"{folder.path} exists and is not empty: give --out a new or empty folder."
        )


def resume_study(
    out: Path,
    study: StudyConfig | None = None,
    workers: int | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
    tell: Callable[[str], None] | None = None,
) -> StudyRun:
    """Continue the run in ``out`` after a crash, Ctrl-C or ``kill -9``: the trials it lacks
    run, the rest are kept. With ``study``, refuses a folder made from another definition.
    ``tell`` gets what the user should know before the trials run (this machine computes
    otherwise than the run's first: :func:`~arteleop.study.run_opening.arithmetic_notes`);
    without it, the run's :attr:`StudyRun.notes` keep it."""
    folder = RunFolder(out)
    require_run_folder(folder)
    with run_lock(folder.path):
        if folder.manifest().get("cohort") == REAL:
            raise RunFolderError(
                f"{folder.path} is a study served to people: 'arteleop study serve --out "
                f"{folder.path}' continues it with the next participant."
            )
        if folder.manifest().get("task") == POINTING.name:
            from arteleop.study.pointing_run import resume_pointing_study  # it imports this

            return resume_pointing_study(folder, study, workers, executor, progress, tell)
        site = StudySite()  # plans the run, then runs its trials: its robot model loads once
        recorded, plan, people, manifest = open_run(folder, study, site)
        if manifest.get("finished") and len(folder.done_rows(repair=True)) == len(plan):
            notes = "".join(f"\nnote: {note}" for note in folder.notes)
            raise RunComplete(
                f"{folder.path} is complete: all {len(plan)} trials are in; nothing to resume."
                + notes
            )
        for note in arithmetic_notes(folder, manifest):
            (tell or folder.notes.append)(note)
        return _execute(
            recorded, site, folder, plan, people, workers, executor, progress, resumed=True
        )


def _begun_only(folder: RunFolder) -> bool:
    """Whether ``folder`` holds nothing but what :meth:`RunFolder.start` writes before the
    manifest (a start cut short: no trial has run), its temporary files, and the lock."""
    begun = {LOCK_FILE, STUDY_FILE, "participants.csv", "trials.csv"}
    for entry in folder.path.iterdir():
        if entry.name not in begun and not files.is_temporary(entry):
            return False
    trials = folder.trials_path
    return not trials.exists() or trials.read_text(encoding="utf-8").count("\n") <= 1


def _execute(
    study: StudyConfig,
    site: StudySite,
    folder: RunFolder,
    plan: list[TrialSpec],
    people: list[ParticipantSpec],
    workers: int | None,
    executor: Executor | None,
    progress: Progress | None,
    resumed: bool = False,
) -> StudyRun:
    """The trials of ``plan`` not yet in ``folder`` run, each row appended as it ends (each
    participant's in order, bringing what the last one left); then trials.csv in plan order,
    the questionnaire, and the manifest says the run is finished. ``resumed``: the manifest
    records this resume first (:func:`~arteleop.study.run_opening.record_resume`)."""
    folder.remove_cut_writes()
    done = folder.done_rows(repair=True)
    pending = [spec for spec in plan if spec.key not in done]
    by_id = {p.id: p for p in people}
    count = len(plan) - len(pending)
    if resumed:
        record_resume(folder, count)
    speed: list[tuple[float, float]] = []
    previous = _previous_trials(plan)
    following = {before: key for key, before in previous.items() if before is not None}
    ends: dict[tuple[str, int], Carried | None] = {}
    # What each trial in trials.csv ended with (the lag believed, a miss seen), as its row says.
    ended = {
        key: line_carried(line, f"{folder.trials_path}, participant {key[0]} trial {key[1]}")
        for key, line in done.items()
    }

    def brought(key: tuple[str, int]) -> Carried | None:
        """What the participant brings to the trial: what it carried from its last one."""
        before = previous[key]
        return None if before is None else ends[before]

    def carry_on(key: tuple[str, int] | None) -> None:
        """What the participant carries from the trial ``key``, and from each trial after it
        already in trials.csv (one set aside and run again reaches those after it), once the
        trial before ``key`` has ended."""
        while key is not None and key in ended:
            before = previous[key]
            if before is not None and before not in ends:
                return
            ends[key] = carried_after(brought(key), *ended[key])
            key = following.get(key)

    for spec in plan:  # each participant's first trial carries its chain of ended ones
        if previous[spec.key] is None:
            carry_on(spec.key)

    def keep(record: TrialRecord) -> None:
        nonlocal count
        folder.append_trial(record.row, record.trace)
        ended[record.spec.key] = row_carried(record.row)
        carry_on(record.spec.key)
        speed.append((record.duration_s, record.wall_s))
        count += 1
        if progress is not None:
            progress(record.spec, count, len(plan))

    # More processes than trials only costs memory (each holds a simulator).
    workers = min(workers or os.cpu_count() or 1, max(len(pending), 1))
    if executor is None and (workers == 1 or len(pending) <= 1):
        for spec in pending:  # plan order: each participant's trials in order
            keep(run_planned_trial(study, site, by_id[spec.participant], spec, brought(spec.key)))
    else:
        # A participant's trials run one after the other, each bringing what the last one
        # ended with (the lag believed, the misses seen); participants run side by side.
        waiting = {p: [s for s in pending if s.participant == p] for p in by_id}
        running: dict[Future[TrialRecord], str] = {}
        fork = multiprocessing.get_context("fork")
        with worker_pool(executor, running, workers, mp_context=fork) as pool:

            def submit_next(participant: str) -> None:
                if waiting[participant]:
                    spec = waiting[participant].pop(0)
                    future = pool.submit(_run_in_worker, study, by_id[participant], spec,
                                         brought(spec.key))  # fmt: skip
                    running[future] = participant

            for participant in by_id:
                submit_next(participant)
            while running:
                finished, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in finished:
                    keep(future.result())
                    submit_next(running.pop(future))
    order = [spec.key for spec in plan]
    folder.finish(order)
    # Answers come from the finished trials.csv, so they depend only on its bytes.
    folder.write_questionnaire(_questionnaire_text(study, folder, people))
    unanswered = [i.id for i in study.questionnaire if i.id not in modelled_items(study)]
    if unanswered and classes_shown(study):
        folder.notes.append(
            f"questionnaire.csv: the simulated participants answer no {', '.join(unanswered)}: "
            "they answer only the original study's items, in its words "
            "(docs/guides/serving-a-study.md); 'arteleop study answer' adds real answers."
        )
    manifest = folder.manifest()
    manifest["finished"] = utc_now()
    folder.write_manifest(manifest)
    return StudyRun(folder.path, folder.trials(), len(pending), speed, tuple(folder.notes),
                    study.task)  # fmt: skip


_WORKER_SITE: StudySite | None = None


def _run_in_worker(
    study: StudyConfig, person: ParticipantSpec, spec: TrialSpec, brought: Carried | None
) -> TrialRecord:
    """One trial in a worker process; the worker keeps its :class:`StudySite` between trials."""
    global _WORKER_SITE
    if _WORKER_SITE is None:
        _WORKER_SITE = StudySite()
    return run_planned_trial(study, _WORKER_SITE, person, spec, brought)


def _previous_trials(plan: Sequence[TrialSpec]) -> dict[tuple[str, int], tuple[str, int] | None]:
    """Each planned trial's key, to the key of the same participant's trial before it in the
    plan (None for its first)."""
    last: dict[str, tuple[str, int]] = {}
    previous = {}
    for spec in plan:
        previous[spec.key] = last.get(spec.participant)
        last[spec.participant] = spec.key
    return previous


def participants_text(people: Sequence[ParticipantSpec]) -> str:
    rows = [
        (p.id, p.age, p.gender, "right", p.avr_experience, p.avr_hours, p.games_experience,
         p.games_hours, "synthetic")
        for p in people
    ]  # fmt: skip
    return table_text(PARTICIPANT_COLUMNS, rows)


def _questionnaire_text(
    study: StudyConfig, folder: RunFolder, people: Sequence[ParticipantSpec]
) -> str:
    trials = folder.trials()
    experimental = trials[trials["phase"] == EXPERIMENTAL]
    rows = []
    classes = classes_shown(study)
    for k, person in enumerate(people):
        own = experimental[experimental["participant"] == person.id]
        rows += simulated_answers(person.id, (study.seed, 4, k), own, study.timeout_s, classes,
                                  modelled_items(study))  # fmt: skip
    return table_text(QUESTIONNAIRE_COLUMNS, rows)
