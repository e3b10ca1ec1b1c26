"""An idle Execute FB found at rest is not tested again while nothing can have touched it.

The compiled caller of MC_Stop, MC_Reset, MC_Home and MC_MoveAbsolute (the `inline` pass)
makes the eight-member idle test (`CALL_NEEDED`) once, notes the FB at rest under the
controller's `ScanContext.seal` and from then on tests only Execute and that note.  The note
ends with the FB's own next call and with a new seal: at every `run` or `scan` call, and in
every scan when an I/O hook not added as quiet or an observer that writes runs (they could
store into an FB's outputs; ST cannot).  Each FB and the axis must end every scan as they do
when every call is made (optimisations off): through Execute edges, a final output held and
cleared, an output written from outside between runs, by a hook and by an observer."""

import pytest

from st_runtime.motion import fbs
from st_runtime.native import NativeFB

from test_motion_idle_calls import CALLED_WHEN_NEEDED, STEPS, _fb_state, counted_calls

EXECUTE_FBS = ("HOME", "GO", "SYNC", "STOP", "RESET")


def _run_in_runs(monkeypatch, optimise: str, calls: list, meddle=None) -> list:
    """The program of test_motion_idle_calls driven through its STEPS, each step one `run` of
    several scans; the state after every scan, recorded by a read-only observer.  `meddle(scan,
    instance)`: what a non-quiet after hook does in each scan."""
    from test_motion_st import AXIS, make_plc

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, task = make_plc(CALLED_WHEN_NEEDED, AXIS)
    controller = plc.controller
    instance = controller.instances["Main"]
    axis = task.axis("Cyl1")
    states = []

    def record(_controller):
        states.append(([_fb_state(getattr(instance, "v_" + name)) for name in EXECUTE_FBS],
                       axis.state, axis.cmd_pos, axis.fault_code, len(calls)))

    controller.add_observer(record, reads_only=True)
    if meddle is not None:
        controller.add_io_hook(after=lambda ctx: meddle(ctx.scan, instance))
    for scans, inputs in STEPS:
        for name, value in inputs.items():
            main[name] = value
        plc.run(scans)
    return states


def test_an_fb_noted_at_rest_in_a_run_ends_every_scan_as_with_every_call(monkeypatch):
    calls = counted_calls(monkeypatch, fbs.MC_Home, fbs.MC_MoveAbsolute, fbs.MC_SyncMoveAbsolute,
                          fbs.MC_Stop, fbs.MC_Reset)
    every_call = _run_in_runs(monkeypatch, "none", calls)
    calls.clear()
    noted = _run_in_runs(monkeypatch, "inline", calls)
    assert [s[:4] for s in noted] == [s[:4] for s in every_call]
    assert len(calls) < len(every_call) * 5 // 2
    assert any(s[1] == 6 for s in every_call)                    # the axis error happened (ErrorStop)


def test_a_run_keeps_its_seal_and_an_fb_at_rest_is_noted_under_it(monkeypatch):
    from test_motion_st import AXIS, make_plc

    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "inline")
    plc, _, _ = make_plc(CALLED_WHEN_NEEDED, AXIS)
    controller = plc.controller
    ctx, stop = controller.ctx, controller.instances["Main"].v_STOP
    seals = []
    controller.add_observer(lambda _: seals.append(ctx.seal), reads_only=True)
    plc.run(3)
    assert seals[0] is seals[1] is seals[2]                      # the motion task's hooks are quiet
    assert stop._at_rest is seals[2]                             # noted at rest in the first scan
    assert ctx.seal is not seals[2]                              # the caller's code runs next
    plc.run(1)
    controller.scan()
    assert len({id(seal) for seal in seals}) == 3                # a new one for each call
    controller.add_io_hook(before=lambda ctx: None)              # not quiet: a new seal every scan
    plc.run(2)
    assert seals[-1] is not seals[-2]
    controller.add_observer(lambda _: None)                      # it may write: a new seal every scan
    plc.run(2)
    assert seals[-1] is not seals[-2]


@pytest.mark.parametrize("where", ["between runs", "in a hook", "in an observer"])
def test_an_output_written_from_outside_an_fb_at_rest_is_cleared_by_its_next_call(monkeypatch, where):
    """Reset.Done and Stop.ErrorID set from Python while both FBs are idle and at rest: the next
    call clears them (PLCopen's output rules), with the notes as with every call made."""
    from test_motion_st import AXIS, make_plc

    noted = []

    def meddle(instance):
        noted.append(instance.v_RESET._at_rest is not None and instance.v_STOP._at_rest is not None)
        instance.v_RESET.v_DONE = True
        instance.v_STOP.v_ERRORID = 0x5401

    results = []
    for optimise in ("none", "inline"):
        monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
        plc, _, _ = make_plc(CALLED_WHEN_NEEDED, AXIS)
        controller = plc.controller
        instance = controller.instances["Main"]
        shown = []
        controller.add_observer(lambda _: shown.append((instance.v_RESET.v_DONE, instance.v_STOP.v_ERRORID)),
                                reads_only=True)
        if where == "in a hook":
            controller.add_io_hook(after=lambda ctx: ctx.scan == 2 and meddle(instance))
        elif where == "in an observer":
            controller.add_observer(lambda c: c.scan_count == 2 and meddle(instance))
        plc.run(4)
        if where == "between runs":
            meddle(instance)
        plc.run(3)
        results.append(shown)
    assert noted == [False, True]           # with every call made, nothing is noted
    assert results[0] == results[1] and results[0][-1] == (False, 0)
    assert len(results[0]) == 7


def test_only_an_fb_whose_every_call_goes_through_the_idle_rules_is_noted_at_rest():
    # `_execute_rules` forgets the note; a class with a HotPath, or one that writes its own
    # `execute`, may act without it, so its caller makes the whole idle test every scan.
    for fb_class in (fbs.MC_Reset, fbs.MC_Home, fbs.MC_Stop, fbs.MC_MoveAbsolute):
        assert fb_class.REST is not None and fb_class.CALL_NEEDED
    assert fbs.MC_SyncMoveAbsolute.REST is None and fbs.MC_Power.REST is None
    assert NativeFB.REST is None

    class Logged(fbs.MC_Stop):
        def execute(self, ctx):
            self._execute_rules(ctx)

    assert Logged.REST is None
    assert type("Plain", (fbs.MC_Stop,), {}).REST is fbs.MC_Stop.REST


# Execute rises and falls inside one run: each FB wakes on its edge and is noted at rest again.
PULSES = """
PROGRAM Main
VAR
    Power : MC_Power;
    Stop : MC_Stop;
    Reset : MC_Reset;
    Count : INT;
END_VAR
Count := Count + 1;
Power(Axis := Cyl1, Enable := TRUE);
Reset(Axis := Cyl1, Execute := (Count MOD 7) = 3);
Stop(Axis := Cyl1, Execute := (Count MOD 11) >= 5 AND (Count MOD 11) < 8, Deceleration := 50000.0,
     BufferMode := _mcAborting);
END_PROGRAM
"""


def test_an_fb_at_rest_wakes_on_an_edge_inside_a_run_as_with_every_call(monkeypatch):
    from test_motion_st import AXIS, make_plc

    calls = counted_calls(monkeypatch, fbs.MC_Stop, fbs.MC_Reset)
    runs = []
    for optimise in ("none", "inline"):
        monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
        plc, _, task = make_plc(PULSES, AXIS)
        instance, axis = plc.controller.instances["Main"], task.axis("Cyl1")
        states = []
        plc.controller.add_observer(lambda _: states.append(
            (_fb_state(instance.v_STOP), _fb_state(instance.v_RESET), axis.state, len(calls))), reads_only=True)
        plc.run(80)
        runs.append(states)
        calls.clear()
    assert [s[:3] for s in runs[1]] == [s[:3] for s in runs[0]]
    assert runs[0][-1][3] == 160 and runs[1][-1][3] < 80        # most calls left out
    done = [(dict(stop[1])["v_DONE"], dict(reset[1])["v_DONE"]) for stop, reset, *_ in runs[0]]
    assert (True, False) in done and (False, True) in done      # both ended commands, and let go
