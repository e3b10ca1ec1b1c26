"""The Hypothesis profile follows the environment (see conftest.py)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from hypothesis import settings

HERE = Path(__file__).parent

PROBE = '''
import json, os
from hypothesis import given, settings, strategies as st

SEEN = []

@given(st.integers())
def test_draw(x):
    SEEN.append(x)

def test_zz_report():
    s = settings.default
    with open(os.environ["PROBE_OUT"], "w") as out:
        json.dump({"derandomize": s.derandomize, "print_blob": s.print_blob,
                   "database": s.database is None, "seen": SEEN}, out)
'''


def test_profile_matches_environment():
    expected = os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if os.environ.get("CI") else "dev")
    assert settings.default.derandomize is (expected == "ci")
    assert settings.default.print_blob is True


def _probe(tmp_path, ci: bool) -> dict:
    import json

    (tmp_path / "conftest.py").write_text((HERE / "conftest.py").read_text())
    (tmp_path / "test_probe.py").write_text(PROBE)
    env = {k: v for k, v in os.environ.items() if k not in ("CI", "HYPOTHESIS_PROFILE")}
    if ci:
        env["CI"] = "true"
    env["PROBE_OUT"] = str(tmp_path / "out.json")
    subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(tmp_path)],
                   env=env, cwd=tmp_path, check=True, capture_output=True)
    return json.loads((tmp_path / "out.json").read_text())


def test_ci_runs_draw_the_same_examples_every_time(tmp_path):
    first = _probe(tmp_path, ci=True)
    second = _probe(tmp_path, ci=True)
    assert first["derandomize"] and first["print_blob"] and first["database"]
    assert first["seen"] == second["seen"] and len(first["seen"]) >= 10


def test_local_runs_explore_randomly(tmp_path):
    local = _probe(tmp_path, ci=False)
    assert local["derandomize"] is False and local["print_blob"] is True
