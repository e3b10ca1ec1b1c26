"""``stgen demo [--out DIR] [--quick] [--config FILE]``: the study, end to end.

1. renders the controller for the platform (the default: the study's) and
   writes it for Sysmac Studio (``DIR/generated/nj501``) and as plain IEC
   (``DIR/generated/iec``);
2. runs the three scenarios with SP_Controller and six simulated axes at the
   task period, with a progress display, and holds every commanded cylinder
   position against the NumPy reference: the study's point-to-point moves
   (+100 mm in x, y, z at 20 mm/s, +6°, +6°, +10° in α, β, γ at 2°/s, each
   out and back to (0, 0, 150, 0, 0, 0), twelve commands in one run), the
   Airy wave and the random wave; then the four path families (issue 12:
   epitrochoid, epicycloid, hypocycloid, Archimedean spiral at roll = pitch
   = 35 deg, each planned by SP_Controller before it moves, lead-in, path) and
   the playback of a recorded JONSWAP sea state (``DIR/sea_state_10hz.csv``,
   60 s at 10 Hz, played at the task period);
3. prints a summary table (scenario, duration, scans, max error, faults),
   a table of the largest |v| and |a| of every cylinder's set-point (what
   SP_Controller hands to MC_SyncMoveAbsolute, finite differences at the task
   period) against the actuator's limits, and Cmd.Pos after any saturation by
   the axis; the durations SP_Controller planned for the moves; the estimated
   NJ501 time of SP_Controller per scan (max, p99, mean against the period and
   OMRON's 80 % rule; st_runtime/compiler/cost.py); and writes for each
   scenario ``DIR/<scenario>.csv`` (every scan) and ``DIR/<scenario>.png``
   (pose, cylinder positions, error, velocity and acceleration, following
   error over time), and says which files it wrote;
4. runs the platform variants' scenarios on their example platforms
   (:mod:`stgen.commands.demo_platforms`): the moving-base study's two 10 s
   motions and two test poses, the crank signals (surge, roll), each with a
   row in a further table (error against the reference at 1e-9, whether the
   stroke or crank angle, joint angles and tilt hold on every scan, the
   extremes, the set-points' velocity and acceleration, a stream's start
   step) and its own ``DIR/<scenario>.csv`` and ``.png``.

DIR is written as ``stgen generate`` writes its folder (:mod:`stgen.exports.folder`):
a file there that stgen did not write (or changed since) is never
overwritten, checked before the scenarios run; nothing is written through a
symbolic link (``DIR/generated`` and the files in DIR included); a second demo
into the same DIR refuses while the first runs.

``--quick`` shortens every scenario: waves of 5 s, point-to-point moves of a
tenth of each displacement with 0.1 s of standstill after each, a quarter
of each path from its first pose, 5 s of sea state, 1 s of each streamed
platform motion, and its CSV traces keep one scan in ten (every scan where the
first and last scan of each state, and the last scan, kept too; every scan is
still checked):
about 3 MB of CSV in all. Exit 1 if any scenario fails (error above 1e-6 mm, any fault, or
a set-point velocity or acceleration above the actuator's limit in any scan).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

from stgen.commands.config_option import add_config_argument, config_from_args
from stgen.exports.folder import FolderError, OwnedFolder, refuse_links_below

#: ``--quick``: seconds of wave, fraction of each point-to-point move, standstill after a move.
QUICK_WAVE_SECONDS = 5.0
QUICK_MOVE_FRACTION = 0.1
QUICK_SETTLE_SECONDS = 0.1
#: ``--quick``: the CSV traces keep one scan in this many (:func:`stgen.scenarios.csv_trace.kept_rows`).
QUICK_CSV_EVERY = 10
#: The demo's axes trail their commands by a first-order lag, so the figures' following-error panel shows a
#: real servo (the commanded positions, compared with the reference, do not depend on it).
DEMO_SERVO_LAG_S = 0.002
#: Seconds of recorded sea state the playback plays; ``--quick``: the share of each path's curve and the
#: seconds of sea state.
SEA_STATE_SECONDS = 60.0
QUICK_PATH_FRACTION = 0.25
QUICK_SEA_STATE_SECONDS = 5.0
#: The recorded motion the playback plays, written into DIR beside the traces.
SEA_STATE_CSV = "sea_state_10hz.csv"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out", metavar="DIR", default="demo", help="output folder (default: ./demo)")
    parser.add_argument("--quick", action="store_true",
                        help=f"every scenario shortened: waves of {QUICK_WAVE_SECONDS:g} s instead of 60 s,"
                             f" point-to-point moves of {QUICK_MOVE_FRACTION:g} of each displacement, CSV traces"
                             f" with one scan in {QUICK_CSV_EVERY}")
    add_config_argument(parser)


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    console = Console()
    if not console.is_terminal:  # a log file or a pipe: room for the whole table
        console = Console(width=120)
    config = config_from_args(args, "demo")
    if config is None:
        return 1
    if not args.out:
        print("stgen demo: error: --out: empty path; name a folder (. for the current one)", file=sys.stderr)
        return 2
    out = Path(args.out)
    from stgen.scenarios.definitions import SCENARIOS

    scenarios = [s.shortened(QUICK_WAVE_SECONDS, QUICK_MOVE_FRACTION, QUICK_SETTLE_SECONDS) if args.quick
                 else s for s in SCENARIOS]
    from stgen.commands import demo_platforms

    platform_items = demo_platforms.platform_scenarios(args.quick)
    try:
        with OwnedFolder(out) as folder, tempfile.TemporaryDirectory(prefix="stgen-demo-") as scratch:
            scenarios += _path_scenarios(args.quick, Path(scratch))
            # refuse before the long runs, not after
            folder.check(_output_names(scenarios) + [SEA_STATE_CSV] + demo_platforms.output_names(platform_items))
            results = _generate_and_run(config, scenarios, out, console)
            if results is None:
                return 1
            platform_runs = _run_platforms(platform_items, console)
            if platform_runs is None:
                return 1
            every = QUICK_CSV_EVERY if args.quick else 1
            for result in results:
                _stage_outputs(result, folder, every)
            for run in platform_runs:
                demo_platforms.stage_outputs(run, folder, every)
            sea_state = Path(scratch) / SEA_STATE_CSV
            if sea_state.is_file():  # the recorded motion the playback played, beside its trace
                folder.stage_with(SEA_STATE_CSV, lambda temp: shutil.copyfile(sea_state, temp))
            update = folder.commit()
    except OSError as error:
        print(f"stgen demo: error: cannot write {error.filename or out}: {error.strerror}", file=sys.stderr)
        return 1
    except FolderError as error:
        print(f"stgen demo: error: {error}", file=sys.stderr)
        return 1
    console.print(_summary(results, config))
    console.print(_limits_table(results, config))
    console.print(demo_platforms.summary_table(platform_runs))
    for result in results:
        if len(result.move_durations_s) > 1:
            durations = ", ".join(f"{d:.3f}" for d in result.move_durations_s)
            console.print(f"{result.scenario.name}: {len(result.move_durations_s)} moves planned by SP_Controller "
                          f"(SpMoveDuration): {durations} s", soft_wrap=True)
    for result in results + [run.result for run in platform_runs]:
        if result.nj_time is not None:
            console.print(f"{result.scenario.name}: SP_Controller {_nj_time(result.nj_time)}", soft_wrap=True)
    summary = update.summary()
    thinned = f" (--quick: each CSV keeps one scan in {QUICK_CSV_EVERY})" if args.quick else ""
    console.print(f"Wrote {len(update.written)} traces and figures in {out}/{thinned}: "
                  + ", ".join(p.name for p in update.written) + (f"; {summary}" if summary else ""), soft_wrap=True)
    failed = [r.scenario.name for r in results if not r.passed] + [r.name for r in platform_runs if not r.passed]
    if failed:
        console.print(f"[bold red]FAILED:[/] {', '.join(failed)}")
        return 1
    console.print("[bold green]All scenarios passed.[/]")
    return 0


def _path_scenarios(quick: bool, scratch: Path) -> list:
    """The path scenarios and the sea-state playback (its CSV written to ``scratch``), shortened under --quick."""
    from stgen.scenarios.path_scenarios import PATH_SCENARIOS, quick_path, sea_state_scenario, write_sea_state_csv

    seconds = QUICK_SEA_STATE_SECONDS if quick else SEA_STATE_SECONDS
    write_sea_state_csv(scratch / SEA_STATE_CSV, seconds)
    paths = [quick_path(s, QUICK_PATH_FRACTION) for s in PATH_SCENARIOS] if quick else list(PATH_SCENARIOS)
    return paths + [sea_state_scenario(scratch / SEA_STATE_CSV, seconds)]


def _output_names(scenarios) -> list[str]:
    return [f"{s.name}{suffix}" for s in scenarios for suffix in (".csv", ".png")]


def _generate_and_run(config, scenarios, out: Path, console):
    """Generate the controller into ``out/generated``, run the scenarios; ``None`` (reported) if they cannot run."""
    from st_runtime.api import LoadError

    generated = _generate(config, out)
    console.print(f"Generated the controller: {generated} files in {out / 'generated'}")
    try:
        return _run_all(scenarios, config, console)
    except LoadError as error:
        print(f"stgen demo: error: the generated controller does not load:\n{error.render()}", file=sys.stderr)
    except (TimeoutError, ValueError) as error:  # no STANDBY after power-on; a start pose outside the stroke
        print(f"stgen demo: error: {error}", file=sys.stderr)
    return None


def _run_platforms(items, console):
    """The platform variants' scenarios on their example platforms; ``None`` (reported) if they cannot run."""
    from st_runtime.api import LoadError

    from stgen.commands import demo_platforms
    from stgen.config import ConfigError

    try:
        return demo_platforms.run_all(items, console, DEMO_SERVO_LAG_S)
    except LoadError as error:
        print(f"stgen demo: error: a platform variant's controller does not load:\n{error.render()}", file=sys.stderr)
    except (ConfigError, OSError, TimeoutError, ValueError) as error:
        print(f"stgen demo: error: platform scenarios: {error}", file=sys.stderr)
    return None


def _generate(config, out: Path) -> int:
    """Write both targets under ``out/generated``, never through a symbolic link below ``out``."""
    from stgen.commands.generate import write_program
    from stgen.scenarios.program import render_controller_program

    program = render_controller_program(config)
    written = 0
    for target, folder in (("nj", "nj501"), ("iec", "iec")):
        refuse_links_below(out, out / "generated" / folder)
        written += len(write_program(program, out / "generated" / folder, target).written)
    return written


def _run_all(scenarios, config, console):
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from stgen.scenarios.runner import run_scenario

    results = []
    columns = (TextColumn("{task.description:<16}"), BarColumn(), TextColumn("{task.fields[sim]:>8} simulated"),
               TimeElapsedColumn())
    period = config.task.period_s
    with Progress(*columns, console=console) as progress:
        tasks = {s.name: progress.add_task(s.name, total=1, sim="0.0 s") for s in scenarios}
        for scenario in scenarios:
            task = tasks[scenario.name]

            def report(done, total, task=task):
                progress.update(task, completed=done, total=total, sim=f"{done * period:.1f} s")

            results.append(run_scenario(scenario, config, progress=report, servo_lag_s=DEMO_SERVO_LAG_S))
    return results


def _stage_outputs(result, folder: OwnedFolder, every: int) -> None:
    from stgen.figures import scenario_figure
    from stgen.scenarios.csv_trace import write_trace_csv

    folder.stage_with(f"{result.scenario.name}.csv", lambda temp: write_trace_csv(result, temp, every))
    folder.stage_with(f"{result.scenario.name}.png", lambda temp: scenario_figure(result, temp))


def _nj_time(t) -> str:
    """One line: the estimated NJ501 time per scan against the period and the 80 % rule."""
    pct = 100 / t.period_ns
    rule = "within" if t.load_ok else "[red]above[/]"
    return (f"estimated NJ501 time per scan: max {t.max_ns / 1e3:.1f} us ({t.max_ns * pct:.1f} %), "
            f"p99 {t.p99_ns / 1e3:.1f} us, mean {t.mean_ns / 1e3:.1f} us ({t.mean_ns * pct:.1f} %) of "
            f"{t.period_ns / 1e3:g} us; {rule} OMRON's 80 % guideline")


def _summary(results, config):
    from rich.table import Table

    table = Table(title=f"Scenarios: SP_Controller + 6 axes, {config.task.period_s * 1000:g} ms scans, vs NumPy reference")
    for column, justify in (("scenario", "left"), ("duration", "right"), ("scans", "right"),
                            ("max error", "right"), ("faults", "right"), ("max |v|", "right"), ("max |a|", "right"),
                            ("real time", "right"), ("result", "left")):
        table.add_column(column, justify=justify, no_wrap=True)
    for result in results:
        table.add_row(
            result.scenario.name,
            f"{result.duration_s:.3f} s",
            f"{result.scans:,}",
            f"{result.max_error_mm:.2e} mm",
            str(result.fault_count),
            f"{result.limits.max_velocity.max():.1f} mm/s",
            f"{result.limits.max_acceleration.max():.1f} mm/s²",
            f"{result.realtime_factor:.1f}x",
            "[green]pass[/]" if result.passed else "[red]FAIL[/]",
        )
    return table


def _limits_table(results, config):
    """Per scenario and cylinder: the largest |v| and |a| of the set-points against the actuator's limits."""
    from rich.table import Table

    actuator = config.actuator
    table = Table(title=f"Cylinder set-points handed to MC_SyncMoveAbsolute, every scan: largest |v| (limit "
                        f"{actuator.max_velocity:g} mm/s) and |a| (limit {actuator.max_acceleration:g} mm/s²)")
    table.add_column("scenario", no_wrap=True)
    table.add_column("", no_wrap=True)
    for leg in range(1, 7):
        table.add_column(f"q{leg}", justify="right", no_wrap=True)
    table.add_column("Cmd.Pos", justify="right", no_wrap=True)
    table.add_column("", no_wrap=True)
    for result in results:
        for label, values, limit, after in (
            ("|v| mm/s", result.limits.max_velocity, actuator.max_velocity, result.commanded_limits.max_velocity),
            ("|a| mm/s²", result.limits.max_acceleration, actuator.max_acceleration,
             result.commanded_limits.max_acceleration),
        ):
            inside = bool((values <= limit).all())
            table.add_row(result.scenario.name, label, *(f"{v:.1f}" for v in values), f"{after.max():.1f}",
                          "[green]within[/]" if inside else "[red]ABOVE[/]")
    return table
