"""'arteleop operator check' and 'arteleop operator synth': wearable recordings."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import tyro

from arteleop.cli.options import Modality, check_seed
from arteleop.cli.progress import trial_progress
from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class OperatorCheckCommand:
    """Validate a wearable recording and summarise it; exit non-zero if it is invalid."""

    file: tyro.conf.Positional[Path]
    """the recording's CSV; its JSON sidecar sits beside it with the same stem"""


def operator_check(cmd: OperatorCheckCommand) -> int:
    from arteleop.analysis import path_length
    from arteleop.operator import load_recording
    from arteleop.teleop import reconstruct

    rec = load_recording(cmd.file)
    traj = reconstruct(rec)
    measured_hz = (len(rec.time_s) - 1) / rec.duration_s
    report = rec.report
    print(f"recording     {cmd.file} (subject {rec.info.subject_id})")
    print(f"duration      {rec.duration_s:.2f} s, {len(rec.time_s)} samples")
    print(
        f"rate          {rec.info.rate_hz:g} Hz in the sidecar, {measured_hz:.2f} Hz after filling"
    )
    print(f"gaps          {report.gaps} filled by slerp ({report.filled_samples} samples)")
    print(
        f"lost          {report.lost_samples} samples marked lost by the wearable (filled "
        "for this summary; a replay loses them again)"
    )
    print(f"renormalised  {report.renormalized} quaternions")
    length = path_length(traj.time_s, traj.hand_m)
    print(
        f"hand path     {length:.3f} m (reconstructed pinch point, torso frame, low-pass "
        "filtered at 6 Hz as the analysis does: summed raw, sensor noise adds metres)"
    )
    return 0


@dataclass(frozen=True)
class OperatorSynthCommand:
    """Run one synthetic trial headless and write the operator's wearable recording."""

    modality: Modality = "full"
    """AR modality shown to the synthetic operator (docs/explanation/study.md §3)"""
    seed: int = 0
    """seed of every random source of the trial (0 or more)"""
    out: Path = Path("synthetic.csv")
    """recording CSV (its JSON sidecar is written beside it)"""
    force: bool = False
    """replace a recording that --out (or its sidecar) already holds"""
    quiet: bool = False
    """print the result only, no progress"""


def operator_synth(cmd: OperatorSynthCommand) -> int:
    from arteleop.operator import sidecar_path, write_recording
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial, trial_operator

    check_seed(cmd.seed)
    _check_out(cmd.out, cmd.force)
    config = TrialConfig(modality=cmd.modality, seed=cmd.seed)
    with RemoteSite(config.site) as site:
        source = trial_operator(site, config)
        with trial_progress(config.timeout_s, "trial", cmd.quiet) as progress:
            result = run_trial(source, config, site, progress=progress)
    rec = source.recording(subject_id=f"synthetic-{cmd.modality}-{cmd.seed}")
    try:
        write_recording(rec, cmd.out)
    except OSError as err:
        raise ConfigurationError(
            f"Cannot write {cmd.out}: {err.strerror or err}. An earlier recording there is "
            "unchanged; free space or fix permissions and run it again."
        ) from None
    print(f"trial outcome {result.outcome.value}")
    print(f"wrote {cmd.out} and its sidecar {sidecar_path(cmd.out)}")
    print(
        f"{len(rec.time_s)} samples at {rec.info.rate_hz:g} Hz, {int(rec.lost.sum())} of them "
        "lost by the wearable in flight (rows with the time only, lost again on replay)"
    )
    return 0


def _check_out(out: Path, force: bool) -> None:
    """Refuse, before the trial runs, an ``--out`` that cannot take a recording or would replace
    one without ``--force``."""
    from arteleop.operator import sidecar_path

    if out.is_dir():
        raise ConfigurationError(
            f"--out {out}: a folder; give the recording's CSV path, such as {out / 'synthetic.csv'}."
        )
    if out.suffix.lower() != ".csv":
        raise ConfigurationError(
            f"--out {out}: a recording's CSV ends in .csv (its sidecar takes the .json beside it)."
        )
    if not force:
        for path in (out, sidecar_path(out)):
            if path.exists():
                raise ConfigurationError(
                    f"--out {out}: {path} exists; give another path, or --force to replace the "
                    "recording."
                )
