"""Read placements one by one: at the moment the simulated participant lets go, what it believed
beside the truth, and where the bowl ended.

Runs the default study's experimental trials under ``--modalities`` (default: none and full) for
its first ``--people`` participants (the study's own traits, seeds and sites), and for each
placement prints, in the table's plane (mm):

- ``belief``: the bowl as the operator believed it against the target as it judged it: what
  it accepted (within its placement criterion, ``crit``);
- ``target``: its judgement of the target against the true target;
- ``bowl``: its belief of the bowl against the true bowl, as the display showed it then;
- ``at_release``: the true bowl against the true target when the robot's fingers opened;
- ``settle``: how far the bowl moved from there until the trial's end (dropped, pushed);
- ``true`` / ``tracked``: the final error, from ground truth and as trials.csv has it;
- whether the bowl was seen at the release glance, or remembered in the hand (``memory``).

With ``--ring`` every camera frame is rendered, and each placement says how much of the target
ring the cloud drew when the fingers opened (``ring_share``, of the most any frame drew) and how
long before that half of it was last drawn (``ring_unseen_s``).

With ``--memory-drift-deg`` the participant's ``PerceptionParams.memory_drift_rad`` is set to
that angle (deg) for every trial, with ``--direction-sd-deg`` its ``MovementScatter``'s
``direction_sd_rad``: the placements' sensitivity to these assumptions.

    python benchmarks/read_placements.py [--people 10] [--modalities none,full] [--seed 0]
        [--ring] [--memory-drift-deg DEG] [--direction-sd-deg DEG]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import math
from dataclasses import replace

import numpy as np
import pandas as pd

from arteleop.ar_features import DisplayFrame
from arteleop.errors import ConfigurationError
from arteleop.operator import MovementScatter, OperatorParams, PerceptionParams
from arteleop.operator.simulated.perception import Perceived
from arteleop.operator.simulated.tasks import pick_and_place
from arteleop.operator.simulated.tasks.task import Action, TaskPhase
from arteleop.scene import RemoteSite, Workspace
from arteleop.study import StudyConfig
from arteleop.study.protocol import operator_traits, trial_config
from arteleop.study.run_opening import plan_run
from arteleop.study.sites import StudySite
from arteleop.teleop import run_trial, trial_operator
from arteleop.teleop.trace import TRACE_COLUMNS

RELEASES: list[dict[str, object]] = []
GRASPS: list[dict[str, object]] = []
_gripped = pick_and_place.PickAndPlace.gripped


def _spy(self: pick_and_place.PickAndPlace, phase: TaskPhase, seen: Perceived) -> None:
    if phase.action is Action.CLOSE:
        believed = self.memory.bowl_m(seen)
        GRASPS.append({
            "believed_bowl": None if believed is None else believed.copy(),
            "seen_gripper": seen.gripper_m.copy(),
        })  # fmt: skip
    if phase.action is Action.OPEN:
        believed = self.memory.bowl_m(seen)
        RELEASES.append({
            "seen_target": seen.target_m.copy(),
            "believed_bowl": None if believed is None else believed.copy(),
            "bowl_seen": seen.bowl_m is not None,
            "placement_sd_mm": 1000 * float(np.sqrt(np.trace(seen.target_cov[:2, :2]) / 2)),
        })  # fmt: skip
    _gripped(self, phase, seen)


pick_and_place.PickAndPlace.gripped = _spy


class RingWatch:
    """A display that counts, in each frame's point cloud, the target ring's points drawn
    (dark points on the ring's band): what a person could see of the marker."""

    def __init__(self, workspace: Workspace) -> None:
        self._ws = workspace
        self.times_s: list[float] = []
        self.points: list[int] = []

    def show(self, frame: DisplayFrame) -> None:
        if frame.cloud_points_m is None:
            return
        pts, colors = frame.cloud_points_m, frame.cloud_colors
        r = np.linalg.norm(pts[:, :2] - np.asarray(self._ws.target_xy_m), axis=1)
        band = np.abs(r - self._ws.target_circle_radius_m) < self._ws.marker_line_width_m / 2
        on_table = np.abs(pts[:, 2] - frame.target_m[2]) < 0.01
        self.times_s.append(frame.time_s)
        self.points.append(int(np.sum(band & on_table & (colors.max(axis=1) < 60))))

    def seen_share(self) -> np.ndarray:
        """Each frame's ring points as a share of the most any frame showed."""
        counts = np.asarray(self.points, dtype=float)
        return counts / max(counts.max(), 1.0)


def _column(trace: dict[str, np.ndarray] | np.ndarray, name: str) -> np.ndarray:
    if isinstance(trace, dict):
        return np.asarray(trace[name])
    return trace[:, TRACE_COLUMNS.index(name)]


def read(
    study: StudyConfig,
    people: int,
    modalities: list[str],
    ring: bool,
    params: OperatorParams | None = None,
) -> pd.DataFrame:
    site = StudySite()
    plan, cohort = plan_run(study, site)
    persons = {p.id: p for p in cohort[:people]}
    rows = []
    for spec in plan:
        if spec.phase != "experimental" or spec.participant not in persons:
            continue
        if spec.modality not in modalities:
            continue
        config = trial_config(study, site, spec)
        RELEASES.clear()
        GRASPS.clear()
        if ring:
            config = replace(config, render_camera=True)
        watch = RingWatch(config.site.workspace)
        with RemoteSite(config.site) as remote:
            source = trial_operator(remote, config, params=params,
                                    traits=operator_traits(study, persons[spec.participant]))  # fmt: skip
            result = run_trial(source, config, remote, watch if ring else None)
            traits = source.operator.traits
        trace = result.trace
        assert trace is not None
        t = _column(trace, "time_s")
        bowl = np.stack([_column(trace, f"bowl_{a}_m") for a in "xyz"], axis=1)
        closure = _column(trace, "gripper_closure")
        gripper = np.stack([_column(trace, f"gripper_{a}_m") for a in "xyz"], axis=1)
        target = np.array([*config.site.workspace.target_xy_m, 0.0])
        row: dict[str, object] = {
            "participant": spec.participant, "modality": spec.modality,
            "outcome": result.outcome.value,
            "crit_mm": 1000 * traits.placement_criterion_m,
            "depth_scale": traits.depth_scale,
            "true_mm": 1000 * result.placement_error_true_m,
            "tracked_mm": 1000 * result.placement_error_m,
            "releases": len(RELEASES),
        }  # fmt: skip
        if RELEASES:
            last = RELEASES[-1]
            believed = last["believed_bowl"]
            seen_target = last["seen_target"]
            # The fingers opened: the last tick the closure fell from held.
            held = closure > 0.5
            opened = np.flatnonzero(held[:-1] & ~held[1:])
            k = int(opened[-1]) + 1 if len(opened) else len(t) - 1
            row |= {
                "memory": not last["bowl_seen"],
                "sd_mm": last["placement_sd_mm"],
                "belief_mm": _mm(believed - seen_target) if believed is not None else np.nan,
                "target_mm": _mm(seen_target - target),
                "bowl_mm": _mm(believed - bowl[k]) if believed is not None else np.nan,
                "at_release_mm": _mm(bowl[k] - target),
                "settle_mm": _mm(bowl[-1] - bowl[k]),
                "release_s": float(t[k]),
            }
            if ring and watch.times_s:
                shown = np.asarray(watch.times_s)
                share = watch.seen_share()
                before = shown <= t[k]
                seen_half = np.flatnonzero(before & (share >= 0.5))
                row |= {
                    # The ring as drawn when the fingers opened, and how long before that
                    # half of it was last drawn.
                    "ring_share": float(share[before][-1]) if before.any() else np.nan,
                    "ring_unseen_s": float(t[k] - shown[seen_half[-1]])
                    if len(seen_half)
                    else np.nan,
                }
            if GRASPS and believed is not None:
                grasp = GRASPS[-1]
                closed = np.flatnonzero(~held[:-1] & held[1:])
                g = int(closed[-1]) + 1 if len(closed) else 0
                in_hand_believed = grasp["believed_bowl"] - grasp["seen_gripper"]
                row |= {
                    # The bowl's place in the hand: believed at the grasp, true then and at
                    # the release (the difference: the bowl moved in the fingers).
                    "in_hand_mm": _mm(in_hand_believed - (bowl[k] - gripper[k])),
                    "grasp_belief_mm": _mm(grasp["believed_bowl"] - bowl[g]),
                    "slip_mm": _mm((bowl[k] - gripper[k]) - (bowl[g] - gripper[g])),
                }
        rows.append(row)
        print(pd.DataFrame([row]).to_string(index=False, header=len(rows) == 1,
                                            float_format="%.1f"), flush=True)  # fmt: skip
    site.close()
    return pd.DataFrame(rows)


def _mm(v: np.ndarray) -> float:
    return float(1000 * np.linalg.norm(np.asarray(v)[:2]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--people", type=int, default=10)
    parser.add_argument("--modalities", default="none,full")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--ring",
        action="store_true",
        help="render every frame and count the target ring's points drawn",
    )
    parser.add_argument("--memory-drift-deg", type=float, default=None,
                        help="the participant's memory drift in its first second (deg)")  # fmt: skip
    parser.add_argument("--direction-sd-deg", type=float, default=None,
                        help="the SD of the participant's movement direction (deg)")  # fmt: skip
    args = parser.parse_args()
    study = StudyConfig(seed=args.seed)
    params = None
    if args.memory_drift_deg is not None or args.direction_sd_deg is not None:
        params = OperatorParams()
    if args.memory_drift_deg is not None:
        drift_rad = np.radians(args.memory_drift_deg)
        params = replace(params, perception=PerceptionParams(memory_drift_rad=drift_rad))
    if args.direction_sd_deg is not None:
        try:
            scatter = MovementScatter(direction_sd_rad=math.radians(args.direction_sd_deg))
        except ConfigurationError as err:
            parser.error(f"--direction-sd-deg {args.direction_sd_deg}: {err}")
        params = replace(params, scatter=scatter)
    table = read(study, args.people, args.modalities.split(","), args.ring, params)
    print()
    print(table.groupby("modality")[[c for c in table.columns
                                     if c.endswith(("_mm", "_s", "_share"))]]
          .median().to_string(float_format="%.1f"))  # fmt: skip


if __name__ == "__main__":
    main()
