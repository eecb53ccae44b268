"""Tasks for the synthetic operator: what each asks of it, apart from how it does it."""

from arteleop.operator.simulated.tasks.pick_and_place import PickAndPlace
from arteleop.operator.simulated.tasks.pointing import PointingTask
from arteleop.operator.simulated.tasks.task import (
    Action,
    Goal,
    Task,
    TaskPhase,
    phase_named,
    planar_goal,
    relative_goal,
)

__all__ = [
    "Action",
    "Goal",
    "PickAndPlace",
    "PointingTask",
    "Task",
    "TaskPhase",
    "phase_named",
    "planar_goal",
    "relative_goal",
]
