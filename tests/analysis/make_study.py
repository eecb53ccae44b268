"""A synthetic run folder with known effects, made inside the tests (no files are shipped)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.data import MODALITIES

TIME_S = {"none": 45.0, "manipulation": 38.0, "embodiment": 40.0, "task": 43.0, "full": 26.0}
ERROR_M = {"none": 0.035, "manipulation": 0.018, "embodiment": 0.030, "task": 0.030, "full": 0.014}
TREMOR_M = {
    "none": 0.004,
    "manipulation": 0.004,
    "embodiment": 0.0005,
    "task": 0.004,
    "full": 0.002,
}


def _reach(rng: np.random.Generator, tremor_m: float) -> pd.DataFrame:
    t = np.arange(0.0, 2.0, 0.01)
    tau = t / 2.0
    s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    wobble = tremor_m * np.sin(2 * np.pi * rng.uniform(3.0, 5.0) * t)
    return pd.DataFrame({
        "time_s": t, "hand_x_m": 0.3 + 0.2 * s, "hand_y_m": -0.2 + 0.3 * s + wobble,
        "hand_z_m": -0.2 + 0.05 * np.sin(np.pi * s),
    })  # fmt: skip


def make_run(root: Path, seed: int = 0, n: int = 22, trajectories: bool = True) -> Path:
    rng = np.random.default_rng(seed)
    root.mkdir(parents=True, exist_ok=True)
    people = [f"P{i + 1:02d}" for i in range(n)]
    experts = set(rng.choice(people, 7, replace=False))
    participants = pd.DataFrame({
        "participant": people, "age": rng.integers(23, 41, n), "gender": rng.choice(["m", "f"], n),
        "handedness": "right", "avr_experience": rng.integers(1, 8, n),
        "avr_hours": [3 if p in experts else 1 for p in people],
        "games_experience": rng.integers(1, 8, n),
        "games_hours": [2 if p in experts else 1 for p in people], "source": "synthetic",
    })  # fmt: skip
    rows = []
    for i, p in enumerate(people):
        for k in range(3):
            rows.append({
                "participant": p, "phase": "familiarization", "trial_index": k + 1,
                "modality": "none", "position": 0, "outcome": "success",
                "completion_time_s": rng.uniform(40, 80),
                "placement_error_m": rng.uniform(0.02, 0.08),
            })  # fmt: skip
        order = MODALITIES[i % 5 :] + MODALITIES[: i % 5]
        for pos, m in enumerate(order, start=1):
            factor = 0.8 if (p in experts and m == "none") else 1.0
            row = {
                "participant": p, "phase": "experimental", "trial_index": 3 + pos, "modality": m,
                "position": pos, "seed": seed * 1000 + i * 10 + pos, "outcome": "success",
                "completion_time_s": TIME_S[m] * factor * rng.lognormal(0, 0.2),
                "placement_error_m": ERROR_M[m] * rng.lognormal(0, 0.3),
            }  # fmt: skip
            if trajectories:
                rel = Path("trajectories") / p / f"{3 + pos}.csv"
                (root / rel).parent.mkdir(parents=True, exist_ok=True)
                _reach(rng, TREMOR_M[m]).to_csv(root / rel, index=False)
                row["trajectory_file"] = str(rel)
            rows.append(row)
    # One failed trial, to be counted and left out: the last participant's full-AR trial.
    next(r for r in reversed(rows) if r["modality"] == "full")["outcome"] = "timeout"
    pd.DataFrame(rows).to_csv(root / "trials.csv", index=False)
    participants.to_csv(root / "participants.csv", index=False)
    q = [
        {
            "participant": p,
            "ar_class": c,
            "item": item,
            "score": int(np.clip(round(rng.normal(base, 1.0)), 1, 7)),
        }
        for p in people
        for c, base in (("embodiment", 6.0), ("manipulation", 5.0), ("task", 3.0))
        for item in ("presence", "embodiment", "ease")
    ]
    pd.DataFrame(q).to_csv(root / "questionnaire.csv", index=False)
    return root
