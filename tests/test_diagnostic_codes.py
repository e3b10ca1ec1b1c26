"""Every registered diagnostic code is exercised by at least one test.

A code counts as tested when a corpus header (`(* expect: CODE ...`) expects
it, or when its
text appears in a test module (other than this one).  The catalogue is read
in a fresh interpreter that imports every stage registering codes, so the
answer does not depend on which test modules ran first.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).parent
ROOT = TESTS.parent
STAGES = ["st_runtime.parser", "st_runtime.loader", "st_runtime.checker", "st_runtime.compiler"]

def registered_codes() -> dict[str, str]:
    script = (
        "import importlib, json\n"
        f"for name in {STAGES!r}:\n"
        "    try:\n        importlib.import_module(name)\n"
        "    except ModuleNotFoundError:\n        pass\n"
        "from st_runtime.diagnostics import CODES\n"
        "print(json.dumps(CODES))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         cwd=ROOT, check=True, timeout=120).stdout
    return json.loads(out)


def codes_named_in_tests() -> set[str]:
    found: set[str] = set()
    header = re.compile(r"\(\* expect: ([EW]-[A-Z]+-\d{3})")
    for path in (TESTS / "corpus").rglob("*.st"):
        m = header.match(path.read_text(encoding="utf-8"))
        if m:
            found.add(m.group(1))
    code = re.compile(r"\b[EW]-[A-Z]+-\d{3}\b")
    for path in TESTS.rglob("test_*.py"):
        if path.name != Path(__file__).name:
            found.update(code.findall(path.read_text(encoding="utf-8")))
    return found


def test_every_registered_code_has_a_test():
    codes = registered_codes()
    assert len(codes) > 60
    untested = sorted(set(codes) - codes_named_in_tests())
    assert not untested, f"codes without a test: {untested}"


def test_every_code_has_an_explanation_and_a_stable_shape():
    for code, text in registered_codes().items():
        assert re.fullmatch(r"[EW]-[A-Z]+-\d{3}", code), code
        assert text and text[0].islower() or text[0].isupper(), code


def test_parser_internal_error_is_a_diagnostic(monkeypatch):
    from st_runtime import parser

    def explode(text, path):
        raise ValueError("boom")

    monkeypatch.setattr(parser, "_parse", explode)
    tree, diagnostics = parser.parse("PROGRAM Main\nEND_PROGRAM\n", "x.st")
    assert tree is None and [d.code for d in diagnostics] == ["E-PARSE-099"]
