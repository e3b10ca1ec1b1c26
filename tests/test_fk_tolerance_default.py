"""SP_ForwardKinematics.Tolerance defaults to the study's Klim = 0.01 (issue 4 item 3),
whatever ``[solver] tolerance`` the configuration holds; callers that need another
bound pass it (SP_Controller's locate step, the verify harnesses)."""

from __future__ import annotations

import dataclasses

import numpy as np

from st_runtime import api
from stgen.config import PlatformConfig
from stgen.reference import forward_kinematics, inverse_kinematics
from stgen.render import RenderOptions, render_program
from stgen.verify import fk_solver, kinematics_sources

STUDY_KLIM = 0.01

#: A configuration whose solver tolerance is NOT the study's: it must not reach the FB's default.
TIGHT = dataclasses.replace(
    PlatformConfig.default(), solver=dataclasses.replace(PlatformConfig.default().solver, tolerance=1e-9)
)

# Calls Fk without Tolerance: the interface default applies.
_DEFAULT_TOLERANCE_PROGRAM = """
PROGRAM FkDefault
VAR
    CylinderPos : ARRAY[1..6] OF LREAL;
    StartPose : ARRAY[1..6] OF LREAL;
    Fk : SP_ForwardKinematics;
END_VAR
Fk(Execute := TRUE, CylinderPos := CylinderPos, StartPose := StartPose, IterationsPerScan := 50, MaxIterations := 50);
END_PROGRAM
"""


def _tolerance_initial(config: PlatformConfig) -> str:
    pou = render_program(config).pou("SP_ForwardKinematics")
    return {v.name: v for v in pou.variables_of("Input")}["Tolerance"].initial


def test_the_interface_default_is_the_study_klim_for_any_configuration():
    assert float(_tolerance_initial(PlatformConfig.default())) == STUDY_KLIM
    assert float(_tolerance_initial(TIGHT)) == STUDY_KLIM


def test_the_controller_locates_with_its_own_explicit_tolerance():
    controller = render_program(TIGHT).pou("SP_Controller").body
    assert "Tolerance := SP_LOCATE_TOLERANCE" in controller


def test_a_call_without_tolerance_stops_where_the_reference_stops_with_klim():
    # Rendered for the tight configuration: were the default taken from it, the FB would
    # need more iterations than the reference with Klim = 0.01 (checked below that it would).
    sources = kinematics_sources(TIGHT, RenderOptions("table"), capacity=1)
    sources["FkDefault.st"] = _DEFAULT_TOLERANCE_PROGRAM
    plc = api.load_sources(sources).controller(period="1ms", stop_on_fault=True)
    program = plc.add_program("FkDefault")

    pose = np.array([40.0, -30.0, 180.0, 4.0, -3.0, 2.0])
    positions = inverse_kinematics(TIGHT.geometry, pose, TIGHT.stroke).positions
    start = TIGHT.solver.start_pose
    klim = forward_kinematics(TIGHT.geometry, positions, start, fk_solver(TIGHT, STUDY_KLIM, iterations_per_scan=50))
    tight = forward_kinematics(TIGHT.geometry, positions, start, fk_solver(TIGHT, 1e-9, iterations_per_scan=50))
    assert klim.converged and tight.iterations > klim.iterations

    program["CylinderPos"] = positions.tolist()
    program["StartPose"] = list(start)
    plc.scan()
    assert program["Fk.Done"] and program["Fk.Iterations"] == klim.iterations
    assert plc.faults == []
