"""``stgen generate`` keeps its output folder in step: stale generated files go,
files a user put there stay, and a user's file is never overwritten."""

from __future__ import annotations

from pathlib import Path

import pytest

from stgen.cli import main
from stgen.commands.generate import generate
from stgen.exports import GENERATED_BANNER
from stgen.exports.folder import ForeignFileError


def _names(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir()}


@pytest.mark.parametrize("target", ["nj", "iec"])
def test_a_second_run_removes_stale_generated_files_and_keeps_the_users(tmp_path, target):
    first = generate(tmp_path, target)
    fresh = _names(tmp_path)
    assert {p.name for p in first.written} == fresh and first.removed == []
    # A POU that no longer exists (as after a rename), in each kind of file stgen writes.
    body = next(p for p in first.written if p.suffix == ".st")
    (tmp_path / "SP_Retired.st").write_text(body.read_text(encoding="utf-8"), encoding="utf-8")
    if target == "nj":
        table = tmp_path / "SP_Atan2.variables.tsv"
        (tmp_path / "SP_Retired.variables.tsv").write_text(table.read_text(encoding="utf-8"), encoding="utf-8")
    # Files of the user's: other text, no banner, same extensions; a sub-folder.
    (tmp_path / "notes.txt").write_text("my notes\n", encoding="utf-8")
    (tmp_path / "Mine.st").write_text("(* my own POU *)\nFUNCTION Mine : INT\nEND_FUNCTION\n", encoding="utf-8")
    (tmp_path / "mine.tsv").write_text("Name\tType\n", encoding="utf-8")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "SP_Retired.st").write_text(GENERATED_BANNER + "\n", encoding="utf-8")

    second = generate(tmp_path, target)
    removed = sorted(p.name for p in second.removed)
    assert removed == (["SP_Retired.st", "SP_Retired.variables.tsv"] if target == "nj" else ["SP_Retired.st"])
    assert _names(tmp_path) == fresh | {"notes.txt", "Mine.st", "mine.tsv", "sub"}
    assert (tmp_path / "sub" / "SP_Retired.st").is_file()  # only the folder itself is cleaned


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


def test_the_cli_names_the_files_it_removed(tmp_path, capsys):
    assert main(["generate", "--target", "iec", "--out", str(tmp_path)]) == 0
    (tmp_path / "SP_Retired.st").write_text(GENERATED_BANNER + "\nFUNCTION_BLOCK SP_Retired\nEND_FUNCTION_BLOCK\n",
                                            encoding="utf-8")
    assert main(["generate", "--target", "iec", "--out", str(tmp_path)]) == 0
    assert "removed 1 stale: SP_Retired.st" in capsys.readouterr().out
    assert not (tmp_path / "SP_Retired.st").exists()


def test_switching_the_determinant_variant_leaves_no_file_of_the_other(tmp_path):
    from stgen.render import RenderOptions

    generate(tmp_path, "iec", options=RenderOptions("unrolled"))
    generate(tmp_path, "iec", options=RenderOptions("table"))
    fresh = tmp_path / "fresh"
    generate(fresh, "iec", options=RenderOptions("table"))
    for path in fresh.iterdir():
        assert (tmp_path / path.name).read_text(encoding="utf-8") == path.read_text(encoding="utf-8")
