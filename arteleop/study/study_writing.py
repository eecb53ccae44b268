"""Study definitions written as TOML: every key explicit, each with its comment, so that a run
folder's study.toml says what the run was and how to change it."""

from __future__ import annotations

import dataclasses
from typing import Any

from arteleop.operator.simulated.params import OperatorParams
from arteleop.study.definition import POINTING_UNUSED, StudyConfig
from arteleop.study.study_constants import OPERATOR_PARAMS_KEYS
from arteleop.study.study_file import TABLES
from arteleop.teleop.trial_task import POINTING


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return '"' + escaped + '"'
    if isinstance(value, tuple | list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, float):
        return repr(value)
    return str(value)


_COMMENTS = {
    "name": "a name for the report",
    "task": "what every trial asks and how it is scored: pick-and-place, or a task of your own "
    'as "package.module:NAME" (docs/guides/extending.md)',
    "consent": "the information and consent page of 'arteleop study serve' (Markdown; \\n is a "
    'new line), the text your ethics board approved; consent_file = "consent.md" reads it from '
    "that file instead; empty: a built-in one that says this file's trials and timeout",
    "instructions": "the page on how to drive the robot, before the first trial (Markdown); "
    'instructions_file = "instructions.md" reads it from that file instead; empty: the '
    "built-in one (the page's controls, the grip, the timer)",
    "seed": "seed of the cohort, the orders, the practice positions and every trial",
    "modalities": "AR modalities compared: none, manipulation, embodiment, task, full",
    "order": "williams (balanced Latin square), cyclic, random (seeded) or listed (in orders)",
    "orders": 'with order = "listed": the sequences, e.g. [["none", "full"], ["full", "none"]]',
    "trials_per_modality": "experimental trials per modality (the data format holds 1)",
    "timeout_s": "simulated time after which a trial ends as a timeout (s)",
    "delay_ms": "one-way network delay between operator and robot (ms), in every trial",
    "depth_aids": "draw the gripper's drop line to the table and its height, in every trial "
    "(for people on a flat screen; the simulated participant judges them too)",
    "camera_offset_mm": "error of the head camera's registration: translation (mm, camera frame)",
    "camera_offset_deg": "and rotation vector (deg, camera frame); zero is a perfect registration",
    "camera_pose": "or its registered pose, 4 rows of T_base_camera (m); camera_graph = "
    '"calibration.json" takes it from that file (arteleop calibrate)',
    "conditions.cues": "modalities and AR layers shown",
    "conditions.round_trip_ms": "round-trip delay between operator and robot (ms), half each way",
    "conditions.jitter_ms": "SD of each one-way delay (ms)",
    "conditions.loss": "chance that an operator sample is lost, in [0, 1)",
    "start_xy_m": "where the bowl starts, Baxter's base frame (m); on the table, in the right "
    "arm's reach and in the head camera's view, as is the target",
    "target_xy_m": "where it must go (m)",
    "familiarization.trials": "practice trials per participant, random start and target",
    "familiarization.modality": "AR modality of the practice trials",
    "familiarization.timeout_s": "timeout of a practice trial (s)",
    "cohort.size": "simulated participants, used when no [[participants]] are listed",
    "cohort.avr_experts": "of them, AR/VR experts (at least 2 h a week)",
    "cohort.games_experts": "gamers (at least 2 h a week)",
    "cohort.both_experts": "of those, expert in both",
    "cohort.movement_time_sd": "between-participant SD of log movement time",
    "cohort.id_prefix": "participant ids: prefix and a two-digit number",
    "operator.miss_rate": "simulated participants' traits (docs/explanation/operator-model.md): "
    "median 1 - confidence",
    "operator.miss_rate_sd": "its SD between participants (of the log; likewise every *_sd)",
    "operator.grasp_criterion_sd": "grasp criterion: a share (median 1) of the gripper's clearance",
    "operator.placement_criterion_m": "median placement criterion: close enough to the target (m)",
    "operator.urgency_s": "median effort after which the criterion has doubled (s)",
    "operator.glance_s": "median time per glance while looking (s)",
    "operator.avr_depth_factor": "AR/VR experts' depth judgement from the cloud: a factor on SD",
    "operator.depth_scale_sd": "how each person sees depth intervals in the rendered scene: "
    "a scale of median 1",
    "operator.games_speed_factor": "gamers' movement time: a factor on their own",
    "pointing.distances_m": "targets' distances from the start cross, along +y (m)",
    "pointing.widths_m": "targets' diameters (m)",
    "pointing.repetitions": "trials of each distance and width under each lag",
    "pointing.timeout_s": "simulated time after which a trial with no selection ends (s)",
    "hand_filter.enabled": "1-euro filter on the operator's reconstructed hand (Casiez 2012)",
    "hand_filter.min_cutoff_hz": "cutoff at rest (Hz): lower removes more jitter, adds more lag",
    "hand_filter.beta_per_m": "how fast the cutoff rises with the hand's speed (Hz per m/s)",
    "hand_filter.derivative_cutoff_hz": "cutoff of the speed estimate (Hz)",
}

_HEADER = """\
# An arteleop study definition. Every key is optional: a missing key takes the default shown.
# The defaults mirror the original study (docs/explanation/study.md §4): 22 participants, five
# modalities, a balanced Latin square, three practice trials under no AR, one trial per modality.
# Run it: arteleop study run THIS_FILE --out RUN_DIR
"""

_POINTING_HEADER = """\
# An arteleop pointing study: a Fitts task under lag, run with simulated participants. Beside
# task and the lags (the [[conditions]]), every key is optional: a missing key takes the default
# shown.
# Run it: arteleop study run THIS_FILE --out RUN_DIR
"""

_OPERATOR_PARAMS_HELP = """
# The simulated participants' constants changed from the model's
# (docs/explanation/operator-model.md): a sensitivity run, to see how far an answer rests on one.
"""

_CONDITIONS_HELP = """\
# Conditions that cross network delay with AR cues replace modalities and delay_ms, e.g.
# [[conditions]]
# cues = ["predictive"]  # modalities and AR layers, e.g. [] or ["ghost", "predictive_ghost"]
# round_trip_ms = 500    # round-trip delay (ms), half each way
# jitter_ms = 0          # SD of each one-way delay (ms)
# loss = 0.0             # chance that an operator sample is lost, in [0, 1)

"""

_QUESTIONNAIRE_HELP = """\
# The questionnaire after the last trial: each item rated 1 (low) to 7 (high) for each AR class
# the study's conditions draw. questionnaire_file = "items.toml" reads [[questionnaire]] tables
# from that file instead. Simulated participants answer the original's three items only.
"""

_PARTICIPANTS_HELP = """\
# Named participants replace the simulated cohort, e.g. (ids name folders of the run):
# [[participants]]
# id = "S01"
# avr_hours = 2          # weekly AR/VR hours bucket: 1 (< 1 h), 2 (2-5 h), 3 (> 5 h)
# games_hours = 1        # weekly video-game hours bucket, same buckets
# avr_experience = 5     # Likert 1-7
# games_experience = 3   # Likert 1-7
# age = 29
# gender = "f"
# movement_time_factor = 1.0  # simulated participants only: < 1 moves faster, less accurately
"""


def study_text(config: StudyConfig) -> str:
    """The definition as commented TOML, every key it reads written out."""
    pointing = config.task == POINTING.name
    out = [_POINTING_HEADER if pointing else _HEADER]
    nested = {"participants", "conditions", "questionnaire", *TABLES}
    if config.conditions:  # they replace the modalities and the delay
        nested |= {"modalities", "delay_ms"}
    # A pointing study's file leaves out what its trials do not read; a pick-and-place
    # study's has no [pointing] table, as before pointing studies.
    left_out = set(POINTING_UNUSED) if pointing else {"pointing"}
    for f in dataclasses.fields(config):
        if f.name not in nested | left_out:
            out.append(_key_line(f.name, getattr(config, f.name), f.name))
    for table in TABLES:
        if table in left_out:
            continue
        sub = getattr(config, table)
        if table == "operator_params":
            out.append(_operator_params_text(sub))
            continue
        out.append(f"\n[{table}]\n")
        for f in dataclasses.fields(sub):
            out.append(_key_line(f.name, getattr(sub, f.name), f"{table}.{f.name}"))
    out.append("\n")
    if config.conditions:
        for condition in config.conditions:
            out.append(f"[[conditions]]  # {condition.name}\n")
            for f in dataclasses.fields(condition):
                value = getattr(condition, f.name)
                out.append(_key_line(f.name, value, f"conditions.{f.name}"))
            out.append("\n")
    else:
        out.append(_CONDITIONS_HELP)
    if not pointing:
        out.append(_QUESTIONNAIRE_HELP)
        for item in config.questionnaire:
            out.append("[[questionnaire]]\n")
            for f in dataclasses.fields(item):
                out.append(f"{f.name} = {_toml_value(getattr(item, f.name))}\n")
            out.append("\n")
    if config.participants:
        for person in config.participants:
            out.append("[[participants]]\n")
            for f in dataclasses.fields(person):
                out.append(f"{f.name} = {_toml_value(getattr(person, f.name))}\n")
            out.append("\n")
    else:
        out.append(_PARTICIPANTS_HELP)
    return "".join(out)


def _operator_params_text(params: OperatorParams) -> str:
    """The model's constants the study changes, as a table; nothing where it changes none: a
    study file does not invite a change of the model."""
    model = OperatorParams()
    changed = [k for k in OPERATOR_PARAMS_KEYS if getattr(params, k) != getattr(model, k)]
    if not changed:
        return ""
    lines = [_OPERATOR_PARAMS_HELP, "[operator_params]\n"]
    lines += [f"{k} = {_toml_value(getattr(params, k))}  # the model's: "
              f"{_toml_value(getattr(model, k))}\n" for k in changed]  # fmt: skip
    return "".join(lines)


def _key_line(key: str, value: Any, path: str) -> str:
    comment = _COMMENTS.get(path)
    return (f"# {comment}\n" if comment else "") + f"{key} = {_toml_value(value)}\n"
