"""The checked-in ``generated/`` folders equal a fresh ``stgen generate`` for the default platform."""

from __future__ import annotations

from pathlib import Path

import pytest

from stgen.commands.generate import generate

ROOT = Path(__file__).resolve().parent.parent
CHECKED_IN = {"nj": ROOT / "generated" / "nj501", "iec": ROOT / "generated" / "iec"}


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
