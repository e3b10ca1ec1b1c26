"""Trace: paths into structs, arrays and FB instances; CSV; NumPy."""

import io
import math

import numpy as np
import pytest

from st_runtime import types as T
from st_runtime.symbols import Symbol
from st_runtime.trace import Trace, TracePathError, parse_path, read_csv, resolve_in_objects

MS = 1_000_000

POINT = T.StructType("Point", {"X": ("X", T.LREAL), "Y": ("Y", T.LREAL)})
TIMER = T.FBType("TON", {
    "IN": Symbol("IN", T.BOOL, "VAR_INPUT"),
    "PT": Symbol("PT", T.TIME, "VAR_INPUT"),
    "Q": Symbol("Q", T.BOOL, "VAR_OUTPUT"),
    "ET": Symbol("ET", T.TIME, "VAR_OUTPUT"),
})


class Point:
    _st_vars = {"X": ("X", T.LREAL), "Y": ("Y", T.LREAL)}

    def __init__(self, x=0.0, y=0.0):
        self.v_X, self.v_Y = x, y


class Timer:
    _st_vars = {"IN": ("IN", T.BOOL), "PT": ("PT", T.TIME), "Q": ("Q", T.BOOL), "ET": ("ET", T.TIME)}

    def __init__(self):
        self.v_IN, self.v_PT, self.v_Q, self.v_ET = False, 0, False, 0


class Program:
    """Stands in for a compiled PROGRAM instance (same layout convention)."""

    _st_vars = {
        "COUNT": ("Count", T.INT),
        "SPEED": ("Speed", T.REAL),
        "POSE": ("Pose", T.ArrayType(((1, 3),), T.LREAL)),
        "M": ("m", T.ArrayType(((1, 2), (0, 1)), T.DINT)),
        "PTS": ("Pts", T.ArrayType(((0, 1),), POINT)),
        "TIMER": ("Timer", TIMER),
        "NAME": ("Name", T.StringType(10)),
    }

    def __init__(self):
        self.v_COUNT = 0
        self.v_SPEED = 0.0
        self.v_POSE = [0.0, 0.0, 0.0]
        self.v_M = [0, 0, 0, 0]
        self.v_PTS = [Point(), Point()]
        self.v_TIMER = Timer()
        self.v_NAME = "a,b"


def test_parse_path():
    assert parse_path("a.b[1, 2].c") == [("name", "a"), ("name", "b"), ("index", (1, 2)), ("name", "c")]
    assert parse_path("x[-3]") == [("name", "x"), ("index", (-3,))]
    for bad in ("1x", "a..b", "a[i]", "a[1"):
        with pytest.raises(TracePathError):
            parse_path(bad)


def test_resolve_in_objects_follows_layouts_and_bounds():
    prog = Program()
    prog.v_M[3] = 42                   # m[2,1]: row 2 (offset 1) * 2 + col 1 = 3
    root, get, t, text = resolve_in_objects("M[2, 1]", [prog])
    assert get(root) == 42 and t == T.DINT and text == "m[2,1]"
    prog.v_PTS[1].v_Y = 7.5
    root, get, t, text = resolve_in_objects("pts[1].y", [prog])
    assert get(root) == 7.5 and text == "Pts[1].Y"
    with pytest.raises(TracePathError, match="outside 1..3"):
        resolve_in_objects("Pose[4]", [prog])
    with pytest.raises(TracePathError, match="no member 'Z'"):
        resolve_in_objects("Pts[0].Z", [prog])
    with pytest.raises(TracePathError, match="no variable named 'nope'"):
        resolve_in_objects("nope", [prog])
    glob = type("Globals", (), {"_st_vars": {"G": ("G", T.BOOL)}})()
    glob.v_G = True
    root, get, _, _ = resolve_in_objects("g", [prog, glob])      # second root
    assert get(root) is True


def test_columns_expand_arrays_structs_and_fbs():
    trace = Trace.for_objects(["Count", "Pose", "m", "Pts", "Timer", "Pose[2]"], [Program()])
    assert trace.column_names == [
        "Count", "Pose[1]", "Pose[2]", "Pose[3]",
        "m[1,0]", "m[1,1]", "m[2,0]", "m[2,1]",
        "Pts[0].X", "Pts[0].Y", "Pts[1].X", "Pts[1].Y",
        "Timer.IN", "Timer.PT", "Timer.Q", "Timer.ET", "Pose[2]",
    ]


def _run(prog, trace, scans=3):
    for k in range(1, scans + 1):
        prog.v_COUNT = k
        prog.v_SPEED = 0.5 * k
        prog.v_POSE[0] = 1.25 * k
        prog.v_M[1] = -k
        prog.v_PTS[1].v_X = k / 4
        prog.v_TIMER.v_Q = k >= 2
        prog.v_TIMER.v_ET = k * MS
        trace.sample((k - 1) * MS, k)


def test_sampling_and_numpy():
    prog = Program()
    trace = Trace.for_objects(["Count", "Speed", "Pose", "m[1,1]", "Pts[1].X", "Timer"], [prog])
    _run(prog, trace)
    data = trace.to_numpy()
    np.testing.assert_array_equal(data["time"], [0.0, 0.001, 0.002])
    np.testing.assert_array_equal(data["scan"], [1, 2, 3])
    np.testing.assert_array_equal(data["Count"], [1, 2, 3])
    assert data["Count"].dtype == np.int64
    np.testing.assert_array_equal(data["Pose[1]"], [1.25, 2.5, 3.75])
    np.testing.assert_array_equal(data["m[1,1]"], [-1, -2, -3])
    np.testing.assert_array_equal(data["Pts[1].X"], [0.25, 0.5, 0.75])
    np.testing.assert_array_equal(data["Timer.Q"], [False, True, True])
    assert data["Timer.Q"].dtype == bool
    np.testing.assert_array_equal(data["Timer.ET"], [MS, 2 * MS, 3 * MS])


def test_csv_layout_and_round_trip(tmp_path):
    prog = Program()
    trace = Trace.for_objects(["Count", "Speed", "Timer", "Name"], [prog])
    _run(prog, trace)
    prog.v_SPEED = math.nan
    trace.sample(3 * MS, 4)
    text = trace.to_csv_text()
    lines = text.splitlines()
    assert lines[0] == "time_s,scan,Count,Speed,Timer.IN,Timer.PT,Timer.Q,Timer.ET,Name"
    assert lines[1] == '0,1,1,0.5,FALSE,T#0s,FALSE,T#1ms,"a,b"'
    assert lines[2] == '0.001,2,2,1.0,FALSE,T#0s,TRUE,T#2ms,"a,b"'
    path = tmp_path / "trace.csv"
    trace.write_csv(path)
    back = read_csv(path)
    np.testing.assert_array_equal(back["time_ns"], [0, MS, 2 * MS, 3 * MS])
    np.testing.assert_array_equal(back["scan"], [1, 2, 3, 4])
    np.testing.assert_array_equal(back["Count"], [1, 2, 3, 3])
    assert back["Timer.Q"].dtype == bool
    np.testing.assert_array_equal(back["Timer.ET"], [MS, 2 * MS, 3 * MS, 3 * MS])
    assert back["Speed"][:3].tolist() == [0.5, 1.0, 1.5] and math.isnan(back["Speed"][3])
    assert back["Name"].tolist() == ["a,b"] * 4
    mine = trace.to_numpy()
    for name in trace.column_names:
        if name != "Speed":
            np.testing.assert_array_equal(back[name], mine[name])


def test_generic_resolver_with_and_without_types():
    state = {"a": [1, 2, 3], "x": 2.5}
    arr = T.ArrayType(((-1, 1),), T.INT)
    trace = Trace(["a", "x"], state.__getitem__, {"a": arr, "x": T.LREAL}.get)
    assert trace.column_names == ["a[-1]", "a[0]", "a[1]", "x"]
    trace.sample(0, 1)
    state["a"][0] = 9
    trace.sample(MS, 2)
    np.testing.assert_array_equal(trace.to_numpy()["a[-1]"], [1, 9])
    untyped = Trace(["a"], state.__getitem__)
    assert untyped.column_names == ["a[0]", "a[1]", "a[2]"]


def test_read_csv_rejects_other_files():
    with pytest.raises(ValueError, match="time_s,scan"):
        read_csv(io.StringIO("a,b\n1,2\n"))


def test_long_trace_is_cheap():
    # 20,000 samples of 10 columns: a handful of list operations per sample.
    prog = Program()
    trace = Trace.for_objects(["Count", "Pose", "Pts", "Timer.Q"], [prog])
    for k in range(20_000):
        prog.v_COUNT = k % 100
        trace.sample(k * MS, k + 1)
    data = trace.to_numpy()
    assert len(data["Count"]) == 20_000 and data["Count"][-1] == 19_999 % 100
