"""`stgen run FILE_OR_DIR... --program NAME [--cycles N] [--period 1ms]
[--set PATH=JSON ...] [--json] [--trace OUT.csv --watch PATH...]`: run a
PROGRAM scan by scan.

The program runs on the primary task of a simulated controller for N scans
(default 1).  `--set` writes a variable of the program instance (or, when it
has none of that name, a global) once, before the first scan.  With `--json`, stdout gets one JSON object: every variable of
the program instance by its declared name (BOOL true/false, integers, reals,
strings, TIME as an IEC literal "T#1s500ms", arrays as nested lists, structs
and FB instances as objects; strict JSON, so a non-finite REAL/LREAL is the
string "NaN", "Infinity" or "-Infinity").  Without it, one `name = value` line per
variable.  Runtime faults go to stderr as
`file:line:col: fault[CODE]: message (scan N)`.

With `--axes FILE.toml` the controller also simulates servo axes: each
`[[axis]]` table (see `st_runtime.motion.axis_config`) becomes a global
AXIS_REF variable of that name, which the program passes to MC_Power,
MC_SyncMoveAbsolute, ... and reads (`Cyl1.Cmd.Pos`); `--watch` traces it.

Exit 0 on success, 1 on diagnostics, runtime faults or an invalid axes
file, 2 on usage errors.
"""

from __future__ import annotations

import os
import re
import sys

from st_runtime.api import LoadError, load, parse_period
from st_runtime.controller import DEFAULT_BUDGET
from st_runtime.values import json_text

MAX_FAULT_LINES = 100


def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, or directories whose .st files form one program")
    parser.add_argument("--program", required=True, metavar="NAME", help="the PROGRAM to run")
    parser.add_argument("--cycles", type=int, default=1, metavar="N", help="scans to run (default 1)")
    parser.add_argument("--period", default="1ms", help="primary task period (default 1ms)")
    parser.add_argument("--set", action="append", default=[], metavar="PATH=JSON",
                        help="write a variable of the program (or a global) before the first scan,"
                             " e.g. 'Setpoint=12.5', 'Pose[1]=3', 'Timer.PT=\"T#2s\"'; the"
                             " program may overwrite it")
    parser.add_argument("--json", action="store_true",
                        help="print the program's variables as one strict JSON object (TIME as"
                             ' "T#1s500ms", arrays as nested lists, structs and FBs as objects;'
                             ' a non-finite REAL/LREAL as the string "NaN", "Infinity" or'
                             ' "-Infinity")')
    parser.add_argument("--trace", metavar="OUT.csv", help="write the watched variables of every scan")
    parser.add_argument("--watch", nargs="+", metavar="PATH", default=[],
                        help="variables to trace: x, fb.Q, Axis.Cmd.Pos, a[3], m[1,2]")
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec")
    parser.add_argument("--stop-on-fault", action="store_true", help="stop at the first runtime fault")
    parser.add_argument("--axes", metavar="FILE.toml",
                        help="simulate servo axes: one [[axis]] table per axis (name, max_velocity;"
                             " optional soft_limit_min, soft_limit_max, max_acceleration,"
                             " in_position_range, following_error_limit, servo_lag,"
                             " initial_position); each axis is a global AXIS_REF variable of its"
                             " name for MC_Power, MC_SyncMoveAbsolute, ... (example:"
                             " examples/axes.toml)")
    parser.add_argument("--budget", type=int, default=DEFAULT_BUDGET, metavar="N",
                        help="loop iterations per scan before 'task period exceeded' "
                             f"(default {DEFAULT_BUDGET})")


def usage(message: str) -> int:
    print(f"stgen run: error: {message}", file=sys.stderr)
    return 2


# ---------------------------------------------------------------- shared checks
# (`stgen call` and `stgen check` use these too: one wording for one mistake;
# stgen.cli makes argparse's own usage errors one line for every command)


def source_problem(paths: list[str]) -> str | None:
    """Why `paths` give nothing to load (a missing path, no .st file at all)."""
    from st_runtime.loader import expand

    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        return f"no such file or directory: '{missing[0]}'"
    files, _ = expand(list(paths))
    if not files:
        where = ", ".join(f"'{p}'" for p in paths)
        return f"no .st file in {where}"
    return None


def output_problem(path: str) -> str | None:
    """Why a file cannot be written at `path` (checked before a long run)."""
    if os.path.isdir(path):
        return f"'{path}' is a directory"
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        return f"cannot write '{path}': directory '{parent}' does not exist"
    if not os.access(parent, os.W_OK) or (os.path.exists(path) and not os.access(path, os.W_OK)):
        return f"cannot write '{path}': permission denied"
    return None


def period_option(text: str) -> int:
    """The `--period` option in nanoseconds; ValueError with the message to show."""
    try:
        period = parse_period(text)
    except ValueError as exc:
        raise ValueError(f"--period: {exc}") from None
    if period <= 0:
        raise ValueError("--period must be positive")
    return period


def kind_hint(project, name: str, wanted: str) -> str:
    """" ('F' is a FUNCTION; <wanted>)" when `name` names a POU of another kind."""
    pou = project.program.pous.get(name.upper())
    if pou is None or pou.node is None:
        return ""
    return f" ('{pou.name}' is a {pou.kind}; {wanted})"


def run(args) -> int:
    problem = argument_problem(args)
    if problem:
        return usage(problem)
    motion = None
    if args.axes:
        try:
            motion = read_axes(args.axes)
        except AxesFileError as exc:
            print(f"stgen run: error: {exc}", file=sys.stderr)
            return 1
    extra = {axes_source_name(args.axes): motion.globals_source()} if motion else None
    try:
        project = load(args.paths, dialect=args.dialect, extra_sources=extra)
    except LoadError as exc:
        print(exc.render(), file=sys.stderr)
        return 1
    if project.diagnostics:
        print("\n".join(d.render(project.sources.get(d.pos.file)) for d in project.diagnostics),
              file=sys.stderr)
    pou = project.program.pous.get(args.program.upper())
    if pou is None or pou.kind != "PROGRAM":
        names = sorted(p.name for p in project.program.pous.values() if p.kind == "PROGRAM")
        hint = kind_hint(project, args.program, "stgen call --pou calls it")
        return usage(f"no PROGRAM named '{args.program}'{hint} (programs: {', '.join(names) or 'none'})")
    plc = project.controller(period=period_option(args.period), budget=args.budget,
                             stop_on_fault=args.stop_on_fault)
    if motion is not None:
        motion.install(plc.controller)
    program = plc.add_program(pou.name)
    problem = write_sets(args.set, program, plc)
    if problem:
        return usage(problem)
    trace = None
    if args.trace:
        try:
            trace = plc.trace(args.watch, program=pou.name)
        except (KeyError, ValueError) as exc:
            return usage(f"--watch: {exc}")
    plc.run(args.cycles)
    values = program.to_json()
    if args.json:
        print(json_text(values))
    else:
        for name, value in values.items():
            print(f"{name} = {json_text(value)}")
    if trace is not None:
        try:
            trace.write_csv(args.trace)
        except OSError as exc:
            print(f"stgen run: error: cannot write {args.trace}: {exc.strerror or exc}", file=sys.stderr)
            return 1
    return report_faults("stgen run", plc.controller)


def write_sets(items: list[str], program, plc) -> str | None:
    """Store each `--set PATH=JSON` in the program instance, else in the globals
    (a direct address such as %IX0.0 or %IW2 in the process image);
    the usage error of the first that cannot be stored."""
    from st_runtime.values import JsonValueError

    from .call import parse_sets

    try:
        values = parse_sets(items)
    except ValueError as exc:
        return str(exc)
    for path, value in values.items():
        if path.strip().startswith("%"):       # a direct address: the process image
            try:
                plc.image[path] = value
            except (KeyError, ValueError) as exc:
                return f"--set {exc.args[0] if exc.args else exc}"
            continue
        root = re.split(r"[.\[]", path, maxsplit=1)[0].strip()
        try:
            program[root]
            target = program
        except KeyError:
            target = plc.globals
        try:
            target[path] = value
        except (KeyError, JsonValueError) as exc:
            return f"--set {exc.args[0] if exc.args else exc}"
    return None


def argument_problem(args) -> str | None:
    """The first usage error in the arguments of `stgen run`, before any loading."""
    problem = source_problem(args.paths)
    if problem:
        return problem
    if args.cycles < 0:
        return "--cycles must be 0 or more"
    if args.budget <= 0:
        return "--budget must be positive"
    if bool(args.trace) != bool(args.watch):
        return "--trace and --watch go together"
    if args.trace and output_problem(args.trace):
        return f"--trace: {output_problem(args.trace)}"
    try:
        period_option(args.period)
    except ValueError as exc:
        return str(exc)
    if args.axes and os.path.isdir(args.axes):
        return f"--axes: '{args.axes}' is a directory; expected a TOML file"
    if args.axes and not os.path.exists(args.axes):
        return f"--axes: no such file: '{args.axes}'"
    return None


class AxesFileError(Exception):
    """An axes file that cannot be read or breaks a rule (names file and key)."""


def read_axes(path: str):
    """The MotionTask of an axes TOML file (AxesFileError if it is not valid)."""
    from st_runtime.motion import MotionTask
    from st_runtime.motion.axis_config import AxisConfigError

    try:
        with open(path, "rb") as handle:
            text = handle.read().decode("utf-8-sig")
    except OSError as exc:
        raise AxesFileError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise AxesFileError(f"{path}: not UTF-8 text (an axes file is TOML)") from None
    try:
        return MotionTask.from_toml(text)
    except (AxisConfigError, ValueError) as exc:
        raise AxesFileError(f"{path}: {exc}") from None


def axes_source_name(path: str) -> str:
    """The name under which the axis globals' ST text is loaded (in diagnostics)."""
    return f"{path} (axis globals)"


def report_faults(prog: str, controller) -> int:
    """Print the runtime faults to stderr; 1 when there were any."""
    for record in controller.faults[:MAX_FAULT_LINES]:
        print(record.render(), file=sys.stderr)
    if controller.fault_count > MAX_FAULT_LINES:
        print(f"{prog}: ... {controller.fault_count - MAX_FAULT_LINES} more fault(s)", file=sys.stderr)
    if controller.stopped is not None:
        print(f"{prog}: stopped at the first fault (scan {controller.stopped.scan})", file=sys.stderr)
    return 1 if controller.fault_count else 0
