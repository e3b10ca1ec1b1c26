"""The study's scenarios end to end (issue 5): SP_Controller and six simulated
axes at 1 ms for the full duration, every commanded cylinder position of
every scan against the NumPy reference trajectory through the reference IK.

Full length: the point-to-point move (10 s + 0.5 s settling) and both 60 s
waves run completely here (about 2 s of wall time each).
"""

from __future__ import annotations

import numpy as np
import pytest

from stgen.config import PlatformConfig
from stgen.scenarios.definitions import AIRY_WAVE, POINT_TO_POINT, RANDOM_WAVE, SCENARIOS, scenario_by_name
from stgen.scenarios.expected import calls_until_done, expected_poses, move_duration
from stgen.scenarios.program import codes_of, render_controller_program
from stgen.scenarios.runner import MAX_ERROR_MM, run_scenario

CONFIG = PlatformConfig.default()


@pytest.fixture(scope="module", params=[s.name for s in SCENARIOS])
def result(request):
    return run_scenario(scenario_by_name(request.param), CONFIG)


def test_every_commanded_position_matches_the_reference(result):
    assert result.max_error_mm <= MAX_ERROR_MM
    assert result.scans == len(result.expected) and result.commanded.shape == (result.scans, 6)


def test_no_fault_of_any_kind(result):
    assert result.runtime_faults == []
    assert not result.axis_fault.any()
    assert not result.fault_id.any()
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
    else:
        assert result.duration_s >= 10.5


def test_point_to_point_takes_10_s_and_ends_on_the_target():
    # 100 mm at 20 mm/s: 2*100/20 = 10 s; 10 deg at 2 deg/s: 2*10/2 = 10 s. Same T: one synchronised move.
    assert move_duration(POINT_TO_POINT, CONFIG) == pytest.approx(10.0, abs=1e-12)
    poses = expected_poses(POINT_TO_POINT, CONFIG, command_scan=5, scans=10_006)
    assert poses[3].tolist() == [0.0, 0.0, 150.0, 0.0, 0.0, 0.0]      # scan 4: before the command
    assert poses[4].tolist() == [0.0, 0.0, 150.0, 0.0, 0.0, 0.0]      # scan 5: the edge, t = 0
    assert poses[5004, :3] == pytest.approx([50.0, 50.0, 200.0])       # t = 5 s: half way
    assert poses[-1] == pytest.approx([100.0, 100.0, 250.0, 6.0, 6.0, 10.0], abs=1e-12)


def test_wave_timeline_lead_in_then_clock_from_zero():
    duration = move_duration(AIRY_WAVE, CONFIG)
    lead = calls_until_done(duration, CONFIG.task.period_s)
    assert (lead - 1) * 0.001 < duration <= lead * 0.001
    poses = expected_poses(AIRY_WAVE, CONFIG, command_scan=1, scans=lead + 3)
    # The lead-in ends on the wave's first pose and the wave starts there: no jump.
    assert np.array_equal(poses[lead], poses[lead + 1])
    assert not np.array_equal(poses[lead + 1], poses[lead + 2])


def test_calls_until_done_by_hand():
    assert calls_until_done(3.0, 0.001) == 3000
    assert calls_until_done(0.0005, 0.001) == 1
    assert calls_until_done(0.0, 0.001) == 0


def test_random_wave_scenario_uses_spec_components():
    amplitudes = [c.amplitude_mm for c in RANDOM_WAVE.motion.wave.components]
    assert amplitudes == [3.0, 2.3, -3.5, 0.7, 5.4]


def test_never_a_jump(result):
    # Every scan's step of every cylinder stays below the actuator's per-scan limit
    # (250 mm/s * 1 ms); the command's first scan repeats the held position.
    steps = np.abs(np.diff(result.commanded, axis=0))
    assert steps.max() < CONFIG.actuator.max_velocity * CONFIG.task.period_s
    edge = result.command_scan - 1  # row of the command scan
    assert np.max(np.abs(result.commanded[edge] - result.commanded[edge - 1])) <= 1e-9


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
