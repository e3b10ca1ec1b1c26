"""Every snippet of the checker's accept corpus compiles and runs three scans
without an exception (runtime faults are allowed: they are data)."""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime import loader
from st_runtime.compiler import compile_program
from st_runtime.controller import Controller

CORPUS = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))


@pytest.mark.parametrize("path", CORPUS, ids=[p.stem for p in CORPUS])
def test_accepted_snippet_compiles_and_runs(path):
    from test_checker_corpus import accept_dialect

    result = loader.load([str(path)], accept_dialect(path.read_text(encoding="utf-8")))
    if result.program is None:
        pytest.skip("not accepted by the checker in this build")
    compiled = compile_program(result.program)
    controller = Controller(compiled, time_limit_ns=500_000)
    for pou in result.program.pous.values():
        if pou.kind == "PROGRAM":
            controller.add_program(pou.name)
    assert controller.run(3) == 3
    for record in controller.faults:
        assert record.code.startswith("F-") and record.line >= 1
