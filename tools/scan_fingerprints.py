"""Per-scan fingerprints of the whole controller on four scenarios: proof that a speed change
to the scan loop, the motion layer or the compiler changed nothing a scan leaves behind.

    # record with the code before the change (any checkout: PYTHONPATH picks the tree)
    PYTHONPATH=/path/to/main .venv/bin/python tools/scan_fingerprints.py record before.json
    # check the working tree against it
    .venv/bin/python tools/scan_fingerprints.py check before.json

A fingerprint hashes, after a scan: every global (the AXIS_REF variables included) and
every program instance with its FB instances (native motion FBs by their variables,
last Execute and command), every axis's state (floats by their bits), the faults
(code, message, POU, file, line, column, scan) and the NJ time charged to the scan
(`--no-times` leaves the time out: a change of the estimate alone).
The scenarios (SP_Controller, six axes) cover the random and the Airy wave, a point-to-point
move, MC_Stop, an injected axis error mid-move and its reset, a servo lag, an observation
set between scans, a command step the sync saturates (VelLimit), power off and on.  Each
runs twice: scan by scan (a fingerprint per scan, every scan its own `scan()` call), and in
chunks of one `Controller.run` call each (a fingerprint per chunk: what a run of many scans
skips, e.g. the feedback in of ScanContext.resumed, must end in the same state).
Not a test: it takes a few minutes and compares two versions of the code.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import sys

from st_runtime.motion.axis import MotionCommand
from st_runtime.motion.error_ids import ErrorID
from st_runtime.native import NativeFB
from st_runtime.objects import STObject
from stgen.config import PlatformConfig
from stgen.scenarios import definitions
from stgen.scenarios.runner import apply_limits, command_scenario, release_commands
from stgen.scenarios.simulation import ControllerSimulation

AXIS_FIELDS = ("state", "power_requested", "powered", "homed", "cmd_pos", "act_pos", "cmd_vel", "cmd_accdec",
               "act_vel", "fault_code", "observation_code", "vel_limit", "in_pos_waiting", "_in_pos_wait_s", "command")


def text(value, seen: set) -> str:
    """A value as text: floats by their bits, objects member by member."""
    if isinstance(value, float):
        return value.hex() if not math.isnan(value) else "nan"
    if isinstance(value, (bool, int, str, bytes)) or value is None:
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(text(v, seen) for v in value) + "]"
    if isinstance(value, MotionCommand):
        return "cmd(" + ",".join(text(getattr(value, f), seen) for f in MotionCommand.__slots__) + ")"
    if id(value) in seen:
        return "cycle"
    if isinstance(value, STObject):
        seen.add(id(value))
        return type(value).__name__ + "{" + ",".join(
            f"{slot}={text(getattr(value, slot, None), seen)}" for slot in type(value).__slots__) + "}"
    if isinstance(value, NativeFB):
        seen.add(id(value))
        members = sorted((k, v) for k, v in vars(value).items() if k.startswith("v_") and k != "v_AXIS")
        axis = getattr(value, "v_AXIS", None)
        extra = [getattr(value, "_previous_execute", None), getattr(value, "_command", None),
                 axis.v_CFG.v_AXNO if axis is not None else None]
        return type(value).__name__ + "{" + ",".join(f"{k}={text(v, seen)}" for k, v in members) + text(extra, seen) + "}"
    return type(value).__name__


class Recorder:
    def __init__(self, sim: ControllerSimulation, chunked: bool, times: bool = True):
        self.sim, self.chunked, self.times, self.prints = sim, chunked, times, []

    def scan(self, count: int = 1) -> None:
        controller = self.sim.plc.controller
        if self.chunked:
            controller.run(count)
            self.fingerprint()
            return
        for _ in range(count):
            controller.scan()
            self.fingerprint()

    def fingerprint(self) -> None:
        controller = self.sim.plc.controller
        seen: set = set()
        parts = [text(controller.compiled.globals, seen)]
        parts += [name + text(instance, seen) for name, instance in sorted(controller.instances.items())]
        parts += [text([getattr(axis, f) for f in AXIS_FIELDS], set()) for axis in self.sim.axes]
        parts.append(repr([(f.code, f.message, f.pou, f.file, f.line, f.col, f.scan) for f in controller.faults]))
        if self.times:
            times = controller.task_times["Primary"]
            parts.append(repr(times[-1] if times else None))
        self.prints.append(hashlib.sha1("|".join(parts).encode()).hexdigest()[:16])


def scenarios(chunked: bool, times: bool = True):
    config = PlatformConfig.default()

    def start(scenario, **kwargs):
        sim = ControllerSimulation(config, scenario.start_pose, **kwargs)
        rec = Recorder(sim, chunked, times)
        sim.globals["SpPowerOn"] = True
        rec.scan(60)
        return sim, rec

    def pulse(sim, rec, name, scans, after):
        sim.globals[name] = True
        rec.scan(scans)
        sim.globals[name] = False
        rec.scan(after)

    # random wave, MC_Stop, reset, power off
    sim, rec = start(definitions.RANDOM_WAVE)
    command_scenario(sim, definitions.RANDOM_WAVE.with_wave_seconds(2.0))
    rec.scan(2500)
    release_commands(sim)
    pulse(sim, rec, "SpStop", 300, 20)
    pulse(sim, rec, "SpReset", 10, 10)
    sim.globals["SpPowerOn"] = False
    rec.scan(30)
    yield "wave_stop", rec.prints

    # point to point, an axis error injected mid-move, reset, the next move, power off and on
    scenario = definitions.POINT_TO_POINT
    sim, rec = start(scenario)
    apply_limits(sim, scenario)
    command_scenario(sim, scenario, 0)
    rec.scan(800)
    release_commands(sim)
    rec.scan(5)
    sim.axes[2].fault(ErrorID.FOLLOWING_ERROR_EXCEEDED)
    rec.scan(50)
    pulse(sim, rec, "SpReset", 20, 20)
    command_scenario(sim, scenario, 1)
    rec.scan(500)
    release_commands(sim)
    rec.scan(5)
    sim.globals["SpPowerOn"] = False
    rec.scan(20)
    sim.globals["SpPowerOn"] = True
    rec.scan(40)
    yield "p2p_fault", rec.prints

    # servo lag, Airy wave, an observation set between scans, power lost mid-wave
    scenario = definitions.AIRY_WAVE.with_wave_seconds(1.5)
    sim, rec = start(scenario, servo_lag_s=0.004)
    command_scenario(sim, scenario)
    rec.scan(1500)
    release_commands(sim)
    sim.axes[4].observation_code = ErrorID.FOLLOWING_ERROR_WARNING
    rec.scan(10)
    sim.globals["SpPowerOn"] = False
    rec.scan(30)
    pulse(sim, rec, "SpReset", 10, 10)
    yield "lag_airy_poweroff", rec.prints

    # a command step the sync saturates, an axis error, MC_Stop, reset, the wave again
    scenario = definitions.RANDOM_WAVE.with_wave_seconds(1.0)
    sim, rec = start(scenario)
    command_scenario(sim, scenario)
    rec.scan(700)
    sim.axes[1].cmd_pos += 0.3
    rec.scan(3)
    sim.axes[0].fault(ErrorID.COMMAND_NOT_FINITE)
    rec.scan(100)
    sim.globals["SpStop"] = True
    rec.scan(50)
    sim.globals["SpStop"] = False
    pulse(sim, rec, "SpReset", 10, 10)
    release_commands(sim)
    command_scenario(sim, scenario)
    rec.scan(300)
    yield "wave_step_fault", rec.prints


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=("record", "check"))
    parser.add_argument("file")
    parser.add_argument("--no-times", action="store_true",
                        help="leave the NJ time charged to each scan out (a change of the estimate "
                             "alone must leave everything else the same); record and check alike")
    args = parser.parse_args()
    got = {}
    for chunked in (False, True):
        for name, prints in scenarios(chunked, not args.no_times):
            got[name + ("_chunked" if chunked else "")] = prints
    if args.mode == "record":
        with open(args.file, "w") as out:
            json.dump(got, out)
        print(", ".join(f"{name}: {len(prints)}" for name, prints in got.items()))
        return 0
    with open(args.file) as f:
        want = json.load(f)
    differing = 0
    for name, prints in want.items():
        mine = got.get(name, [])
        first = next((i for i, (a, b) in enumerate(zip(prints, mine)) if a != b), None)
        if first is None and len(prints) == len(mine):
            print(f"{name}: the same ({len(prints)} fingerprints)")
        else:
            differing += 1
            print(f"{name}: DIFFERS from fingerprint {first if first is not None else min(len(prints), len(mine))}")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
