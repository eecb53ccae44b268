"""Studies: a definition, its counterbalanced plan, simulated participants, the protocol of a
trial, durable run folders, the runner that drives them on any executor, and the server that
gives the same study to people in their browser (``StudyServer``, imported on first use: it
pulls in viser's server)."""

import importlib
from typing import TYPE_CHECKING, Any

from arteleop.study.carry import Carried
from arteleop.study.cohort import participants
from arteleop.study.counterbalancing import (
    cyclic_sequences,
    participant_orders,
    williams_sequences,
)
from arteleop.study.definition import (
    MODALITY_NAMES,
    ORDER_SCHEMES,
    FamiliarizationConfig,
    StudyConfig,
)
from arteleop.study.demographics import Demographics, SessionInputError
from arteleop.study.participants import CohortConfig, ParticipantSpec
from arteleop.study.plan import PracticePoints, TrialSpec, plan_study, trial_seed
from arteleop.study.pointing_session import PointingSpec, ServedPointingRun
from arteleop.study.protocol import TrialRecord, operator_traits, run_planned_trial
from arteleop.study.questionnaire import classes_shown, simulated_answers
from arteleop.study.questionnaire_items import ORIGINAL_QUESTIONNAIRE, QuestionnaireItem
from arteleop.study.run_folder import FORMAT_VERSION, TRIAL_COLUMNS, RunFolder
from arteleop.study.run_lock import run_lock
from arteleop.study.runner import RunComplete, StudyRun, resume_study, run_study
from arteleop.study.session import BrowserCheck, ServedRun, served_run
from arteleop.study.sites import StudySite
from arteleop.study.study_file import first_difference, load_study_file, parse_study
from arteleop.study.study_writing import study_text

if TYPE_CHECKING:
    from arteleop.study.serve import StudyServer

__all__ = [
    "FORMAT_VERSION",
    "MODALITY_NAMES",
    "ORDER_SCHEMES",
    "ORIGINAL_QUESTIONNAIRE",
    "TRIAL_COLUMNS",
    "BrowserCheck",
    "Carried",
    "CohortConfig",
    "Demographics",
    "FamiliarizationConfig",
    "ParticipantSpec",
    "PointingSpec",
    "PracticePoints",
    "QuestionnaireItem",
    "RunComplete",
    "RunFolder",
    "ServedPointingRun",
    "ServedRun",
    "SessionInputError",
    "StudyConfig",
    "StudyRun",
    "StudyServer",
    "StudySite",
    "TrialRecord",
    "TrialSpec",
    "classes_shown",
    "cyclic_sequences",
    "first_difference",
    "load_study_file",
    "operator_traits",
    "parse_study",
    "participant_orders",
    "participants",
    "plan_study",
    "resume_study",
    "run_lock",
    "run_planned_trial",
    "run_study",
    "served_run",
    "simulated_answers",
    "study_text",
    "trial_seed",
    "williams_sequences",
]


def __getattr__(name: str) -> Any:
    if name == "StudyServer":
        return importlib.import_module("arteleop.study.serve").StudyServer
    raise AttributeError(f"module 'arteleop.study' has no attribute {name!r}")
