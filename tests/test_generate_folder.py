"""``stgen generate`` keeps its output folder in step without ever losing a user's file.

The folder's manifest names stgen's files: only those are replaced or swept,
and only while unchanged; files are renamed into place, under a folder lock.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from stgen.cli import main
from stgen.commands.generate import generate
from stgen.exports import GENERATED_BANNER
from stgen.exports.folder import (LOCK_NAME, MANIFEST_NAME, TEMP_PREFIX, FolderBusyError, FolderLock,
                                  ForeignFileError, sha256_of, write_files)


def _names(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir()}


def _manifest(folder: Path) -> dict:
    return json.loads((folder / MANIFEST_NAME).read_text(encoding="utf-8"))


@pytest.mark.parametrize("target", ["nj", "iec"])
def test_the_manifest_lists_every_written_file_with_its_sha256(tmp_path, target):
    update = generate(tmp_path, target)
    manifest = _manifest(tmp_path)
    assert manifest["generator"] == "stgen" and "pending" not in manifest
    assert set(manifest["files"]) == {p.name for p in update.written}
    assert _names(tmp_path) == set(manifest["files"]) | {MANIFEST_NAME}  # no lock, no temporary file left
    for name, digest in manifest["files"].items():
        assert digest == sha256_of((tmp_path / name).read_bytes())


def test_sysmac_tables_carry_no_header_row_and_the_readme_states_the_columns(tmp_path):
    from stgen.exports.sysmac import GLOBAL_COLUMNS, POU_COLUMNS

    generate(tmp_path, "nj")
    for table in tmp_path.glob("*.tsv"):
        first = table.read_text(encoding="utf-8").splitlines()[0].split("\t")
        assert first[0] != "Name", table.name  # a pasted header becomes a variable named Name (issue 8)
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "no header row" in readme
    assert ", ".join(GLOBAL_COLUMNS) in readme and ", ".join(POU_COLUMNS) in readme


def test_cli_sweeps_only_files_of_the_previous_run_and_keeps_changed_and_lookalike_files(tmp_path, capsys):
    # The previous run (an earlier configuration) wrote two files that this run does not write.
    retired = GENERATED_BANNER + "\nFUNCTION_BLOCK SP_Retired\nEND_FUNCTION_BLOCK\n"
    write_files({"SP_Retired.st": retired, "SP_Gone.st": retired.replace("Retired", "Gone")}, tmp_path)
    (tmp_path / "SP_Gone.st").write_text(retired + "(* my change *)\n", encoding="utf-8")
    # The user's files that start with stgen's banner (the case: the old sweep removed them).
    backup = GENERATED_BANNER + "\nPROGRAM SP_Controller (* my edited copy *)\nEND_PROGRAM\n"
    (tmp_path / "SP_Controller_backup.st").write_text(backup, encoding="utf-8")
    (tmp_path / "SP_Controller.st.orig").write_text(backup, encoding="utf-8")
    (tmp_path / "notes.txt").write_text("my notes\n", encoding="utf-8")
    (tmp_path / "sub").mkdir()

    assert main(["generate", "--target", "iec", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "removed 1 stale: SP_Retired.st" in out
    assert "kept 1 changed since stgen wrote them (yours now): SP_Gone.st" in out
    assert not (tmp_path / "SP_Retired.st").exists()
    assert (tmp_path / "SP_Gone.st").read_text(encoding="utf-8").endswith("(* my change *)\n")
    assert (tmp_path / "SP_Controller_backup.st").read_text(encoding="utf-8") == backup
    assert (tmp_path / "SP_Controller.st.orig").read_text(encoding="utf-8") == backup
    assert {"notes.txt", "sub"} <= _names(tmp_path)
    assert "SP_Gone.st" not in _manifest(tmp_path)["files"]  # the user's now: never swept later


def test_a_file_stgen_did_not_write_is_never_overwritten(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_text("# My project\n", encoding="utf-8")
    with pytest.raises(ForeignFileError, match="README.md"):
        generate(tmp_path, "iec")
    assert readme.read_text(encoding="utf-8") == "# My project\n"
    assert _names(tmp_path) == {"README.md"}  # refused before writing anything

    assert main(["generate", "--target", "nj", "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "README.md" in err and "not written by stgen" in err and "Traceback" not in err
    assert _names(tmp_path) == {"README.md"}


def test_a_generated_file_the_user_changed_is_not_overwritten(tmp_path, capsys):
    generate(tmp_path, "iec")
    edited = tmp_path / "SP_Atan2.st"
    edited.write_text(edited.read_text(encoding="utf-8") + "(* tuned by hand *)\n", encoding="utf-8")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    assert main(["generate", "--target", "iec", "--out", str(tmp_path)]) == 1
    assert "SP_Atan2.st: changed since stgen wrote it" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_a_symlink_at_a_generated_name_is_refused_and_its_target_untouched(tmp_path, capsys):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n", encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    (out / "README.md").symlink_to(victim)
    assert main(["generate", "--target", "iec", "--out", str(out)]) == 1
    assert "README.md: is a symbolic link" in capsys.readouterr().err
    assert victim.read_text(encoding="utf-8") == "precious\n"


def test_a_file_already_holding_exactly_the_new_content_is_replaced_without_a_manifest(tmp_path):
    generate(tmp_path, "iec")
    (tmp_path / MANIFEST_NAME).unlink()  # e.g. written by an stgen from before the manifest
    update = generate(tmp_path, "iec")
    assert len(update.written) == len(_manifest(tmp_path)["files"])


def test_switching_the_determinant_variant_leaves_no_file_of_the_other(tmp_path):
    from stgen.render import RenderOptions

    generate(tmp_path, "iec", options=RenderOptions("unrolled"))
    generate(tmp_path, "iec", options=RenderOptions("table"))
    fresh = tmp_path / "fresh"
    generate(fresh, "iec", options=RenderOptions("table"))
    for path in fresh.iterdir():
        assert (tmp_path / path.name).read_bytes() == path.read_bytes()


def test_a_second_run_refuses_at_once_naming_the_first(tmp_path, capsys):
    import socket

    out = tmp_path / "out"
    out.mkdir()
    lock = FolderLock(out)
    lock.acquire()  # the first run, as far as the second can tell
    try:
        with pytest.raises(FolderBusyError):
            write_files({"a.txt": "a\n"}, out)
        assert main(["generate", "--target", "iec", "--out", str(out)]) == 1
        err = capsys.readouterr().err
        assert f"pid {os.getpid()} on host {socket.gethostname()}" in err and "Traceback" not in err
        assert _names(out) == {LOCK_NAME}
    finally:
        lock.release()
    assert main(["generate", "--target", "iec", "--out", str(out)]) == 0
    assert LOCK_NAME not in _names(out)


def test_an_unfinished_temporary_file_is_recognised_and_cleared(tmp_path, capsys):
    generate(tmp_path, "iec")
    (tmp_path / (TEMP_PREFIX + "SP_Atan2.st")).write_bytes(b"")  # a run killed while writing
    assert main(["generate", "--target", "iec", "--out", str(tmp_path)]) == 0
    assert "cleared 1 unfinished file(s) of an interrupted run" in capsys.readouterr().out
    assert not any(n.startswith(TEMP_PREFIX) for n in _names(tmp_path))


def test_write_files_removes_only_unchanged_files_of_its_previous_run(tmp_path):
    write_files({"a.txt": "a\n", "b.txt": "b\n", "c.txt": "c\n"}, tmp_path)
    (tmp_path / "c.txt").write_text("c, mine now\n", encoding="utf-8")
    update = write_files({"a.txt": "a2\n"}, tmp_path)
    assert [p.name for p in update.removed] == ["b.txt"] and [p.name for p in update.kept] == ["c.txt"]
    assert _names(tmp_path) == {"a.txt", "c.txt", MANIFEST_NAME}
    assert set(_manifest(tmp_path)["files"]) == {"a.txt"}
