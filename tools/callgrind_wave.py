"""Machine instructions per scan of the whole controller in the random wave, by callgrind.

    # this tree
    .venv/bin/python tools/callgrind_wave.py [--scans 1000] [--keep out.callgrind]
    # any other tree (the code measured is the one PYTHONPATH puts first)
    PYTHONPATH=/path/to/tree .venv/bin/python tools/callgrind_wave.py

Prints the machine instructions (callgrind's Ir) of one scan, the mean of ``--scans`` scans
in the wave. A figure the machine's load does not change, unlike a time: read it beside
``benchmarks/bench_wave_realtime.py``. ``--keep`` keeps callgrind's output file for
``callgrind_annotate``.

How: the script runs itself under ``valgrind --tool=callgrind --instr-atstart=no`` with
PYTHONHASHSEED=0. The child loads SP_Controller, powers on and runs into the wave
(2,500 scans, uninstrumented), then asks callgrind (``callgrind_control -i on``) to
instrument and runs the measured scans as one ``sim.run(n)`` inside ``itertools.starmap``;
``--toggle-collect=starmap_next`` counts only what happens inside that call, so neither the
load nor the switching is counted. Slow (a minute or two: callgrind runs some 50x slower).
"""

from __future__ import annotations

import argparse
import itertools
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: Scans run before the measured ones: power on, locate and the lead-in are over by then.
INTO_THE_WAVE = 2500
_CHILD = "--child"


def measured_run(scans: int) -> None:
    """The child: into the wave uninstrumented, then ``scans`` scans with the instrumentation on."""
    from stgen.config import PlatformConfig
    from stgen.scenarios.definitions import RANDOM_WAVE
    from stgen.scenarios.runner import command_scenario
    from stgen.scenarios.simulation import ControllerSimulation

    config = PlatformConfig.default()
    scenario = RANDOM_WAVE.with_wave_seconds(60.0)
    sim = ControllerSimulation(config, scenario.start_pose)
    sim.power_on()
    command_scenario(sim, scenario)
    sim.run(INTO_THE_WAVE)
    instrument("on")
    for _ in itertools.starmap(sim.run, [(scans,)]):
        pass
    if sim.globals["SpFaultID"] or sim.runtime_faults:
        raise SystemExit(f"the controller faulted: {sim.globals['SpFaultID']:#06x} {sim.runtime_faults[:3]}")


def instrument(state: str) -> None:
    """Switch callgrind's instrumentation of this process on or off (waits until it is done)."""
    subprocess.run(["callgrind_control", "-i", state, str(os.getpid())], check=True,
                   stdout=subprocess.DEVNULL)


def instructions(out_file: Path) -> int:
    """The Ir total of a callgrind output file."""
    match = re.search(r"^(?:summary|totals):\s+(\d+)", out_file.read_text(), re.MULTILINE)
    if match is None:
        raise SystemExit(f"no instruction total in {out_file}")
    return int(match.group(1))


def run_under_callgrind(scans: int, out_file: Path, script: str = __file__, *child_args: str) -> int:
    """Instructions counted inside ``starmap`` when ``script --child scans *child_args`` runs."""
    env = dict(os.environ, PYTHONHASHSEED="0")
    command = ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--toggle-collect=starmap_next",
               f"--callgrind-out-file={out_file}", sys.executable, script, _CHILD, str(scans), *child_args]
    result = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode:
        raise SystemExit(f"callgrind run failed ({result.returncode}):\n{result.stderr[-3000:]}")
    return instructions(out_file)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == [_CHILD]:
        measured_run(int(argv[1]))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scans", type=int, default=1000, help="scans measured (default 1000)")
    parser.add_argument("--keep", type=Path, help="keep callgrind's output file here")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as scratch:
        out_file = args.keep or Path(scratch) / "callgrind.out"
        started = time.perf_counter()
        total = run_under_callgrind(args.scans, out_file)
    import stgen

    tree = Path(stgen.__file__).resolve().parent.parent
    print(f"{tree}: {total / args.scans:,.0f} machine instructions a wave scan "
          f"({total:,} in {args.scans:,} scans; {time.perf_counter() - started:.0f} s under callgrind)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
