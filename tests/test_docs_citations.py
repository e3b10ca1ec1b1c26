"""Every citation a reader meets resolves inside the repository (issue 15).

The README, the templates, the figures, the example TOML and the code cite
"docs/<file>", "docs/mathematics.md section N" and the study's equation
numbers [n]: each file must exist, each section must be a heading of
docs/mathematics.md, and each equation number must appear there.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MATHEMATICS = ROOT / "docs" / "mathematics.md"

#: Where citations are made: what a newcomer reads first, then the code.
CITING = [ROOT / "README.md", ROOT / "examples" / "default_platform.toml", ROOT / "stgen" / "figures.py",
          *sorted((ROOT / "st_templates").rglob("*.j2")), *sorted((ROOT / "stgen").rglob("*.py"))]

_DOC_PATH = re.compile(r"\bdocs/[\w.-]+\.md\b")
_SECTION = re.compile(r"docs/mathematics\.md sections? (\d+(?:\.\d+)?)(?:[-–](\d+))?")
# Equation citations: [12], [5-12], [13–18, 34–36], [2,4]; not indexes (A[1]), bounds ([1..6]) or data ([0,0,150]).
_N = r"[1-9]\d?(?:\s*[-–]\s*[1-9]\d?)?"
_EQUATIONS = re.compile(rf"(?<![\w\]])\[({_N}(?:,\s*{_N})?)\]")


def _texts():
    return [(path, path.read_text(encoding="utf-8")) for path in CITING]


def _headings() -> set[str]:
    numbers = set()
    for line in MATHEMATICS.read_text(encoding="utf-8").splitlines():
        match = re.match(r"#{2,3} (\d+(?:\.\d+)?)\.? ", line)
        if match:
            numbers.add(match.group(1))
    return numbers


def test_no_citation_points_outside_the_repository():
    for path, text in _texts():
        assert "SPEC" not in text, f"{path.relative_to(ROOT)} cites SPEC, which is not in the repository"


def test_every_cited_doc_exists():
    cited = {match for _, text in _texts() for match in _DOC_PATH.findall(text)}
    assert "docs/mathematics.md" in cited
    for name in cited:
        assert (ROOT / name).is_file(), name


def test_every_cited_section_is_a_heading():
    headings = _headings()
    assert {"1", "2", "3", "4", "5", "6", "6.1", "6.2", "6.3"} <= headings
    for path, text in _texts():
        for first, last in _SECTION.findall(text):
            for number in ([first] if not last else [str(n) for n in range(int(first), int(last) + 1)]):
                assert number in headings, f"{path.relative_to(ROOT)}: section {number}"


@pytest.mark.parametrize("folder", ["st_templates", "README.md", "examples/default_platform.toml"])
def test_every_equation_number_is_in_the_index(folder):
    index = MATHEMATICS.read_text(encoding="utf-8").split("## Equation index", 1)[1]
    listed = {int(n) for n in re.findall(r"\d+", " ".join(re.findall(r"\[[\d\s,–-]+\]", index)))}
    target = ROOT / folder
    paths = sorted(target.rglob("*.j2")) if target.is_dir() else [target]
    for path in paths:
        for group in _EQUATIONS.findall(path.read_text(encoding="utf-8")):
            for number in re.findall(r"\d+", group):
                assert int(number) in listed, f"{path.relative_to(ROOT)}: [{group}] not in docs/mathematics.md"


def test_the_nj501_study_is_cited_in_full():
    text = MATHEMATICS.read_text(encoding="utf-8")
    assert "https://doi.org/10.3390/machines10080711" in text
    assert "*Machines* 2022" in text
