"""`stgen call` / `Project.call`: a POU's own output named `cycles` is never
overwritten by the call count; the "is a PROGRAM" hint only for a POU of the
wrong kind; `python -m stgen` runs the CLI."""

from __future__ import annotations

import json
import subprocess
import sys

from st_runtime import load
from stgen.cli import main

COUNTS_BY_TEN = """
FUNCTION_BLOCK Cnt
VAR_OUTPUT
    cycles : INT;
    done : BOOL;
END_VAR
cycles := cycles + 10;
done := cycles >= 30;
END_FUNCTION_BLOCK

FUNCTION Twice : INT
VAR_INPUT x : INT; END_VAR
Twice := 2 * x;
END_FUNCTION
"""


def write(tmp_path):
    path = tmp_path / "cnt.st"
    path.write_text(COUNTS_BY_TEN)
    return str(path)


def test_api_keeps_the_fb_output_named_cycles(tmp_path):
    result = load([write(tmp_path)]).call("Cnt", until="done")
    # 10, 20, 30: done after the third scan
    assert result["outputs"] == {"cycles": 30, "done": True}
    assert result["cycles"] == 3 and result["reached"]


def test_api_count_for_a_function(tmp_path):
    result = load([write(tmp_path)]).call("Twice", {"x": 4})
    assert result["outputs"] == {"return": 8, "cycles": 1} and result["cycles"] == 1


def test_cli_output_named_cycles_wins_count_on_stderr(tmp_path, capsys):
    code = main(["call", write(tmp_path), "--pou", "Cnt", "--until", "done", "--json"])
    captured = capsys.readouterr()
    assert code == 0 and json.loads(captured.out) == {"cycles": 30, "done": True, "reached": True}
    assert "3 cycle(s)" in captured.err


def test_unknown_input_of_a_function_has_no_program_hint(tmp_path, capsys):
    code = main(["call", write(tmp_path), "--pou", "Twice", "--set", "y=1", "--json"])
    err = capsys.readouterr().err
    assert code == 2 and "Twice has no input named y (inputs: x)" in err
    assert "stgen run --program" not in err


def test_python_dash_m_stgen(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "stgen", "call", write(tmp_path), "--pou", "Twice",
                           "--set", "x=21", "--json"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and json.loads(proc.stdout) == {"return": 42, "cycles": 1}


def test_check_on_a_sysmac_body_folder_names_the_way_out(tmp_path, capsys):
    (tmp_path / "Fb.st").write_text("X := 1;\n")
    (tmp_path / "Fb.variables.tsv").write_text("Name\tUsage\tData Type\nX\tVar\tINT\n")
    code = main(["check", str(tmp_path)])
    err = capsys.readouterr().err
    # First and in one line, instead of a syntax error per body (issue 15).
    assert code == 1 and "error[" not in err
    first = err.splitlines()[0]
    assert "Sysmac Studio statement body" in first and "--target iec" in first and "--dialect nj" in first


def test_check_without_tsv_has_no_sysmac_note(tmp_path, capsys):
    (tmp_path / "Fb.st").write_text("X := 1;\n")
    assert main(["check", str(tmp_path)]) == 1
    assert "Sysmac" not in capsys.readouterr().err


def test_trace_csv_writes_a_real_in_its_shortest_float32_form(tmp_path):
    source = tmp_path / "lvl.st"
    source.write_text("PROGRAM P\nVAR Level : REAL; Big : LREAL; END_VAR\n"
                      "Level := Level + 0.01;\nBig := Big + 0.01;\nEND_PROGRAM\n")
    plc = load([str(source)]).controller()
    plc.add_program("P")
    trace = plc.trace(["Level", "Big"], program="P")
    plc.run(2)
    rows = trace.to_csv_text().splitlines()
    # REAL 0.01f is 0.009999999776482582 as a double; its shortest REAL text is 0.01.
    # 0.01f + 0.01f = 2 * 0.01f exactly, which is the float32 nearest 0.02.
    assert rows[1].split(",")[2:] == ["0.01", "0.01"]
    assert rows[2].split(",")[2:] == ["0.02", "0.02"]


HALF = """
FUNCTION Half : LREAL
VAR_INPUT x : LREAL; END_VAR
Half := x / 2.0;
END_FUNCTION

FUNCTION HalfReal : REAL
VAR_INPUT x : REAL; END_VAR
HalfReal := x / 2.0;
END_FUNCTION
"""


def call_half(tmp_path, capsys, pou, text):
    path = tmp_path / "half.st"
    path.write_text(HALF)
    code = main(["call", str(path), "--pou", pou, "--set", f"x={text}", "--json"])
    return code, capsys.readouterr()


def test_set_numbers_beyond_the_range_are_usage_errors(tmp_path, capsys):
    # an integer beyond the double range was an internal error (OverflowError)
    code, out = call_half(tmp_path, capsys, "Half", "1" + "0" * 400)
    assert code == 2 and "outside the range of LREAL" in out.err and "internal" not in out.err
    # 1e999 was read by json as infinity
    code, out = call_half(tmp_path, capsys, "Half", "1e999")
    assert code == 2 and "--set x: 1e999 is too large" in out.err
    # REAL's largest finite value is about 3.4028235e38; 1e40 rounded to +inf silently
    code, out = call_half(tmp_path, capsys, "HalfReal", "1e40")
    assert code == 2 and "outside the range of REAL" in out.err
    code, out = call_half(tmp_path, capsys, "HalfReal", "3e38")
    assert code == 0 and json.loads(out.out)["return"] == 1.5e38


def test_set_infinity_is_still_taken_by_name(tmp_path, capsys):
    code, out = call_half(tmp_path, capsys, "HalfReal", '"-Infinity"')
    assert code == 0 and json.loads(out.out)["return"] == "-Infinity"


def test_nj_reserves_the_p_underscore_prefix(tmp_path, capsys):
    # W501 6-3-12: variable names may not start with "P_" (P_On, P_CY... are the system's);
    # the NJ is not case sensitive, so p_ too.  "Pump_1" and "P1_x" are fine.
    (tmp_path / "p.st").write_text("PROGRAM Main\nVAR P_Speed : INT; p_low : INT; Pump_1 : INT;"
                                   " P1_x : INT; END_VAR\nP_Speed := 1;\nEND_PROGRAM\n")
    assert main(["check", "--dialect", "nj", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "p.st:2:5: error[E-NJ-005]: identifier 'P_Speed'" in err
    assert "p.st:2:20: error[E-NJ-005]: identifier 'p_low'" in err
    assert "2 error(s)" in err and "'Pump_1'" not in err and "'P1_x'" not in err
    assert main(["check", str(tmp_path)]) == 0
    assert "warning[W-NJ-005]" in capsys.readouterr().err


def test_generate_out_naming_a_file_is_a_usage_error(tmp_path, capsys):
    target = tmp_path / "platform.toml"
    target.write_text("# mine\n")
    assert main(["generate", "--target", "iec", "--out", str(target)]) == 2
    assert "is a file; --out names a folder" in capsys.readouterr().err
    assert target.read_text() == "# mine\n"


def test_unknown_option_is_named_by_its_subcommand(tmp_path, capsys):
    # was "stgen: error: ... (see 'stgen --help')", whose help does not list run's options
    code = None
    try:
        main(["run", write(tmp_path), "--program", "P", "--sett", "x=1"])
    except SystemExit as exc:
        code = exc.code
    assert code == 2
    assert capsys.readouterr().err.strip() == (
        "stgen run: error: unrecognized arguments: --sett x=1 (see 'stgen run --help')")


def test_version(capsys):
    from importlib.metadata import version

    code = None
    try:
        main(["--version"])
    except SystemExit as exc:
        code = exc.code
    assert code == 0 and capsys.readouterr().out.strip() == f"stgen {version('stgen')}"


GATE = """
VAR_GLOBAL Gain : LREAL := 1.0; END_VAR
PROGRAM Gate
VAR
    Present : BOOL;
    Count : INT;
    Pose : ARRAY[1..3] OF LREAL;
    Out : LREAL;
END_VAR
IF Present THEN
    Count := Count + 1;
END_IF;
Out := Pose[2] * Gain;
END_PROGRAM
"""


def run_gate(tmp_path, capsys, *sets, cycles="3"):
    path = tmp_path / "gate.st"
    path.write_text(GATE)
    argv = ["run", str(path), "--program", "Gate", "--cycles", cycles, "--json"]
    for item in sets:
        argv += ["--set", item]
    return main(argv), capsys.readouterr()


def test_run_set_writes_program_variables_and_globals_before_scan_one(tmp_path, capsys):
    code, out = run_gate(tmp_path, capsys, "Present=true", "Pose[2]=1.5", "Gain=4")
    data = json.loads(out.out)
    # Present stays TRUE: three scans count 3; Out = 1.5 * 4
    assert code == 0 and data["Count"] == 3 and data["Out"] == 6.0
    code, out = run_gate(tmp_path, capsys)
    assert json.loads(out.out)["Count"] == 0


def test_run_set_errors_name_the_path(tmp_path, capsys):
    assert run_gate(tmp_path, capsys, "Pose[4]=1")[1].err.strip() == (
        "stgen run: error: --set Pose[4]: index 4 out of bounds 1..3")
    assert run_gate(tmp_path, capsys, "Nope=1")[1].err.strip() == (
        "stgen run: error: --set Nope: no variable 'Nope'")
    code, out = run_gate(tmp_path, capsys, "Count=40000")
    assert code == 2 and "--set Count: 40000 is outside the range of INT" in out.err


def check_text(tmp_path, capsys, text):
    (tmp_path / "r.st").write_text(text)
    code = main(["check", str(tmp_path)])
    return code, capsys.readouterr().err


def test_real_constants_beyond_the_range_are_refused(tmp_path, capsys):
    # REAL's largest value is (2 - 2**-23) * 2**127 = 3.4028234663852886e38;
    # 3.4028235e38 rounds to it, 3.40282357e38 is past the half-ulp and rounds to +inf.
    code, err = check_text(tmp_path, capsys, "PROGRAM M\nVAR r : REAL := 3.4028235e38; END_VAR\n"
                                              "r := -1e39;\nEND_PROGRAM\n")
    assert code == 1 and "r.st:3:6: error[E-TYPE-005]: constant -1e+39 does not fit REAL" in err
    assert "1 error(s)" in err
    code, err = check_text(tmp_path, capsys, "PROGRAM M\nVAR r : REAL := 3.40282357e38; END_VAR\n"
                                              "END_PROGRAM\n")
    assert code == 1 and "r.st:2:17: error[E-TYPE-005]: constant 3.40282357e+38 does not fit REAL" in err
    code, err = check_text(tmp_path, capsys, "PROGRAM M\nVAR l : LREAL; END_VAR\nl := 2.0 * 1e400;\n"
                                              "END_PROGRAM\n")
    assert code == 1 and "r.st:3:12: error[E-TYPE-005]: a real literal does not fit LREAL" in err


def test_lreal_range_and_division_by_zero_constant_stay_accepted(tmp_path, capsys):
    # 1e39 fits an LREAL; a folded 1.0 / 0.0 is +inf on purpose, as at run time
    code, err = check_text(tmp_path, capsys, "PROGRAM M\nVAR l : LREAL := 1e39; r : REAL; END_VAR\n"
                                              "r := 1.0 / 0.0;\nEND_PROGRAM\n")
    assert code == 0, err


def test_verify_negative_seed_is_a_usage_error(capsys):
    code = None
    try:
        main(["verify", "--seed=-3", "--poses", "5"])
    except SystemExit as exc:
        code = exc.code
    assert code == 2    # was "stgen: internal error: ValueError: expected non-negative integer"
    assert "argument --seed: expected an integer 0 or more, got -3" in capsys.readouterr().err
