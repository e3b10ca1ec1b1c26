"""Motion behaviour that the seed-23 (merged main) and seed-24 mutation samples found unchecked
(issue 16, docs/mutation.md, session 9).

Expected values are worked out by hand from the rules the motion package documents (OMRON's
Cmd.AccDec sign rule, W507 p. 6-28; the following error warning 16#644C, W503 p. 3-549; the
PLCopen output rules of fbs.py), not read from a run.
"""

from __future__ import annotations

import math

import pytest

from motion_rig import PERIOD_S, make_fb
from test_motion_fbs import powered_rig
from test_motion_mutants import powered
from st_runtime.motion import MotionTask, fbs
from st_runtime.motion.axis import AxisState
from st_runtime.motion.error_ids import ErrorID


def test_cmd_accdec_is_negative_while_a_slow_sync_stream_slows_down():
    # W507 p. 6-28: AccDec has a plus sign while |velocity| grows and a minus sign while it
    # falls.  A stream (MotionTask.process's short path) creeping at 0.5 mm/s, then 0.25 mm/s
    # (0.5 and 0.25 um per 1 ms period): AccDec = -(0.5 - 0.25) / 0.001 = -250 mm/s^2.  Slow
    # speeds matter: the sign test must compare magnitudes below 1 mm/s as well.
    rig, _ = powered_rig()
    sync = make_fb(fbs.MC_SyncMoveAbsolute)
    for position in (0.0005, 0.00075):
        rig.scan(lambda: rig.call(sync, Execute=True, Position=position, BufferMode=0))
    cmd = rig.ref().v_CMD
    assert cmd.v_VEL == pytest.approx(0.25, rel=1e-9)
    assert cmd.v_ACCDEC == pytest.approx(-250.0, rel=1e-6)
    # and the opposite way (growing again, 0.25 -> 0.75 mm/s): +500 mm/s^2
    rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0015, BufferMode=0))
    assert cmd.v_ACCDEC == pytest.approx(500.0, rel=1e-6)


def test_an_execute_fbs_poll_hook_gets_the_fbs_axis():
    # _ExecuteFB's documented hook: `_poll(axis, command, first_call)` is called, with the FB's
    # axis, in every call while the command runs (here the call of the rising edge: a home
    # command runs until the motion processing after it).
    rig, _ = powered_rig()
    seen = []
    probe = make_fb(type("HomeProbe", (fbs.MC_Home,),
                         {"_poll": lambda self, axis, command, first: seen.append((axis, first))}))
    rig.scan(lambda: rig.call(probe, Execute=True))
    assert seen == [(rig.task.axis("Ax"), True)]
    rig.scan(lambda: rig.call(probe, Execute=True))
    assert probe.v_DONE and len(seen) == 1      # done: no more polls


@pytest.mark.parametrize("below, observed", [(False, False), (True, True)])
def test_the_following_error_warning_is_for_a_deviation_above_the_warning_value(below, observed):
    # 16#644C "Following Error Warning" (W503 p. 3-549): the following error exceeded the warning
    # value.  One period of a first-order lag (tau 10 ms) towards a target 0.05 mm away leaves
    # the actual position at 0.05 * (1 - e^(-dt/tau)): the deviation is what remains.  A warning
    # value equal to it is not exceeded; one a hair below it is.
    tau, target = 0.01, 0.05
    actual = 0.0 + (target - 0.0) * (1.0 - math.exp(-PERIOD_S / tau))
    deviation = abs(target - actual)
    warning = math.nextafter(deviation, 0.0) if below else deviation
    axis = powered(servo_lag=tau, following_error_warning=warning)
    axis.start_sync().target = target
    axis.step(PERIOD_S)
    assert axis.act_pos == actual and axis.state == AxisState.DISCRETE
    assert axis.observation_code == (ErrorID.FOLLOWING_ERROR_WARNING if observed else ErrorID.NONE)


def test_in_position_of_an_ended_sync_is_the_bool_false():
    # A sync aborted by MC_Stop ends with CommandAborted and InPosition FALSE: a BOOL output
    # holds FALSE (the instance state, e.g. its JSON, shows false), not "nothing".
    rig, _ = powered_rig()
    sync, stop = make_fb(fbs.MC_SyncMoveAbsolute), make_fb(fbs.MC_Stop)
    for _ in range(3):
        rig.scan(lambda: rig.call(sync, Execute=True, Position=0.0, BufferMode=0))
    assert sync.v_INPOSITION is True
    rig.scan(lambda: rig.call(stop, Execute=True, Deceleration=0.0, BufferMode=0),
             lambda: rig.call(sync, Execute=True, Position=0.0, BufferMode=0))
    assert sync.v_COMMANDABORTED is True and sync.v_INPOSITION is False


def test_a_task_without_axis_variables_runs_both_stages():
    # A task that was never bound (no AXIS_REF variables: an axis simulation on its own) has
    # nothing to publish before the programs, and its processing still advances the axes.
    task = MotionTask.from_tables([{"name": "Ax", "max_velocity": 100.0}])
    axis = task.axis("Ax")
    axis.request_power(True)
    task.feedback_in()
    task.process(PERIOD_S)
    task.feedback_in()
    assert axis.powered and axis.state == AxisState.STANDSTILL
