"""The study's scenarios end to end (issue 5): SP_Controller and six simulated
axes at 1 ms for the full duration, every commanded cylinder position of
every scan against the NumPy reference trajectory through the reference IK.

Full length: the twelve point-to-point moves (six out, six back: 104 s of
motion and 0.5 s of standstill after each, about 3 s of wall time), both 60 s
waves (about 2 s each) and the synchronised move of all six coordinates run
completely here.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from stgen.config import PlatformConfig
from stgen.scenarios.definitions import (
    AIRY_WAVE,
    POINT_TO_POINT,
    RANDOM_WAVE,
    SCENARIOS,
    STUDY_START_POSE,
    SYNCHRONISED_MOVE,
    describe_move,
)
from stgen.scenarios.expected import calls_until_done, expected_poses, planned_moves
from stgen.scenarios.program import codes_of, render_controller_program
from stgen.scenarios.runner import MAX_ERROR_MM, run_scenario

CONFIG = PlatformConfig.default()


RUNS = SCENARIOS + (SYNCHRONISED_MOVE,)


@functools.cache
def _run(scenario):
    """Each scenario runs once for the whole module."""
    return run_scenario(scenario, CONFIG)


@pytest.fixture(params=RUNS, ids=[s.name for s in RUNS])
def result(request):
    return _run(request.param)


@pytest.fixture()
def point_to_point():
    return _run(POINT_TO_POINT)


def test_every_commanded_position_matches_the_reference(result):
    assert result.max_error_mm <= MAX_ERROR_MM
    assert result.scans == len(result.expected) and result.commanded.shape == (result.scans, 6)


def test_no_fault_of_any_kind(result):
    assert result.runtime_faults == []
    assert not result.axis_fault.any()
    assert not result.fault_id.any()
    assert not result.refusal_id.any()  # every command was accepted
    assert result.passed


def test_full_duration_was_simulated(result):
    motion = result.scenario.motion
    seconds = getattr(motion, "wave_seconds", None)
    if seconds is not None:
        # SpState shows WAVE from the lead-in's last scan (its end state) on; the wave
        # clock runs in the 60,000 scans after it (t = 0 .. 59.999 s).
        wave_state = codes_of(render_controller_program(CONFIG), "SP_ControllerConstants")["SP_STATE_WAVE"]
        wave_scans = np.count_nonzero(result.state == wave_state) - 1
        assert wave_scans == round(seconds / CONFIG.task.period_s) == 60_000
    elif result.scenario is POINT_TO_POINT:
        # Twelve moves: eight of 10 s (x, y, z, gamma out and back) and four of 6 s (alpha, beta),
        # each with its edge scan and 500 scans of standstill: 8*10,001 + 4*6,001 + 12*500 after the first edge.
        assert result.scans - (result.command_scan - 1) == 8 * 10_001 + 4 * 6_001 + 12 * 500 == 110_012
    else:
        assert result.scans - (result.command_scan - 1) == 10_001 + 500


# --------------------------------------------------------------------------- the study's point-to-point moves


def test_point_to_point_is_six_single_coordinate_moves_out_and_back():
    targets = POINT_TO_POINT.motion.targets
    start = STUDY_START_POSE
    assert start == (0.0, 0.0, 150.0, 0.0, 0.0, 0.0)
    assert targets[1::2] == (start,) * 6  # every second move returns to the start pose
    assert targets[0::2] == (
        (100.0, 0.0, 150.0, 0.0, 0.0, 0.0),
        (0.0, 100.0, 150.0, 0.0, 0.0, 0.0),
        (0.0, 0.0, 250.0, 0.0, 0.0, 0.0),
        (0.0, 0.0, 150.0, 6.0, 0.0, 0.0),
        (0.0, 0.0, 150.0, 0.0, 6.0, 0.0),
        (0.0, 0.0, 150.0, 0.0, 0.0, 10.0),
    )
    assert [describe_move(start, t) for t in targets[0::2]] == [
        "x +100 mm", "y +100 mm", "z +100 mm", "α +6°", "β +6°", "γ +10°"]
    assert POINT_TO_POINT.limits.linear_velocity == 20.0 and POINT_TO_POINT.limits.angular_velocity == 2.0


def test_point_to_point_durations_by_hand(point_to_point):
    # Cycloid: peak velocity 2h/T, so T = 2h/v: 2*100/20 = 10 s; 2*6/2 = 6 s; 2*10/2 = 10 s.
    # The acceleration and jerk bounds are shorter: sqrt(2*pi*100/500) = 1.12 s, cbrt(4*pi^2*100/5000) = 0.68 s;
    # sqrt(2*pi*10/50) = 1.12 s, cbrt(4*pi^2*10/500) = 0.68 s.
    by_hand = [10.0, 10.0, 10.0, 10.0, 10.0, 10.0, 6.0, 6.0, 6.0, 6.0, 10.0, 10.0]
    planned = planned_moves(POINT_TO_POINT, CONFIG)
    assert [m.duration for m in planned] == pytest.approx(by_hand, abs=1e-12)
    assert [m.calls for m in planned] == [round(t * 1000) for t in by_hand]
    # TRJ_Cycloidal in the controller planned the same (from the located pose: to 1e-9 s).
    assert point_to_point.move_durations_s == pytest.approx(by_hand, abs=1e-9)


def test_each_move_starts_when_the_last_one_ended(point_to_point):
    # One controller run: every SpMoveStart edge comes in STANDBY, 500 scans after the
    # previous move output its target, and the set-point then holds the target.
    standby = codes_of(render_controller_program(CONFIG), "SP_ControllerConstants")["SP_STATE_STANDBY"]
    planned = planned_moves(POINT_TO_POINT, CONFIG)
    assert len(point_to_point.command_scans) == 12
    for move, edge in zip(planned, point_to_point.command_scans):
        row = edge - 1
        assert point_to_point.state[row - 1] == standby
        done = row + move.calls
        assert point_to_point.state[done] == standby and point_to_point.state[done - 1] != standby
        np.testing.assert_allclose(point_to_point.setpoint_pose[done], move.target, rtol=0, atol=1e-9)
    final = point_to_point.setpoint_pose[-1]
    np.testing.assert_allclose(final, STUDY_START_POSE, rtol=0, atol=1e-9)  # back where it started


def test_velocity_governs_every_move(point_to_point):
    # The moving coordinate peaks at 2h/T = v: 20 mm/s or 2 deg/s (finite differences at 1 ms: to 1e-5).
    period = CONFIG.task.period_s
    for move, edge in zip(planned_moves(POINT_TO_POINT, CONFIG), point_to_point.command_scans):
        rows = slice(edge - 1, edge + move.calls)
        coordinate = int(np.argmax(np.abs(move.target - move.start)))
        speed = np.abs(np.diff(point_to_point.setpoint_pose[rows, coordinate])).max() / period
        assert speed == pytest.approx(20.0 if coordinate < 3 else 2.0, rel=1e-5)


def test_synchronised_move_takes_10_s_and_ends_on_the_target():
    # Not a demo scenario: all six coordinates in one move. 100 mm at 20 mm/s: 2*100/20 = 10 s;
    # 10 deg at 2 deg/s: 2*10/2 = 10 s; 6 deg needs only 6 s but shares T.
    (move,) = planned_moves(SYNCHRONISED_MOVE, CONFIG)
    assert move.duration == pytest.approx(10.0, abs=1e-12)
    poses = expected_poses(SYNCHRONISED_MOVE, CONFIG, command_scan=5, scans=10_006)
    assert poses[3].tolist() == [0.0, 0.0, 150.0, 0.0, 0.0, 0.0]      # scan 4: before the command
    assert poses[4].tolist() == [0.0, 0.0, 150.0, 0.0, 0.0, 0.0]      # scan 5: the edge, t = 0
    assert poses[5004, :3] == pytest.approx([50.0, 50.0, 200.0])       # t = 5 s: half way
    assert poses[-1] == pytest.approx([100.0, 100.0, 250.0, 6.0, 6.0, 10.0], abs=1e-12)


def test_wave_timeline_lead_in_then_clock_from_zero():
    # The lead-in goes to the centre pose; the study's waves are centred on the start pose, so it is a zero move,
    # done on its edge (call 0), and the wave clock starts (t = 0) in the next scan, at rest at the centre.
    (lead_in,) = planned_moves(AIRY_WAVE, CONFIG)
    assert lead_in.duration == 0.0 and lead_in.calls == 0
    np.testing.assert_array_equal(lead_in.target, AIRY_WAVE.motion.centre_pose)
    poses = expected_poses(AIRY_WAVE, CONFIG, command_scan=1, scans=4)
    assert np.array_equal(poses[0], poses[1])  # the edge, then t = 0: both the centre
    assert np.array_equal(poses[1], np.asarray(STUDY_START_POSE))
    assert 0.0 < np.abs(poses[2] - poses[1]).max() < 1e-6  # the fade starts at rest: sigma(tau) ~ tau^3


def test_every_setpoint_inside_the_actuator_limits(result):
    # The set-points handed to MC_SyncMoveAbsolute, every scan and every cylinder, by finite differences at 1 ms.
    limits = result.limits
    assert limits.passed, limits.describe()
    assert limits.max_velocity.max() <= CONFIG.actuator.max_velocity
    assert limits.max_acceleration.max() <= CONFIG.actuator.max_acceleration
    assert result.commanded_limits.passed  # and the axes did not saturate them


def test_wave_away_from_the_start_pose_leads_in_then_fades_in():
    # Centre 20 mm below the start: a real cycloidal lead-in (ends at rest, zero acceleration), then the fade.
    import dataclasses

    centre = (0.0, 0.0, 130.0, 0.0, 0.0, 0.0)
    scenario = dataclasses.replace(
        RANDOM_WAVE, motion=dataclasses.replace(RANDOM_WAVE.motion, centre_pose=centre, wave_seconds=3.0))
    (lead_in,) = planned_moves(scenario, CONFIG)
    assert lead_in.calls > 100
    run = run_scenario(scenario, CONFIG)
    assert run.passed, run.limits.describe()
    assert run.max_error_mm <= MAX_ERROR_MM


def test_calls_until_done_by_hand():
    assert calls_until_done(3.0, 0.001) == 3000
    assert calls_until_done(0.0005, 0.001) == 1
    assert calls_until_done(0.0, 0.001) == 0


def test_random_wave_scenario_uses_spec_components():
    amplitudes = [c.amplitude_mm for c in RANDOM_WAVE.motion.wave.components]
    assert amplitudes == [3.0, 2.3, -3.5, 0.7, 5.4]


def test_never_a_jump(result):
    # Every scan's step of every cylinder stays below the actuator's per-scan limit
    # (250 mm/s * 1 ms); every command's first scan repeats the held position.
    steps = np.abs(np.diff(result.commanded, axis=0))
    assert steps.max() < CONFIG.actuator.max_velocity * CONFIG.task.period_s
    for edge in result.command_scans:
        row = edge - 1  # row of the command scan
        assert np.max(np.abs(result.commanded[row] - result.commanded[row - 1])) <= 1e-9


def test_random_wave_with_lagging_servos():
    # A 2 ms first-order servo lag: the actual positions trail the commands, the
    # FK locates the platform from them, and the commands still follow the reference.
    from stgen.scenarios.simulation import FOLLOWING_ERROR_LIMIT_MM

    lagging = run_scenario(RANDOM_WAVE.with_wave_seconds(5.0), CONFIG, servo_lag_s=0.002)
    assert lagging.passed and lagging.max_error_mm <= MAX_ERROR_MM
    lag = np.abs(lagging.following_error).max()
    assert 0.0 < lag < FOLLOWING_ERROR_LIMIT_MM


def test_another_platform_and_a_2_ms_task():
    # Nothing is tied to the study's numbers: other radii, a 2 ms period, other limits.
    from stgen.config import GeometryConfig, TaskConfig, TrajectoryConfig

    other = PlatformConfig(
        geometry=GeometryConfig(rb=500.0, rp=400.0),
        task=TaskConfig(period_s=0.002),
        trajectory=TrajectoryConfig(linear_velocity=50.0),
    )
    for scenario in (POINT_TO_POINT, RANDOM_WAVE.with_wave_seconds(2.0)):
        outcome = run_scenario(scenario, other)
        assert outcome.passed, (scenario.name, outcome.max_error_mm, outcome.fault_count)
        assert outcome.period_s == 0.002
