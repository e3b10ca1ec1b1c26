"""Every generated IEC file parses with blark, an independent IEC 61131-3 parser.

blark's grammar is ambiguous for array initializers (a bracketed list may hold
bare lists, so ``[1, 2, 3]`` has many parse trees) and its Earley parser slows
down steeply with the list length: 60 elements take seconds, 240 minutes. The
720 x 6 Leibniz table would never finish. So before handing a file to blark,
initializer lists longer than :data:`MAX_INITIALIZER_ITEMS` are cut to their
first items; everything else is parsed as written. The full tables are checked
by the in-house checker (``stgen check``) and by the differential tests.
"""

from __future__ import annotations

import re
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest

blark = pytest.importorskip("blark", reason="blark (independent IEC parser) is not installed; pip install blark")

from stgen.render import RenderOptions, render_program  # noqa: E402
from stgen.exports import iec  # noqa: E402

GENERATED_IEC = Path(__file__).resolve().parent.parent / "generated" / "iec"
MAX_INITIALIZER_ITEMS = 12
#: Terms of the unrolled Leibniz determinant handed to blark (all 720 share one statement shape).
UNROLLED_TERMS_CHECKED = 12

_INITIALIZER = re.compile(r":= \[([^\]]*)\]", re.S)


def shorten_initializers(text: str) -> str:
    def cut(match: re.Match) -> str:
        items = [item.strip() for item in match.group(1).split(",")]
        return ":= [" + ", ".join(items[:MAX_INITIALIZER_ITEMS]) + "]"

    return _INITIALIZER.sub(cut, text)


def blark_error(name_and_text: tuple[str, str]) -> str | None:
    name, text = name_and_text
    result = blark.parse_source_code(text, fn=name)
    return None if result.exception is None else f"{name}: {result.exception}"


def _parse_all(sources: dict[str, str]) -> list[str]:
    with ProcessPoolExecutor(max_workers=2) as pool:
        return [error for error in pool.map(blark_error, sources.items()) if error]


def test_shortening_keeps_the_declaration_shape():
    text = "T : ARRAY[1..20] OF INT := [" + ", ".join(str(i) for i in range(20)) + "];"
    assert shorten_initializers(text) == "T : ARRAY[1..20] OF INT := [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];"


def test_every_checked_in_iec_file_parses_with_blark():
    files = sorted(GENERATED_IEC.glob("*.st"))
    assert len(files) >= 7, f"expected the generated IEC files in {GENERATED_IEC}"
    sources = {path.name: shorten_initializers(path.read_text(encoding="utf-8")) for path in files}
    assert _parse_all(sources) == []


def test_blark_rejects_a_broken_file():
    """The check has teeth: a missing semicolon is a blark error."""
    text = (GENERATED_IEC / "SP_Atan2.st").read_text(encoding="utf-8").replace("SP_Atan2 := 0.0;", "SP_Atan2 := 0.0")
    assert blark_error(("broken.st", text)) is not None


def test_the_unrolled_and_lu_variants_parse_with_blark():
    unrolled = iec.pou_text(render_program(options=RenderOptions("unrolled")).pou("SP_LeibnizDeterminant"))
    lines = unrolled.splitlines()
    terms = [i for i, line in enumerate(lines) if line.startswith("Determinant := Determinant ")]
    assert len(terms) == 720
    kept = lines[: terms[UNROLLED_TERMS_CHECKED]] + lines[terms[-1] + 1 :]
    fk_lu = iec.pou_text(render_program(options=RenderOptions("lu")).pou("SP_ForwardKinematics"))
    sources = {"unrolled.st": "\n".join(kept) + "\n", "fk_lu.st": fk_lu}
    assert _parse_all(sources) == []
