"""An axis FB keeps the axis it resolved while its AXIS_REF value is the same object and
nothing wrote that value's Cfg (st_runtime/motion/binding.py): a write to the Cfg of the
same object, by ST or by Python, and a Cfg object swapped in from Python make it resolve
again, so it always drives the axis `Cfg.AxNo` names (W508: the FB finds its axis through
the axis variable), with and without the compiled caller's hot paths."""

import pytest

from st_runtime.motion import binding, fbs
from st_runtime.motion.error_ids import ErrorID

from test_motion_st import AXIS, make_plc

# `Local := Cyl2` copies Cyl2 into the same Local object (struct assignment keeps identities),
# so the FB is given the same AXIS_REF value while its Cfg now names the other axis.
FOLLOWS_LOCAL = """
PROGRAM Main
VAR
    Power : MC_Power;
    Local : AXIS_REF;
    UseSecond, Detach : BOOL;
END_VAR
IF UseSecond THEN Local := Cyl2; ELSE Local := Cyl1; END_IF;
IF Detach THEN Local.Cfg.AxEnable := FALSE; END_IF;
Power(Axis := Local, Enable := TRUE);
END_PROGRAM
"""


def _run_local(monkeypatch, optimise: str) -> list:
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, task = make_plc(FOLLOWS_LOCAL, AXIS, dict(AXIS, name="Cyl2"))
    seen = []
    for inputs in ({}, {}, {"UseSecond": True}, {}, {"Detach": True}, {"Detach": False}, {}):
        for name, value in inputs.items():
            main[name] = value
        plc.run(1)
        seen.append(([axis.power_requested for axis in task.axes], [axis.powered for axis in task.axes],
                     main["Power.Status"], main["Power.Error"], main["Power.ErrorID"]))
    return seen


@pytest.mark.parametrize("optimise", ["none", "inline"])
def test_an_fb_given_the_same_axis_ref_follows_what_its_cfg_names(monkeypatch, optimise):
    seen = _run_local(monkeypatch, optimise)
    # Enable TRUE on Cyl1: the servo switches at the motion processing, Status one scan later.
    assert seen[0] == ([True, False], [True, False], False, False, 0)
    assert seen[1] == ([True, False], [True, False], True, False, 0)
    # Local now names Cyl2 (AxNo 1): MC_Power requests power for Cyl2; its Status follows it.
    assert seen[2] == ([True, True], [True, True], False, False, 0)
    assert seen[3][2:] == (True, False, 0)
    # AxEnable FALSE: no axis, Error 16#5401 while Enable (W508); the same object again after.
    assert seen[4][2:] == (False, True, ErrorID.AXIS_NOT_ASSIGNED)
    assert seen[5][2:] == (True, False, 0) and seen[6][2:] == (True, False, 0)


def test_a_cfg_object_swapped_in_from_python_is_followed(monkeypatch):
    plc, main, task = make_plc(FOLLOWS_LOCAL.replace("Local := Cyl1;", ";"), AXIS, dict(AXIS, name="Cyl2"))
    local = plc.controller.instances["Main"].v_LOCAL
    local.v_CFG.v_AXNO, local.v_CFG.v_AXENABLE = 0, True
    plc.run(2)
    assert [axis.power_requested for axis in task.axes] == [True, False]
    local.v_CFG = plc.controller.globals.v_CYL2.v_CFG       # the object itself: AxNo 1
    plc.run(1)
    assert [axis.power_requested for axis in task.axes] == [True, True]


def test_a_watched_struct_reads_as_before():
    """The watched value keeps its class's name and members: what reads a struct member by
    member (STObject._assign, the values' text, the scan fingerprints) sees no change."""
    plc, main, task = make_plc(FOLLOWS_LOCAL, AXIS, dict(AXIS, name="Cyl2"))
    ref = plc.controller.globals.v_CYL1
    cfg_class = type(ref.v_CFG)
    kinds = {name: (type(value).__name__, type(value).__qualname__, type(value).__slots__)
             for name, value in (("ref", ref), ("cfg", ref.v_CFG))}
    plc.run(1)                                              # MC_Power resolves Local
    local = plc.controller.instances["Main"].v_LOCAL
    assert type(local.v_CFG).__setattr__ is binding._store_and_unbind    # watched now
    assert {name: (type(value).__name__, type(value).__qualname__, type(value).__slots__)
            for name, value in (("ref", ref), ("cfg", ref.v_CFG))} == kinds
    # One watched subclass per struct class, made once: Cyl1's and Local's are the same.
    assert type(ref) is not type(local)                     # Cyl1 itself is not watched yet
    assert binding.hold(plc.controller.instances["Main"].v_POWER, ref)
    assert type(ref) is type(local) and type(ref.v_CFG) is type(local.v_CFG)
    local._assign(plc.controller.globals.v_CYL2)
    assert (local.v_CFG.v_AXNO, local.v_CFG.v_AXENABLE) == (1, True)
    assert type(local.v_CFG).__mro__[1] is cfg_class


def test_values_that_cannot_be_watched_are_resolved_every_call():
    """A stand-in that is no ST struct (the FB bench's) is never held: the FB resolves it on
    every call, as if each call were the first."""
    from motion_rig import Rig, make_fb
    from test_motion_fbs import axis_config

    rig = Rig(axis_config(name="A0"), axis_config(name="A1"))
    power = make_fb(fbs.MC_Power)
    rig.call(power, "A0", Enable=True)
    assert power._bound_ref is fbs._UNBOUND and not binding.hold(power, rig.ref("A0"))
    assert rig.task.axes[0].power_requested


def test_a_copy_of_the_same_values_every_scan_keeps_the_binding(monkeypatch):
    """`Local := Cyl1` every scan stores the values Local holds: the FB is not resolved again."""
    resolved = []
    resolve = fbs.resolve_axis
    monkeypatch.setattr(fbs, "resolve_axis", lambda ref, ctx: resolved.append(ref) or resolve(ref, ctx))
    plc, main, task = make_plc(FOLLOWS_LOCAL, AXIS, dict(AXIS, name="Cyl2"))
    plc.run(5)
    assert len(resolved) == 1
    main["UseSecond"] = True                              # other values: resolved once more
    plc.run(5)
    assert len(resolved) == 2 and task.axes[1].powered
