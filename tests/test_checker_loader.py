"""The loader: directories, unreadable and non-UTF-8 files, the prelude."""

from __future__ import annotations

import os

from st_runtime.loader import load

MAIN = "PROGRAM Main\nVAR t : TON; x : LREAL; END_VAR\nt(IN := TRUE, PT := T#1s);\nx := Half(2.0);\nEND_PROGRAM\n"
HALF = "FUNCTION Half : LREAL\nVAR_INPUT a : LREAL; END_VAR\nHalf := a / 2.0;\nEND_FUNCTION\n"


def test_directory_expands_to_its_st_files_sorted(tmp_path):
    (tmp_path / "b_main.st").write_text(MAIN)
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "a_half.ST").write_text(HALF)
    (tmp_path / "notes.txt").write_text("not ST")
    result = load([str(tmp_path)])
    assert result.program is not None, result.render()
    assert list(result.sources) == ["<builtin>", str(tmp_path / "b_main.st"), str(tmp_path / "sub" / "a_half.ST")]
    assert set(result.program.sources) == {str(tmp_path / "b_main.st"), str(tmp_path / "sub" / "a_half.ST")}


def test_files_are_checked_together(tmp_path):
    (tmp_path / "main.st").write_text(MAIN)
    only_main = load([str(tmp_path / "main.st")])
    assert [d.code for d in only_main.errors] == ["E-DECL-001"]     # Half is in another file
    (tmp_path / "half.st").write_text(HALF)
    both = load([str(tmp_path / "main.st"), str(tmp_path / "half.st")])
    assert both.program is not None


def test_missing_path(tmp_path):
    result = load([str(tmp_path / "nope.st")])
    assert result.program is None
    assert [d.code for d in result.errors] == ["E-LOAD-001"]
    assert "nope.st" in result.errors[0].message


def test_non_utf8_file_reports_where(tmp_path):
    path = tmp_path / "latin1.st"
    path.write_bytes("PROGRAM Main\n(* Gr\u00fc\u00dfe *)\nEND_PROGRAM\n".encode("latin-1"))
    result = load([str(path)])
    [d] = result.errors
    assert d.code == "E-LOAD-003"
    assert (d.pos.line, d.pos.col) == (2, 6)
    assert "0xFC" in d.message


def test_unreadable_file(tmp_path, monkeypatch):
    path = tmp_path / "locked.st"
    path.write_text(MAIN)

    real_open = os.open

    def refuse(name, *args, **kwargs):  # (chmod does not stop root, who runs the CI)
        if os.fspath(name) == str(path):
            raise PermissionError(13, "Permission denied")
        return real_open(name, *args, **kwargs)

    monkeypatch.setattr(os, "open", refuse)
    result = load([str(path)])
    assert [d.code for d in result.errors] == ["E-LOAD-002"]
    assert "Permission denied" in result.errors[0].message


def test_empty_directory_is_a_warning(tmp_path):
    result = load([str(tmp_path)])
    assert [d.code for d in result.diagnostics] == ["W-LOAD-004"]
    assert result.program is not None


def test_diagnostics_are_sorted_by_file_then_line(tmp_path):
    (tmp_path / "a.st").write_text("PROGRAM A\nVAR i : INT; END_VAR\ni := 1.5;\ni := q;\nEND_PROGRAM\n")
    (tmp_path / "b.st").write_text("PROGRAM B\nVAR i : INT; END_VAR\ni := z;\nEND_PROGRAM\n")
    result = load([str(tmp_path)])
    assert [(d.pos.file.rsplit("/", 1)[-1], d.pos.line) for d in result.errors] == [
        ("a.st", 3), ("a.st", 4), ("b.st", 3)]
