"""What the served pages say to a participant: the consent, the tutorial, the questionnaire's
items, a trial's outcome; the built-in texts say only what is true of the study file."""

from __future__ import annotations

from arteleop.study.definition import StudyConfig
from arteleop.teleop.trial_task import POINTING

CONSENT = """\
You are invited to take part in a study of how {about} people steer a robot arm from a
distance. The robot, the table and the bowl are simulated.

**What you do.** {what_you_do}

**What is recorded.** Your movements, each trial's time and accuracy, your answers about
yourself{ratings}, under a participant number: never your name.

**Your choice.** Taking part is voluntary. You may stop at any time, without giving a reason,
by closing this page; what was recorded until then is kept unless you ask the researcher to
delete it.

Ask the researcher who runs the study about anything that is not clear before you go on.
"""
"""The information and consent page when the study file gives none (its key ``consent``),
before :func:`consent_text` fills in the study's trials and their limit."""


WHAT_YOU_DO = (
    "With the mouse or the keyboard you move the gripper of a robot arm, pick up a bowl and put "
    "it on a target: {trials}. Each trial ends when the bowl stands still after you let it go, "
    "or after {limit} at most. Afterwards you rate the displays."
)
WHAT_YOU_DO_POINTING = (
    "With the mouse or the keyboard you move the gripper of a robot arm over a cross on a "
    "table, then over a circle, and close its grip there: {trials}{blocks}. Each trial ends "
    "when you close the grip, or after {limit} at most."
)


def consent_text(study: StudyConfig) -> str:
    """The information and consent page: the study file's own (``consent``), else the
    built-in one, saying only what is true of ``study``: its task, its trials and how long one
    may last."""
    if study.consent:
        return study.consent
    if study.task == POINTING.name:
        blocks = len(study.planned_conditions)
        trials = _count(blocks * len(study.pointing.block(0)), "measured trial")
        lags = (f", in {blocks} blocks, the robot's view late by a different amount in each"
                if blocks > 1 else "")  # fmt: skip
        what = WHAT_YOU_DO_POINTING.format(trials=trials, blocks=lags,
                                           limit=_limit(study.pointing.timeout_s))  # fmt: skip
        about = "a delay in a robot's camera view changes how"
        return CONSENT.format(about=about, what_you_do=what, ratings="")
    practice = study.familiarization.trials
    measured = len(study.planned_conditions) * study.trials_per_modality
    displays = len(study.condition_names)
    trials = f"{_count(practice, 'practice trial')} and then " if practice else ""
    trials += _count(measured, "measured trial")
    if displays > 1:
        trials += f", one under each of {displays} different display conditions"
    limit_s = max(study.timeout_s, study.familiarization.timeout_s if practice else 0.0)
    what = WHAT_YOU_DO.format(trials=trials, limit=_limit(limit_s))
    about = "drawings over a robot's camera view help"
    return CONSENT.format(about=about, what_you_do=what, ratings=" and your ratings")


def _limit(limit_s: float) -> str:
    return f"{round(limit_s / 60, 1):g} minutes" if limit_s >= 120 else f"{limit_s:g} seconds"


def instructions_text(study: StudyConfig) -> str:
    """The page on how to drive the robot: the study file's own (``instructions``), else the
    built-in one, which says practice trials come first only if ``study`` has some."""
    if study.instructions:
        return study.instructions
    if study.task == POINTING.name:
        return DRIVE + POINTING_TUTORIAL
    return DRIVE + TUTORIAL + ("\n" + PRACTICE_FIRST if study.familiarization.trials else "")


def _count(n: int, what: str) -> str:
    return f"{n} {what}" + ("" if n == 1 else "s")


AGREE = "I have read the information above and agree to take part."
DRIVE = """\
**Drive the robot.** Drag the arrows of the handle at the gripper: the robot's gripper follows
the handle. Or step the handle with the **Move** and **Height** buttons, as the camera sees it
(left, away, nearer, right; up, down), by the **Step** chosen, or with the keys: W A S D or
the arrows to move, E up, Q down. The robot is seen through its head camera, a moment late;
move, then watch the gripper arrive.

"""
"""How to move the gripper, the first paragraph of every built-in page on driving the robot."""
POINTING_TUTORIAL = """\
**Choose a target.** In each trial, move the gripper over the cross on the table first, then
over the middle of the circle, and close the grip there: move the Grip slider to *closed*, or
press G. Closing the grip chooses the place under the gripper and ends the trial.

**The time** runs from when the gripper leaves the cross to when you close the grip. Be as
quick and as accurate as you can: the circles differ in size and distance.
"""
"""The rest of the built-in page on driving the robot in a pointing study."""
TUTORIAL = """\
**Grip.** The fingers open sideways, across the view: take the bowl by its left or right
wall. Move the Grip slider to *closed* to close the gripper on the bowl (it closes past the
first mark) and back to *open* to let go (it opens below the second mark); or press G, once
to close, again to open.

**The timer** starts when you first move the handle and stops when the bowl, released,
stands still. Be as quick and as accurate as you can: put the bowl's centre on the
target.
"""
"""The rest of the built-in page on driving the robot in a pick-and-place study, before
:func:`instructions_text` says whether practice trials come first."""
PRACTICE_FIRST = "The practice trials come first; they teach the controls and are not compared.\n"
TRY_IT = (
    "**Try it now**: the robot in the view follows you as it will in the trials, as late; "
    "nothing is recorded. Continue when you are ready."
)
"""Below the page on how to drive the robot, built in or the study's own: the robot runs."""
SESSION_OVER = "Your session is over: thank you for taking part."
OBSERVING = (
    "The experimenter's view: the robot as the participant sees it, read-only. The "
    "participant's pages show in their own tab."
)
IN_PROGRESS = (
    "A session is in progress in another browser tab. This page shows the robot's view only; "
    "close the other tab to take over."
)
CANNOT_SAVE = ("The study has stopped", "The study's computer could not save what you just did "
               "(its disk is full, or its files cannot be written). Please tell the researcher. "
               "What was saved before it is kept; the study can carry on from there.")  # fmt: skip
CUT_SHORT = ("Trial cut short", "The page was closed or lost during the trial: the trial starts "
             "again from its beginning in a moment.")  # fmt: skip
AR_CLASS_TEXT = {
    "embodiment": "The robot's ghost: a model of the arm drawn over the camera view",
    "manipulation": "The red beam to the grasp point, and the green and blue bars (distance "
    "and grip)",
    "task": "The green bowl drawn at the target",
}


def outcome_text(outcome: str, completion_time_s: float, placement_error_m: float) -> str:
    """What the page tells a participant after a trial, from its ``trials.csv`` row's
    outcome, time (s) and error (m)."""
    if outcome == "success":
        error_mm = 1000 * placement_error_m
        return f"Placed in {completion_time_s:.1f} s, {error_mm:.0f} mm from the target."
    return f"Not placed: {outcome.replace('_', ' ')}."
