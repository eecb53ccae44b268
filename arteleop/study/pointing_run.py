"""Run a pointing study (``task = "pointing"``) with simulated participants into a run folder.

Each participant does one block per lag (the study's conditions, in the order its scheme gives
the participant): every cell of :class:`~arteleop.study.pointing_design.PointingDesign`
``repetitions`` times, one trial after the other, carrying what it believes of the lag and what
it has seen of its outcomes (a miss told, as Fitts experiments tell it) from each trial to the
next; a block begins with the belief from practice on the system (``familiar_lag_s``), as
``benchmarks/bench_fitts.py`` has always run it. Blocks run side by side, each in a fresh worker
process (a worker's memory grew about 13 MB a trial: benchmarks/README.md).

The run folder holds ``study.toml``, ``manifest.json``, ``participants.csv`` and, once every
block is in, ``pointing.csv`` (docs/reference/data-format.md#pointingcsv): the table ``arteleop
analyze`` reports as ISO 9241-9 asks, in the plan's order, so that the same seed gives the same
bytes. Until then each finished block is kept in a file of its own (:data:`BLOCKS_DIR`), so that
a stop loses only the blocks under way and ``arteleop study resume`` runs the rest.
"""

from __future__ import annotations

import math
import os
import shutil
from collections.abc import Callable, Sequence
from concurrent.futures import Executor, Future, as_completed
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import pandas as pd

from arteleop.analysis.pointing import POINTING_COLUMNS, POINTING_FILE
from arteleop.operator import (
    ACTIVITIES,
    OperatorParams,
    OperatorTraits,
    believed_error_scale,
)
from arteleop.study.cohort import participants
from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec
from arteleop.study.plan import condition_orders
from arteleop.study.pointing_design import PointingTrial
from arteleop.study.protocol import operator_traits
from arteleop.study.run_folder import (
    PARTICIPANTS_FILE,
    STUDY_FILE,
    RunFolder,
    csv_line,
    table_text,
    write_atomic,
)
from arteleop.study.run_lock import run_lock
from arteleop.study.run_opening import (
    arithmetic_notes,
    check_plan,
    new_manifest,
    opened_definition,
    record_resume,
    utc_now,
)
from arteleop.study.runner import (
    Progress,
    RunComplete,
    StudyRun,
    check_new,
    make_folder,
    participants_text,
)
from arteleop.study.study_writing import study_text
from arteleop.study.worker_pool import worker_pool
from arteleop.teleop.trial_task import POINTING

BLOCKS_DIR = "pointing-blocks"
"""Each finished block's rows, a CSV a block, until every block is in and pointing.csv is
written: what a stop keeps, and what ``arteleop study resume`` carries on from."""
RUN_COLUMNS = (*POINTING_COLUMNS, "block", "trial", "rep", "seed", "slips", "corrections",
               "looks", "believed_lag_s", "error_scale")  # fmt: skip
"""``pointing.csv`` of a simulated run: the analysed columns, then each trial's place (its
block and its number in the participant's session, from 1), its seed, and the simulated
participant's own account: slips (closures before it decided), corrections and looks in the
movement time, the lag it believed at the end (s), and the error scale it began with (what its
misses so far taught it)."""


@dataclass(frozen=True)
class PointingBlock:
    """One participant's trials under one lag, in order.

    Attributes:
        participant: The participant's id.
        traits: Their lasting traits.
        round_trip_ms: The block's lag: the network's round trip, half each way (ms).
        trials: The trials, in the order they come.
        block: The block's place in the participant's session, from 1.
        first_trial: The number of its first trial in the session, from 1.
        timeout_s: A trial with no selection ends after this much simulated time (s).
        depth_aids: The display draws the depth aids.
        fresh: Every trial meets the lag anew, as the block's first (a benchmark's check).
        params: The operator's constants at the block's start.
    """

    participant: str
    traits: OperatorTraits
    round_trip_ms: float
    trials: tuple[PointingTrial, ...]
    block: int = 1
    first_trial: int = 1
    timeout_s: float = 40.0
    depth_aids: bool = False
    fresh: bool = False
    params: OperatorParams = field(default_factory=OperatorParams)

    @property
    def trial_index(self) -> int:
        """The number of its last trial in the session (for progress)."""
        return self.first_trial + len(self.trials) - 1


def pointing_blocks(
    study: StudyConfig, people: Sequence[ParticipantSpec] | None = None
) -> list[PointingBlock]:
    """Every block of ``study``, participant by participant (``people``: the study's), in each
    one's order of lags."""
    people = participants(study) if people is None else people
    lags = [c.round_trip_ms for c in study.planned_conditions]
    blocks = []
    for k, (person, order) in enumerate(
        zip(people, condition_orders(study, len(people)), strict=True)
    ):
        traits = operator_traits(study, person)
        trials = study.pointing.block(k, study.seed)
        for place, c in enumerate(order):
            blocks.append(PointingBlock(person.id, traits, lags[c], trials, place + 1,
                                        place * len(trials) + 1, study.pointing.timeout_s,
                                        study.depth_aids,
                                        params=study.operator_params))  # fmt: skip
    return blocks


def run_pointing_block(block: PointingBlock) -> list[dict[str, float | str]]:
    """A block's trials, one after the other: each trial's row of :data:`RUN_COLUMNS`, and
    where its movement time went (``<activity>_s``, :data:`~arteleop.operator.ACTIVITIES`)."""
    from arteleop.teleop.pointing import run_pointing_trial

    practice = block.params
    rows: list[dict[str, float | str]] = []
    for n, trial in enumerate(block.trials):
        r = run_pointing_trial(trial.distance_m, trial.width_m, block.traits, trial.seed,
                               block.round_trip_ms / 1000, block.timeout_s, practice,
                               block.depth_aids)  # fmt: skip
        scale = believed_error_scale(practice.seen_outcomes, block.traits.confidence,
                                     practice.own_error_prior_sd)  # fmt: skip
        if not block.fresh:
            practice = replace(practice, familiar_lag_s=r.believed_lag_s,
                               seen_outcomes=practice.seen_outcomes.after(not r.hit))  # fmt: skip
        selected = r.selected
        nan = math.nan
        rows.append({
            "participant": block.participant, "round_trip_ms": block.round_trip_ms,
            "distance_m": trial.distance_m, "width_m": trial.width_m,
            "movement_time_s": r.movement_time_s if selected else nan,
            "along_m": r.along_m if selected else nan, "across_m": r.across_m if selected else nan,
            "hit": float(r.hit) if selected else nan,
            "block": block.block, "trial": block.first_trial + n, "rep": trial.rep,
            "seed": trial.seed, "slips": r.slips, "corrections": r.corrections, "looks": r.looks,
            "believed_lag_s": r.believed_lag_s, "error_scale": scale,
            **{f"{a}_s": r.activity_s.get(a, 0.0) for a in ACTIVITIES},
        })  # fmt: skip
    return rows


def run_blocks(
    blocks: Sequence[PointingBlock],
    workers: int | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
    keep: Callable[[int, list[dict[str, float | str]]], None] | None = None,
    done_before: int = 0,
) -> list[dict[str, float | str]]:
    """The rows of every block, in the order of ``blocks`` whichever ends first; each block in a
    fresh worker process (``workers`` of them, default one per core), or on ``executor``; a
    single block in this process. ``keep`` is given each block's place in ``blocks`` and its
    rows as it ends, also when another block fails, before ``progress`` hears (the block, trials
    done, trials in all: ``done_before`` more, run earlier)."""
    total = done_before + sum(len(b.trials) for b in blocks)
    done = done_before
    results: dict[int, list[dict[str, float | str]]] = {}

    def tell(k: int, rows: list[dict[str, float | str]]) -> None:
        nonlocal done
        if keep is not None:
            keep(k, rows)
        done += len(rows)
        results[k] = rows
        if progress is not None:
            progress(blocks[k], done, total)

    if executor is None and len(blocks) <= 1:
        for k, block in enumerate(blocks):
            tell(k, run_pointing_block(block))
        return [row for k in sorted(results) for row in results[k]]
    futures: dict[Future[list[dict[str, float | str]]], int] = {}
    # A fresh process for each block: a worker's memory grew about 13 MB a trial.
    workers = min(workers or os.cpu_count() or 1, len(blocks))
    with worker_pool(executor, futures, workers, max_tasks_per_child=1) as pool:
        for k, block in enumerate(blocks):
            futures[pool.submit(run_pointing_block, block)] = k
        try:
            for future in as_completed(futures):
                tell(futures[future], future.result())
        except BaseException:
            # Blocks that ended beside the one that failed (or a stop) are kept all the same.
            for future, k in futures.items():
                if keep is not None and k not in results and _succeeded(future):
                    keep(k, future.result())
            raise
    return [row for k in sorted(results) for row in results[k]]


def _succeeded(future: Future[Any]) -> bool:
    return future.done() and not future.cancelled() and future.exception() is None


def run_pointing_study(
    study: StudyConfig,
    out: Path,
    workers: int | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
) -> StudyRun:
    """Run the pointing study ``study`` in the new folder ``out``, to the end (see the module's
    docstring); the arguments as :func:`~arteleop.study.run_study`'s."""
    folder = RunFolder(out)
    check_new(folder)
    people = participants(study)
    blocks = pointing_blocks(study, people)
    text = study_text(study)
    manifest = pointing_manifest(study, text, blocks, people)
    make_folder(folder)
    with run_lock(folder.path):
        check_new(folder)
        write_atomic(folder.path / STUDY_FILE, text)
        write_atomic(folder.path / PARTICIPANTS_FILE, participants_text(people))
        folder.write_manifest(manifest)
        return _execute(folder, blocks, workers, executor, progress)


def pointing_manifest(
    study: StudyConfig,
    text: str,
    blocks: Sequence[PointingBlock],
    people: Sequence[ParticipantSpec],
) -> dict[str, object]:
    """A new pointing run's manifest.json: its definition's ``text``, plan of ``blocks`` and
    ``people``, its task and its trials planned."""
    manifest = new_manifest(study, text, blocks, len(people))
    manifest.update(task=study.task, trials_planned=sum(len(b.trials) for b in blocks))
    return manifest


def resume_pointing_study(
    folder: RunFolder,
    study: StudyConfig | None = None,
    workers: int | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
    tell: Callable[[str], None] | None = None,
) -> StudyRun:
    """Run the blocks a pointing run cut short lacks, keeping those it finished; the folder
    checked as a pick-and-place run's is (:func:`~arteleop.study.run_opening.opened_definition`),
    and its blocks against the plan it began with. With ``study``, refuses a folder made from
    another definition. The caller holds the folder's lock."""
    recorded, manifest = opened_definition(folder, study)
    if manifest.get("finished"):
        shutil.rmtree(folder.path / BLOCKS_DIR, ignore_errors=True)  # left by a stop at the end
        raise RunComplete(f"{folder.path} is complete: all its blocks are in; nothing to resume.")
    blocks = pointing_blocks(recorded)
    check_plan(folder, manifest, blocks)
    for note in arithmetic_notes(folder, manifest):  # ``tell``: as resume_study's
        (tell or folder.notes.append)(note)
    return _execute(folder, blocks, workers, executor, progress, resumed=True)


def _execute(
    folder: RunFolder,
    blocks: list[PointingBlock],
    workers: int | None,
    executor: Executor | None,
    progress: Progress | None,
    resumed: bool = False,
) -> StudyRun:
    """The blocks not yet kept in ``folder`` run, each kept as it ends; then pointing.csv, in
    plan order, and the manifest says the run is finished; last the kept blocks go.
    ``resumed``: the manifest records this resume first
    (:func:`~arteleop.study.run_opening.record_resume`)."""
    kept = folder.path / BLOCKS_DIR
    kept.mkdir(exist_ok=True)
    bodies = [_kept_body(folder, kept / _block_file(n), block) for n, block in enumerate(blocks)]
    pending = [n for n, body in enumerate(bodies) if body is None]

    def keep(n: int, rows: list[dict[str, float | str]]) -> None:
        text = table_text(RUN_COLUMNS, [[row[c] for c in RUN_COLUMNS] for row in rows])
        write_atomic(kept / _block_file(n), text)
        bodies[n] = text.split("\n", 1)[1]

    done_before = sum(len(blocks[n].trials) for n in range(len(blocks)) if n not in pending)
    if resumed:
        record_resume(folder, done_before)
    run_blocks([blocks[n] for n in pending], workers, executor, progress,
               lambda k, rows: keep(pending[k], rows), done_before)  # fmt: skip
    write_atomic(folder.path / POINTING_FILE, csv_line(RUN_COLUMNS) + "".join(map(str, bodies)))
    manifest = folder.manifest()
    manifest["finished"] = utc_now()
    folder.write_manifest(manifest)
    shutil.rmtree(kept, ignore_errors=True)  # pointing.csv holds them now
    table = pd.read_csv(folder.path / POINTING_FILE, dtype={"participant": str})
    ran = sum(len(blocks[n].trials) for n in pending)
    return StudyRun(folder.path, table, ran, [], tuple(folder.notes), POINTING.name)


def _block_file(n: int) -> str:
    """The file of the plan's block ``n`` (from 0) in :data:`BLOCKS_DIR`: named by its place,
    as participants' ids may differ in case alone."""
    return f"block-{n + 1:05d}.csv"


def _kept_body(folder: RunFolder, path: Path, block: PointingBlock) -> str | None:
    """The rows of ``block`` kept in ``path``, without the header; None if it is not there
    whole (with this header and a row per trial), and then a note when something else is."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return None
    except (OSError, UnicodeDecodeError) as err:
        text = f"unreadable: {err}"
    header, _, body = text.partition("\n")
    if header + "\n" == csv_line(RUN_COLUMNS) and body.count("\n") == len(block.trials):
        return body
    folder.notes.append(
        f"{path}: not the rows of participant {block.participant}'s block {block.block} as "
        "this arteleop writes them; that block ran again."
    )
    return None
