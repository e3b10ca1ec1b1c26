"""``stgen generate`` killed midway (kill -9) or run concurrently, with real processes.

Before the manifest, a run killed midway left a 0-byte file that made every
later run refuse ("exists and was not written by stgen") until the user
deleted it; 2 of 8 concurrent runs into one folder failed that way (issue 9).
Now the next run always succeeds and the folder ends as a fresh generation.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from stgen.exports.folder import MANIFEST_NAME

#: Runs ``stgen`` with SIGKILL sent to itself at the N-th call of ``os.<function>``:
#: a kill -9 at a chosen point of the write (argv: function, N, stgen arguments...).
_KILLED_AT = """
import os, signal, sys
function, when = sys.argv[1], int(sys.argv[2])
real, calls = getattr(os, function), [0]
def killing(*args, **kwargs):
    calls[0] += 1
    if calls[0] == when:
        os.kill(os.getpid(), signal.SIGKILL)
    return real(*args, **kwargs)
setattr(os, function, killing)
from stgen.cli import main
sys.exit(main(sys.argv[3:]))
"""


def _contents(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def _stgen(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "stgen", *args], capture_output=True, text=True, **kwargs)


@pytest.fixture(scope="module")
def fresh_nj(tmp_path_factory) -> dict[str, bytes]:
    out = tmp_path_factory.mktemp("fresh") / "nj"
    assert _stgen("generate", "--target", "nj", "--out", str(out)).returncode == 0
    return _contents(out)


# os.replace: 1 = the pending manifest, 2..21 = the 20 files, 22 = the final manifest.
# os.fsync: 3 = while staging the second file (temporary files on disk, nothing renamed yet).
@pytest.mark.parametrize("function, when", [("fsync", 3), ("replace", 1), ("replace", 2), ("replace", 12),
                                            ("replace", 22)])
def test_a_run_killed_midway_leaves_a_folder_the_next_run_completes(tmp_path, fresh_nj, function, when):
    out = tmp_path / "nj"
    # An earlier complete run of the other determinant variant, so the killed run has files to replace.
    assert _stgen("generate", "--target", "nj", "--determinant", "unrolled", "--out", str(out)).returncode == 0
    killed = subprocess.run([sys.executable, "-c", _KILLED_AT, function, str(when),
                             "generate", "--target", "nj", "--out", str(out)], capture_output=True, text=True)
    assert killed.returncode == -signal.SIGKILL
    rerun = _stgen("generate", "--target", "nj", "--out", str(out))
    assert rerun.returncode == 0, rerun.stderr
    assert _contents(out) == fresh_nj  # every file, the manifest included; no lock or temporary file left


def test_concurrent_runs_refuse_at_once_or_succeed_and_leave_a_complete_folder(tmp_path, fresh_nj):
    out = tmp_path / "nj"
    runs = [subprocess.Popen([sys.executable, "-m", "stgen", "generate", "--target", "nj", "--out", str(out)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(8)]
    results = [(run.wait(), run.stderr.read()) for run in runs]
    for run in runs:
        run.stdout.close()
        run.stderr.close()
    assert any(code == 0 for code, _ in results)
    for code, err in results:
        assert code == 0 or (code == 1 and "another stgen run is writing this folder (pid " in err), err
    assert _contents(out) == fresh_nj


def test_a_real_kill_at_a_random_moment_never_blocks_the_next_run(tmp_path, fresh_nj):
    """The issue's experiment, a few times: kill -9 after a moment the test does not choose."""
    import random
    import time

    out = tmp_path / "nj"
    for attempt in range(3):
        run = subprocess.Popen([sys.executable, "-m", "stgen", "generate", "--target", "nj", "--out", str(out)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(random.uniform(0.2, 0.8))
        os.kill(run.pid, signal.SIGKILL)
        run.wait()
        rerun = _stgen("generate", "--target", "nj", "--out", str(out))
        assert rerun.returncode == 0, rerun.stderr
        assert _contents(out) == fresh_nj
        assert MANIFEST_NAME in _contents(out)


def test_two_runs_killed_in_a_row_still_leave_a_folder_the_next_run_completes(tmp_path):
    """Two runs killed after writing their pending manifest, before renaming any file: the folder
    still holds the first run's files, which the second run's manifest must still know (three
    configurations, so the global table has three different contents)."""
    out, fresh = tmp_path / "nj", tmp_path / "fresh"
    configs = []
    for stroke in (650.0, 700.0):
        config = tmp_path / f"stroke{stroke:g}.toml"
        config.write_text(f"[stroke]\nmax = {stroke}\n", encoding="utf-8")
        configs.append(str(config))
    assert _stgen("generate", "--target", "nj", "--out", str(out)).returncode == 0
    for config in configs:
        killed = subprocess.run([sys.executable, "-c", _KILLED_AT, "replace", "2", "generate", "--target", "nj",
                                 "--config", config, "--out", str(out)], capture_output=True, text=True)
        assert killed.returncode == -signal.SIGKILL
    for folder in (out, fresh):  # not the first run's content: only the manifest can tell it is stgen's
        done = _stgen("generate", "--target", "nj", "--config", configs[0], "--out", str(folder))
        assert done.returncode == 0, done.stderr
    assert _contents(out) == _contents(fresh)
