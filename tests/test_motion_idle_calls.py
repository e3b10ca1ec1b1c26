"""The call with Execute FALSE after a command ended: its final output goes (PLCopen's output
rules, st_runtime/motion/fbs.py): every final output of MC_Reset and MC_Stop, which answer an
idle call on a short path, is held while Execute stays TRUE and cleared by the first call
with Execute FALSE, ErrorID with it."""

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
