"""``stgen run --trace`` streams to disk: bounded memory, write-then-rename, Ctrl-C keeps what ran (issue 9).

Before: every sample stayed in memory (10 million scans of one DINT took
1.65 GB; 30 million ended in MemoryError with no CSV at all), and the CSV was
written only at the end.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time
import tracemalloc

from st_runtime import load
from st_runtime.trace import read_csv

COUNTER = "PROGRAM Count\nVAR n : DINT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"


def _trace_bytes_held_after_a_streamed_run(source, out, scans: int) -> int:
    """Bytes still allocated by the trace module (st_runtime/trace.py) once the run is over.

    Only the trace's own allocations are counted: the controller keeps other
    per-scan records (the NJ time estimate) that are not the trace's.
    """
    plc = load([str(source)]).controller(period="1ms")
    plc.add_program("Count")
    tracemalloc.start(5)
    try:
        trace_file = plc.trace(["n"], program="Count").stream_to(out)
        plc.run(scans)
        snapshot = tracemalloc.take_snapshot().filter_traces([tracemalloc.Filter(True, "*st_runtime/trace.py",
                                                                                  all_frames=True)])
        return sum(stat.size for stat in snapshot.statistics("filename"))
    finally:
        tracemalloc.stop()
        trace_file.close()


def test_memory_of_a_streamed_trace_does_not_grow_with_the_number_of_scans(tmp_path):
    source = tmp_path / "count.st"
    source.write_text(COUNTER, encoding="utf-8")
    short = _trace_bytes_held_after_a_streamed_run(source, tmp_path / "short.csv", 2_000)
    long = _trace_bytes_held_after_a_streamed_run(source, tmp_path / "long.csv", 40_000)
    # Kept in memory, 38,000 more rows cost megabytes (a tuple, a time and a scan number each).
    assert long - short < 64 * 1024, (short, long)
    data = read_csv(tmp_path / "long.csv")
    assert list(data["scan"][:3]) == [1, 2, 3] and len(data["scan"]) == 40_000
    assert data["n"][-1] == 40_000


def _start_long_run(tmp_path):
    source = tmp_path / "count.st"
    source.write_text(COUNTER, encoding="utf-8")
    out = tmp_path / "out.csv"
    run = subprocess.Popen([sys.executable, "-m", "stgen", "run", str(source), "--program", "Count",
                            "--cycles", "100000000", "--trace", str(out), "--watch", "n"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    partial = tmp_path / "out.csv.partial"
    for _ in range(600):  # until some rows have reached the disk (at most a minute on a loaded machine)
        if partial.exists() and partial.stat().st_size > 100_000:
            break
        time.sleep(0.1)
    return run, out, partial


def test_ctrl_c_leaves_a_complete_trace_of_the_scans_that_ran(tmp_path):
    run, out, partial = _start_long_run(tmp_path)
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=60)
    assert run.returncode == 130, stderr
    assert "interrupted after" in stderr and f"{out} holds the" in stderr and "Traceback" not in stderr
    rows = int(stderr.split(" holds the ")[1].split(" ")[0])
    assert f"interrupted after {rows} of 100000000 scans" in stderr
    assert not partial.exists()
    data = read_csv(out)  # every line whole: the last row is a scan, not half of one
    assert len(data["scan"]) == rows > 0
    assert list(data["scan"]) == list(range(1, rows + 1)) and list(data["n"]) == list(range(1, rows + 1))


def test_a_killed_run_leaves_only_a_file_named_partial(tmp_path):
    run, out, partial = _start_long_run(tmp_path)
    run.kill()
    run.communicate(timeout=60)
    assert not out.exists()  # nothing that looks like a finished trace
    assert partial.read_text(encoding="utf-8").startswith("time_s,scan,n\n")


def test_a_symlink_at_the_trace_path_is_replaced_not_followed(tmp_path):
    from stgen.cli import main

    source = tmp_path / "count.st"
    source.write_text(COUNTER, encoding="utf-8")
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n", encoding="utf-8")
    (tmp_path / "out.csv").symlink_to(victim)
    assert main(["run", str(source), "--program", "Count", "--cycles", "3", "--trace", str(tmp_path / "out.csv"),
                 "--watch", "n"]) == 0
    assert victim.read_text(encoding="utf-8") == "precious\n"
    assert list(read_csv(tmp_path / "out.csv")["n"]) == [1, 2, 3]


def test_a_second_ctrl_c_stops_a_scan_that_does_not_end(tmp_path):
    source = tmp_path / "spin.st"
    source.write_text("PROGRAM Spin\nVAR n : DINT; END_VAR\nWHILE TRUE DO n := n + 1; END_WHILE\nEND_PROGRAM\n",
                      encoding="utf-8")
    out = tmp_path / "out.csv"
    run = subprocess.Popen([sys.executable, "-m", "stgen", "run", str(source), "--program", "Spin", "--cycles", "5",
                            "--time-limit", "100000s", "--trace", str(out), "--watch", "n"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    partial = tmp_path / "out.csv.partial"
    for _ in range(600):
        if partial.exists():
            break
        time.sleep(0.1)
    time.sleep(0.5)  # inside the first scan's loop
    run.send_signal(signal.SIGINT)  # asks to stop after the scan: this one never ends
    time.sleep(0.5)
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=60)
    assert run.returncode == 130, stderr
    assert "interrupted during scan 1 of 5" in stderr and "holds the scans before it" in stderr
    assert out.read_text(encoding="utf-8") == "time_s,scan,n\n" and not partial.exists()
