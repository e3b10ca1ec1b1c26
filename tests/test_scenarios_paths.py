"""Paths and playback through SP_Controller and six simulated axes (issue 12, step 5).

Every scan's commanded cylinder positions against the reference IK of the reference path
(stgen.reference.paths, playback) at 1e-9 mm, every scan's set-point velocity and
acceleration within the actuator's limits, the rates along the path as planned, and the
refusals before motion (SP_REFUSED_PATH_PLAN with TRJ_Path's / TRJ_Playback's ErrorID and
the leg the reference names; the axes never move).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from stgen.config import PlatformConfig
from stgen.reference.actuator_rates import actuator_rates
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.paths import PathSpec, plan_path, sample
from stgen.reference.playback import evaluate
from stgen.scenarios.definitions import STUDY_START_POSE
from stgen.scenarios.path_scenarios import (
    PATH_SCENARIOS,
    PathMotion,
    PlaybackMotion,
    command_planned,
    motion_duration,
    playback_scenario,
    release_planned,
)
from stgen.scenarios.program import codes_of, render_controller_program
from stgen.scenarios.runner import run_scenario
from stgen.scenarios.sea_state import jonswap_motion, write_csv
from stgen.scenarios.setpoint_limits import check_setpoint_limits
from stgen.scenarios.simulation import ControllerSimulation

CONFIG = PlatformConfig.default()
PERIOD = CONFIG.task.period_s
#: Issue 12: positions against the reference to 1e-9 mm on every scan.
TOLERANCE_MM = 1e-9
TRJ = codes_of(render_controller_program(CONFIG), "TRJ_Constants")


@functools.cache
def _run(scenario):
    return run_scenario(scenario, CONFIG)


@pytest.fixture(scope="module")
def sea_csv(tmp_path_factory):
    """A recorded motion: 12 s of a JONSWAP sea state sampled at 10 Hz, as CSV."""
    t, poses = jonswap_motion(duration_s=12.0, rate_hz=10.0)
    path = tmp_path_factory.mktemp("sea") / "jonswap_10hz.csv"
    write_csv(path, t, poses)
    return str(path)


def _states(result, *names):
    return [next(v for v, n in result.state_names.items() if n == name) for name in names]


def _check_run(result, run_state):
    assert result.runtime_faults == [] and not result.axis_fault.any()
    assert not result.fault_id.any() and not result.refusal_id.any()
    assert result.max_error_mm <= TOLERANCE_MM
    assert result.limits.passed, (result.limits.max_velocity, result.limits.max_acceleration)
    planning, lead_in, running, standby = _states(result, f"{run_state}_PLANNING", f"{run_state}_LEAD_IN",
                                                  run_state, "SP_STATE_STANDBY")
    # Planning (the pose held), lead-in, the motion, back in STANDBY holding the end pose.
    order = [s for i, s in enumerate(result.state) if i == 0 or s != result.state[i - 1]]
    assert order[-5:] == [standby, planning, lead_in, running, standby]
    held = result.state == planning
    assert np.all(result.commanded[held] == result.commanded[np.argmax(held) - 1])
    assert np.abs(result.setpoint_pose[-1] - result.expected_pose[-1]).max() <= 1e-9


@pytest.mark.parametrize("scenario", PATH_SCENARIOS, ids=[s.name for s in PATH_SCENARIOS])
def test_path_through_the_controller_matches_the_reference(scenario):
    result = _run(scenario)
    _check_run(result, "SP_STATE_PATH")
    motion = scenario.motion
    # The end pose is the path's at phi_end, reached after the planned duration.
    end = sample(motion.spec, 1.0, np.ones(1)).poses[0]
    assert np.abs(result.setpoint_pose[-1] - end).max() < 1e-9
    # Rates as planned: along the path the set-point's finite differences reach the planned leg
    # velocity extremes (reference plan at the task period) to within one period of acceleration.
    plan = plan_path(motion.spec, dataclasses.replace(CONFIG, trajectory=scenario.limits),
                     plan_samples=motion.plan_samples)
    running = result.state == _states(result, "SP_STATE_PATH")[0]
    rows = np.flatnonzero(running)
    q = result.commanded[rows[0] - 1:rows[-1] + 1]
    velocity = np.abs(np.diff(q, axis=0)).max(axis=0) / PERIOD
    planned = plan.extremes()["velocity_max"]
    slack = plan.extremes()["acceleration_max"].max() * PERIOD
    assert np.all(np.abs(velocity - planned) <= slack), (velocity, planned)
    assert np.all(planned <= CONFIG.actuator.max_velocity)
    # Even the planning scans (200 samples each) stay below 80 % of the period by the cost model.
    assert result.nj_time.max_ns <= 0.8 * result.nj_time.period_ns


def test_playback_of_a_recorded_sea_state_matches_the_reference(sea_csv):
    result = _run(playback_scenario(sea_csv))
    _check_run(result, "SP_STATE_PLAYBACK")
    table = result.scenario.motion.table
    assert np.abs(result.setpoint_pose[-1] - table.poses[-1]).max() < 1e-9
    # The whole recording was played: 12 s at 1 ms, calls t = 0 .. 12.000 s.
    playing = result.state == _states(result, "SP_STATE_PLAYBACK")[0]
    assert np.count_nonzero(playing) == 12_001
    assert result.nj_time.max_ns <= 0.8 * result.nj_time.period_ns


# --- refusals before motion ---------------------------------------------------------------------

def _command_and_watch(motion, playback=None, scans_max=2000):
    """Power on at the study's start pose, give the command, scan until STANDBY again; the
    commanded positions of every scan after the command and the simulation."""
    sim = ControllerSimulation(CONFIG, STUDY_START_POSE, playback=playback)
    sim.power_on()
    before = sim.command_positions()
    command_planned(sim, motion)
    positions = []
    for _ in range(scans_max):
        sim.run(1)
        release_planned(sim)
        positions.append(sim.command_positions())
        if sim.globals["SpReady"]:
            break
    return sim, before, np.array(positions)


def _plan_extremes(spec, samples):
    """Per leg at T = 1 on ``samples`` points of u (as TRJ_Path's planning pass): positions, |rate|, |acc|."""
    unit = sample(spec, 1.0, np.linspace(0.0, 1.0, samples))
    legs = actuator_rates(CONFIG.geometry, unit.poses, unit.rates, unit.accelerations)
    positions = inverse_kinematics(CONFIG.geometry, unit.poses).positions
    return positions, np.abs(legs.velocities).max(axis=0), np.abs(legs.accelerations).max(axis=0)


def _assert_refused(sim, before, positions, detail, leg):
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_PATH_PLAN"]
    assert sim.globals["SpRefusalDetail"] == detail
    assert sim.globals["SpRefusalLeg"] == leg
    assert sim.state_name == "SP_STATE_STANDBY" and sim.globals["SpFaultID"] == 0
    assert np.all(positions == before)  # never moved


def test_path_whose_planned_rates_break_a_limit_is_refused_before_motion():
    samples = 1001
    spec = PathSpec("epitrochoid", R=60.0, r=20.0, d=30.0, orientation=(0.0, 35.0, 35.0))
    _, rate, acc = _plan_extremes(spec, samples)
    # Per leg, the shortest duration its velocity and acceleration allow; ask for one between the
    # largest two, so exactly one leg breaks its limit.
    needed = np.maximum(rate / CONFIG.actuator.max_velocity, np.sqrt(acc / CONFIG.actuator.max_acceleration))
    ranked = np.sort(needed)
    duration = 0.5 * (ranked[-1] + ranked[-2])
    leg = int(np.argmax(needed)) + 1
    motion = PathMotion(dataclasses.replace(spec, duration=duration), plan_samples=samples)
    sim, before, positions = _command_and_watch(motion)
    _assert_refused(sim, before, positions, TRJ["TRJ_ERR_PATH_RATE"], leg)


def test_path_leaving_the_stroke_is_refused_with_the_leg():
    samples = 1001
    spec = PathSpec("spiral", a=10.0, b=45.0, centre=(20.0, -10.0, 240.0), orientation=(0.0, 10.0, 5.0))
    positions_ref, _, _ = _plan_extremes(spec, samples)
    outside = (positions_ref.min(axis=0) < CONFIG.stroke.min) | (positions_ref.max(axis=0) > CONFIG.stroke.max)
    assert outside.any() and not outside.all()
    sim, before, positions = _command_and_watch(PathMotion(spec, plan_samples=samples))
    _assert_refused(sim, before, positions, TRJ["TRJ_ERR_PATH_STROKE"], int(np.argmax(outside)) + 1)


def test_path_slower_than_its_pose_limits_allow_is_refused_with_leg_0():
    spec = PathSpec("hypocycloid", R=100.0, r=25.0)
    shortest = plan_path(spec, CONFIG, samples=2, plan_samples=1001).shortest
    motion = PathMotion(dataclasses.replace(spec, duration=0.9 * shortest), plan_samples=1001)
    _, rate, acc = _plan_extremes(spec, 1001)
    assert (rate / (0.9 * shortest)).max() < CONFIG.actuator.max_velocity  # legs fine: x, y set it
    sim, before, positions = _command_and_watch(motion)
    _assert_refused(sim, before, positions, TRJ["TRJ_ERR_PATH_POSE_LIMIT"], 0)


def test_playback_too_fast_for_the_actuators_is_refused_with_the_leg(tmp_path):
    # 60 mm of heave with some sway in 0.3 s: over 250 mm/s on some legs.
    t = np.array([0.0, 0.3])
    poses = np.array([[0.0, 0.0, 240.0, 0.0, 0.0, 0.0], [15.0, 0.0, 300.0, 0.0, 4.0, 0.0]])
    path = tmp_path / "fast.csv"
    write_csv(path, t, poses)
    motion = PlaybackMotion(str(path))
    table = motion.table
    count = int(np.floor(table.duration / PERIOD + 1e-9)) + 1
    q = inverse_kinematics(CONFIG.geometry, evaluate(table, np.arange(count) * PERIOD)[0]).positions
    check = check_setpoint_limits(q, PERIOD, CONFIG.actuator.max_velocity, CONFIG.actuator.max_acceleration)
    broken = (check.max_velocity > CONFIG.actuator.max_velocity) | (
        check.max_acceleration > CONFIG.actuator.max_acceleration)
    assert broken.any()
    sim, before, positions = _command_and_watch(motion, playback=table)
    _assert_refused(sim, before, positions, TRJ["TRJ_ERR_PATH_RATE"], int(np.argmax(broken)) + 1)


def test_playback_without_a_rendered_table_is_refused():
    sim = ControllerSimulation(CONFIG, STUDY_START_POSE)
    sim.power_on()
    sim.globals["SpPlaybackStart"] = True
    sim.run(2)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_NO_TABLE"]
    assert sim.state_name == "SP_STATE_STANDBY"


def test_stop_during_a_path_ramps_to_rest_within_the_limits():
    spec = PathSpec("epicycloid", R=60.0, r=20.0, orientation=(0.0, 35.0, 35.0))
    motion = PathMotion(spec, plan_samples=1001)
    sim = ControllerSimulation(CONFIG, STUDY_START_POSE)
    sim.power_on()
    command_planned(sim, motion)
    sim.run(1)
    release_planned(sim)
    sim.run_until(lambda: sim.state_name == "SP_STATE_PATH", 20_000)
    positions, states = [], []

    def scan(count):
        for _ in range(count):
            sim.run(1)
            positions.append(sim.command_positions())
            states.append(sim.state_name)

    scan(int(0.3 * motion_duration(motion, CONFIG) / PERIOD))  # well into the path, at speed
    # A second SpPathStart in motion is refused (not ready); the path goes on.
    sim.globals["SpPathStart"] = True
    scan(1)
    release_planned(sim)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_NOT_READY"] and states[-1] == "SP_STATE_PATH"
    sim.globals["SpStop"] = True
    scan(1)
    sim.globals["SpStop"] = False
    while sim.state_name != "SP_STATE_STANDBY" and len(states) < 20_000:
        scan(1)
    assert "SP_STATE_STOP_RAMP" in states and sim.state_name == "SP_STATE_STANDBY"
    assert sim.globals["SpFaultID"] == 0
    q = np.array(positions)
    moving = np.array([s in ("SP_STATE_PATH", "SP_STATE_STOP_RAMP") for s in states])
    check = check_setpoint_limits(q, PERIOD, CONFIG.actuator.max_velocity, CONFIG.actuator.max_acceleration, moving)
    assert check.passed
    # Moving at the stop, at rest at the end of the ramp.
    stop = states.index("SP_STATE_STOP_RAMP")
    assert np.abs(q[stop] - q[stop - 1]).max() > 1e-3
    ramp_end = len(states) - 1 - states[::-1].index("SP_STATE_STOP_RAMP")
    assert np.abs(q[ramp_end] - q[ramp_end - 1]).max() < 1e-4


def test_controller_with_a_playback_table_keeps_the_nj_rules(tmp_path, sea_csv, capsys):
    from stgen.cli import main

    out = tmp_path / "iec"
    assert main(["generate", "--target", "iec", "--playback", sea_csv, "--out", str(out)]) == 0
    assert main(["check", "--dialect", "nj", str(out)]) == 0
    assert "18 file(s), 0 error(s), 0 warning(s)" in capsys.readouterr().err
