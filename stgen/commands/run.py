"""`stgen run FILE_OR_DIR... --program NAME [--cycles N] [--period 1ms]
[--set PATH=JSON ...] [--json] [--trace OUT.csv --watch PATH[,PATH...] ...]`: run a
PROGRAM scan by scan.

The program runs on the primary task of a simulated controller for N scans
(default 1).  `--set` writes a variable of the program instance (or, when it
has none of that name, a global) once, before the first scan.  With `--json`, stdout gets one JSON object: every variable of
the program instance by its declared name (BOOL true/false, integers, reals,
strings, TIME as an IEC literal "T#1s500ms", arrays as nested lists, structs
and FB instances as objects; strict JSON, so a non-finite REAL/LREAL is the
string "NaN", "Infinity" or "-Infinity").  Without it, one `name = value` line per
variable.  Runtime faults go to stderr as
`file:line:col: fault[CODE]: message (scan N)`.  The JSON also carries
"scans" (scans run), "time" (simulated time, e.g. "T#1s") and "faults" (each
with code, message, pou, file, line, column, scan), except where the program
declares a variable of that name.

With `--axes FILE.toml` the controller also simulates servo axes: each
`[[axis]]` table (see `st_runtime.motion.axis_config`) becomes a global
AXIS_REF variable of that name, which the program passes to MC_Power,
MC_SyncMoveAbsolute, ... and reads (`Cyl1.Cmd.Pos`); `--watch` traces it.

Execution time: every scan's estimated NJ501 time per task (the ST code's
basic blocks, st_runtime/compiler/cost.py) is reported after the run, max,
p99 and mean against the period and OMRON's 80 % rule, on stderr; with
`--json --time-report` also in the JSON object, under the key
"$nj501_time" (never an ST name).  A task run whose
estimate passes the period (or `--time-limit`) ends with F-PERIOD.
`--budget` (loop iterations) is deprecated and ignored.

Exit 0 on success, 1 on diagnostics, runtime faults or an invalid axes
file, 2 on usage errors.
"""

from __future__ import annotations

import os
import re
import signal
import sys

from st_runtime.api import LoadError, load, parse_period
from st_runtime.values import json_text

from .sources import DIALECT_HELP, source_problem  # noqa: F401  (call uses them from here too)

MAX_FAULT_LINES = 100



def add_arguments(parser) -> None:
    parser.add_argument("paths", nargs="+", metavar="FILE_OR_DIR",
                        help="ST files, PLCopen TC6 or IEC 61131-10 .xml files, or directories whose .st files form one program")
    parser.add_argument("--program", required=True, metavar="NAME", help="the PROGRAM to run")
    parser.add_argument("--cycles", type=int, default=1, metavar="N", help="scans to run (default 1)")
    parser.add_argument("--period", default="1ms", metavar="TIME",
                        help="primary task period: a duration with its unit, 1ms, 250us or"
                             " T#2ms (default 1ms)")
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
    parser.add_argument("--watch", action="append", metavar="PATH[,PATH...]", default=[],
                        help="variables to trace, one per --watch or a comma-separated list:"
                             " --watch x --watch fb.Q, or --watch x,fb.Q,Axis.Cmd.Pos,a[3],m[1,2]")
    parser.add_argument("--dialect", choices=("iec", "nj", "codesys"), default="iec", help=DIALECT_HELP)
    parser.add_argument("--stop-on-fault", action="store_true", help="stop at the first runtime fault")
    parser.add_argument("--axes", metavar="FILE.toml",
                        help="simulate servo axes: one [[axis]] table per axis (name, max_velocity;"
                             " optional soft_limit_min, soft_limit_max, max_acceleration,"
                             " in_position_range, in_position_check_time, following_error_limit,"
                             " following_error_warning, error_deceleration, servo_lag,"
                             " initial_position); each axis is a global AXIS_REF variable of its"
                             " name for MC_Power, MC_SyncMoveAbsolute, ... (example:"
                             " examples/axes.toml)")
    parser.add_argument("--time-limit", metavar="DURATION",
                        help="estimated NJ501 time a scan may use before 'task period exceeded'"
                             " (default: the period)")
    parser.add_argument("--time-report", action="store_true",
                        help='with --json: add the estimated NJ501 time per task under "$nj501_time"')
    parser.add_argument("--budget", type=int, metavar="N",
                        help="deprecated and ignored (counted loop iterations; the scan is now"
                             " limited by its estimated NJ501 time, see --time-limit)")


def usage(message: str) -> int:
    print(f"stgen run: error: {message}", file=sys.stderr)
    return 2


# ---------------------------------------------------------------- shared checks
# (`stgen call` and `stgen check` use these too: one wording for one mistake;
# stgen.cli makes argparse's own usage errors one line for every command)


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


#: What a duration looks like, for the messages of `--period` and `--time-limit`.
PERIOD_FORM = "write a duration with its unit, e.g. 1ms, 250us, 2ms or T#1s500ms (units d, h, m, s, ms, us, ns)"


def period_option(text: str, option: str = "--period") -> int:
    """A duration option (`--period`, `--time-limit`) in nanoseconds; ValueError with the message to show."""
    try:
        period = parse_period(text)
    except ValueError:
        bare = text.strip().lstrip("+-").replace(".", "", 1).replace("_", "")
        what = "has no unit" if bare.isdigit() else "is not a duration"
        raise ValueError(f"{option} {text!r} {what}: {PERIOD_FORM}") from None
    if period <= 0:
        raise ValueError(f"{option} must be positive")
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
    if args.budget is not None:
        print("stgen run: warning: --budget is deprecated and ignored: a scan is now limited by its"
              " estimated NJ501 time (--time-limit, default the period)", file=sys.stderr)
    plc = project.controller(period=period_option(args.period), stop_on_fault=args.stop_on_fault,
                             time_limit=time_limit_option(args.time_limit))
    if motion is not None:
        motion.install(plc.controller)
    program = plc.add_program(pou.name)
    problem = write_sets(args.set, program, plc)
    if problem:
        return usage(problem)
    trace_file = None
    if args.trace:
        try:
            trace_file = plc.trace(watch_paths(args.watch), program=pou.name).stream_to(args.trace)
        except (KeyError, ValueError) as exc:
            return usage(f"--watch: {clipped(str(exc))}")
        except OSError as exc:
            print(f"stgen run: error: cannot write {args.trace}: {exc.strerror or exc}", file=sys.stderr)
            return 1
    try:
        if run_scans(plc.controller, args.cycles):
            return interrupted(plc.controller.scan_count, args.cycles, trace_file, between_scans=True)
    except KeyboardInterrupt:
        return interrupted(plc.controller.scan_count, args.cycles, trace_file, between_scans=False)
    values = program.to_json()
    times = plc.controller.time_report()
    if args.json:
        if args.time_report:
            values[TIME_KEY] = [t.to_json() for t in times]
        print(json_text(add_run_summary(values, plc.controller)))
    else:
        for name, value in values.items():
            print(f"{name} = {json_text(value)}")
    if trace_file is not None:
        try:
            trace_file.close()
        except OSError as exc:
            print(f"stgen run: error: cannot write {args.trace}: {exc.strerror or exc}", file=sys.stderr)
            return 1
    status = report_faults("stgen run", plc.controller)
    for t in times:
        print(t.render(), file=sys.stderr)
    return status


TIME_KEY = "$nj501_time"     # `$` cannot start an ST identifier: no variable has this name


def time_limit_option(text: str | None) -> int | None:
    """`--time-limit` in nanoseconds (None: the period); ValueError with the message to show."""
    return None if text is None else period_option(text, "--time-limit")


def clipped(message: str, width: int = 160) -> str:
    """A message cut to one readable line (a hostile path may be 100,000 characters)."""
    return message if len(message) <= width else message[:width - 3] + "..."


def watch_paths(items: list[str]) -> list[str]:
    """The paths of the `--watch` options: each one path or a comma-separated
    list; a comma inside brackets (`m[1,2]`) belongs to the path."""
    paths = []
    for item in items:
        depth, start = 0, 0
        for here, char in enumerate(item):
            depth += {"[": 1, "]": -1}.get(char, 0)
            if char == "," and depth <= 0:
                paths.append(item[start:here].strip())
                start = here + 1
        paths.append(item[start:].strip())
    return paths


def add_run_summary(values: dict, controller) -> dict:
    """The program's variables, then "scans", "time" (simulated, an IEC TIME
    literal) and "faults" (one object per recorded fault), each unless the
    program declares a variable of that name: a declared one is never
    overwritten, and the summary line goes to stderr instead."""
    from st_runtime.values import format_time

    summary = {"scans": controller.scan_count, "time": format_time(controller.now_ns),
               "faults": [fault_json(record) for record in controller.faults]}
    declared = {name.upper() for name in values}
    clashing = [key for key in summary if key.upper() in declared]
    if clashing:
        print(f"stgen run: {summary['scans']} scan(s), {summary['time']}, {len(summary['faults'])} fault(s);"
              f" not in the JSON, whose {', '.join(repr(k) for k in clashing)} the program declares",
              file=sys.stderr)
    return {**values, **{key: value for key, value in summary.items() if key not in clashing}}


def fault_json(record) -> dict:
    """A runtime fault as JSON: code, message, POU, file, line, column, scan."""
    return {"code": record.code, "message": record.message, "pou": record.pou, "file": record.file,
            "line": record.line, "column": record.col, "scan": record.scan}


#: Exit status after Ctrl-C, as shells report a process ended by SIGINT.
EXIT_INTERRUPTED = 130


def run_scans(controller, cycles: int) -> bool:
    """Run up to `cycles` scans; a first Ctrl-C ends the run after the current scan (True returned),
    a second one at once (KeyboardInterrupt), for a scan that takes too long."""
    requested = []

    def on_interrupt(signum, frame):
        requested.append(signum)
        signal.signal(signal.SIGINT, signal.default_int_handler)

    try:
        previous = signal.signal(signal.SIGINT, on_interrupt)
    except ValueError:  # not the main thread: no handler of ours
        controller.run(cycles)
        return False
    try:
        scan = controller.scan
        for _ in range(cycles):
            if requested or not scan():
                break
    finally:
        signal.signal(signal.SIGINT, previous)
    return bool(requested)


def interrupted(scans_done: int, cycles: int, trace_file, between_scans: bool) -> int:
    """Ctrl-C during the run: the trace file of the scans that completed is put in place, and said so."""
    if between_scans:
        message = f"stgen run: interrupted after {scans_done} of {cycles} scans"
        holds = f"the {trace_file.rows if trace_file else 0} scan(s) that ran"
    else:
        message = f"stgen run: interrupted during scan {scans_done + 1} of {cycles}"
        holds = "the scans before it"
    if trace_file is not None:
        try:
            trace_file.close()
            message += f"; {trace_file.path} holds {holds}"
        except OSError as exc:
            message += f"; cannot write {trace_file.path}: {exc.strerror or exc}"
    print(message, file=sys.stderr)
    return EXIT_INTERRUPTED


def write_sets(items: list[str], program, plc) -> str | None:
    """Store each `--set PATH=JSON` in the program instance, else in the globals
    (a direct address such as %IX0.0 or %IW2 in the process image);
    the usage error of the first that cannot be stored."""
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
        except (KeyError, ValueError) as exc:      # JsonValueError, a path that does not parse
            return f"--set {clipped(str(exc.args[0] if exc.args else exc))}"
    return None


def argument_problem(args) -> str | None:
    """The first usage error in the arguments of `stgen run`, before any loading."""
    problem = source_problem(args.paths)
    if problem and args.watch and problem.startswith("no such file"):
        return f"{problem} (--watch takes one path: write --watch A --watch B, or --watch A,B)"
    if problem:
        return problem
    if args.cycles < 0:
        return "--cycles must be 0 or more"
    try:
        time_limit_option(args.time_limit)
    except ValueError as exc:
        return str(exc)
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

    from st_runtime.input_files import MAX_TOML_BYTES, InputFileError, read_bounded

    try:
        text = read_bounded(path, MAX_TOML_BYTES).decode("utf-8-sig")  # never a FIFO or a device
    except InputFileError as exc:
        raise AxesFileError(f"{path}: {exc.reason}") from None
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
