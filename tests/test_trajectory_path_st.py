"""TRJ_Path (issue 12) rendered and run in st_runtime, held against stgen.reference.paths:
positions to 1e-9 mm on every call, the planned duration and leg extremes, and every refusal
with its ErrorID and leg."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from st_harness import load_with_harness, scan_while_planning
from stgen.config import ActuatorConfig, PlatformConfig
from stgen.reference.paths import PathSpec, plan_path, sample
from stgen.scenarios.path_inputs import trj_path_inputs
from stgen.scenarios.program import codes_of, render_controller_program

PLAN_SAMPLES = 801
PER_SCAN = 100
INPUTS = ("Family", "FixedRadius", "RollingRadius", "PenDistance", "SpiralStart", "SpiralPitch", "ParameterEnd",
          "Centre", "Orientation", "Law", "BlendFraction", "Duration", "PlanSamples", "SamplesPerScan")

HARNESS = """
PROGRAM TestPath
VAR
    Path : TRJ_Path;
    Execute : BOOL;
    RunClock : BOOL;
    Family : INT;
    FixedRadius : LREAL;
    RollingRadius : LREAL;
    PenDistance : LREAL;
    SpiralStart : LREAL;
    SpiralPitch : LREAL;
    ParameterEnd : LREAL;
    Centre : ARRAY[1..3] OF LREAL;
    Orientation : ARRAY[1..3] OF LREAL;
    Law : INT;
    BlendFraction : LREAL;
    Duration : LREAL;
    PlanSamples : DINT;
    SamplesPerScan : DINT;
    ActuatorVelocity : LREAL := 250.0;
END_VAR
Path(Execute := Execute, RunClock := RunClock, Family := Family, FixedRadius := FixedRadius,
     RollingRadius := RollingRadius, PenDistance := PenDistance, SpiralStart := SpiralStart,
     SpiralPitch := SpiralPitch, ParameterEnd := ParameterEnd, Centre := Centre, Orientation := Orientation,
     Law := Law, BlendFraction := BlendFraction, Duration := Duration, PlanSamples := PlanSamples,
     SamplesPerScan := SamplesPerScan, ActuatorVelocity := ActuatorVelocity);
END_PROGRAM
"""

CONFIG = PlatformConfig()


@pytest.fixture(scope="module")
def rendered():
    return render_controller_program(CONFIG)


@pytest.fixture(scope="module")
def project(rendered):
    return load_with_harness(rendered, HARNESS)


@pytest.fixture(scope="module")
def codes(rendered):
    return codes_of(rendered, "TRJ_Constants")


def _start(project, spec, actuator_velocity=250.0):
    plc = project.controller(period="1ms")
    program = plc.add_program("TestPath")
    for name, value in trj_path_inputs(spec, PLAN_SAMPLES, PER_SCAN).items():
        program[name] = value
    program["ActuatorVelocity"] = actuator_velocity
    program["Execute"] = True
    return plc, program


def _plan(plc, program):
    """Scans until planning ends; the number of planning calls."""
    return scan_while_planning(plc, program, "Path")


SPECS = {
    "epitrochoid": PathSpec("epitrochoid", R=60.0, r=20.0, d=30.0),
    "epicycloid-tilted": PathSpec("epicycloid", R=30.0, r=20.0, orientation=(0.0, 35.0, 35.0)),
    "hypocycloid-cycloidal": PathSpec("hypocycloid", R=100.0, r=25.0, law="cycloidal", centre=(5.0, -3.0, 250.0)),
    "spiral": PathSpec("spiral", a=10.0, b=5.0, orientation=(10.0, -5.0, 8.0), blend=0.25),
}


@pytest.mark.parametrize("name", list(SPECS))
def test_path_positions_match_the_reference_on_every_call(project, name):
    spec = SPECS[name]
    reference = plan_path(spec, CONFIG, samples=2, plan_samples=PLAN_SAMPLES)
    plc, program = _start(project, spec)
    calls = _plan(plc, program)
    assert calls == -(-PLAN_SAMPLES // PER_SCAN)          # the pass is spread over the calls
    assert program["Path.Ready"] and not program["Path.Error"]
    assert program["Path.PlannedDuration"] == pytest.approx(reference.duration, abs=1e-12)
    first = sample(spec, reference.duration, 0.0).poses
    assert np.abs(np.array(program["Path.Pose"]) - first).max() < 1e-9       # holds the first pose
    # leg extremes of the planning pass against the reference's at the same u samples
    unit = plan_path(dataclasses.replace(spec, duration=reference.duration), CONFIG, samples=PLAN_SAMPLES,
                     plan_samples=PLAN_SAMPLES).extremes()
    for output, key in (("LegPositionMin", "position_min"), ("LegPositionMax", "position_max"),
                        ("LegVelocityMax", "velocity_max"), ("LegAccelerationMax", "acceleration_max")):
        assert np.abs(np.array(program[f"Path.{output}"]) - unit[key]).max() < 1e-6, output
    # run: every call against the reference at t = n * 1 ms
    program["RunClock"] = True
    count = int(round(reference.duration / 0.001)) + 1
    poses = []
    for _ in range(count):
        plc.scan()
        poses.append(program["Path.Pose"])
    assert program["Path.Done"]
    expected = sample(spec, reference.duration, np.arange(count) * 0.001).poses
    assert np.abs(np.array(poses) - expected).max() < 1e-9


def test_refused_out_of_stroke_with_the_leg_before_motion(project, codes):
    spec = PathSpec("epitrochoid", centre=(0.0, 0.0, 300.0), orientation=(0.0, 35.0, 35.0))
    plc, program = _start(project, spec)
    _plan(plc, program)
    reference = plan_path(spec, CONFIG, samples=2, plan_samples=PLAN_SAMPLES).check
    unit = plan_path(spec, CONFIG, samples=PLAN_SAMPLES, plan_samples=PLAN_SAMPLES).check
    first_leg = min(leg for leg, what, _, _ in unit.breaches(CONFIG) if what.startswith("stroke"))
    assert program["Path.Error"] and not program["Path.Ready"]
    assert program["Path.ErrorID"] == codes["TRJ_ERR_PATH_STROKE"]
    assert program["Path.ErrorLeg"] == first_leg
    program["RunClock"] = True
    plc.scan()
    assert not program["Path.Busy"]
    assert np.abs(np.array(program["Path.Pose"]) - reference.poses[0]).max() < 1e-9   # never moved


def test_refused_when_the_requested_duration_breaks_an_actuator_rate(project, codes):
    spec = PathSpec("epitrochoid", orientation=(0.0, 20.0, 20.0), duration=12.0)
    slow = PlatformConfig(actuator=ActuatorConfig(max_velocity=10.0, max_acceleration=2500.0))
    unit = plan_path(spec, slow, samples=PLAN_SAMPLES, plan_samples=PLAN_SAMPLES)
    breaking = [leg for leg, what, _, _ in unit.check.breaches(slow) if what == "velocity"]
    assert breaking                                       # the case does break the limit
    plc, program = _start(project, spec, actuator_velocity=10.0)
    _plan(plc, program)
    assert program["Path.ErrorID"] == codes["TRJ_ERR_PATH_RATE"]
    assert program["Path.ErrorLeg"] == min(breaking)


def test_refused_when_the_requested_duration_breaks_a_pose_limit(project, codes):
    plc, program = _start(project, PathSpec("epicycloid", duration=2.0))
    _plan(plc, program)
    assert program["Path.ErrorID"] == codes["TRJ_ERR_PATH_POSE_LIMIT"]
    assert program["Path.ErrorLeg"] == 0


@pytest.mark.parametrize("field, value", [("Family", 5), ("Law", 3), ("BlendFraction", 0.6),
                                          ("ParameterEnd", 0.0), ("PlanSamples", 1), ("RollingRadius", 0.0)])
def test_bad_parameters_are_refused_on_the_edge(project, codes, field, value):
    plc, program = _start(project, SPECS["epitrochoid"])
    program[field] = value
    plc.scan()
    assert program["Path.Error"] and not program["Path.Planning"]
    assert program["Path.ErrorID"] == codes["TRJ_ERR_INVALID_PATH"]


def test_hypocycloid_with_r_not_below_R_is_refused(project, codes):
    plc, program = _start(project, PathSpec("hypocycloid", R=100.0, r=25.0))
    program["RollingRadius"] = 100.0
    plc.scan()
    assert program["Path.ErrorID"] == codes["TRJ_ERR_INVALID_PATH"]


def test_stgen_plan_gives_the_extremes_of_the_controller_run(project, capsys):
    """`stgen plan` against TRJ_Path run at 1 ms for the plan's duration: leg positions from the
    IK of every pose the FB output, their min/max within 1e-6 mm of the plan's."""
    import json

    from stgen.cli import main
    from stgen.path_spec import parse_path_spec
    from stgen.reference.kinematics import inverse_kinematics

    text = "hypocycloid:R=100,r=25,roll=20,pitch=-15"
    assert main(["plan", "--path", text, "--json"]) == 0
    plan = json.loads(capsys.readouterr().out)["motions"][0]
    spec = dataclasses.replace(parse_path_spec(text), duration=plan["duration_s"])
    plc, program = _start(project, spec)
    _plan(plc, program)
    assert program["Path.Ready"]
    program["RunClock"] = True
    poses = []
    while not program["Path.Done"]:
        plc.scan()
        poses.append(program["Path.Pose"])
    q = inverse_kinematics(CONFIG.geometry, np.array(poses)).positions
    assert len(q) == int(round(plan["duration_s"] / 0.001)) + 1
    assert np.abs(q.min(axis=0) - plan["position_min"]).max() < 1e-6
    assert np.abs(q.max(axis=0) - plan["position_max"]).max() < 1e-6
    # rates: the set-point differences the drive sees, against the plan's analytic extremes (O(dt^2))
    v = np.abs(np.diff(q, axis=0)).max(axis=0) / 0.001
    assert np.abs(v - plan["velocity_max"]).max() < 1e-3
