"""The project's own ST unit tests (tests/st_unit/test_*.st), run with `stgen test`.

Each TEST block becomes one pytest case, so a failure names the block and
shows the file:line of its assert with both values.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime.testing import run_tests

FILES = sorted(str(p) for p in (Path(__file__).parent / "st_unit").glob("test_*.st"))
RUN = run_tests(FILES)


def test_the_st_unit_tests_load():
    assert RUN.loaded, RUN.render_diagnostics()
    assert len(RUN.results) >= 6


@pytest.mark.parametrize("result", RUN.results, ids=lambda r: r.name)
def test_st_unit_test(result):
    assert result.status == "passed", result.detail
