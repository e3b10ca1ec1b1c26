"""TRJ_Cycloidal and TRJ_OceanWave, rendered and run in st_runtime, scan by scan.

Expected values by hand (docs/mathematics.md section 4 formulas worked out below) and from the NumPy
reference (stgen.reference.cycloidal / wave) on seeded random cases.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from st_runtime import api
from stgen.config import PlatformConfig, TrajectoryConfig
from stgen.reference.cycloidal import cycloidal_duration, cycloidal_pose
from stgen.reference.wave import RANDOM_5, OceanWave, WaveComponent, wave_pose
from stgen.scenarios.program import codes_of, iec_sources, render_controller_program

PERIOD = 0.001

HARNESS = """
PROGRAM TestCycloid
VAR
    Move : TRJ_Cycloidal;
    Execute : BOOL;
    Start : ARRAY[1..6] OF LREAL;
    Target : ARRAY[1..6] OF LREAL;
    Limits : ARRAY[1..6] OF LREAL := [100.0, 500.0, 5000.0, 10.0, 50.0, 500.0];
END_VAR
Move(Execute := Execute, StartPose := Start, TargetPose := Target,
     LinearVelocity := Limits[1], LinearAcceleration := Limits[2], LinearJerk := Limits[3],
     AngularVelocity := Limits[4], AngularAcceleration := Limits[5], AngularJerk := Limits[6]);
END_PROGRAM

PROGRAM TestWave
VAR
    Wave : TRJ_OceanWave;
    Enable : BOOL;
    RunClock : BOOL;
    Count : INT;
    Amplitude : ARRAY[1..8] OF LREAL;
    Period : ARRAY[1..8] OF LREAL;
    Length : ARRAY[1..8] OF LREAL;
    Phase : ARRAY[1..8] OF LREAL;
    Unit : LREAL := 1000.0;
    Heading : LREAL;
    Rest : LREAL;
    Centre : ARRAY[1..6] OF LREAL;
    Fade : BOOL;
END_VAR
Wave(Enable := Enable, RunClock := RunClock, FadeIn := Fade, ComponentCount := Count, Amplitude := Amplitude,
     WavePeriod := Period, WaveLength := Length, Phase := Phase, WaveLengthUnit := Unit,
     Heading := Heading, RestPosition := Rest, CentrePose := Centre);
END_PROGRAM

PROGRAM TestBrake
VAR
    Stop : TRJ_Brake;
    Execute : BOOL;
    Start : ARRAY[1..6] OF LREAL;
    Velocity : ARRAY[1..6] OF LREAL;
    Acceleration : ARRAY[1..6] OF LREAL;
END_VAR
Stop(Execute := Execute, StartPose := Start, Velocity := Velocity, Acceleration := Acceleration);
END_PROGRAM
"""


@pytest.fixture(scope="module")
def rendered():
    return render_controller_program(PlatformConfig.default())


@pytest.fixture(scope="module")
def project(rendered):
    sources = iec_sources(rendered)
    sources["harness.st"] = HARNESS
    return api.load_sources(sources)


@pytest.fixture(scope="module")
def trj_codes(rendered):
    return codes_of(rendered, "TRJ_Constants")


def _cycloid(project, start, target, limits=None):
    plc = project.controller(period="1ms")
    program = plc.add_program("TestCycloid")
    program["Start"] = list(map(float, start))
    program["Target"] = list(map(float, target))
    if limits is not None:
        program["Limits"] = list(map(float, limits))
    return plc, program


def _run_cycloid(plc, program, scans):
    """Poses and Done of ``scans`` calls, the first with the rising edge."""
    program["Execute"] = True
    poses, done = [], []
    for _ in range(scans):
        plc.scan()
        poses.append(program["Move.Pose"])
        done.append(program["Move.Done"])
    return np.array(poses), np.array(done)


# --------------------------------------------------------------------------- TRJ_Cycloidal


def test_cycloid_30_mm_at_20_mm_per_s_takes_3_s_by_hand(project):
    # docs/mathematics.md section 4 example: 30 mm with 20 mm/s -> T = 2*30/20 = 3 s. Acceleration
    # SQRT(2*pi*30/500) = 0.868 s and jerk (4*pi^2*30/5000)^(1/3) = 0.619 s do not bind.
    plc, program = _cycloid(project, [0, 0, 0, 0, 0, 0], [30, 0, 0, 0, 0, 0], [20, 500, 5000, 10, 50, 500])
    poses, done = _run_cycloid(plc, program, 3002)
    assert program["Move.Duration"] == pytest.approx(3.0, abs=1e-12)
    assert poses[0, 0] == 0.0  # the edge outputs the start: no jump
    # sigma(1/2) = 1/2 - sin(pi)/(2 pi) = 1/2: half way at t = 1.5 s (call 1500).
    assert poses[1500, 0] == pytest.approx(15.0, abs=1e-9)
    # sigma(1/4) = 1/4 - 1/(2 pi) at t = 0.75 s.
    assert poses[750, 0] == pytest.approx(30.0 * (0.25 - 1.0 / (2.0 * math.pi)), abs=1e-9)
    # Done exactly on call 3000 (t = 3.0 s), with the target.
    assert not done[2999] and done[3000]
    assert poses[3000, 0] == pytest.approx(30.0, abs=1e-12)
    assert np.all(poses[:, 1:] == 0.0)


def test_cycloid_jerk_limit_binds_by_hand(project):
    # 1 mm with v = 100, a = 500, j = 10: T = (4 pi^2 * 1 / 10)^(1/3) = 1.5808 s (v: 0.02 s, a: 0.112 s).
    plc, program = _cycloid(project, [0] * 6, [0, 0, 1, 0, 0, 0], [100, 500, 10, 10, 50, 500])
    _run_cycloid(plc, program, 1)
    assert program["Move.Duration"] == pytest.approx((4 * math.pi**2 / 10) ** (1 / 3), rel=1e-12)


def test_cycloid_angular_limits_apply_to_the_angles(project):
    # 6 deg at 2 deg/s -> 6 s; the 1 mm of x would take 0.02 s at 100 mm/s.
    plc, program = _cycloid(project, [0] * 6, [1, 0, 0, 0, 6, 0], [100, 500, 5000, 2, 50, 500])
    _run_cycloid(plc, program, 1)
    assert program["Move.Duration"] == pytest.approx(6.0, abs=1e-12)


def test_cycloid_matches_reference_on_random_moves(project):
    rng = np.random.default_rng(5)
    for _ in range(3):
        start = rng.uniform(-50, 50, 6) * [1, 1, 1, 0.1, 0.1, 0.1]
        target = start + rng.uniform(-20, 20, 6) * [1, 1, 1, 0.2, 0.2, 0.2]
        limits = TrajectoryConfig(
            linear_velocity=rng.uniform(20, 200), linear_acceleration=rng.uniform(50, 500),
            linear_jerk=rng.uniform(200, 5000), angular_velocity=rng.uniform(2, 20),
            angular_acceleration=rng.uniform(5, 50), angular_jerk=rng.uniform(20, 500),
        )
        plc, program = _cycloid(project, start, target, [
            limits.linear_velocity, limits.linear_acceleration, limits.linear_jerk,
            limits.angular_velocity, limits.angular_acceleration, limits.angular_jerk])
        duration = cycloidal_duration(target - start, limits)
        scans = int(duration / PERIOD) + 3
        poses, done = _run_cycloid(plc, program, scans)
        assert program["Move.Duration"] == pytest.approx(duration, rel=1e-12)
        expected = cycloidal_pose(start, target, duration, np.arange(scans) * PERIOD)
        assert np.max(np.abs(poses - expected)) <= 1e-9
        assert done[-1] and not done[0]


def test_cycloid_new_edge_restarts_and_zero_move_is_done_at_once(project):
    plc, program = _cycloid(project, [1, 2, 3, 4, 5, 6], [1, 2, 3, 4, 5, 6])
    poses, done = _run_cycloid(plc, program, 1)
    assert done[0] and program["Move.Duration"] == 0.0
    assert poses[0].tolist() == [1, 2, 3, 4, 5, 6]
    program["Execute"] = False
    plc.scan()
    assert not program["Move.Done"]
    program["Target"] = [11.0, 2, 3, 4, 5, 6]
    poses, done = _run_cycloid(plc, program, 2)
    assert program["Move.Busy"] and poses[0, 0] == 1.0 and poses[1, 0] > 1.0


def test_cycloid_refuses_non_positive_limit(project, trj_codes):
    plc, program = _cycloid(project, [0] * 6, [10, 0, 0, 0, 0, 0], [100, 0, 5000, 10, 50, 500])
    program["Move.Pose"] = [7.0] * 6
    _run_cycloid(plc, program, 3)
    assert program["Move.Error"] and not program["Move.Busy"] and not program["Move.Done"]
    assert program["Move.ErrorID"] == trj_codes["TRJ_ERR_INVALID_LIMIT"]
    assert program["Move.Pose"] == [7.0] * 6  # no set-point was produced


def test_cycloid_refuses_non_finite_pose(project, trj_codes):
    plc, program = _cycloid(project, [0] * 6, [0, 0, 0, 0, 0, 0])
    program.obj.v_TARGET[2] = float("nan")  # the JSON interface has no NaN
    _run_cycloid(plc, program, 1)
    assert program["Move.Error"]
    assert program["Move.ErrorID"] == trj_codes["TRJ_ERR_NON_FINITE_POSE"]


# --------------------------------------------------------------------------- TRJ_OceanWave


def _wave(project, wave: OceanWave, centre=(0.0,) * 6, rest=0.0):
    plc = project.controller(period="1ms")
    program = plc.add_program("TestWave")
    n = len(wave.components)
    pad = [0.0] * (8 - n)
    program["Count"] = n
    program["Amplitude"] = [c.amplitude_mm for c in wave.components] + pad
    program["Period"] = [c.period_s for c in wave.components] + pad
    program["Length"] = [c.wavelength for c in wave.components] + pad
    program["Phase"] = [c.phase_deg for c in wave.components] + pad
    program["Unit"] = wave.wavelength_unit_mm
    program["Heading"] = wave.heading_deg
    program["Rest"] = rest
    program["Centre"] = list(map(float, centre))
    return plc, program


def test_wave_one_component_by_hand(project):
    # A = 2 mm, Tw = 4 s, L = 1000 mm, phi = 0, heading 0. At t = 1 s: psi = -w*t = -pi/2,
    # so x = -A*sin(psi) = 2, z = A*cos(psi) = 0, slope = -A*k*sin(psi) = A*k = 2*2*pi/1000,
    # beta = -atan(slope) in degrees, gamma = atan(0) = 0, alpha = 0.
    wave = OceanWave((WaveComponent(2.0, 4.0, 1000.0, 0.0),), wavelength_unit_mm=1.0)
    plc, program = _wave(project, wave)
    program["Enable"] = True
    program["RunClock"] = True
    poses = []
    for _ in range(1001):
        plc.scan()
        poses.append(program["Wave.Pose"])
    assert poses[0] == pytest.approx([0.0, 0.0, 2.0, 0.0, 0.0, 0.0], abs=1e-12)
    slope = 2.0 * 2.0 * math.pi / 1000.0
    assert poses[1000] == pytest.approx([2.0, 0.0, 0.0, 0.0, -math.degrees(math.atan(slope)), 0.0], abs=1e-9)
    assert program["Wave.WaveTime"] == pytest.approx(1.0, abs=1e-12)


def test_wave_clock_holds_at_zero_until_run(project):
    wave = OceanWave((WaveComponent(2.0, 4.0, 1000.0, 0.0),), wavelength_unit_mm=1.0)
    plc, program = _wave(project, wave)
    program["Enable"] = True
    plc.run(5)  # RunClock FALSE: the first pose, t = 0
    assert program["Wave.WaveTime"] == 0.0 and program["Wave.Pose"][2] == pytest.approx(2.0, abs=1e-12)
    program["RunClock"] = True
    plc.scan()
    assert program["Wave.WaveTime"] == 0.0  # the first running call is still t = 0
    plc.scan()
    assert program["Wave.WaveTime"] == pytest.approx(PERIOD, abs=1e-15)


def test_random_wave_with_heading_and_steep_slopes_matches_reference(project):
    # L read in mm (unit 1) so the tilts are large (tens of degrees); heading 30 deg,
    # a centre pose and a rest position: every term of docs/mathematics.md section 4 shows.
    wave = OceanWave(RANDOM_5.components, heading_deg=30.0, wavelength_unit_mm=1.0)
    centre = (5.0, -3.0, 150.0, 1.0, 2.0, -1.5)
    plc, program = _wave(project, wave, centre, rest=12.5)
    program["Enable"] = True
    program["RunClock"] = True
    poses = []
    for _ in range(2000):
        plc.scan()
        poses.append(program["Wave.Pose"])
    expected = wave_pose(wave, np.arange(2000) * PERIOD, centre, position_mm=12.5)
    assert np.max(np.abs(np.array(poses) - expected)) <= 1e-9
    assert np.max(np.abs(expected[:, 4] - centre[4])) > 10.0  # the tilt really is exercised


def test_airy_preset_with_metres_matches_reference(project):
    from stgen.reference.wave import AIRY

    plc, program = _wave(project, AIRY, (0, 0, 150, 0, 0, 0))
    program["Enable"] = True
    program["RunClock"] = True
    poses = []
    for _ in range(500):
        plc.scan()
        poses.append(program["Wave.Pose"])
    expected = wave_pose(AIRY, np.arange(500) * PERIOD, (0, 0, 150, 0, 0, 0))
    assert np.max(np.abs(np.array(poses) - expected)) <= 1e-9


@pytest.mark.parametrize(
    "field, value",
    [("Count", 9), ("Count", -1), ("Period", [0.0] + [1.0] * 7), ("Length", [-1.0] + [1.0] * 7), ("Unit", 0.0)],
)
def test_wave_refuses_invalid_parameters(project, trj_codes, field, value):
    wave = OceanWave((WaveComponent(2.0, 4.0, 1000.0, 0.0),), wavelength_unit_mm=1.0)
    plc, program = _wave(project, wave)
    program[field] = value
    program["Enable"] = True
    plc.run(2)
    assert program["Wave.Error"] and not program["Wave.Active"]
    assert program["Wave.ErrorID"] == trj_codes["TRJ_ERR_INVALID_WAVE"]
    assert program["Wave.Pose"] == [0.0] * 6
    program["Enable"] = False
    plc.scan()
    assert not program["Wave.Error"] and program["Wave.ErrorID"] == 0


# --------------------------------------------------------------------------- fade-in (issue 8, docs/mathematics.md section 4)


def test_fade_in_matches_reference_and_starts_at_rest(project):
    from stgen.reference.wave import fade_in_duration

    wave = OceanWave(RANDOM_5.components, heading_deg=30.0)
    centre = (5.0, -3.0, 150.0, 1.0, 2.0, -1.5)
    plc, program = _wave(project, wave, centre, rest=12.5)
    program["Fade"] = True
    program["Enable"] = True
    program["RunClock"] = True
    poses = []
    for _ in range(1500):
        plc.scan()
        poses.append(program["Wave.Pose"])
    fade = fade_in_duration(wave, TrajectoryConfig())
    assert program["Wave.FadeDuration"] == pytest.approx(fade, rel=1e-12)
    assert 0.1 < fade < 1.5  # the run covers the fade and beyond
    expected = wave_pose(wave, np.arange(1500) * PERIOD, centre, position_mm=12.5, fade_s=fade)
    assert np.max(np.abs(np.array(poses) - expected)) <= 1e-9
    # Starts at rest at the centre: the first two calls (t = 0 and 1 ms) hardly move (sigma(tau) ~ tau^3).
    assert poses[0] == pytest.approx(list(centre), abs=1e-15)
    assert np.max(np.abs(np.array(poses[1]) - centre)) < 1e-6


def test_fade_in_refuses_a_wave_faster_than_the_limits(project, trj_codes):
    from stgen.reference.wave import fade_in_duration

    # 60 mm at Tw = 1 s: the wave alone moves z at 2*pi*60 = 377 mm/s > 100 mm/s.
    wave = OceanWave((WaveComponent(60.0, 1.0, 100.0, 0.0),))
    with pytest.raises(ValueError):
        fade_in_duration(wave, TrajectoryConfig())
    plc, program = _wave(project, wave)
    program["Fade"] = True
    program["Enable"] = True
    plc.run(2)
    assert program["Wave.Error"] and not program["Wave.Active"]
    assert program["Wave.ErrorID"] == trj_codes["TRJ_ERR_WAVE_LIMIT"]


# --------------------------------------------------------------------------- TRJ_Brake (issue 8)


def _brake(project, start, velocity, acceleration, scans):
    plc = project.controller(period="1ms")
    program = plc.add_program("TestBrake")
    program["Start"] = list(map(float, start))
    program["Velocity"] = list(map(float, velocity))
    program["Acceleration"] = list(map(float, acceleration))
    program["Execute"] = True
    poses, done = [], []
    for _ in range(scans):
        plc.scan()
        poses.append(program["Stop.Pose"])
        done.append(program["Stop.Done"])
    return program, np.array(poses), np.array(done)


def test_brake_from_100_mm_per_s_by_hand(project):
    # v0 = 100 mm/s in x, a0 = 0, limits 500 mm/s^2 and 5000 mm/s^3: T_S = max(1.5*100/500 = 0.3 s,
    # SQRT(12*100/5000) = 0.49 s) = 490 periods; stop distance v0*T_S/2 = 24.5 mm; the edge outputs t = 1 ms.
    program, poses, done = _brake(project, [10, 0, 150, 0, 0, 0], [100, 0, 0, 0, 0, 0], [0] * 6, 492)
    assert program["Stop.Duration"] == pytest.approx(0.49, abs=1e-12)
    assert done.tolist().index(True) == 489 and done[489:].all()
    assert poses[489][0] == pytest.approx(10.0 + 24.5, abs=1e-9)
    assert poses[0][0] == pytest.approx(10.0 + 0.1, abs=1e-4)  # one period at about 100 mm/s
    assert poses[-1].tolist() == poses[489].tolist()


def test_brake_matches_reference(project):
    from stgen.reference.brake import brake_duration, brake_pose

    start = (5.0, -3.0, 150.0, 1.0, 2.0, -1.5)
    velocity = (20.0, -35.0, 60.0, 3.0, -4.0, 1.0)
    acceleration = (100.0, 50.0, -200.0, 10.0, 5.0, -20.0)
    duration = brake_duration(velocity, acceleration, TrajectoryConfig(), PERIOD)
    scans = round(duration / PERIOD) + 3
    program, poses, _ = _brake(project, start, velocity, acceleration, scans)
    assert program["Stop.Duration"] == pytest.approx(duration, rel=1e-12)
    expected = brake_pose(start, velocity, acceleration, duration, np.arange(1, scans + 1) * PERIOD)
    assert np.max(np.abs(poses - expected)) <= 1e-9


def test_brake_refuses_an_acceleration_at_the_limit(project, trj_codes):
    program, _, _ = _brake(project, [0] * 6, [0] * 6, [0, 0, 500, 0, 0, 0], 2)
    assert program["Stop.Error"] and program["Stop.ErrorID"] == trj_codes["TRJ_ERR_STOP_LIMIT"]
