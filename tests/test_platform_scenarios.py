"""SP_Controller on the platform variants (issue 11): the study's motions and test poses on the
moving-base platform and the crank signals on the crank platform, every commanded axis position
against the NumPy reference at 1e-9 every scan; the limits of every scan against the reference's
own evaluation of the same motion (stgen.reference.study_motions); refusals and faults that name
the limit and the leg, by the reference's ErrorID (stgen.reference.feasibility.error_ids)."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.reference.feasibility import error_ids, feasibility
from stgen.reference.study_motions import fixed_base_upper, moving_base_base, motion_report, moving_base_upper
from stgen.scenarios.actuators import actuator_positions
from stgen.scenarios.platform_report import PLATFORM_MAX_ERROR, run_platform_scenario
from stgen.scenarios.platforms import PLATFORM_SCENARIOS, platform_scenario
from stgen.scenarios.runner import command_move, release_commands
from stgen.scenarios.simulation import ControllerSimulation
from stgen.scenarios.track import TrackScenario

#: The crank signals run shortened: one surge period, half a roll period (-26 deg to +26 deg: the whole range).
SHORTENED_S = {"crank_surge": 4.0, "crank_roll": 6.81}


@pytest.fixture(scope="module")
def runs():
    out = {}
    for item in PLATFORM_SCENARIOS:
        if item.name in SHORTENED_S:
            item = item.shortened(SHORTENED_S[item.name], 1.0)
        out[item.name] = run_platform_scenario(item)
    return out


@pytest.mark.parametrize("name", [item.name for item in PLATFORM_SCENARIOS])
def test_every_scan_commands_the_reference_and_keeps_every_limit(runs, name):
    run = runs[name]
    result = run.result
    assert result.scans > 4000
    assert result.max_error_mm <= PLATFORM_MAX_ERROR
    assert result.fault_count == 0 and result.refused_commands == 0
    assert run.pose_limits.feasible and run.pose_limits.first_violation is None
    assert run.motion_limits.passed
    low, high = run.pose_limits.actuator_range
    limit_low, limit_high = ((run.config.crank.angle_min_deg, run.config.crank.angle_max_deg) if run.config.is_crank
                             else (run.config.stroke.min, run.config.stroke.max))
    assert limit_low <= low < high <= limit_high
    if isinstance(run.item.scenario, TrackScenario):
        assert "SP_STATE_TRACK" in {result.state_names[int(s)] for s in np.unique(result.state)}


@pytest.mark.parametrize("name, upper, base", [
    ("moving_base_motion", moving_base_upper, lambda t: moving_base_base(t, True)),
    ("fixed_base_motion", fixed_base_upper, None),
])
def test_the_study_motions_match_the_references_extremes(runs, name, upper, base):
    """The extremes of the run are those of the reference sampled at the task period (same t grid)."""
    run = runs[name]
    report = motion_report(run.config, name, upper, base, duration=10.0, period=run.config.task.period_s)
    assert report.feasible
    limits = run.pose_limits
    assert limits.actuator_range == pytest.approx(report.extension_range, abs=1e-9)
    assert limits.max_universal_gamma == pytest.approx(report.max_universal_gamma, abs=1e-9)
    assert limits.max_universal_psi == pytest.approx(report.max_universal_psi, abs=1e-9)
    assert limits.max_tilt == pytest.approx(report.max_tilt, abs=1e-9)
    # Finite differences of the set-points against the analytic leg rates: within O(dt) of them.
    assert run.motion_limits.max_velocity.max() == pytest.approx(report.max_velocity, rel=1e-2)
    assert run.motion_limits.max_acceleration.max() <= report.max_acceleration * 1.05 + 1.0


@pytest.mark.parametrize("name", ["moving_base_motion", "fixed_base_motion"])
def test_a_study_motion_starting_at_speed_is_a_velocity_step(runs, name):
    """The study's motions have non-zero rates at t = 0: one scan's set-point acceleration is about
    the legs' initial velocity / dt, above the 2500 mm/s^2 limit; reported, not hidden."""
    run = runs[name]
    upper, base = (moving_base_upper, lambda t: moving_base_base(t, True)) if name == "moving_base_motion" \
        else (fixed_base_upper, None)
    dt = run.config.task.period_s
    t = np.array([0.0, dt])
    q = actuator_positions(run.config, upper(t)[0], None if base is None else base(t)[0])
    step = np.abs(q[1] - q[0]).max() / dt / dt
    assert not run.start_step.passed
    assert run.start_step.max_acceleration.max() == pytest.approx(step, rel=1e-6)


def _moving():
    return platform_scenario("test_pose_1").config()


def _crank():
    return platform_scenario("crank_surge").config()


def _power_on(config, pose, base=None) -> ControllerSimulation:
    sim = ControllerSimulation(config, pose, base_pose=base)
    sim.power_on(200)
    return sim


def _command(sim, target) -> None:
    command_move(sim, target)
    sim.run(1)
    release_commands(sim)


def test_a_target_outside_a_universal_joint_limit_is_refused_naming_limit_and_leg():
    config = _moving()
    target = np.array([59.4, -111.4, 56.4, -4.7, 9.9, -3.5])
    code = int(error_ids(feasibility(config, target))[0])
    assert code & 0xFFF0 == 0x1070  # the reference: a universal-joint angle, stroke inside
    sim = _power_on(config, (0.0,) * 6)
    before = sim.command_positions()
    _command(sim, target)
    g = sim.globals
    assert g["SpRefusalID"] == sim.codes["SP_REFUSED_OUT_OF_STROKE"]
    assert g["SpRefusalDetail"] == code and g["SpRefusalLeg"] == code & 0xF
    sim.run(5)
    assert sim.state_name == "SP_STATE_STANDBY" and np.array_equal(sim.command_positions(), before)


def test_a_crank_target_out_of_reach_is_refused_naming_the_leg():
    config = _crank()
    target = np.array([0.0, 0.0, 300.0, 0.0, 0.0, 0.0])
    code = int(error_ids(feasibility(config, target))[0])
    assert code & 0xFFF0 == 0x1050
    sim = _power_on(config, (0.0,) * 6)
    _command(sim, target)
    assert sim.globals["SpRefusalDetail"] == code and sim.globals["SpRefusalLeg"] == code & 0xF


def test_a_stream_starting_away_from_the_held_pose_is_refused():
    config = _crank()
    sim = _power_on(config, (0.0,) * 6)
    track = np.array([4.0, 2.0, 0.0, 0.0, 0.0, 0.0])
    jump = np.abs(actuator_positions(config, track) - actuator_positions(config, np.zeros(6)))
    step = config.actuator.max_velocity * config.task.period_s
    assert jump.max() > step
    sim.set_pose("SpTrackPose", track)
    sim.globals["SpTrackStart"] = True
    sim.run(3)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_TRACK_START"]
    assert sim.globals["SpRefusalLeg"] == int(np.argmax(jump > step)) + 1
    assert sim.state_name == "SP_STATE_STANDBY"


def test_standby_compensates_a_rolling_deck_until_a_limit_breaks_then_faults_naming_it():
    """Compensation mode: the upper pose is held in the world while SpBasePose rolls 0.01 deg a scan;
    every scan commands the reference legs of that base pose, and the first scan the reference finds
    infeasible is a fault with its ErrorID (limit and leg); nothing further is commanded."""
    config = _moving()
    upper = np.array([0.0, 0.0, 75.0, 0.0, 0.0, 0.0])
    sim = _power_on(config, upper)
    base = np.zeros(6)
    for scan in range(1, 4001):
        base = base.copy()
        base[5] = 0.01 * scan
        sim.set_pose("SpBasePose", base)
        sim.run(1)
        code = int(error_ids(feasibility(config, upper, base))[0])
        if code:
            break
        assert np.abs(sim.command_positions() - actuator_positions(config, upper, base)).max() <= PLATFORM_MAX_ERROR
        assert sim.globals["SpFaultID"] == 0
    assert code, "the deck never rolled the platform out of its limits"
    g = sim.globals
    assert g["SpFaultID"] == sim.codes["SP_FAULT_OUT_OF_STROKE"]
    assert g["SpFaultDetail"] == code and g["SpFaultAxis"] == code & 0xF
    held = actuator_positions(config, upper, np.where(np.arange(6) == 5, base - 0.01, base))
    assert np.abs(np.asarray(g["SpCylinderSetpoint"]) - held).max() <= PLATFORM_MAX_ERROR


def _stream(sim, poses) -> None:
    sim.globals["SpTrackStart"] = True
    for pose in poses:
        sim.set_pose("SpTrackPose", pose)
        sim.run(1)


def test_a_stream_released_holds_its_last_pose_in_standby():
    config = _crank()
    sim = _power_on(config, (0.0,) * 6)
    poses = [np.array([0.05 * k, 0.0, 0.0, 0.0, 0.0, 0.0]) for k in range(50)]
    _stream(sim, poses)
    assert sim.state_name == "SP_STATE_TRACK"
    sim.globals["SpTrackStart"] = False
    sim.run(20)
    assert sim.state_name == "SP_STATE_STANDBY" and sim.globals["SpFaultID"] == 0
    assert np.abs(sim.command_positions() - actuator_positions(config, poses[-1])).max() <= PLATFORM_MAX_ERROR


def test_spstop_in_a_stream_ramps_to_rest_then_stops():
    config = _crank()
    sim = _power_on(config, (0.0,) * 6)
    _stream(sim, [np.array([0.05 * k, 0.0, 0.0, 0.0, 0.0, 0.0]) for k in range(50)])
    sim.globals["SpStop"] = True
    sim.run(1)
    assert sim.state_name == "SP_STATE_STOP_RAMP"
    sim.run_until(lambda: sim.state_name == "SP_STATE_STANDBY", 3000)
    assert sim.globals["SpFaultID"] == 0
    # Ramped to rest from 50 mm/s at the configured 500 mm/s^2: past the last streamed x = 2.45 mm.
    assert sim.globals["SpSetpointPose"][0] > 2.45


@pytest.mark.parametrize("platform", ["moving", "crank"])
@pytest.mark.parametrize("command", ["SpPathStart", "SpPlaybackStart"])
def test_a_path_or_playback_on_a_variant_is_refused_and_nothing_moves(platform, command):
    # TRJ_Path and TRJ_Playback plan with linear legs on a fixed base; a variant refuses them.
    config = _moving() if platform == "moving" else _crank()
    sim = _power_on(config, (0.0,) * 6)
    before = sim.command_positions()
    sim.globals[command] = True
    sim.run(3)
    assert sim.globals["SpRefusalID"] == sim.codes["SP_REFUSED_PLATFORM"] == 0x1322
    sim.run(20)
    assert sim.state_name == "SP_STATE_STANDBY" and np.array_equal(sim.command_positions(), before)
