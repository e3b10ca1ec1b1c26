"""The study's motions run end to end: SP_Controller and six simulated axes in
``st_runtime``, every commanded cylinder position held against the NumPy
reference.

* :mod:`~stgen.scenarios.definitions` the scenarios (point-to-point moves, Airy wave, random wave)
* :mod:`~stgen.scenarios.program`     rendering and loading the controller's ST
* :mod:`~stgen.scenarios.simulation`  SP_Controller with its axes, scan by scan
* :mod:`~stgen.scenarios.expected`    the reference trajectory of a scenario, per scan
* :mod:`~stgen.scenarios.runner`      run a scenario, record and compare
"""

from stgen.scenarios.definitions import (
    AIRY_WAVE,
    POINT_TO_POINT,
    RANDOM_WAVE,
    SCENARIOS,
    SYNCHRONISED_MOVE,
    Scenario,
    scenario_by_name,
)
from stgen.scenarios.runner import MAX_ERROR_MM, ScenarioResult, run_scenario
from stgen.scenarios.simulation import ControllerSimulation

__all__ = [
    "AIRY_WAVE",
    "MAX_ERROR_MM",
    "POINT_TO_POINT",
    "RANDOM_WAVE",
    "SCENARIOS",
    "SYNCHRONISED_MOVE",
    "ControllerSimulation",
    "Scenario",
    "ScenarioResult",
    "run_scenario",
    "scenario_by_name",
]
