"""The short paths of the motion FBs called every scan do what the general ones do.

The call with Execute FALSE after a command ended: its final output goes (PLCopen's output
rules, st_runtime/motion/fbs.py): every final output of MC_Reset and MC_Stop, which answer an
idle call on a short path, is held while Execute stays TRUE and cleared by the first call
with Execute FALSE, ErrorID with it.  MC_Power, which keeps the axis it found, finds it
again when the AXIS_REF's Cfg changes."""

import pytest

from st_runtime.motion import fbs
from st_runtime.motion.error_ids import ErrorID
from motion_rig import make_axis_ref, make_fb

from test_motion_fbs import outputs, powered_rig

FINALS = {fbs.MC_Reset: ("Done", "Failure", "Error"), fbs.MC_Stop: ("Done", "CommandAborted", "Error")}


def ended(fb_class, output):
    """A rig, the FB and a call of it, after a command that ended with `output`."""
    if output == "Failure":    # the following error is still above its limit (docs/nj501.md)
        rig, _ = powered_rig(servo_lag=0.01, following_error_limit=0.03)
        sync = make_fb(fbs.MC_SyncMoveAbsolute)
        rig.scan(lambda: rig.call(sync, Execute=True, Position=0.05))
    elif output == "CommandAborted":   # MC_Stop on an axis in ErrorStop
        rig, _ = powered_rig(soft_limit_max=0.15)
        sync = make_fb(fbs.MC_SyncMoveAbsolute)
        rig.scan(lambda: rig.call(sync, Execute=True, Position=0.16))
    else:
        rig, _ = powered_rig()
    fb = make_fb(fb_class)
    unbound = make_axis_ref()          # a local AXIS_REF (AxEnable FALSE): Error 16#5401

    def call(execute):
        if output == "Error":
            fb.v_AXIS, fb.v_EXECUTE = unbound, execute
            fb.execute(rig.ctx)
        else:
            rig.call(fb, Execute=execute)

    return rig, fb, call


@pytest.mark.parametrize("fb_class,output", [(c, o) for c, names in FINALS.items() for o in names])
def test_a_final_output_is_held_while_execute_is_true_and_goes_with_it(fb_class, output):
    rig, fb, call = ended(fb_class, output)
    for _ in range(3):                 # MC_Stop is Done once the motion processing has stopped it
        rig.scan(lambda: call(True))
    assert outputs(fb, *FINALS[fb_class]) == tuple(name == output for name in FINALS[fb_class])
    assert fb.v_ERRORID == (ErrorID.AXIS_NOT_ASSIGNED if output == "Error" else 0)
    assert not fb.v_BUSY
    rig.scan(lambda: call(True))       # held
    assert getattr(fb, "v_" + output.upper())
    rig.scan(lambda: call(False))
    assert outputs(fb, *FINALS[fb_class], "ErrorID", "Busy") == (False,) * len(FINALS[fb_class]) + (0, False)
    rig.scan(lambda: call(False))      # and idle from then on
    assert outputs(fb, *FINALS[fb_class], "ErrorID", "Busy") == (False,) * len(FINALS[fb_class]) + (0, False)


def test_mc_power_follows_the_axis_ref_it_is_given_every_call():
    """MC_Power finds its axis through Axis.Cfg.AxNo on every call (fbs.py): a variable whose
    AxEnable goes FALSE is no axis (Error 16#5401 while Enable), one whose AxNo changes is the
    other axis."""
    from test_motion_fbs import axis_config
    from motion_rig import Rig

    rig = Rig(axis_config(name="A0"), axis_config(name="A1"))
    power = make_fb(fbs.MC_Power)
    ref = rig.ref("A0")
    for _ in range(2):
        rig.scan(lambda: rig.call(power, "A0", Enable=True))
    assert power.v_STATUS and rig.task.axes[0].powered and not rig.task.axes[1].powered
    ref.v_CFG.v_AXNO = 1
    rig.call(power, "A0", Enable=True)
    assert rig.task.axes[1].power_requested and outputs(power, "Status", "Busy", "Error") == (False, True, False)
    ref.v_CFG.v_AXENABLE = False
    rig.call(power, "A0", Enable=True)
    assert outputs(power, "Status", "Busy", "Error", "ErrorID") == (False, False, True, ErrorID.AXIS_NOT_ASSIGNED)


# Every Execute FB of a program, driven through starts, holds, falls, an axis error and its
# reset: the compiled caller leaves out the calls that change nothing (`CALL_NEEDED`, with
# the `inline` pass), and every FB and the axis end each scan as with every call made.
CALLED_WHEN_NEEDED = """
PROGRAM Main
VAR
    Power : MC_Power;
    Home : MC_Home;
    Go : MC_MoveAbsolute;
    Sync : MC_SyncMoveAbsolute;
    Stop : MC_Stop;
    Reset : MC_Reset;
    DoHome, DoMove, DoSync, DoStop, DoReset : BOOL;
    Target : LREAL;
END_VAR
Power(Axis := Cyl1, Enable := TRUE);
Home(Axis := Cyl1, Execute := DoHome);
Go(Axis := Cyl1, Execute := DoMove, Position := Target, Velocity := 50.0, BufferMode := _mcAborting);
Sync(Axis := Cyl1, Execute := DoSync, Position := Target, BufferMode := _mcAborting);
Stop(Axis := Cyl1, Execute := DoStop, Deceleration := 50000.0, BufferMode := _mcAborting);
Reset(Axis := Cyl1, Execute := DoReset);
END_PROGRAM
"""

# (scans, the inputs set before them)
STEPS = [(3, {}), (2, {"DoHome": True}), (2, {"DoHome": False}),
         (5, {"DoMove": True, "Target": 5.0}), (2, {"DoMove": False}),
         (4, {"DoStop": True}), (3, {"DoStop": False}), (3, {}),
         (1, {"DoMove": True, "Target": 60.0}), (3, {"DoMove": False}),          # beyond the limit
         (2, {"DoReset": True}), (2, {"DoReset": False}),
         (2, {"DoReset": True}), (1, {"Reset.Done": False}),   # an output cleared from outside
         (1, {"DoReset": False}), (2, {"DoReset": True}), (2, {"DoReset": False}),
         (4, {"DoSync": True, "Target": 1.0}), (2, {"DoStop": True}), (2, {"DoSync": False}),
         (3, {"DoStop": False}), (20, {})]


def _fb_state(fb) -> tuple:
    variables = sorted((k, v) for k, v in vars(fb).items() if k.startswith("v_") and k != "v_AXIS")
    command = fb._command
    shown = None if command is None else tuple(getattr(command, f) for f in type(command).__slots__)
    return (type(fb).__name__, variables, fb._previous_execute, shown)


def _run_steps(monkeypatch, optimise: str, calls: list) -> list:
    from test_motion_st import AXIS, make_plc

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, task = make_plc(CALLED_WHEN_NEEDED, AXIS)
    instance = plc.controller.instances["Main"]
    axis = task.axis("Cyl1")
    states = []
    for scans, inputs in STEPS:
        for name, value in inputs.items():
            main[name] = value
        for _ in range(scans):
            before = len(calls)
            plc.run(1)
            fbs_after = [_fb_state(getattr(instance, "v_" + n)) for n in
                         ("HOME", "GO", "SYNC", "STOP", "RESET")]
            states.append((fbs_after, axis.state, axis.cmd_pos, axis.fault_code, len(calls) - before))
    return states


def counted_calls(monkeypatch, *classes) -> list:
    """The calls of `execute` of each class, by class name, as they happen."""
    calls = []
    for cls in classes:
        def counted(self, ctx, _execute=cls.execute):
            calls.append(type(self).__name__)
            _execute(self, ctx)
        monkeypatch.setattr(cls, "execute", counted)
    return calls


def test_a_call_that_would_change_nothing_is_left_out_and_nothing_else(monkeypatch):
    calls = counted_calls(monkeypatch, fbs.MC_Home, fbs.MC_MoveAbsolute, fbs.MC_SyncMoveAbsolute,
                          fbs.MC_Stop, fbs.MC_Reset)
    every_call = _run_steps(monkeypatch, "none", calls)
    needed_only = _run_steps(monkeypatch, "inline", calls)
    assert [s[:4] for s in needed_only] == [s[:4] for s in every_call]
    assert {s[4] for s in every_call} == {5}                     # five Execute FBs, every scan
    assert sum(s[4] for s in needed_only) < sum(s[4] for s in every_call) // 2
    assert needed_only[0][4] == 0 and needed_only[-1][4] == 0   # all idle: no call at all
    assert any(s[1] == 6 for s in every_call)                    # the axis error happened (ErrorStop)


# MC_Power and MC_SyncMoveAbsolute on two axes: the compiled caller runs each FB's HotPath in
# place of the call while the AXIS_REF is the one the FB resolved before (the `inline` pass).
# Driven through power on, a stream, an AXIS_REF whose Cfg names the other axis and then no
# axis (Error 16#5401), a re-execution while Busy (16#543B), an axis error and power off.
HOT_PATHS = """
PROGRAM Main
VAR
    Power : MC_Power;
    Sync : MC_SyncMoveAbsolute;
    Reset : MC_Reset;
    PowerOn, DoSync, DoReset : BOOL;
    Target : LREAL;
END_VAR
Power(Axis := Cyl1, Enable := PowerOn);
Sync(Axis := Cyl1, Execute := DoSync, Position := Target, BufferMode := _mcAborting);
Reset(Axis := Cyl1, Execute := DoReset);
Target := Target + 0.125;
END_PROGRAM
"""

# (scans, the inputs set before them, Cyl1.Cfg as (AxNo, AxEnable) or None to leave it)
HOT_STEPS = [(3, {"PowerOn": True}, None), (6, {"DoSync": True}, None), (2, {}, (1, True)),
             (2, {}, (0, True)), (2, {}, (0, False)), (2, {}, (0, True)),          # aborted: no axis
             (1, {"DoSync": False}, None), (3, {"DoSync": True}, None),
             (1, {"DoSync": False}, None), (2, {"DoSync": True}, None),            # a new edge: 16#543B
             (2, {"DoSync": False, "DoReset": True}, None), (2, {"DoReset": False}, None),
             (4, {"DoSync": True}, None), (3, {"PowerOn": False}, None), (3, {"PowerOn": True}, None),
             (1, {"DoSync": False}, None), (4, {"DoSync": True}, None)]


def _run_hot_steps(monkeypatch, optimise: str, calls: list, program: str = HOT_PATHS) -> list:
    from test_motion_st import AXIS, make_plc

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, task = make_plc(program, AXIS, dict(AXIS, name="Cyl2"))
    instance = plc.controller.instances["Main"]
    cfg = plc.controller.globals.v_CYL1.v_CFG
    states = []
    for scans, inputs, axis_cfg in HOT_STEPS:
        for name, value in inputs.items():
            main[name] = value
        if axis_cfg is not None:
            cfg.v_AXNO, cfg.v_AXENABLE = axis_cfg
        for _ in range(scans):
            before = len(calls)
            plc.run(1)
            power = instance.v_POWER
            fbs_after = [sorted((k, v) for k, v in vars(power).items() if k.startswith("v_") and k != "v_AXIS"),
                         _fb_state(instance.v_SYNC), _fb_state(instance.v_RESET)]
            axes = [(a.state, a.powered, a.power_requested, a.cmd_pos, a.fault_code) for a in task.axes]
            states.append((fbs_after, axes, len(calls) - before, power.v_ERRORID, instance.v_SYNC.v_ERRORID))
    return states


def test_the_hot_paths_run_in_place_of_the_call_do_what_the_call_does(monkeypatch):
    calls = counted_calls(monkeypatch, fbs.MC_Power, fbs.MC_SyncMoveAbsolute)
    every_call = _run_hot_steps(monkeypatch, "none", calls)
    in_place = _run_hot_steps(monkeypatch, "inline", calls)
    assert [s[:2] for s in in_place] == [s[:2] for s in every_call]
    assert {s[2] for s in every_call} == {2}                    # both FBs called every scan
    assert sum(s[2] for s in in_place) < sum(s[2] for s in every_call) // 2
    assert in_place[-1][2] == 0                                 # powered and streaming: no call
    assert {s[3] for s in every_call} == {0, ErrorID.AXIS_NOT_ASSIGNED}
    assert ErrorID.RE_EXECUTION_DISABLED in {s[4] for s in every_call}
    assert any(axes[1][1] for _, axes, *_ in every_call)        # Cyl2 powered while Cfg named it


@pytest.fixture()
def hot_paths_built_in_the_test(monkeypatch):
    """MC_Power's and MC_SyncMoveAbsolute's `execute` built again from their HotPath inside the
    test: the module builds them at import, before a test (or a mutation tool) can change
    `HotPath.install`, so the tests above alone cannot tell a broken `install` (restored after)."""
    for cls in (fbs.MC_Power, fbs.MC_SyncMoveAbsolute):
        built_at_import = cls.execute
        monkeypatch.setattr(cls, "execute", built_at_import)
        cls.HOT_PATH.install(cls)
        assert cls.execute is not built_at_import


def test_mc_power_built_from_its_hot_path_in_the_test_follows_its_axis_ref(hot_paths_built_in_the_test):
    test_mc_power_follows_the_axis_ref_it_is_given_every_call()


def test_the_calls_built_from_the_hot_paths_in_the_test_do_what_the_hot_paths_do(
        hot_paths_built_in_the_test, monkeypatch):
    test_the_hot_paths_run_in_place_of_the_call_do_what_the_call_does(monkeypatch)


def test_an_execute_fb_that_writes_its_own_execute_keeps_it_and_gets_the_idle_rules():
    # `_spell_out_idle_call` runs as each class is made (module import for the library's FBs):
    # a class made here shows what it does with a class that writes its own `execute`.
    class Logged(fbs.MC_Stop):
        def execute(self, ctx):
            self._execute_rules(ctx)

    class Plain(fbs.MC_Stop):
        pass

    assert Logged.execute.__qualname__.endswith("Logged.execute")
    assert Plain.execute is Plain._execute_rules
    assert Logged._execute_rules.__name__ == "_execute_rules"


def test_the_inputs_stored_from_names_are_read_back_by_name(monkeypatch):
    """Inputs given from locals of the generated body (an AXIS_REF global, VAR_TEMPs): the
    hot paths' and the rest test's reads of Axis, Enable and Execute are those names
    (compiler/calls.py `_read_back`), scan by scan the same as every call made."""
    from test_motion_st import AXIS, make_plc

    # The inputs given from VAR_TEMP variables: locals of the generated body.
    program = HOT_PATHS.replace("END_VAR\n", "END_VAR\nVAR_TEMP Enabled, Go, Resetting : BOOL; END_VAR\n"
                                "Enabled := PowerOn; Go := DoSync; Resetting := DoReset;\n")
    for given, temp in (("Enable := PowerOn", "Enable := Enabled"), ("Execute := DoSync", "Execute := Go"),
                        ("Execute := DoReset", "Execute := Resetting")):
        program = program.replace(given, temp)
    calls = counted_calls(monkeypatch, fbs.MC_Power, fbs.MC_SyncMoveAbsolute)
    every_call = _run_hot_steps(monkeypatch, "none", calls, program)
    all_passes = _run_hot_steps(monkeypatch, "all", calls, program)
    assert [s[:2] for s in all_passes] == [s[:2] for s in every_call]
    assert sum(s[2] for s in all_passes) < sum(s[2] for s in every_call) // 2
    plc, _, _ = make_plc(program, AXIS, dict(AXIS, name="Cyl2"))
    source = plc.controller.compiled.python_sources["MAIN"]
    assert "if v_CYL1 is " in source and ".v_AXIS is " not in source
    assert "True if v_ENABLED else False" in source and "or not v_GO)" in source
    assert "if v_RESETTING or " in source


# MC_SyncMoveAbsolute's hot path takes Position as the command's target, a Python float.
# Given at the call site, the compiled store has just made it one (an INT through float(), an
# LREAL as the float it is), so the path takes it as it is; not given, it holds whatever was
# stored (here an int, written by Python), and the path makes it a float.
POSITIONS = """
PROGRAM Main
VAR
    Power1, Power2, Power3 : MC_Power;
    Counted : MC_SyncMoveAbsolute;
    Ramped : MC_SyncMoveAbsolute;
    Held : MC_SyncMoveAbsolute;
    Steps : INT;
    Ramp : LREAL;
END_VAR
Power1(Axis := Cyl1, Enable := TRUE);
Power2(Axis := Cyl2, Enable := TRUE);
Power3(Axis := Cyl3, Enable := TRUE);
IF Power1.Status AND Power2.Status AND Power3.Status THEN
    Steps := Steps + 1;
    Ramp := Ramp + 0.25;
    Counted(Axis := Cyl1, Execute := TRUE, Position := Steps);
    Ramped(Axis := Cyl2, Execute := TRUE, Position := Ramp);
    Held(Axis := Cyl3, Execute := TRUE);
END_IF;
END_PROGRAM
"""


@pytest.mark.parametrize("optimise", ["none", "all"])
def test_the_sync_hot_path_takes_a_position_stored_as_a_float_as_it_is(monkeypatch, optimise):
    from test_motion_st import AXIS, make_plc

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, _ = make_plc(POSITIONS, *(dict(AXIS, name=f"Cyl{k}") for k in (1, 2, 3)))
    instance = plc.controller.instances["Main"]
    instance.v_HELD.v_POSITION = 0
    for scan in range(1, 9):
        plc.run(1)
        if scan == 5:
            instance.v_HELD.v_POSITION = 2                  # an int, as Python may store one
    steps = main["Steps"]
    assert steps >= 5                                       # powered in the first scans
    targets = [instance.v_COUNTED._command.target, instance.v_RAMPED._command.target,
               instance.v_HELD._command.target]
    assert targets == [float(steps), 0.25 * steps, 2.0]
    assert [type(target) for target in targets] == [float] * 3
    if optimise == "all":
        source = plc.controller.compiled.python_sources["MAIN"]
        assert source.count("_type(") == 1                  # Held's Position alone is tested
