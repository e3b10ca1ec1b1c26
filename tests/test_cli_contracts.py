"""The command-line contracts of issue 15, through `stgen` itself: what a
user reads from `call --json` and `run --json`, how `--watch` takes its
paths, what a standard FB shows, and the messages of `--period`, `--dialect`,
keyword typos and a folder of Sysmac Studio bodies."""

from __future__ import annotations

import csv
import json

import pytest

from stgen.cli import main

TIMERS = """
PROGRAM Main
VAR
  count : INT;
  m : ARRAY[1..2, 1..2] OF INT := [1, 2, 3, 4];
  t : TON;
END_VAR
count := count + 1;
t(IN := TRUE, PT := T#2ms);
END_PROGRAM
"""

FAULTY = """
PROGRAM Bad
VAR a : ARRAY[1..3] OF INT; i : INT := 4; END_VAR
a[i] := 1;
END_PROGRAM
"""

# A program that declares the names of the summary: they are never overwritten.
CLASHING = """
PROGRAM Busy
VAR scans : INT := 7; Time : LREAL := 2.5; END_VAR
scans := scans;
END_PROGRAM
"""

DELAY = """
FUNCTION_BLOCK Delay
VAR_INPUT start : BOOL; END_VAR
VAR_OUTPUT done : BOOL; END_VAR
VAR t : TON; END_VAR
t(IN := start, PT := T#3ms); done := t.Q;
END_FUNCTION_BLOCK
"""


@pytest.fixture()
def files(tmp_path):
    for name, text in (("main.st", TIMERS), ("bad.st", FAULTY), ("busy.st", CLASHING), ("delay.st", DELAY)):
        (tmp_path / name).write_text(text)
    return tmp_path


def stgen(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


# ---------------------------------------------------------------- call --json "reached"

def test_call_until_reached_says_so(files, capsys):
    # TON with PT = 3 ms: ET = 0, 1, 2, 3 ms on calls 1..4, so Q on the fourth call.
    code, out, _ = stgen(capsys, "call", files / "delay.st", "--pou", "Delay", "--set", "start=true",
                         "--until", "done", "--json")
    assert code == 0 and json.loads(out) == {"done": True, "cycles": 4, "reached": True}


def test_call_until_not_reached_exits_1_with_the_outputs(files, capsys):
    code, out, err = stgen(capsys, "call", files / "delay.st", "--pou", "Delay", "--set", "start=true",
                           "--until", "done", "--max-cycles", "3", "--json")
    assert code == 1 and json.loads(out) == {"done": False, "cycles": 3, "reached": False}
    assert "did not become TRUE within 3 cycles" in err


def test_call_without_until_has_no_reached(files, capsys):
    code, out, _ = stgen(capsys, "call", files / "delay.st", "--pou", "Delay", "--json")
    assert code == 0 and "reached" not in json.loads(out)


# ---------------------------------------------------------------- run --json summary

def test_run_json_carries_scans_time_and_faults(files, capsys):
    code, out, _ = stgen(capsys, "run", files / "bad.st", "--program", "Bad", "--cycles", "3",
                         "--period", "2ms", "--json")
    data = json.loads(out)
    assert code == 1
    assert data["scans"] == 3 and data["time"] == "T#6ms"     # 3 scans of 2 ms
    assert [f["scan"] for f in data["faults"]] == [1, 2, 3]
    first = data["faults"][0]
    assert first["code"] == "F-INDEX" and first["pou"].upper() == "BAD"
    assert first["line"] == 4 and first["file"].endswith("bad.st")


def test_run_json_without_faults_has_an_empty_list(files, capsys):
    code, out, _ = stgen(capsys, "run", files / "main.st", "--program", "Main", "--cycles", "2", "--json")
    data = json.loads(out)
    assert code == 0 and data["faults"] == [] and data["scans"] == 2 and data["time"] == "T#2ms"


def test_run_json_never_overwrites_a_declared_variable(files, capsys):
    code, out, err = stgen(capsys, "run", files / "busy.st", "--program", "Busy", "--cycles", "2", "--json")
    data = json.loads(out)
    assert code == 0 and data["scans"] == 7 and data["Time"] == 2.5 and data["faults"] == []
    assert "time" not in data
    assert "2 scan(s)" in err


# ---------------------------------------------------------------- --watch

def _header(path):
    with open(path, newline="") as stream:
        return next(csv.reader(stream))


def test_watch_is_repeatable_and_takes_comma_lists(files, capsys, tmp_path):
    out_csv = tmp_path / "t.csv"
    code, _, err = stgen(capsys, "run", files / "main.st", "--program", "Main", "--cycles", "2",
                         "--trace", out_csv, "--watch", "count,m[1,2]", "--watch", "t.Q")
    assert code == 0, err
    assert _header(out_csv) == ["time_s", "scan", "count", "m[1,2]", "t.Q"]


def test_watch_never_swallows_the_file_argument(files, capsys, tmp_path):
    # Before: --watch took every word up to the next option, the file included.
    code, _, err = stgen(capsys, "run", "--trace", tmp_path / "t.csv", "--watch", "count", "t.Q",
                         files / "main.st", "--program", "Main")
    assert code == 2
    assert "no such file or directory: 't.Q'" in err and "--watch A,B" in err


# ---------------------------------------------------------------- standard FB JSON

def test_ton_json_is_its_iec_interface(files, capsys):
    code, out, _ = stgen(capsys, "run", files / "main.st", "--program", "Main", "--cycles", "2", "--json")
    # Scan 2 runs at 1 ms: ET = 1 ms of PT = 2 ms, Q still FALSE.
    assert json.loads(out)["t"] == {"IN": True, "PT": "T#2ms", "Q": False, "ET": "T#1ms"}


def test_ton_internals_stay_readable_by_an_explicit_path(files, capsys, tmp_path):
    out_csv = tmp_path / "t.csv"
    code, _, err = stgen(capsys, "run", files / "main.st", "--program", "Main", "--cycles", "2",
                         "--trace", out_csv, "--watch", "t.StartTime,t.Running")
    assert code == 0, err
    rows = list(csv.reader(out_csv.open()))
    assert rows[0][2:] == ["t.StartTime", "t.Running"] and rows[2][2:] == ["T#0s", "TRUE"]


# ---------------------------------------------------------------- messages

@pytest.mark.parametrize("period, what", [("2", "has no unit"), ("2x", "is not a duration"),
                                          ("fast", "is not a duration")])
def test_period_says_what_a_time_literal_looks_like(files, capsys, period, what):
    code, _, err = stgen(capsys, "run", files / "main.st", "--program", "Main", f"--period={period}")
    assert code == 2
    assert f"--period '{period}' {what}" in err and "1ms" in err and "T#1s500ms" in err
    assert "T#2'" not in err   # never the text the user did not write


@pytest.mark.parametrize("command", ["check", "run", "call"])
def test_dialect_has_help_everywhere(capsys, command):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "--dialect {iec,nj,codesys}" in help_text and "OMRON NJ/Sysmac Studio" in help_text


@pytest.mark.parametrize("typo, keyword", [("ENDIF", "END_IF"), ("END_FI", "END_IF"), ("end_fro", "END_FOR")])
def test_keyword_typo_gets_did_you_mean(tmp_path, capsys, typo, keyword):
    opener = "FOR x := 1 TO 2 DO" if keyword == "END_FOR" else "IF x > 0 THEN"
    path = tmp_path / "typo.st"
    path.write_text(f"PROGRAM P\nVAR x : INT; END_VAR\n{opener}\n  x := 1;\n{typo};\nEND_PROGRAM\n")
    code, _, err = stgen(capsys, "check", path)
    assert code == 1 and f"typo.st:5:1: error[E-PARSE-001]" in err
    assert f"(did you mean {keyword}?)" in err


def test_no_keyword_hint_for_an_ordinary_name(tmp_path, capsys):
    path = tmp_path / "name.st"
    path.write_text("PROGRAM P\nVAR x : INT; END_VAR\ncounter;\nEND_PROGRAM\n")
    code, _, err = stgen(capsys, "check", path)
    assert code == 1 and "did you mean" not in err
