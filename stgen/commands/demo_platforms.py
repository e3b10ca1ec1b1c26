"""The platform variants' part of ``stgen demo`` (issue 11): the moving-base study's motions and
test poses and the crank signals (:mod:`stgen.scenarios.platforms`), each on its example platform,
with progress, a table, a CSV trace and a PNG per scenario (``<scenario>.csv``, ``<scenario>.png``).
"""

from __future__ import annotations

#: ``--quick``: seconds of every streamed motion, fraction of each point-to-point move.
QUICK_STREAM_SECONDS = 1.0
QUICK_MOVE_FRACTION = 0.1


def platform_scenarios(quick: bool):
    from stgen.scenarios.platforms import PLATFORM_SCENARIOS

    return [item.shortened(QUICK_STREAM_SECONDS, QUICK_MOVE_FRACTION) if quick else item
            for item in PLATFORM_SCENARIOS]


def output_names(items) -> list[str]:
    return [f"{item.name}{suffix}" for item in items for suffix in (".csv", ".png")]


def run_all(items, console, servo_lag_s: float):
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from stgen.scenarios.platform_report import run_platform_scenario

    runs = []
    columns = (TextColumn("{task.description:<18}"), BarColumn(), TextColumn("{task.fields[sim]:>8} simulated"),
               TimeElapsedColumn())
    with Progress(*columns, console=console) as progress:
        tasks = {item.name: progress.add_task(item.name, total=1, sim="0.0 s") for item in items}
        for item in items:
            task = tasks[item.name]
            period = item.config().task.period_s

            def report(done, total, task=task, period=period):
                progress.update(task, completed=done, total=total, sim=f"{done * period:.1f} s")

            runs.append(run_platform_scenario(item, progress=report, servo_lag_s=servo_lag_s))
    return runs


def stage_outputs(run, folder, every: int = 1) -> None:
    from stgen.platform_figures import platform_figure
    from stgen.scenarios.platform_csv import write_platform_csv

    folder.stage_with(f"{run.name}.csv", lambda temp: write_platform_csv(run, temp, every))
    folder.stage_with(f"{run.name}.png", lambda temp: platform_figure(run, temp))


def _joints(limits) -> str:
    if limits.max_universal_gamma is None:
        return "-"
    return f"{limits.max_universal_gamma:.1f}/{limits.max_universal_psi:.1f}/{limits.max_tilt:.1f}"


def summary_table(runs):
    """One row per run: error against the reference, the pose limits, the extremes, the set-point rates
    (unit: mm for cylinders, deg for crank angles; per second and per second squared for v and a)."""
    from rich.table import Table

    from rich import box

    table = Table(title="Platform variants: SP_Controller + 6 axes vs NumPy reference, limits on every scan "
                        "(v, a: per s, s²)", box=box.SIMPLE_HEAD,
                  caption="|v|, |a|: within the motion, checked against the actuator limits (result); start|a|: "
                          "including the first streamed scan, reported apart: the study's moving-base motions "
                          "start at speed, so that scan steps above the acceleration limit")
    for column in ("scenario", "error", "limits", "axis range", "γ/ψ/tilt°", "|v|", "|a|", "start|a|",
                   "result"):
        table.add_column(column, justify="left" if column in ("scenario", "limits", "result") else "right",
                         no_wrap=True)
    for run in runs:
        limits = run.pose_limits
        first = limits.first_violation
        pose = "[green]hold[/]" if limits.feasible else f"[red]scan {first[0]}: {first[1]} leg {first[2]}[/]"
        motion = run.motion_limits
        table.add_row(
            run.name, f"{run.result.max_error_mm:.0e}", pose,
            f"{limits.actuator_range[0]:.1f}..{limits.actuator_range[1]:.1f} {run.unit}", _joints(limits),
            f"{motion.max_velocity.max():.1f}", f"{motion.max_acceleration.max():.1f}",
            f"{run.start_step.max_acceleration.max():.0f}",
            "[green]pass[/]" if run.passed else "[red]FAIL[/]",
        )
    return table
