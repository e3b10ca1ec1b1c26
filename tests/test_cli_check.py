"""`stgen check`: exit codes, the rendered format, directories, no tracebacks."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from stgen.cli import main

ROOT = Path(__file__).resolve().parents[1]
GOOD = "PROGRAM Main\nVAR x : LREAL; END_VAR\nx := x + 1.0;\nEND_PROGRAM\n"
BAD = "PROGRAM Main\nVAR i : INT; x : LREAL; END_VAR\n    i := x * 2.0;\nEND_PROGRAM\n"


def run_check(capsys, *args):
    code = main(["check", *map(str, args)])
    out = capsys.readouterr()
    return code, out.out + out.err


def test_clean_file_exits_0(tmp_path, capsys):
    (tmp_path / "good.st").write_text(GOOD)
    code, text = run_check(capsys, tmp_path / "good.st")
    assert code == 0
    assert "0 error(s)" in text


def test_errors_exit_1_with_location_source_line_and_caret(tmp_path, capsys):
    path = tmp_path / "bad.st"
    path.write_text(BAD)
    code, text = run_check(capsys, path)
    assert code == 1
    lines = text.splitlines()
    header = f"{path}:3:10: error[E-TYPE-004]: "
    i = next(n for n, line in enumerate(lines) if line.startswith(header))
    assert "expected INT, found LREAL" in lines[i]
    assert lines[i + 1] == "        i := x * 2.0;"
    assert lines[i + 2] == "             ^"


def test_warnings_alone_exit_0_but_nj_dialect_makes_them_errors(tmp_path, capsys):
    (tmp_path / "w.st").write_text("PROGRAM Main\nVAR Limit : LREAL; END_VAR\nEND_PROGRAM\n")
    code, text = run_check(capsys, tmp_path / "w.st")
    assert code == 0 and "warning[W-NJ-004]" in text
    code, text = run_check(capsys, tmp_path / "w.st", "--dialect", "nj")
    assert code == 1 and "error[E-NJ-004]" in text


def test_missing_path_is_a_usage_error(tmp_path, capsys):
    code, text = run_check(capsys, tmp_path / "absent.st")
    assert code == 2
    assert "absent.st" in text


def test_bad_dialect_is_a_usage_error(tmp_path, capsys):
    (tmp_path / "good.st").write_text(GOOD)
    try:
        main(["check", str(tmp_path / "good.st"), "--dialect", "twincat"])
    except SystemExit as exc:
        assert exc.code == 2
    else:
        raise AssertionError("argparse should exit with 2")


def test_directory_means_every_st_file(tmp_path, capsys):
    (tmp_path / "one.st").write_text(GOOD)
    (tmp_path / "two.st").write_text(BAD.replace("Main", "Other"))
    code, text = run_check(capsys, tmp_path)
    assert code == 1
    assert "two.st:3:10: error[E-TYPE-004]" in text
    assert "2 file(s)" in text


def test_broken_input_never_prints_a_traceback(tmp_path):
    garbage = tmp_path / "garbage.st"
    garbage.write_bytes(bytes(range(256)) * 4)
    half = tmp_path / "half.st"
    half.write_text("PROGRAM Main\nVAR x : LREAL; END_VAR\nIF x > THEN x := ; END_")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    for path in (garbage, half):
        proc = subprocess.run([sys.executable, "-m", "stgen.cli", "check", str(path)],
                              capture_output=True, text=True, env=env, cwd=ROOT, timeout=120)
        assert proc.returncode == 1, proc.stderr
        assert "Traceback" not in proc.stdout + proc.stderr
        assert "error[E-" in proc.stderr
