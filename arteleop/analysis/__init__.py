"""Analysis of study files: smoothness metrics, statistics, figures and reports.

This package imports nothing else from arteleop: it works on any CSVs of the documented format
(docs/data-format.md), from the simulator or from a real lab.
"""

from arteleop.analysis.data import MEASURES, MODALITIES, StudyData, load_study, load_trajectory
from arteleop.analysis.errors import AnalysisInputError
from arteleop.analysis.report import write_report
from arteleop.analysis.smoothness import (
    log_dimensionless_jerk,
    normalized_jerk,
    path_length,
    spectral_arc_length,
)
from arteleop.analysis.statistics import (
    AnalysisOptions,
    NormalityResult,
    TestResult,
    cohens_d,
    compare_independent,
    compare_paired,
    holm,
    normality,
    order_effect,
    pairwise,
    rank_biserial,
    stars,
    trim_extremes,
)
from arteleop.analysis.study_analysis import AnalysisResult, analyse

__all__ = [
    "MEASURES",
    "MODALITIES",
    "AnalysisInputError",
    "AnalysisOptions",
    "AnalysisResult",
    "NormalityResult",
    "StudyData",
    "TestResult",
    "analyse",
    "cohens_d",
    "compare_independent",
    "compare_paired",
    "holm",
    "load_study",
    "load_trajectory",
    "log_dimensionless_jerk",
    "normality",
    "normalized_jerk",
    "order_effect",
    "pairwise",
    "path_length",
    "rank_biserial",
    "spectral_arc_length",
    "stars",
    "trim_extremes",
    "write_report",
]
