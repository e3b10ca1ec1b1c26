"""A bench for the motion FBs without the ST compiler: FB instances built from
their declarations, AXIS_REF values as plain objects, one scan = feedback in,
the calls the test makes, motion processing.  (End-to-end tests through ST
live in test_motion_st.py.)"""

from __future__ import annotations

import re
from types import SimpleNamespace

from st_runtime.motion import MotionTask
from st_runtime.motion.axis_config import AxisConfig
from st_runtime.motion.types import AXIS_REF_SOURCE

PERIOD_S = 0.001

_DEFAULTS = {"BOOL": False, "WORD": 0, "UINT": 0, "LREAL": 0.0}
_SECTION = re.compile(r"VAR(?:_INPUT|_OUTPUT|_IN_OUT)?\s*(.*?)END_VAR", re.S)
_DECL = re.compile(r"(\w+)\s*:\s*(\w+)\s*;")


def make_fb(cls):
    """An instance of native FB `cls`, variables at their declared defaults."""
    # `execute` named in the subclass: else _ExecuteFB.__init_subclass__ gives it the general
    # rules, and MC_SyncMoveAbsolute's own per-scan path (the one ST runs) would go untested.
    bench_class = type(cls.__name__ + "Bench", (cls,), {"execute": cls.execute})
    pairs = []
    for section in _SECTION.findall(cls.DECLARATION):
        for name, type_name in _DECL.findall(section):
            value = None if type_name == "AXIS_REF" else _DEFAULTS.get(type_name.upper(), 0)
            pairs.append(("v_" + name.upper(), lambda value=value: value))
    bench_class.set_initializers(pairs)
    return bench_class()


_STRUCT = re.compile(r"(\w+)\s*:\s*STRUCT(.*?)END_STRUCT", re.S)


def _struct_layouts() -> dict[str, list[tuple[str, str]]]:
    """Struct name -> [(member, type)] from the AXIS_REF declaration itself,
    so the bench always has exactly the members ST sees."""
    return {name.upper(): _DECL.findall(body) for name, body in _STRUCT.findall(AXIS_REF_SOURCE)}


_LAYOUTS = _struct_layouts()


def _struct_value(type_name: str):
    members = {}
    for name, member_type in _LAYOUTS[type_name.upper()]:
        if member_type.upper() in _LAYOUTS:
            members["v_" + name.upper()] = _struct_value(member_type)
        else:
            members["v_" + name.upper()] = _DEFAULTS.get(member_type.upper(), 0)
    return SimpleNamespace(**members)


def make_axis_ref():
    return _struct_value("AXIS_REF")


class Rig:
    def __init__(self, *configs: AxisConfig):
        self.task = MotionTask(configs)
        self.refs = {c.name: make_axis_ref() for c in configs}
        self.task.bind(lambda name: self.refs[name])
        self.ctx = SimpleNamespace(motion=self.task, now_ns=0, scan=0, period_ns=int(PERIOD_S * 1e9))

    def ref(self, name: str = "Ax"):
        return self.refs[name]

    def call(self, fb, axis: str = "Ax", **inputs) -> None:
        fb.v_AXIS = self.refs[axis]
        for name, value in inputs.items():
            setattr(fb, "v_" + name.upper(), value)
        fb.execute(self.ctx)

    def scan(self, *calls) -> None:
        """One primary period: feedback in, `calls` (zero-argument), motion processing."""
        self.ctx.scan += 1
        self.task.feedback_in()
        for call in calls:
            call()
        self.task.process(PERIOD_S)
        self.ctx.now_ns += self.ctx.period_ns
