"""`stgen check`, `stgen run` and `stgen call` on broken inputs: each is one
clear line on stderr, exit 1 (bad input) or 2 (usage), never a traceback."""

from __future__ import annotations

import re

import pytest

from stgen.cli import main

SUMMARY = re.compile(r"stgen check: \d+ file\(s\), \d+ error\(s\), \d+ warning\(s\)$")
PROGRAM = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"
FUNCTION = "FUNCTION F : INT\nVAR_INPUT a : INT; END_VAR\nF := a;\nEND_FUNCTION\n"
FB = ("FUNCTION_BLOCK Acc\nVAR_INPUT x : INT; p : ARRAY[1..2] OF LREAL; END_VAR\n"
      "VAR_OUTPUT y : INT; done : BOOL; END_VAR\ny := y + x; done := y > 5;\nEND_FUNCTION_BLOCK\n")


@pytest.fixture
def d(tmp_path):
    (tmp_path / "main.st").write_text(PROGRAM)
    (tmp_path / "f.st").write_text(FUNCTION)
    (tmp_path / "fb.st").write_text(FB)
    (tmp_path / "bin.st").write_bytes(b"PROGRAM \xff\xfe\x00\x01 END_PROGRAM")
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "main.st").write_text(PROGRAM)
    (tmp_path / "lib" / "f.st").write_text(FUNCTION)
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "notes.txt").write_text("no ST here")
    return tmp_path


CASES = [
    # (argv, exit code, fragment of the one stderr line)
    (["check", "{d}/missing.st"], 2, "no such file or directory: '{d}/missing.st'"),
    (["check", "{d}/empty"], 2, "no .st file in '{d}/empty'"),
    (["check", "{d}/bin.st"], 1, "{d}/bin.st:1:9: error[E-LOAD-003]: '{d}/bin.st' is not UTF-8 text"),
    (["check", "{d}/main.st", "--dialect", "twincat"], 2, "argument --dialect: invalid choice"),
    (["run", "{d}/missing.st", "--program", "Main"], 2, "no such file or directory"),
    (["run", "{d}/empty", "--program", "Main"], 2, "no .st file in '{d}/empty'"),
    (["run", "{d}/bin.st", "--program", "Main"], 1, "error[E-LOAD-003]"),
    (["run", "{d}/main.st", "--program", "Nope"], 2, "no PROGRAM named 'Nope' (programs: Main)"),
    (["run", "{d}/lib", "--program", "F"], 2, "'F' is a FUNCTION; stgen call --pou calls it"),
    (["run", "{d}/main.st"], 2, "the following arguments are required: --program"),
    (["run", "{d}/main.st", "--program", "Main", "--cycles", "-1"], 2, "--cycles must be 0 or more"),
    (["run", "{d}/main.st", "--program", "Main", "--cycles", "ten"], 2, "invalid int value: 'ten'"),
    (["run", "{d}/main.st", "--program", "Main", "--period", "fast"], 2, "--period 'fast' is not a duration"),
    (["run", "{d}/main.st", "--program", "Main", "--period", "1x"], 2, "--period '1x' is not a duration"),
    (["run", "{d}/main.st", "--program", "Main", "--period", "0ms"], 2, "--period must be positive"),
    (["run", "{d}/main.st", "--program", "Main", "--period=-1ms"], 2, "--period must be positive"),
    (["run", "{d}/main.st", "--program", "Main", "--period", "-1ms"], 2, "--option=VALUE"),
    (["check", "{d}/main.st", "--dialect"], 2, "argument --dialect: expected one argument (see"),
    (["run", "{d}/main.st", "--program", "Main", "--time-limit", "0ms"], 2, "--time-limit must be positive"),
    (["run", "{d}/main.st", "--program", "Main", "--trace", "{d}/t.csv", "--watch", "nothere"], 2,
     "--watch: 'nothere': no variable named 'nothere'"),
    (["run", "{d}/main.st", "--program", "Main", "--trace", "{d}/t.csv", "--watch", "x["], 2,
     "--watch: 'x['"),
    (["run", "{d}/main.st", "--program", "Main", "--watch", "x"], 2, "--trace and --watch go together"),
    (["run", "{d}/main.st", "--program", "Main", "--trace", "{d}", "--watch", "x"], 2,
     "--trace: '{d}' is a directory"),
    (["run", "{d}/main.st", "--program", "Main", "--trace", "{d}/no/dir/t.csv", "--watch", "x"], 2,
     "directory '{d}/no/dir' does not exist"),
    (["call", "{d}/missing.st", "--pou", "F"], 2, "no such file or directory"),
    (["call", "{d}/empty", "--pou", "F"], 2, "no .st file in '{d}/empty'"),
    (["call", "{d}/bin.st", "--pou", "F"], 1, "error[E-LOAD-003]"),
    (["call", "{d}/f.st", "--pou", "Nope"], 2, "no FUNCTION or FUNCTION_BLOCK named Nope"),
    (["call", "{d}/lib", "--pou", "Main"], 2, "'Main' is a PROGRAM; stgen run --program runs it"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a=oops"], 2, "--set a: not JSON"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a"], 2, "--set 'a': expected NAME=JSON"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "=3"], 2, "expected NAME=JSON"),
    (["call", "{d}/f.st", "--pou", "F", "--set", 'a="x"'], 2, "--set a: expected INT integer, got string 'x'"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a=1.5"], 2, "--set a: expected INT integer, got 1.5"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a=99999"], 2, "99999 is outside the range of INT"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a=true"], 2, "expected INT integer, got true"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "a=1", "--set", "A=2"], 2, "--set A: given twice"),
    (["call", "{d}/f.st", "--pou", "F", "--set", "b=1"], 2, "F has no input named b (inputs: a)"),
    (["call", "{d}/f.st", "--pou", "F", "--until", "a"], 2, "a FUNCTION is called once"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--set", "p=[1]"], 2, "--set p: expected a list of 2 elements"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--set", "y=1"], 2, "Acc has no input named y"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--until", "y"], 2, "--until needs a BOOL output of Acc"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--max-cycles", "0"], 2, "--max-cycles must be positive"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--period", "0ms"], 2, "--period must be positive"),
    (["call", "{d}/fb.st", "--pou", "Acc", "--period", "1x"], 2, "--period '1x' is not a duration"),
    # the top-level parser speaks like the subcommands (was: a usage block, then the error)
    ([], 2, "stgen: error: the following arguments are required: COMMAND (commands: check, run, call,"),
    (["--bogus"], 2, "stgen: error: the following arguments are required: COMMAND"),
    (["frob"], 2, "stgen: error: argument COMMAND: invalid choice: 'frob'"),
    (["check", "{d}/main.st", "--bogus"], 2, "stgen check: error: unrecognized arguments: --bogus (see 'stgen check --help')"),
    (["generate", "--bogus"], 2, "stgen generate: error: the following arguments are required: --out"),
]


@pytest.mark.parametrize("argv, code, fragment", CASES, ids=[f"{n}-{(c[0] or ['none'])[0]}" for n, c in enumerate(CASES)])
def test_broken_input_is_one_clear_line(d, capsys, argv, code, fragment):
    try:
        got = main([a.format(d=d) for a in argv])
    except SystemExit as exc:          # argparse's own usage errors
        got = exc.code
    out, err = capsys.readouterr()
    assert got == code, err
    assert out == ""
    # (`stgen check` always ends with its one-line summary of the counts)
    lines = [line for line in err.strip().splitlines() if not SUMMARY.match(line)]
    assert len(lines) == 1, err
    assert fragment.format(d=d) in lines[0]
    assert "Traceback" not in err and "internal error" not in err


def test_a_trace_file_that_cannot_be_written_is_refused_before_running(d, capsys):
    # The simulation does not run (no variables printed) when the trace
    # could never be written.
    got = main(["run", str(d / "main.st"), "--program", "Main", "--cycles", "100000",
                "--trace", str(d), "--watch", "x"])
    out, _ = capsys.readouterr()
    assert got == 2 and out == ""


def test_a_directory_with_st_files_next_to_an_empty_one_still_loads(d, capsys):
    got = main(["check", str(d / "main.st"), str(d / "empty")])
    _, err = capsys.readouterr()
    assert got == 0 and "warning[W-LOAD-004]" in err
