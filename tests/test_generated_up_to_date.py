"""The checked-in ``generated/`` folders equal a fresh ``stgen generate`` for the default platform."""

from __future__ import annotations

from pathlib import Path

import pytest

from stgen.commands.generate import generate

ROOT = Path(__file__).resolve().parent.parent
CHECKED_IN = {"nj": ROOT / "generated" / "nj501", "iec": ROOT / "generated" / "iec",
              "sysmac-xml": ROOT / "generated" / "sysmac-xml", "plcopen": ROOT / "generated" / "plcopen"}


def _files(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): p.read_text(encoding="utf-8") for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("target", sorted(CHECKED_IN))
def test_checked_in_output_is_up_to_date(target, tmp_path):
    folder = CHECKED_IN[target]
    generate(tmp_path, target)
    fresh, stored = _files(tmp_path), _files(folder)
    how = f"regenerate with: stgen generate --target {target} --out {folder.relative_to(ROOT)}"
    assert sorted(fresh) == sorted(stored), f"{folder.relative_to(ROOT)} has other files than a fresh generation; " + how
    stale = [name for name in fresh if fresh[name] != stored[name]]
    assert not stale, f"out of date in {folder.relative_to(ROOT)}: {', '.join(stale)}; " + how


def test_checked_in_iec_checks_clean_under_the_nj_dialect(capsys):
    """`stgen check --dialect nj generated/iec`: no error and no warning."""
    from stgen.cli import main

    assert main(["check", "--dialect", "nj", str(CHECKED_IN["iec"])]) == 0
    out = capsys.readouterr()
    assert "0 error(s), 0 warning(s)" in out.out + out.err


@pytest.mark.parametrize("determinant", ["unrolled", "lu"])
def test_other_variants_check_clean_under_the_nj_dialect(determinant):
    from st_runtime import api
    from stgen.render import RenderOptions
    from stgen.verify import KINEMATICS_POUS
    from stgen.exports.iec import pou_text
    from stgen.render import render_program

    program = render_program(options=RenderOptions(determinant))
    project = api.load_sources({f"{n}.st": pou_text(program.pou(n)) for n in KINEMATICS_POUS}, dialect="nj")
    assert project.diagnostics == []
