"""Motion behaviour that the seed-25 and seed-26 mutation samples found unchecked (issue 16,
docs/mutation.md, session 11).

Expected values are worked out by hand from the rules the motion package documents (OMRON's
16#6447 In-position Check Time Exceeded, W503 p. 3-526: the waiting time *exceeds* the check time;
the limit slack of axis.py; the binding rules of binding.py), not read from a run.  Several tests
make their classes inside the test: the library's are made once per process (the watched AXIS_REF
classes at the first binding, the FBs' hot paths and idle rules at import), before a mutation
tool switches a mutant in, so a test that only uses them cannot tell a broken builder.
"""

from __future__ import annotations

import math
import traceback

import pytest

from st_runtime.api import load_sources
from st_runtime.motion import MotionTask, binding, fbs
from st_runtime.motion.axis import Axis, AxisState, MotionRefused
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.motion.error_ids import ErrorID
from st_runtime.motion.types import AxisRefWriter
from st_runtime.objects import STObject

from test_motion_st import AXIS, make_plc


def _powered_axis(dt: float, **settings) -> Axis:
    axis = Axis(AxisConfig(**{"name": "Ax", "max_velocity": 100.0, **settings}))
    axis.request_power(True)
    axis.step(dt)
    assert axis.state == AxisState.STANDSTILL
    return axis


# --- seed 25 --------------------------------------------------------------------------------------


def test_a_move_at_exactly_the_slackened_maximum_velocity_is_accepted():
    # axis.py: limit checks accept max_velocity * (1 + 1e-9) (the relative slack for float64 rounding);
    # 0 < Velocity <= that bound, so the bound itself is accepted and the next float above it refused.
    bound = 100.0 * (1 + 1e-9)
    axis = _powered_axis(0.001)
    axis.start_move_absolute(1.0, bound, 0.0, 0.0)
    assert axis.state == AxisState.DISCRETE
    axis = _powered_axis(0.001)
    with pytest.raises(MotionRefused) as refused:
        axis.start_move_absolute(1.0, math.nextafter(bound, math.inf), 0.0, 0.0)
    assert refused.value.code == ErrorID.PARAMETER_OUT_OF_RANGE and axis.state == AxisState.STANDSTILL


class _Holder:
    """Stands for an axis FB that holds a binding (`binding.hold`): counts `end_binding`."""

    def __init__(self):
        self.ended = 0

    def end_binding(self):
        self.ended += 1


def _fresh_axis_ref():
    """An AXIS_REF-like struct value of classes made here (never watched before in this process)."""
    cfg_class = type("FreshCfg", (STObject,), {"__slots__": ("v_AXNO", "v_AXENABLE")})
    ref_class = type("FreshRef", (STObject,), {"__slots__": ("v_CFG",)})
    ref, ref.v_CFG = ref_class(), cfg_class()
    ref.v_CFG.v_AXNO, ref.v_CFG.v_AXENABLE = 0, True
    return ref, cfg_class


def test_a_store_of_another_value_into_a_watched_cfg_ends_the_binding():
    # binding.py: a watched value keeps its class's name and members, and a store of another value into
    # it ends every binding; a store of the value a member holds ends none.
    ref, cfg_class = _fresh_axis_ref()
    holder = _Holder()
    assert binding.hold(holder, ref)
    cfg = ref.v_CFG
    assert type(cfg).__name__ == "FreshCfg" and type(cfg).__mro__[1] is cfg_class
    assert (type(cfg).__qualname__, type(cfg).__module__) == (cfg_class.__qualname__, cfg_class.__module__)
    cfg.v_AXNO = 0                       # the value it holds
    assert holder.ended == 0
    cfg.v_AXNO = 1                       # another axis
    assert holder.ended == 1 and cfg.v_AXNO == 1


def test_one_watched_class_per_struct_class_made_once():
    # binding._watched_class: the watched subclass is made once and kept on the struct class.
    first, cfg_class = _fresh_axis_ref()
    second = type(first)()
    second.v_CFG = cfg_class()
    second.v_CFG.v_AXNO, second.v_CFG.v_AXENABLE = 1, True
    assert binding.hold(_Holder(), first) and binding.hold(_Holder(), second)
    assert type(first.v_CFG) is type(second.v_CFG) is cfg_class.__dict__["_st_watched"]
    assert type(first) is type(second)


def test_the_motion_step_written_at_run_time_is_named_in_tracebacks(monkeypatch):
    # generated.define: the label names the source in tracebacks (and in benchmarks' opcode reports).
    plc, main, task = make_plc("PROGRAM Main\nEND_PROGRAM\n", AXIS)

    def broken(self, axis, direction):
        raise RuntimeError("flags")

    monkeypatch.setattr(AxisRefWriter, "_write_flags", broken)
    task.axes[0].request_power(True)          # the next step changes Status: the flags are written
    with pytest.raises(RuntimeError) as raised:
        task.process(0.001)
    assert "<motion task process>" in [frame.filename for frame in traceback.extract_tb(raised.tb)]


def test_the_hot_paths_are_named_for_tracebacks(monkeypatch):
    # As above, for the hot paths, built again here (the module builds them at import).
    for cls in (fbs.MC_Power, fbs.MC_SyncMoveAbsolute):
        monkeypatch.setattr(cls, "execute", cls.execute)
        cls.HOT_PATH.install(cls)
        assert cls.execute.__code__.co_filename == f"<{cls.__name__} hot path>"


# --- seed 26 --------------------------------------------------------------------------------------


def test_a_waiting_time_equal_to_the_in_position_check_time_is_no_error():
    # 16#6447 (W503 p. 3-526) is for a waiting time that exceeds the check time; axis.py compares against
    # check * (1 + 1e-9).  Periods of 1/1024 s are exact in binary, so the waiting time after n periods is
    # n/1024 exactly, and a check time of (3/1024) / (1 + 1e-9) puts that bound exactly on 3 periods.
    dt = 1.0 / 1024.0
    check = (3.0 / 1024.0) / (1 + 1e-9)
    assert check * (1 + 1e-9) == 3.0 / 1024.0
    # A 1 s servo lag keeps the actual position far (> 0.01 mm) from a 0.05 mm target the command reaches
    # in its first period (100 mm/s, no acceleration limit): InPosWaiting from that period on.
    axis = _powered_axis(dt, servo_lag=1.0, in_position_check_time=check)
    axis.start_move_absolute(0.05, 100.0, 0.0, 0.0)
    for waited in range(3):
        axis.step(dt)
        assert axis.in_pos_waiting and axis.state == AxisState.DISCRETE, waited
    assert axis.fault_code == 0
    axis.step(dt)                             # 4/1024 s > the bound: the error
    assert axis.state == AxisState.ERRORSTOP and axis.fault_code == ErrorID.IN_POSITION_CHECK_TIME_EXCEEDED


def test_only_an_execute_fb_whose_every_call_runs_the_idle_rules_may_be_left_at_rest():
    # fbs._spell_out_idle_call: the compiled caller may skip an FB it found at rest (REST) only when every
    # call goes through `_execute_rules`, which forgets the rest; a class that writes its own `execute`,
    # or has a hot path, gets no REST.  Classes made here (the library's are made at import).
    class Plain(fbs.MC_Stop):
        pass

    class OwnExecute(fbs.MC_Stop):
        def execute(self, ctx):
            self._execute_rules(ctx)

    assert Plain.REST is fbs._REST
    assert OwnExecute.REST is None


# --- seed 27 (a fresh sample after the tests above) -----------------------------------------------------


def test_a_motion_task_with_no_axes_installs_and_runs():
    # No [[axis]] table: no global, no lane; the motion processing is an empty step and the programs run.
    task = MotionTask.from_tables([])
    project = load_sources({"axes.st": task.globals_source(),
                            "main.st": "PROGRAM Main\nVAR n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"}, dialect="nj")
    plc = project.controller(period="1ms")
    task.install(plc.controller)
    main = plc.add_program("Main")
    plc.run(3)
    assert main["n"] == 3 and task.axes == []
