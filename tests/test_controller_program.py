"""SP_Controller's state machine with six simulated axes: power on, locate,
refusals, stop, step limit, axis fault, reset. Short runs; the full-length
scenarios are in test_scenarios.py."""

from __future__ import annotations

import numpy as np
import pytest

from st_runtime.motion.axis import AxisState
from st_runtime.motion.error_ids import ErrorID
from stgen.config import PlatformConfig
from stgen.reference.kinematics import inverse_kinematics
from stgen.reference.wave import AIRY
from stgen.scenarios.definitions import STUDY_START_POSE, WaveMotion
from stgen.scenarios.runner import command_scenario
from stgen.scenarios.definitions import AIRY_WAVE
from stgen.scenarios.simulation import ControllerSimulation

CONFIG = PlatformConfig.default()


@pytest.fixture()
def sim():
    simulation = ControllerSimulation(CONFIG, STUDY_START_POSE)
    simulation.power_on()
    return simulation


def _state(sim, name):
    return sim.codes[f"SP_STATE_{name}"]


def test_power_on_locates_the_start_pose_and_holds_it(sim):
    assert sim.state == _state(sim, "STANDBY")
    # FK with the tight locate tolerance recovers the pose the axes were put at.
    assert np.allclose(sim.globals["SpSetpointPose"], STUDY_START_POSE, atol=1e-9)
    start_q = inverse_kinematics(CONFIG.geometry, np.array(STUDY_START_POSE)).positions
    assert np.max(np.abs(sim.command_positions() - start_q)) <= 1e-9
    # DISCRETE, not SYNCHRONIZED: MC_SyncMoveAbsolute keeps the axis in
    # Status.Discrete on the NJ (changed in issue 8, docs/nj501.md).
    assert all(axis.state == AxisState.DISCRETE for axis in sim.axes)
    sim.run(50)  # holding: nothing moves
    assert np.max(np.abs(sim.command_positions() - start_q)) <= 1e-9
    assert sim.globals["SpFaultID"] == 0 and not sim.runtime_faults


def test_power_off_disables(sim):
    sim.globals["SpPowerOn"] = False
    sim.run(3)
    assert sim.state == _state(sim, "DISABLED")
    assert all(axis.state == AxisState.DISABLED for axis in sim.axes)
    sim.set_pose("SpTargetPose", (10.0, 0.0, 150.0, 0.0, 0.0, 0.0))
    sim.globals["SpMoveStart"] = True
    sim.run(2)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_NOT_READY"]


def test_target_outside_the_stroke_is_refused_before_any_motion(sim):
    # z = +700 mm stretches every leg far beyond the 600 mm stroke; find the first leg by the reference.
    target = np.array([0.0, 0.0, 700.0, 0.0, 0.0, 0.0])
    ik = inverse_kinematics(CONFIG.geometry, target, CONFIG.stroke)
    first_out = int(np.flatnonzero(~ik.in_stroke)[0]) + 1
    before = sim.command_positions()
    sim.set_pose("SpTargetPose", target)
    sim.globals["SpMoveStart"] = True
    for _ in range(200):
        sim.run(1)
        assert np.array_equal(sim.command_positions(), before)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_OUT_OF_STROKE"]
    assert sim.globals["SpRefusalLeg"] == first_out
    assert sim.state == _state(sim, "STANDBY") and sim.globals["SpFaultID"] == 0


def test_tilted_target_reports_the_leg_out_of_stroke(sim):
    # A large tilt about X pushes some legs out while others stay in: the leg number must be the first one out.
    target = np.array([0.0, 0.0, 150.0, 0.0, 0.0, 40.0])
    ik = inverse_kinematics(CONFIG.geometry, target, CONFIG.stroke)
    assert not ik.in_stroke.all() and ik.in_stroke.any()
    sim.set_pose("SpTargetPose", target)
    sim.globals["SpMoveStart"] = True
    sim.run(2)
    assert sim.globals["SpRefusalLeg"] == int(np.flatnonzero(~ik.in_stroke)[0]) + 1


def test_move_command_while_moving_is_refused_as_not_ready(sim):
    sim.set_pose("SpTargetPose", (20.0, 0.0, 150.0, 0.0, 0.0, 0.0))
    sim.globals["SpMoveStart"] = True
    sim.run(10)
    assert sim.state == _state(sim, "MOVING")
    sim.globals["SpMoveStart"] = False
    sim.run(1)
    sim.globals["SpWaveStart"] = True
    sim.run(1)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_NOT_READY"]
    assert sim.state == _state(sim, "MOVING")


def test_stop_mid_move_stops_all_axes_and_relocates(sim):
    # Issue 8: SpStop ramps the set-point to rest first (TRJ_Brake, the reference's brake_pose), then MC_Stop.
    from stgen.reference.brake import brake_duration, brake_pose, setpoint_motion
    from stgen.scenarios.setpoint_limits import check_setpoint_limits

    sim.set_pose("SpTargetPose", (50.0, 0.0, 200.0, 0.0, 0.0, 0.0))
    sim.globals["SpMoveStart"] = True
    poses, cylinders = [], []
    for _ in range(500):
        sim.run(1)
        poses.append(sim.globals["SpSetpointPose"])
        cylinders.append(sim.globals["SpCylinderSetpoint"])
    sim.globals["SpStop"] = True
    period = CONFIG.task.period_s
    v0, a0 = setpoint_motion(poses[-3], poses[-2], poses[-1], period)
    stop_s = brake_duration(v0, a0, CONFIG.trajectory, period)
    assert 0.3 < stop_s < 1.0 and abs(v0[2]) > 40.0  # a real ramp from a real speed
    ramp_scans = round(stop_s / period)
    for _ in range(ramp_scans + 1):  # the ramp's scans (the edge outputs t = 1 ms, the last t = T_S), then MC_Stop
        sim.run(1)
        poses.append(sim.globals["SpSetpointPose"])
        cylinders.append(sim.globals["SpCylinderSetpoint"])
        assert sim.state == _state(sim, "STOP_RAMP" if len(poses) <= 500 + ramp_scans else "STOPPING")
    expected = brake_pose(poses[499], v0, a0, stop_s, np.arange(1, ramp_scans + 1) * period)
    np.testing.assert_allclose(np.array(poses[500:-1]), expected, rtol=0, atol=1e-9)
    # Continuous: velocity and acceleration of the cylinder set-points inside the actuator limits, pose at rest.
    check = check_setpoint_limits(np.array(cylinders), period, CONFIG.actuator.max_velocity,
                                  CONFIG.actuator.max_acceleration)
    assert check.passed, check.describe()
    pose_acceleration = np.diff(np.array(poses)[:, :3], n=2, axis=0) / period**2
    assert np.abs(pose_acceleration).max() <= CONFIG.trajectory.linear_acceleration
    assert np.array_equal(poses[-1], poses[-2])  # at rest when MC_Stop comes
    sim.run_until(lambda: sim.globals["SpReady"], 200)
    # Holding again: the located pose's IK differs from where the axes stopped by rounding only.
    assert all(abs(axis.cmd_vel) < 1e-6 for axis in sim.axes)
    pose = np.array(sim.globals["SpSetpointPose"])
    assert 0.0 < pose[0] < 50.0  # stopped on the way
    # The located pose is the pose of the positions where the axes stopped.
    ik = inverse_kinematics(CONFIG.geometry, pose).positions
    assert np.max(np.abs(ik - sim.command_positions())) <= 1e-6


def test_too_fast_move_is_caught_by_the_step_check_before_the_axes(sim):
    # 1000 mm/s with large acceleration and jerk: legs would move > 0.25 mm per scan.
    for name, value in (("SpLinearVelocity", 1000.0), ("SpLinearAcceleration", 1e5), ("SpLinearJerk", 1e8)):
        sim.globals[name] = value
    sim.set_pose("SpTargetPose", (0.0, 0.0, 250.0, 0.0, 0.0, 0.0))
    sim.globals["SpMoveStart"] = True
    sim.run_until(lambda: sim.globals["SpFaultID"] != 0, 300)
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_STEP_LIMIT"]
    assert 1 <= sim.globals["SpFaultAxis"] <= 6
    # MC_Stop brakes from about 250 mm/s at 2500 mm/s^2: about 100 scans.
    sim.run_until(lambda: sim.state == _state(sim, "FAULT"), 300)
    assert not any(axis.fault_active for axis in sim.axes)  # the controller refused it, not the axes
    assert all(axis.cmd_vel == 0.0 for axis in sim.axes)


def test_axis_fault_mid_wave_stops_all_six_and_reports_which(sim):
    command_scenario(sim, AIRY_WAVE)
    sim.run(2000)
    assert sim.state == _state(sim, "WAVE")
    sim.axes[2].fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)  # cylinder 3 fails between two scans
    sim.run(1)
    assert sim.state == _state(sim, "FAULT_STOPPING")
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_AXIS"]
    assert sim.globals["SpFaultAxis"] == 3
    assert sim.globals["SpFaultDetail"] == int(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    assert all(axis.state in (AxisState.STOPPING, AxisState.ERRORSTOP) for axis in sim.axes)
    sim.run_until(lambda: sim.state == _state(sim, "FAULT"), 100)
    sim.run(5)
    assert all(axis.cmd_vel == 0.0 for axis in sim.axes)
    assert [axis.state for axis in sim.axes] == [AxisState.STANDSTILL] * 2 + [AxisState.ERRORSTOP] + [AxisState.STANDSTILL] * 3
    # The reason stays readable until reset.
    held = sim.command_positions()
    sim.run(100)
    assert np.array_equal(sim.command_positions(), held)
    assert sim.globals["SpFaultAxis"] == 3


def test_reset_after_fault_returns_to_standby_and_moves_again(sim):
    sim.axes[4].fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    sim.run_until(lambda: sim.state == _state(sim, "FAULT"), 100)
    assert sim.globals["SpFaultAxis"] == 5
    sim.globals["SpReset"] = True
    sim.run_until(lambda: sim.globals["SpReady"], 100)
    assert sim.globals["SpFaultID"] == 0 and sim.globals["SpFaultAxis"] == 0
    assert not any(axis.fault_active for axis in sim.axes)
    sim.set_pose("SpTargetPose", (10.0, 0.0, 150.0, 0.0, 0.0, 0.0))
    sim.globals["SpMoveStart"] = True
    sim.run_until(lambda: sim.globals["SpReady"], 2000)
    assert sim.globals["SpSetpointPose"][0] == pytest.approx(10.0, abs=1e-9)


def test_unreachable_wave_is_refused(sim):
    command_scenario(sim, AIRY_WAVE)
    sim.globals["SpWaveCentrePose"] = [0.0, 0.0, 800.0, 0.0, 0.0, 0.0]
    before = sim.command_positions()
    sim.run(50)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_OUT_OF_STROKE"]
    assert np.array_equal(sim.command_positions(), before)


def test_wave_with_invalid_parameters_is_refused(sim):
    command_scenario(sim, AIRY_WAVE)
    sim.globals["SpWaveComponentCount"] = 9
    sim.run(5)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_INVALID"]
    assert sim.state == _state(sim, "STANDBY")
    assert isinstance(AIRY_WAVE.motion, WaveMotion) and AIRY_WAVE.motion.wave is AIRY


def test_stop_mid_wave_then_a_new_wave_starts_from_its_lead_in(sim):
    command_scenario(sim, AIRY_WAVE)
    sim.run(1500)
    assert sim.state == _state(sim, "WAVE")
    sim.globals["SpWaveStart"] = False
    sim.globals["SpStop"] = True
    sim.run_until(lambda: sim.globals["SpReady"], 200)
    sim.globals["SpStop"] = False
    sim.globals["SpWaveStart"] = True
    sim.run(2)
    assert sim.state == _state(sim, "WAVE_LEAD_IN")
    sim.run_until(lambda: sim.state == _state(sim, "WAVE"), 2000)
    sim.run(2)
    # The wave clock restarted from zero: one scan after the lead-in is t = 1 ms.
    assert sim.globals["SpWaveTime"] == pytest.approx(0.001, abs=1e-12)


def test_a_fault_survives_a_power_cycle_until_reset(sim):
    sim.axes[0].fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    sim.run_until(lambda: sim.state == _state(sim, "FAULT"), 100)
    sim.globals["SpPowerOn"] = False
    sim.run(3)
    assert sim.state == _state(sim, "DISABLED")
    sim.globals["SpPowerOn"] = True
    sim.run(10)
    assert sim.state == _state(sim, "FAULT")
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_AXIS"] and sim.globals["SpFaultAxis"] == 1
    sim.globals["SpReset"] = True
    sim.run_until(lambda: sim.globals["SpReady"], 100)
    assert sim.globals["SpFaultID"] == 0


def test_simulated_axes_are_named_as_the_generated_axis_variables():
    from stgen.scenarios.program import AXIS_NAMES, render_controller_program

    declared = [v.name for v in render_controller_program(CONFIG).pou("SP_Axes").variables]
    assert declared == list(AXIS_NAMES)


def test_mc_stop_is_not_given_to_the_axis_that_stopped_itself_in_errorstop(sim):
    # PLCopen refuses MC_Stop on an axis in ErrorStop (it reports Error); the faulted axis
    # has stopped itself, so the controller stops only the other five.
    command_scenario(sim, AIRY_WAVE)
    sim.run(2000)
    sim.axes[2].fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    sim.run(2)
    assert sim.state == _state(sim, "FAULT_STOPPING")
    stops = sim.program["AxisStop"]
    assert [stop["Execute"] for stop in stops] == [True, True, False, True, True, True]
    assert not any(stop["Error"] for stop in stops)


# --------------------------------------------------------------------------- issue 8: supervision and ramped stops


def test_command_aborted_sync_is_a_fault_naming_the_axis(sim):
    # Another command (here an MC_MoveAbsolute started on cylinder 3 from outside the program) aborts
    # its MC_SyncMoveAbsolute: CommandAborted is a fault the user sees, with the axis, and all six stop.
    sim.run(5)
    sim.axes[2].start_move_absolute(sim.axes[2].cmd_pos, 10.0, 100.0, 100.0)
    sim.run(2)
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_SYNC_ABORTED"]
    assert sim.globals["SpFaultAxis"] == 3
    sim.run_until(lambda: sim.state == _state(sim, "FAULT"), 300)


def test_sync_not_active_while_executed_is_a_fault(sim):
    # MC_SyncMoveAbsolute called with Execute for two scans must be Active (OMRON: one period after Execute).
    sim.run(5)
    sim.program["AxisSync[5].Active"] = False
    sim.run(1)
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_SYNC_INACTIVE"]
    assert sim.globals["SpFaultAxis"] == 5


def test_trajectory_fault_mid_wave_is_ramped_to_rest_then_stopped(sim):
    from stgen.scenarios.setpoint_limits import check_setpoint_limits

    command_scenario(sim, AIRY_WAVE)
    sim.run(1500)  # past the fade-in: the wave moves
    assert sim.state == _state(sim, "WAVE")
    sim.program["WaveMotion.Active"] = False  # the wave FB stops delivering poses
    cylinders, states = [], []
    for _ in range(3000):
        sim.run(1)
        cylinders.append(sim.globals["SpCylinderSetpoint"])
        states.append(sim.state)
        if sim.state == _state(sim, "FAULT"):
            break
    assert sim.globals["SpFaultID"] == sim.codes["SP_FAULT_TRAJECTORY"]
    assert states[0] == _state(sim, "FAULT_RAMP") and states[-1] == _state(sim, "FAULT")
    ramp = [row for row, state in zip(cylinders, states) if state == _state(sim, "FAULT_RAMP")]
    assert len(ramp) > 10
    check = check_setpoint_limits(np.array(ramp), CONFIG.task.period_s, CONFIG.actuator.max_velocity,
                                  CONFIG.actuator.max_acceleration)
    assert check.passed
    # At rest before MC_Stop: v ~ (1 - tau)^2 near the end, the last step is below 1e-6 mm (1e-3 mm/s).
    assert np.abs(np.diff(np.array(ramp[-2:]), axis=0)).max() < 1e-6
    assert not any(axis.fault_active for axis in sim.axes)
