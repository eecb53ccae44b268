"""A pointing study (``task = "pointing"``) served to people: its run folder.

The plan is a simulated pointing run's (:func:`~arteleop.study.pointing_run.pointing_blocks`):
the same participant ids, orders of lags and targets. Each person does their blocks' trials in
order; a trial is theirs to start, and ends when they close the grip
(:class:`~arteleop.teleop.task_monitor.SelectionMonitor`), scored as
:func:`~arteleop.teleop.pointing.person_pointing_result` says: it counts if the gripper had been
over the start cross before. Beside what every served run keeps (:mod:`arteleop.study.session`:
``participants.csv``, ``browser.csv``, ``links.key``), the folder holds:

- ``pointing.csv``: a row for each trial that ended, in plan order, with the columns ``arteleop
  analyze`` reports (docs/reference/data-format.md#pointingcsv), then the trial's block, number,
  repetition, seed, how it ended and its trajectory file (:data:`SERVED_POINTING_COLUMNS`);
  rewritten whole at each trial;
- ``trajectories/<participant>/<trial>.csv``: each trial's trace, as a pick-and-place run's;
- ``interrupted.csv``: each attempt a lost tab cut short, with the first of those columns and
  the outcome ``interrupted``; the trial runs again from its start.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from arteleop.analysis.data import PARTICIPANT_COLUMNS
from arteleop.analysis.pointing import POINTING_COLUMNS, POINTING_FILE
from arteleop.errors import RunFolderError
from arteleop.study.cohort import participants
from arteleop.study.definition import StudyConfig
from arteleop.study.plan import EXPERIMENTAL
from arteleop.study.pointing_design import PointingTrial
from arteleop.study.pointing_run import pointing_blocks, pointing_manifest
from arteleop.study.protocol import trajectory_file
from arteleop.study.run_folder import (
    PARTICIPANTS_FILE,
    REAL,
    STUDY_FILE,
    RunFolder,
    read_table,
    table_text,
    trace_text,
    write_atomic,
)
from arteleop.study.run_opening import check_plan, opened_definition
from arteleop.study.runner import check_new
from arteleop.study.session import ServedRun
from arteleop.study.sites import StudySite
from arteleop.study.study_writing import study_text
from arteleop.teleop import PERSON_POINTING, Outcome, TrialConfig, TrialResult
from arteleop.teleop.pointing import person_pointing_result, pointing_config

SERVED_POINTING_COLUMNS = (*POINTING_COLUMNS, "block", "trial", "rep", "seed", "outcome",
                           "trajectory_file")  # fmt: skip
"""``pointing.csv`` of a served pointing run: the analysed columns, then the trial's block and
number in the person's session (from 1), its repetition and seed, how it ended (``selected``;
``not_from_start``: the grip closed before the gripper was over the start cross; else the
trial's outcome, ``timeout`` or ``dropped``) and its trace's file."""
INTERRUPTED_COLUMNS = (*POINTING_COLUMNS[:4], "block", "trial", "outcome")
"""``interrupted.csv`` of a served pointing run."""
TASK_TEXT = (
    "Move the gripper over the cross, then as quickly and as accurately as you can over the "
    "middle of the circle, and close the grip there (G, or the Grip slider): that is your "
    "choice of the target, and it ends the trial."
)
"""What a pointing trial's page asks of the person."""

NOT_CHOSEN = {
    "not_from_start": "the grip closed before the gripper had been over the cross",
    "timeout": "the time ran out before the grip closed",
    "dropped": "the bowl was knocked off the table",
}
"""Why a trial counts no selection, by how it ended, as its page says it."""


@dataclass(frozen=True)
class PointingSpec:
    """One planned trial of a served pointing study.

    Attributes:
        participant: The participant's id.
        trial_index: Its number in the participant's session, from 1.
        block: Its block's number in the session, from 1.
        round_trip_ms: The block's lag: the network's round trip, half each way (ms).
        trial: Its target and seed.
        timeout_s: A trial with no selection ends after this (s).
        depth_aids: The display draws the depth aids.
    """

    participant: str
    trial_index: int
    block: int
    round_trip_ms: float
    trial: PointingTrial
    timeout_s: float
    depth_aids: bool
    modality: str = "none"
    phase: str = EXPERIMENTAL

    @property
    def key(self) -> tuple[str, int]:
        """(participant, trial_index): names the trial in every file."""
        return self.participant, self.trial_index


class ServedPointingRun(ServedRun):
    """The run folder of a pointing study served to people; see the module's docstring."""

    @classmethod
    def create(
        cls, study: StudyConfig, out: Path, site: StudySite | None = None
    ) -> ServedPointingRun:
        folder = RunFolder(out)
        check_new(folder)
        people = participants(study)
        text = study_text(study)
        manifest = {**pointing_manifest(study, text, pointing_blocks(study, people), people),
                    "cohort": REAL}  # fmt: skip
        write_atomic(folder.path / STUDY_FILE, text)
        write_atomic(folder.path / PARTICIPANTS_FILE, table_text(PARTICIPANT_COLUMNS, []))
        folder.write_manifest(manifest)
        return cls(folder, study, _plan(study), people, site or StudySite())

    @classmethod
    def reopen(cls, folder: RunFolder, study: StudyConfig | None, site: StudySite) -> ServedRun:
        recorded, manifest = opened_definition(folder, study)
        check_plan(folder, manifest, pointing_blocks(recorded))
        return cls(folder, recorded, _plan(recorded), participants(recorded), site)

    def done_keys(self) -> set[tuple[str, int]]:
        return set(self._kept())

    def trial_config(self, spec: PointingSpec, site: StudySite) -> TrialConfig:  # type: ignore[override]
        t = spec.trial
        config = pointing_config(t.distance_m, t.width_m, t.seed, spec.round_trip_ms / 1000,
                                 spec.timeout_s, spec.depth_aids)  # fmt: skip
        return replace(config, site=replace(site.base, workspace=config.site.workspace),
                       task=PERSON_POINTING)  # fmt: skip

    def trial_text(self, spec: PointingSpec) -> str:  # type: ignore[override]
        return TASK_TEXT

    def keep_result(self, spec: PointingSpec, result: TrialResult, wall_s: float) -> str:  # type: ignore[override]
        """The trial's row and trace kept; what its outcome page says."""
        if result.trace is None:
            raise RunFolderError("A served pointing trial recorded no trace.")
        config = self.trial_config(spec, self.site)
        r = person_pointing_result(result.trace, config.site.workspace)
        t, nan = spec.trial, math.nan
        selected = "selected" if r.selected else None
        ended = selected or ("not_from_start" if result.outcome is Outcome.SUCCESS
                             else result.outcome.value)  # fmt: skip
        row = (spec.participant, spec.round_trip_ms, t.distance_m, t.width_m,
               r.movement_time_s if r.selected else nan, r.along_m if r.selected else nan,
               r.across_m if r.selected else nan, float(r.hit) if r.selected else nan,
               spec.block, spec.trial_index, t.rep, t.seed, ended,
               trajectory_file(spec))  # fmt: skip
        write_atomic(self.folder.path / trajectory_file(spec), trace_text(result.trace))
        kept: dict[tuple[str, int], Sequence[object]] = {**self._kept(), spec.key: row}
        order = [s.key for s in self.plan if s.key in kept]
        write_atomic(self._table, table_text(SERVED_POINTING_COLUMNS, [kept[k] for k in order]))
        if not r.selected:
            return f"No target counted: {NOT_CHOSEN.get(ended, ended.replace('_', ' '))}."
        where = "inside" if r.hit else "outside"
        off_mm = 1000 * math.hypot(r.along_m, r.across_m)
        return (f"Chosen in {r.movement_time_s:.2f} s, {off_mm:.0f} mm from the middle: {where} "
                "the circle.")  # fmt: skip

    def keep_interrupted(self, spec: PointingSpec) -> None:  # type: ignore[override]
        t = spec.trial
        self._add_interrupted(INTERRUPTED_COLUMNS, [spec.participant, spec.round_trip_ms,
                              t.distance_m, t.width_m, spec.block, spec.trial_index,
                              "interrupted"])  # fmt: skip

    def _put_in_order(self) -> None:
        """Nothing to do: ``pointing.csv`` is kept in plan order as each trial ends."""

    @property
    def _table(self) -> Path:
        return self.folder.path / POINTING_FILE

    def _kept(self) -> dict[tuple[str, int], list[str]]:
        """The rows of ``pointing.csv`` by (participant, trial)."""
        if not self._table.exists():
            return {}
        rows = read_table(self._table, SERVED_POINTING_COLUMNS)[1:]
        trial = SERVED_POINTING_COLUMNS.index("trial")
        try:
            return {(row[0], int(row[trial])): row for row in rows}
        except ValueError:
            raise RunFolderError(
                f"{self._table}: a trial number that is not a whole number; mend the row or "
                "move the file away (its trials then run again)."
            ) from None


def _plan(study: StudyConfig) -> list[PointingSpec]:
    """Every planned trial, participant by participant, block by block."""
    plan = []
    for b in pointing_blocks(study):
        for n, trial in enumerate(b.trials):
            plan.append(PointingSpec(b.participant, b.first_trial + n, b.block, b.round_trip_ms,
                                     trial, b.timeout_s, b.depth_aids))  # fmt: skip
    return plan
