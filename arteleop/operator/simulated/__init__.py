"""The simulated participant: what it perceives of the display and how sure it is
(``perception``, ``judging``, ``acuity``, ``perceptual_errors``, the memories of the marks and the
bowl), how it decides (``belief``, ``criterion``, ``own_errors``, ``look``, ``watch``), how it
moves (``hand``, ``submovements``, ``scatter``), who it is (``traits``) and the constants of all
of it (``params``), put together in ``synthetic``; and the tasks it is asked to do (``tasks``).
docs/explanation/operator-model.md gives each mechanism and constant with its source.
"""

from arteleop.operator.simulated.acuity import (
    Acuities,
    DisplayGeometry,
    Judgement,
    fixations,
    judgement_sd,
    reading_sd_m,
)
from arteleop.operator.simulated.belief import (
    probability_within,
)
from arteleop.operator.simulated.bowl_memory import (
    BowlMemory,
)
from arteleop.operator.simulated.mark_memory import (
    MarkMemory,
)
from arteleop.operator.simulated.own_errors import (
    SeenOutcomes,
    believed_error_scale,
)
from arteleop.operator.simulated.params import (
    OperatorParams,
)
from arteleop.operator.simulated.perception import (
    Perceived,
    PerceptionParams,
    perceive,
)
from arteleop.operator.simulated.perceptual_errors import (
    PerceptualErrors,
)
from arteleop.operator.simulated.phase_log import (
    ACTIVITIES,
    PhaseRecord,
)
from arteleop.operator.simulated.scatter import (
    MovementScatter,
)
from arteleop.operator.simulated.submovements import (
    expected_time_s,
    submovement_duration_s,
)
from arteleop.operator.simulated.synthetic import (
    SyntheticOperator,
)
from arteleop.operator.simulated.tasks import (
    Action,
    Goal,
    PickAndPlace,
    PointingTask,
    Task,
    TaskPhase,
)
from arteleop.operator.simulated.traits import (
    Expertise,
    OperatorTraits,
    TraitDistribution,
)

__all__ = [
    "ACTIVITIES",
    "Action",
    "Acuities",
    "BowlMemory",
    "DisplayGeometry",
    "Expertise",
    "Goal",
    "Judgement",
    "MarkMemory",
    "MovementScatter",
    "OperatorParams",
    "OperatorTraits",
    "Perceived",
    "PerceptionParams",
    "PerceptualErrors",
    "PhaseRecord",
    "PickAndPlace",
    "PointingTask",
    "SeenOutcomes",
    "SyntheticOperator",
    "Task",
    "TaskPhase",
    "TraitDistribution",
    "believed_error_scale",
    "expected_time_s",
    "fixations",
    "judgement_sd",
    "perceive",
    "probability_within",
    "reading_sd_m",
    "submovement_duration_s",
]
