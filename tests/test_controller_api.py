"""The Python API: load, instantiate, set, scan, read, call (mirrors the CLI)."""

from __future__ import annotations

import pytest

import st_runtime
from st_runtime import LoadError, load, load_text

SOURCE = """
TYPE Limits : STRUCT lo : LREAL := -1.0; hi : LREAL := 1.0; END_STRUCT; END_TYPE
VAR_GLOBAL Gain : LREAL := 2.0; END_VAR
PROGRAM Main
VAR
  input : ARRAY[1..3] OF LREAL;
  output : ARRAY[1..3] OF LREAL;
  lim : Limits;
  hold : TIME;
  i : INT;
END_VAR
VAR_EXTERNAL Gain : LREAL; END_VAR
FOR i := 1 TO 3 DO
  output[i] := LIMIT(lim.lo, input[i] * Gain, lim.hi);
END_FOR;
hold := hold + T#1ms;
END_PROGRAM
FUNCTION_BLOCK Ramp
VAR_INPUT target : LREAL; step : LREAL := 0.5; END_VAR
VAR_OUTPUT value : LREAL; done : BOOL; END_VAR
IF value < target THEN value := MIN(value + step, target); END_IF;
done := value >= target;
END_FUNCTION_BLOCK
FUNCTION Hyp : LREAL
VAR_INPUT a, b : LREAL; END_VAR
Hyp := SQRT(a * a + b * b);
END_FUNCTION
"""


def test_set_scan_read_with_json_values():
    plc = load_text(SOURCE).controller(period="1ms")
    main = plc.add_program("Main")
    main["input"] = [0.25, -3, 1]
    main["lim"] = {"hi": 0.75}
    main["lim.lo"] = -2.5
    main["hold"] = "T#1s"
    plc.globals["Gain"] = 4.0
    assert plc.run(2) == 2
    assert main["output"] == [0.75, -2.5, 0.75]
    assert main["lim"] == {"lo": -2.5, "hi": 0.75}
    assert main["hold"] == "T#1s2ms"
    assert main["input[2]"] == -3.0
    assert main.raw("hold") == 1_002_000_000
    assert plc.now_ns == 2_000_000
    assert set(main.to_json()) == {"input", "output", "lim", "hold", "i"}


def test_bad_paths_and_values_raise_clear_errors():
    plc = load_text(SOURCE).controller()
    main = plc.add_program("Main")
    with pytest.raises(KeyError, match="no variable"):
        main["nothing"]
    with pytest.raises(KeyError, match="out of bounds"):
        main["input[4]"]
    with pytest.raises(ValueError):
        main["input"] = [1, 2]
    with pytest.raises(KeyError):
        plc.add_program("Ramp")


def test_constants_cannot_be_set():
    src = "PROGRAM Main\nVAR CONSTANT t : ARRAY[1..2] OF INT := [1, 2]; END_VAR\nVAR x : INT; END_VAR\nx := t[2];\nEND_PROGRAM\n"
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    with pytest.raises(KeyError, match="CONSTANT"):
        main["t"] = [5, 6]
    with pytest.raises(KeyError, match="CONSTANT"):
        main["t[1]"] = 5
    plc.run(1)
    assert main["x"] == 2


def test_project_call_function_and_fb():
    project = load_text(SOURCE)
    result = project.call("Hyp", {"a": 3, "b": 4})
    assert result["outputs"] == {"return": 5.0, "cycles": 1} and result["faults"] == []
    result = project.call("Ramp", {"target": 2.0}, until="done")
    assert result["outputs"] == {"value": 2.0, "done": True, "cycles": 4}
    assert result["reached"] is True


def test_load_reports_diagnostics(tmp_path):
    (tmp_path / "a.st").write_text("PROGRAM P\nVAR x : INT; END_VAR\nx := 1.5;\nEND_PROGRAM\n")
    with pytest.raises(LoadError) as info:
        load([tmp_path])
    assert any(d.is_error for d in info.value.diagnostics)
    assert "a.st:3:" in info.value.render()


def test_load_directory_and_run(tmp_path):
    (tmp_path / "main.st").write_text(SOURCE)
    plc = load([tmp_path]).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["hold"] == "T#1ms"


def test_package_exports_the_api():
    assert st_runtime.load is load and st_runtime.load_text is load_text
    assert {"Controller", "FaultRecord", "STFault", "Project", "Plc"} <= set(st_runtime.__all__)


def test_each_controller_has_its_own_globals():
    project = load_text(SOURCE)
    one, two = project.controller(), project.controller()
    one.globals["Gain"] = 10.0
    assert two.globals["Gain"] == 2.0
    a, b = one.add_program("Main"), two.add_program("Main")
    a["input"] = [0.1, 0.1, 0.1]
    b["input"] = [0.1, 0.1, 0.1]
    one.run(1)
    two.run(1)
    assert a["output"] == [1.0, 1.0, 1.0] and b["output"] == [0.2, 0.2, 0.2]


FB_WITH_TEMP = """
FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT y : INT; END_VAR
VAR_TEMP t : INT; END_VAR
t := x * 2;
y := y + t;
END_FUNCTION_BLOCK
PROGRAM Main
VAR a : Acc; pair : ARRAY[1..2] OF Acc; END_VAR
a(x := 3);
pair[2](x := 1);
END_PROGRAM
"""


def test_one_json_walk_for_fb_instances_with_temps():
    # Two scans: y = 0 + 2*3 + 2*3 = 12 for a, 2 + 2 = 4 for pair[2].  A
    # VAR_TEMP lives only during a call: it is no member in JSON or a trace.
    from st_runtime.values import to_json

    project = load_text(FB_WITH_TEMP)
    plc = project.controller()
    main = plc.add_program("Main")
    trace = plc.trace(["a", "pair[2]"], program="Main")
    plc.run(2)
    expected_a = {"x": 3, "y": 12}
    assert main["a"] == expected_a
    acc = project.program.pous["MAIN"].variables["A"].type
    assert to_json(main.raw("a"), acc) == expected_a
    pair = project.program.pous["MAIN"].variables["PAIR"].type
    assert to_json(main.raw("pair"), pair) == [{"x": 0, "y": 0}, {"x": 1, "y": 4}]
    assert main.to_json() == {"a": expected_a, "pair": [{"x": 0, "y": 0}, {"x": 1, "y": 4}]}
    assert trace.column_names == ["a.x", "a.y", "pair[2].x", "pair[2].y"]
