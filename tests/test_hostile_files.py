"""Hostile inputs never hang, never exhaust memory and are never an internal error (issue 9).

Before: a FIFO named as an ``.st`` file, ``--config`` or ``--axes`` hung
forever; ``/dev/zero`` was read until MemoryError; skipped directory entries
went unsaid; a string literal cost about 450 bytes per character; absurd but
valid TOML numbers allocated gigabytes or crashed; a 5,000-digit hex literal
was "internal checker error"; an axis named END_VAR passed validation;
control characters of the source reached the terminal raw.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tracemalloc
from pathlib import Path

import pytest

from stgen.cli import main

ROOT = Path(__file__).resolve().parent.parent
AXES_DEMO = str(ROOT / "examples" / "axes_demo.st")
PROGRAM = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"


def _stgen(*args: str) -> subprocess.CompletedProcess:
    """A separate process with a deadline: a regression hangs that process, not the suite."""
    return subprocess.run([sys.executable, "-m", "stgen", *args], capture_output=True, text=True, timeout=120)


# --------------------------------------------------------------------------- files that are not regular


@pytest.fixture
def fifo(tmp_path) -> Path:
    path = tmp_path / "pipe.st"
    os.mkfifo(path)
    return path


def test_a_fifo_or_a_device_named_on_the_command_line_is_refused_not_read(tmp_path, fifo):
    zero = tmp_path / "zero.st"
    zero.symlink_to("/dev/zero")
    done = _stgen("check", str(fifo), str(zero))
    assert done.returncode == 1
    assert f"cannot read '{fifo}': is a FIFO (named pipe), not a regular file" in done.stderr
    assert f"cannot read '{zero}': is a character device, not a regular file" in done.stderr


def test_directory_entries_that_are_skipped_are_named_with_the_reason(tmp_path, fifo):
    (tmp_path / "main.st").write_text(PROGRAM, encoding="utf-8")
    (tmp_path / "zero.st").symlink_to("/dev/zero")
    (tmp_path / "gone.st").symlink_to(tmp_path / "missing.st")
    elsewhere = tmp_path.parent / f"{tmp_path.name}-elsewhere"
    elsewhere.mkdir()
    (tmp_path / "linked").symlink_to(elsewhere, target_is_directory=True)
    done = _stgen("check", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert f"warning[W-LOAD-005]: skipped '{fifo}': a FIFO (named pipe), not a regular file" in done.stderr
    assert f"skipped '{tmp_path / 'zero.st'}': a character device, not a regular file" in done.stderr
    assert f"skipped '{tmp_path / 'gone.st'}': a broken symbolic link" in done.stderr
    assert f"skipped '{tmp_path / 'linked'}': a symbolic link to a directory (not followed)" in done.stderr
    assert "1 file(s), 0 error(s), 4 warning(s)" in done.stdout + done.stderr


def test_an_unreadable_subdirectory_is_named(tmp_path, monkeypatch, capsys):
    (tmp_path / "main.st").write_text(PROGRAM, encoding="utf-8")
    (tmp_path / "locked").mkdir()
    real_scandir = os.scandir

    def scandir(path):  # (chmod does not stop root, who runs the CI)
        if os.fspath(path) == str(tmp_path / "locked"):
            raise PermissionError(13, "Permission denied")
        return real_scandir(path)

    monkeypatch.setattr(os, "scandir", scandir)
    assert main(["check", str(tmp_path)]) == 0
    assert (f"skipped '{tmp_path / 'locked'}': cannot read the directory: Permission denied"
            in capsys.readouterr().err)


@pytest.mark.parametrize("option", ["--config", "--axes"])
@pytest.mark.parametrize("kind", ["fifo", "/dev/zero", "link to /dev/zero"])
def test_config_and_axes_files_must_be_regular_files(tmp_path, option, kind):
    path = tmp_path / "file.toml"
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero") if kind.startswith("link") else None
    name = "/dev/zero" if kind == "/dev/zero" else str(path)
    if option == "--config":
        done = _stgen("generate", "--config", name, "--out", str(tmp_path / "out"))
    else:
        done = _stgen("run", AXES_DEMO, "--axes", name, "--program", "AxesDemo", "--cycles", "1")
    assert done.returncode == 1 and "Traceback" not in done.stderr
    what = "a FIFO (named pipe)" if kind == "fifo" else "a character device"
    assert f"{name}: is {what}, not a regular file" in done.stderr
    assert not (tmp_path / "out").exists()


def test_a_config_file_above_the_size_limit_is_refused(tmp_path, capsys):
    from st_runtime.input_files import MAX_TOML_BYTES

    big = tmp_path / "big.toml"
    big.write_text("#" * (MAX_TOML_BYTES + 1), encoding="utf-8")
    assert main(["generate", "--config", str(big), "--out", str(tmp_path / "out")]) == 1
    assert f"big.toml: is {MAX_TOML_BYTES + 1:,} bytes; the limit is {MAX_TOML_BYTES:,}" in capsys.readouterr().err


# --------------------------------------------------------------------------- TOML


@pytest.mark.parametrize("section, key, value, rule", [
    ("task", "period_s", "1e-6", "must lie in [0.0005, 0.1] s, got 1e-06"),
    ("task", "period_s", "1e300", "must lie in [0.0005, 0.1] s, got 1e+300"),
    ("trajectory", "linear_velocity", "1e-6", "must lie in [5, 10000] mm/s, got 1e-06"),
    ("solver", "iterations_per_scan", "32768", "must lie in [1, 100], got 32768"),
    ("solver", "max_iterations", "40000", "must lie in [1, 32767], got 40000"),
    ("geometry", "rb", "1e300", "must lie in [1, 100000] mm, got 1e+300"),
])
def test_absurd_numbers_are_refused_with_the_allowed_range(tmp_path, capsys, section, key, value, rule):
    config = tmp_path / "p.toml"
    config.write_text(f"[{section}]\n{key} = {value}\n", encoding="utf-8")
    assert main(["generate", "--config", str(config), "--out", str(tmp_path / "out")]) == 1
    assert f"{config}:2:1: {section}.{key}: {rule}" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_bad_utf8_and_deep_nesting_in_toml_are_clear_errors(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b"[task]\nperiod_s = 0.001 # caf\xe9\n")
    assert main(["generate", "--config", str(bad), "--out", str(tmp_path / "out")]) == 1
    assert f"{bad}:2:23: not UTF-8 text: byte 0xE9 cannot be decoded" in capsys.readouterr().err
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 2000 + "]" * 2000 + "\n", encoding="utf-8")
    assert main(["generate", "--config", str(deep), "--out", str(tmp_path / "out")]) == 1
    assert f"{deep}: invalid TOML: arrays or inline tables nested too deeply" in capsys.readouterr().err
    axes = tmp_path / "axes.toml"
    axes.write_text('[[axis]]\nname = "A"\nx = ' + "[" * 2000 + "]" * 2000 + "\n", encoding="utf-8")
    assert main(["run", AXES_DEMO, "--axes", str(axes), "--program", "AxesDemo"]) == 1
    assert "arrays or inline tables nested too deeply" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["END_VAR", "end_var", "If"])
def test_an_axis_named_like_a_keyword_is_refused_by_the_axes_validation(tmp_path, capsys, name):
    axes = tmp_path / "axes.toml"
    axes.write_text(f'[[axis]]\nname = "{name}"\nmax_velocity = 200.0\n', encoding="utf-8")  # complete otherwise
    assert main(["run", AXES_DEMO, "--axes", str(axes), "--program", "AxesDemo"]) == 1
    err = capsys.readouterr().err
    assert f"key 'name' must not be an ST keyword, found '{name}'" in err and "E-PARSE" not in err


def test_generate_never_writes_st_that_does_not_check(tmp_path):
    from stgen.commands.generate import generate
    from stgen.config import PlatformConfig
    from stgen.render import RenderError

    config = PlatformConfig.default()
    object.__setattr__(config.solver, "iterations_per_scan", 32768)  # past the TOML validation
    with pytest.raises(RenderError, match=r"(?s)does not pass stgen check.*32768 does not fit INT"):
        generate(tmp_path / "out", "iec", config)
    assert not (tmp_path / "out").exists()


# --------------------------------------------------------------------------- ST text


def test_string_literal_memory_is_linear(tmp_path):
    from st_runtime.parser import parse

    parse(PROGRAM, "warm.st")
    source = "PROGRAM P\nVAR s : STRING[10]; END_VAR\ns := '" + "a$$" * 20_000 + "';\nEND_PROGRAM\n"
    tracemalloc.start()
    try:
        parse(source, "p.st")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # A 60,000-character literal with 20,000 escapes: 22 MB with the grouped lexer pattern, 0.8 MB with the
    # possessive one, which keeps no state per character or escape.
    assert peak < 4_000_000, peak


def test_a_string_literal_above_the_limit_is_a_diagnostic(tmp_path, capsys):
    source = tmp_path / "long.st"
    source.write_text("PROGRAM P\nVAR s : STRING[10]; END_VAR\ns := '" + "a" * 70_000 + "';\nEND_PROGRAM\n",
                      encoding="utf-8")
    assert main(["check", str(source)]) == 1
    err = capsys.readouterr().err
    assert "error[E-PARSE-009]" in err and "string literal of 70,000 characters; the limit is 65,535" in err


@pytest.mark.parametrize("literal", ["16#" + "F" * 5000, "9" * 5000, "LWORD#2#" + "1" * 5000])
def test_a_5000_digit_integer_literal_is_a_diagnostic_not_an_internal_error(tmp_path, capsys, literal):
    source = tmp_path / "big.st"
    source.write_text(f"PROGRAM P\nVAR x : LWORD; END_VAR\nx := {literal};\nEND_PROGRAM\n", encoding="utf-8")
    assert main(["check", str(source)]) == 1
    err = capsys.readouterr().err
    assert "error[E-PARSE-009]" in err and "5,000 digits, far beyond the largest integer type (64 bits)" in err
    assert "E-CHECK-999" not in err and "internal" not in err


def test_control_characters_of_the_source_are_escaped_in_diagnostics(tmp_path, capsys):
    source = tmp_path / "esc.st"
    source.write_text("PROGRAM P\nVAR x : INT; END_VAR\nx := \x1b[2J; (* \u202e *)\nEND_PROGRAM\n", encoding="utf-8")
    assert main(["check", str(source)]) == 1
    err = capsys.readouterr().err
    assert "\x1b" not in err and "\u202e" not in err
    assert "    x := \\x1b[2J; (* \\u202e *)\n         ^" in err  # the caret still under the character

