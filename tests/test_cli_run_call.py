"""`stgen run` and `stgen call`: the fixed command-line contracts."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from stgen.cli import main

COUNTER = """
TYPE Pair : STRUCT a : INT; b : LREAL; END_STRUCT; END_TYPE
PROGRAM Main
VAR
  count : INT;
  enable : BOOL := TRUE;
  level : REAL := 0.5;
  total : LREAL;
  name : STRING[8] := 'pump';
  wait : TIME := T#1s500ms;
  grid : ARRAY[1..2, 0..1] OF INT := [1, 2, 3, 4];
  p : Pair;
  t : TON;
END_VAR
count := count + 1;
total := total + 0.25;
p.a := count;
t(IN := enable, PT := T#2ms);
END_PROGRAM
"""

FAULTY = """
PROGRAM Bad
VAR a : ARRAY[1..3] OF INT; i : INT := 9; END_VAR
a[i] := 1;
END_PROGRAM
"""

LIB = """
FUNCTION Clamp : LREAL
VAR_INPUT x, lo, hi : LREAL; END_VAR
VAR_OUTPUT clipped : BOOL; END_VAR
Clamp := LIMIT(lo, x, hi); clipped := Clamp <> x;
END_FUNCTION
FUNCTION Sum6 : LREAL
VAR_INPUT v : ARRAY[1..6] OF LREAL; END_VAR
VAR i : INT; END_VAR
FOR i := 1 TO 6 DO Sum6 := Sum6 + v[i]; END_FOR;
END_FUNCTION
FUNCTION_BLOCK Delay
VAR_INPUT start : BOOL; pt : TIME; END_VAR
VAR_OUTPUT done : BOOL; elapsed : TIME; END_VAR
VAR t : TON; END_VAR
t(IN := start, PT := pt); done := t.Q; elapsed := t.ET;
END_FUNCTION_BLOCK
FUNCTION Negate : BOOL
VAR_IN_OUT v : ARRAY[1..3] OF LREAL; count : INT; END_VAR
VAR i : INT; END_VAR
FOR i := 1 TO 3 DO v[i] := -v[i]; END_FOR;
count := count + 1;
Negate := TRUE;
END_FUNCTION
FUNCTION DivBy : INT
VAR_INPUT a, b : INT; END_VAR
DivBy := a / b;
END_FUNCTION
"""


@pytest.fixture
def files(tmp_path):
    (tmp_path / "counter.st").write_text(COUNTER)
    (tmp_path / "bad.st").write_text(FAULTY)
    (tmp_path / "lib.st").write_text(LIB)
    return tmp_path


def stgen(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_run_json_renders_every_variable(files, capsys):
    code, out, err = stgen(capsys, "run", files / "counter.st", "--program", "Main", "--cycles", "3", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data == {
        "count": 3, "enable": True, "level": 0.5, "total": 0.75, "name": "pump", "wait": "T#1s500ms",
        "grid": [[1, 2], [3, 4]], "p": {"a": 3, "b": 0.0},
        "t": data["t"], "scans": 3, "time": "T#3ms", "faults": [],
    }
    assert data["t"]["Q"] is True and data["t"]["ET"] == "T#2ms" and data["t"]["PT"] == "T#2ms"


def test_run_a_directory_defaults_to_one_cycle(files, capsys):
    code, out, _ = stgen(capsys, "run", files, "--program", "main", "--json")
    assert code == 0 and json.loads(out)["count"] == 1


def test_run_faults_go_to_stderr_and_exit_1(files, capsys):
    code, out, err = stgen(capsys, "run", files / "bad.st", "--program", "Bad", "--cycles", "2", "--json")
    assert code == 1
    assert json.loads(out)["i"] == 9
    lines = err.strip().splitlines()
    assert lines[0].startswith(f"{files / 'bad.st'}:4:")
    assert "fault[F-INDEX]" in lines[0] and lines[0].endswith("(scan 1)")
    assert lines[1].endswith("(scan 2)")


def test_run_trace_writes_csv(files, capsys, tmp_path):
    out_csv = tmp_path / "out.csv"
    code, _, err = stgen(capsys, "run", files / "counter.st", "--program", "Main", "--cycles", "4",
                         "--period", "2ms", "--trace", out_csv, "--watch", "count,p.a", "--watch", "t.Q")
    assert code == 0, err
    rows = out_csv.read_text().splitlines()
    assert rows[0] == "time_s,scan,count,p.a,t.Q"
    assert rows[1].split(",")[1:] == ["1", "1", "1", "FALSE"]
    assert rows[4].split(",")[1:] == ["4", "4", "4", "TRUE"]


@pytest.mark.parametrize("argv", [
    ["run", "{dir}/counter.st", "--program", "Nope"],
    ["run", "{dir}/missing.st", "--program", "Main"],
    ["run", "{dir}/counter.st", "--program", "Main", "--period", "fast"],
    ["run", "{dir}/counter.st", "--program", "Main", "--trace", "x.csv"],
    ["call", "{dir}/lib.st", "--pou", "Clamp", "--set", "x=oops"],
    ["call", "{dir}/lib.st", "--pou", "Clamp", "--set", "nope=1"],
    ["call", "{dir}/lib.st", "--pou", "Missing"],
    ["call", "{dir}/lib.st", "--pou", "Delay", "--until", "elapsed"],
])
def test_usage_errors_exit_2(files, capsys, argv):
    code, _, err = stgen(capsys, *[a.format(dir=files) for a in argv])
    assert code == 2
    assert "error" in err and "Traceback" not in err


def test_run_with_check_errors_exits_1(tmp_path, capsys):
    (tmp_path / "broken.st").write_text("PROGRAM Main\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n")
    code, out, err = stgen(capsys, "run", tmp_path / "broken.st", "--program", "Main")
    assert code == 1 and out == ""
    assert "broken.st:3:6: error[" in err


def test_call_function_prints_outputs_and_return(files, capsys):
    code, out, err = stgen(capsys, "call", files / "lib.st", "--pou", "Clamp",
                           "--set", "x=5", "--set", "hi=2.5", "--json")
    assert code == 0, err
    assert json.loads(out) == {"clipped": True, "return": 2.5, "cycles": 1}


def test_call_function_with_array_input(files, capsys):
    code, out, _ = stgen(capsys, "call", files / "lib.st", "--pou", "Sum6", "--set", "v=[1,2,3,4,5,6.5]")
    assert code == 0 and json.loads(out) == {"return": 21.5, "cycles": 1}


def test_call_fb_until_output(files, capsys):
    code, out, err = stgen(capsys, "call", files / "lib.st", "--pou", "Delay", "--set", "start=true",
                           "--set", 'pt="T#5ms"', "--until", "done", "--json")
    assert code == 0, err
    # Scan k runs at (k - 1) ms: ET = 5 ms in scan 6.
    assert json.loads(out) == {"done": True, "elapsed": "T#5ms", "cycles": 6, "reached": True}


def test_call_fb_max_cycles(files, capsys):
    code, out, err = stgen(capsys, "call", files / "lib.st", "--pou", "Delay", "--set", "start=false",
                           "--until", "done", "--max-cycles", "7")
    # Not reached: the outputs all the same, "reached": false, exit 1 (issue 15).
    assert code == 1 and json.loads(out)["cycles"] == 7 and json.loads(out)["reached"] is False
    assert "did not become TRUE" in err


def test_call_fault_exits_1(files, capsys):
    code, out, err = stgen(capsys, "call", files / "lib.st", "--pou", "DivBy", "--set", "a=1", "--set", "b=0")
    assert code == 1
    assert json.loads(out) == {"return": 0, "cycles": 1}
    assert "fault[F-DIV-ZERO]" in err and "(scan 1)" in err


def test_console_script_never_shows_a_traceback(files):
    result = subprocess.run([sys.executable, "-m", "stgen.cli", "call", str(files / "lib.st"),
                             "--pou", "Sum6", "--set", "v=[1,2]"], capture_output=True, text=True)
    assert result.returncode == 2
    assert "Traceback" not in result.stderr and "v" in result.stderr


def test_call_with_var_in_out_prints_the_variables_after_the_call(files, capsys):
    code, out, err = stgen(capsys, "call", files / "lib.st", "--pou", "Negate",
                           "--set", "v=[1, -2, 3.5]", "--set", "count=41")
    assert code == 0, err
    assert json.loads(out) == {"return": True, "v": [-1.0, 2.0, -3.5], "count": 42, "cycles": 1}


NON_FINITE = """
PROGRAM Inf
VAR zero : LREAL; up : LREAL; down : REAL; undefined : LREAL; v : ARRAY[0..1] OF LREAL; END_VAR
up := 1.0 / zero;                      (* IEC 60559: +inf *)
down := LREAL_TO_REAL(-1.0 / zero);    (* -inf *)
undefined := zero / zero;              (* NaN *)
v[1] := up;
END_PROGRAM
FUNCTION Div : LREAL
VAR_INPUT a : LREAL; b : LREAL; END_VAR
Div := a / b;
END_FUNCTION
"""


def strict_loads(text):
    """json.loads as a strict RFC 8259 reader: bare NaN/Infinity are refused."""
    def refuse(word):
        raise ValueError(f"not JSON: {word}")
    return json.loads(text, parse_constant=refuse)


def test_json_is_strict_non_finite_reals_are_strings(tmp_path, capsys):
    # Python's json would print bare NaN/Infinity, which JSON.parse and jq
    # refuse; the contract is strict JSON with those values as strings.
    (tmp_path / "inf.st").write_text(NON_FINITE)
    code, out, err = stgen(capsys, "run", tmp_path / "inf.st", "--program", "Inf", "--json")
    assert code == 0, err
    assert strict_loads(out) == {"zero": 0.0, "up": "Infinity", "down": "-Infinity",
                                 "undefined": "NaN", "v": [0.0, "Infinity"],
                                 "scans": 1, "time": "T#1ms", "faults": []}
    code, out, err = stgen(capsys, "call", tmp_path / "inf.st", "--pou", "Div",
                           "--set", "a=-1", "--set", "b=0", "--json")
    assert code == 0, err
    assert strict_loads(out) == {"return": "-Infinity", "cycles": 1}


def test_call_takes_the_non_finite_strings_back(tmp_path, capsys):
    (tmp_path / "inf.st").write_text(NON_FINITE)
    code, out, _ = stgen(capsys, "call", tmp_path / "inf.st", "--pou", "Div",
                         "--set", 'a="Infinity"', "--set", "b=-2", "--json")
    assert code == 0 and strict_loads(out)["return"] == "-Infinity"
    code, out, _ = stgen(capsys, "call", tmp_path / "inf.st", "--pou", "Div",
                         "--set", 'a="NaN"', "--set", "b=1", "--json")
    assert code == 0 and strict_loads(out)["return"] == "NaN"
    code, _, err = stgen(capsys, "call", tmp_path / "inf.st", "--pou", "Div",
                         "--set", 'a="inf"', "--set", "b=1", "--json")
    assert code == 2 and 'expected LREAL number (or "NaN", "Infinity", "-Infinity")' in err


def test_json_help_states_the_non_finite_rule(capsys):
    for command in ("run", "call"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        out, _ = capsys.readouterr()
        assert '"Infinity"' in " ".join(out.split()), command


EVERY_TYPE = """
PROGRAM AllTypes
VAR
  b : BOOL := TRUE; si : SINT := -128; i : INT := INT#-5; di : DINT := 16#7FFF_FFFF;
  li : LINT := -9223372036854775808; us : USINT := 255; ui : UINT := 8#17;
  ud : UDINT := 2#1010_0101; ul : ULINT := 18446744073709551615;
  bt : BYTE := 16#FF; w : WORD := 16#ABCD; dw : DWORD := 16#DEADBEEF; lw : LWORD := 16#FFFF_FFFF_FFFF_FFFF;
  r : REAL := 0.1; lr : LREAL := LREAL#1.5E-3;
  t : TIME := TIME#-2.5s; d : DATE := D#2024-02-29; tod1 : TIME_OF_DAY := TOD#23:59:59.5;
  dt1 : DATE_AND_TIME := DT#2024-02-29-12:30:00.25; s : STRING[10] := 'it$'s $$5$N';
END_VAR
END_PROGRAM
FUNCTION Later : DATE_AND_TIME
VAR_INPUT at : DATE_AND_TIME; wait : TIME; END_VAR
VAR_OUTPUT day : DATE; clock : TOD; END_VAR
Later := at + wait;
day := DT_TO_DATE(Later);
clock := DT_TO_TOD(Later);
END_FUNCTION
"""


def test_every_elementary_type_in_run_json(tmp_path, capsys):
    (tmp_path / "all.st").write_text(EVERY_TYPE)
    code, out, err = stgen(capsys, "run", tmp_path / "all.st", "--program", "AllTypes", "--cycles", "0",
                           "--json")
    assert code == 0, err
    assert strict_loads(out) == {
        "b": True, "si": -128, "i": -5, "di": 2**31 - 1, "li": -2**63, "us": 255, "ui": 15,
        "ud": 165, "ul": 2**64 - 1, "bt": 255, "w": 0xABCD, "dw": 0xDEADBEEF, "lw": 2**64 - 1,
        "r": 0.1, "lr": 0.0015, "t": "T#-2s500ms", "d": "D#2024-02-29", "tod1": "TOD#23:59:59.5",
        "dt1": "DT#2024-02-29-12:30:00.25", "s": "it's $5\n",
        "scans": 0, "time": "T#0s", "faults": [],
    }


def test_call_takes_and_gives_date_and_time_literals(tmp_path, capsys):
    (tmp_path / "all.st").write_text(EVERY_TYPE)
    code, out, err = stgen(capsys, "call", tmp_path / "all.st", "--pou", "Later",
                           "--set", 'at="DT#2024-12-31-23:59:59.5"', "--set", 'wait="T#1h500ms"',
                           "--json")
    assert code == 0, err
    assert strict_loads(out) == {"return": "DT#2025-01-01-01:00:00", "day": "D#2025-01-01",
                                 "clock": "TOD#01:00:00", "cycles": 1}
