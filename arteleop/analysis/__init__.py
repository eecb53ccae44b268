"""Analysis of study files: smoothness metrics, statistics, figures and reports.

This package imports nothing else from arteleop: it works on any CSVs of the documented format
(docs/reference/data-format.md), from the simulator or from a real lab.
"""

import importlib
from typing import TYPE_CHECKING, Any

from arteleop.analysis.data import (
    MEASURES,
    MODALITIES,
    SMOOTHNESS,
    StudyData,
    load_study,
    load_trajectory,
)
from arteleop.analysis.errors import AnalysisInputError
from arteleop.analysis.smoothness import (
    idle_share,
    log_dimensionless_jerk,
    normalized_jerk,
    path_length,
    spectral_arc_length,
    submovement_count,
)

if TYPE_CHECKING:
    from arteleop.analysis.cohorts import (
        cohort_medians,
        expert_gaps,
        pool_cohorts,
        pooled_effects,
        write_cohort_report,
    )
    from arteleop.analysis.order import order_effect
    from arteleop.analysis.pooling import check_cohorts
    from arteleop.analysis.power import Pool, PowerOptions, check_pool_size, make_pool, power
    from arteleop.analysis.power_report import write_power_report
    from arteleop.analysis.report import write_report
    from arteleop.analysis.statistics import (
        METHODS,
        AnalysisOptions,
        NormalityResult,
        TestResult,
        cohens_d,
        compare,
        compare_independent,
        compare_paired,
        compare_trimmed_differences,
        compare_yuen,
        holm,
        holm_test,
        normality,
        pairwise,
        rank_biserial,
        stars,
        trim_extremes,
    )
    from arteleop.analysis.study_analysis import AnalysisResult, analyse

# The statistics (statsmodels) and the report's figures (matplotlib) take about a second to
# import; a trial needs only the smoothness metrics, so those load on first use.
_LAZY = {
    **dict.fromkeys(
        (
            "METHODS", "AnalysisOptions", "NormalityResult", "TestResult", "cohens_d", "compare",
            "compare_independent", "compare_paired", "compare_trimmed_differences", "compare_yuen",
            "holm", "holm_test", "normality",
            "pairwise", "rank_biserial", "stars", "trim_extremes",
        ),
        "arteleop.analysis.statistics",
    ),
    **dict.fromkeys(
        ("cohort_medians", "expert_gaps", "pool_cohorts", "pooled_effects",
         "write_cohort_report"),
        "arteleop.analysis.cohorts",
    ),
    "check_cohorts": "arteleop.analysis.pooling",
    **dict.fromkeys(
        ("Pool", "PowerOptions", "check_pool_size", "make_pool", "power"),
        "arteleop.analysis.power",
    ),
    "write_power_report": "arteleop.analysis.power_report",
    **dict.fromkeys(
        ("load_pointing", "pointing_table_path", "fitts_fits", "lag_models"),
        "arteleop.analysis.pointing",
    ),
    "write_pointing_report": "arteleop.analysis.pointing_report",
    "AnalysisResult": "arteleop.analysis.study_analysis",
    "analyse": "arteleop.analysis.study_analysis",
    "write_report": "arteleop.analysis.report",
    "order_effect": "arteleop.analysis.order",
}  # fmt: skip


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'arteleop.analysis' has no attribute '{name}'")


__all__ = [
    "MEASURES",
    "METHODS",
    "MODALITIES",
    "SMOOTHNESS",
    "AnalysisInputError",
    "AnalysisOptions",
    "AnalysisResult",
    "NormalityResult",
    "Pool",
    "PowerOptions",
    "StudyData",
    "TestResult",
    "analyse",
    "check_cohorts",
    "check_pool_size",
    "cohens_d",
    "cohort_medians",
    "compare",
    "compare_independent",
    "compare_paired",
    "compare_trimmed_differences",
    "compare_yuen",
    "expert_gaps",
    "fitts_fits",
    "holm",
    "holm_test",
    "idle_share",
    "lag_models",
    "load_pointing",
    "load_study",
    "load_trajectory",
    "log_dimensionless_jerk",
    "make_pool",
    "normality",
    "normalized_jerk",
    "order_effect",
    "pairwise",
    "path_length",
    "pointing_table_path",
    "pool_cohorts",
    "pooled_effects",
    "power",
    "rank_biserial",
    "spectral_arc_length",
    "stars",
    "submovement_count",
    "trim_extremes",
    "write_cohort_report",
    "write_pointing_report",
    "write_power_report",
    "write_report",
]
