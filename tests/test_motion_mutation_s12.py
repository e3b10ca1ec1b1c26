"""Motion behaviour that the seed-28 mutation sample found unchecked (issue 16, docs/mutation.md,
session 12).

Expected values are worked out by hand from the rules the motion package documents (axis.py's
trapezoid: a command moving away from its target brakes at the Deceleration; the controller's
record of a fault raised in an I/O hook, named by the hook's qualname; binding.py's watched class),
not read from a run.  Positions, velocities and periods are chosen exact in binary.
"""

from __future__ import annotations

from types import SimpleNamespace

from st_runtime.faults import STFault
from st_runtime.motion import MotionTask, binding
from st_runtime.motion.axis import Axis, AxisState
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.objects import STObject

from test_motion_mutation_s11 import _Holder
from test_motion_st import AXIS, make_plc

DT = 1.0 / 1024.0       # a period exact in binary


def _ideal_axis() -> Axis:
    axis = Axis(AxisConfig(name="Ax", max_velocity=100.0, soft_limit_min=-50.0, soft_limit_max=50.0))
    axis.request_power(True)
    axis.step(DT)
    assert axis.state == AxisState.STANDSTILL and axis.cmd_pos == 0.0
    return axis


def test_a_move_that_reverses_brakes_at_its_deceleration_not_its_acceleration():
    # axis._trapezoid_step: speed is negative while the command moves away from the target, and then
    # changes by Deceleration * dt a period (braking), not Acceleration * dt.
    axis = _ideal_axis()
    axis.start_move_absolute(40.0, 8.0, 0.0, 0.0)     # 0: no limit (no max_acceleration), 8 mm/s at once
    axis.step(DT)
    assert axis.cmd_vel == 8.0 and axis.cmd_pos == 8.0 / 1024.0
    # Aborted by a move back to -40 at Acceleration 2048, Deceleration 1024 mm/s^2: the speed towards
    # -40 is -8 and goes up by 1024 / 1024 = 1 a period: -7, so the command still moves forwards by 7 dt.
    axis.start_move_absolute(-40.0, 8.0, 2048.0, 1024.0)
    axis.step(DT)
    assert axis.cmd_vel == 7.0 and axis.cmd_pos == 15.0 / 1024.0
    axis.step(DT)                             # -6: the speed after braking twice
    assert axis.cmd_vel == 6.0 and axis.cmd_pos == 21.0 / 1024.0


def test_the_watched_class_keeps_a_qualname_other_than_its_name():
    # binding._watched_class: the watched class takes the struct class's qualname (a class made in a
    # function is `<function>.<locals>.Name`), not only its name.
    class NestedCfg(STObject):
        __slots__ = ("v_AXNO", "v_AXENABLE")

    class NestedRef(STObject):
        __slots__ = ("v_CFG",)

    ref, ref.v_CFG = NestedRef(), NestedCfg()
    ref.v_CFG.v_AXNO, ref.v_CFG.v_AXENABLE = 0, True
    assert NestedCfg.__qualname__ != NestedCfg.__name__
    holder = _Holder()
    assert binding.hold(holder, ref)
    assert type(ref.v_CFG).__qualname__ == NestedCfg.__qualname__
    assert type(ref).__qualname__ == NestedRef.__qualname__


def test_a_fault_raised_in_the_motion_step_is_recorded_against_the_motion_task():
    # controller._hook_fault: a fault an I/O hook raises is recorded against the hook's qualname, which
    # for the bound motion task's after hook is MotionTask._after_programs.
    plc, main, task = make_plc("PROGRAM Main\nEND_PROGRAM\n", AXIS)

    def broken(dt):
        raise STFault("F-MATH", "the step broke")

    task.axes[0].step = broken                # the lane step of an axis with no command calls axis.step
    plc.run(1)
    record = plc.controller.faults[0]
    assert (record.code, record.pou, record.file) == ("F-MATH", "MotionTask._after_programs", "<io>")


def test_an_unbound_motion_task_steps_its_axes_by_the_scan_period():
    # MotionTask._step_after_programs (the after hook before `bind`): every axis steps by the context's
    # period, period_ns * 1e-9 s.  A sync command one period's length (in mm) ahead: 1 mm/s.
    dt = 1_000_000 * 1e-9
    task = MotionTask.from_tables([AXIS])
    axis = task.axes[0]
    axis.request_power(True)
    axis.step(dt)
    command = axis.start_sync()
    command.target = dt
    controller = SimpleNamespace(before_hooks=[], after_hooks=[task._after_programs])
    task._after_programs(SimpleNamespace(period_ns=1_000_000, controller=controller))
    assert axis.cmd_pos == dt and axis.cmd_vel == 1.0
