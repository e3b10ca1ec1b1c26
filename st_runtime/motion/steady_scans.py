"""The steady scans of a run: the controller's scan loop fused with the motion task's hooks.

In a `Controller.run` whose controller has the shape of the project's controllers (the motion
task's two hooks its only I/O hooks, one task every scan, observers that only read), every
scan after the first runs the same way: the seal and the motion epoch go on, the feedback in
is skipped (the previous scan's motion processing published the axes: `ScanContext.resumed`),
and the motion processing is the lanes of `_steady_lanes`.  This module writes that scan once
per motion task as one loop, with the lanes inline: no call of the `before` hook (which would
return at once) nor of the `after` hook, and none of the loop's tests of what the shape
already decides (`Controller._scans` re-reads hooks, tasks and the seal's counts each scan).
A task of one program (most controllers) takes a loop that holds it in locals.

`offer(task, controller)` gives the loop only while the shape holds, and the loop checks it
again at the end of every scan; a scan that leaves it (a fault in the motion processing, a
hook or task added, an observer that writes, a fault that stops the run) ends as the general
loop ends it, and the rest of the run takes `Controller._scans`.  What the loop reads once a
call (the period, the time limit, the task's NJ time record, the motion epoch, each axis's
step slack and soft limits) only Python code between runs changes: inside a run the scans
run compiled ST, the FBs' own calls, the motion hooks and read-only observers.
"""

from __future__ import annotations

import textwrap

from ..faults import ScanOverrun, StopRun, STFault

# `{lanes}`: the lane steps of the axes (motion_task._steady_lanes), as the `after` hook runs them
# but for the locals `{constants}` sets once a call.
# `task._published` and `task._continuing` stay TRUE from scan to scan, as the hooks leave
# them in the shape; only the hooks read them, so they are stored only where an exception
# leaves the programs (the feedback-in hook had stored FALSE) or the motion processing (the
# `after` hook had stored both FALSE).  A try block costs nothing in CPython 3.11 until it
# catches.  The shape is checked at the end of each scan, after the observers: besides the
# programs (compiled ST, which cannot reach the controller, and native FBs, which must not
# change its hooks, tasks or observers: no FB of the runtime does) only they run in a scan.
# So a run that starts with no observer has none at any scan's end, and its shape is the one
# `offer` found: only the stop and the hooks' own flag are read again (`unobserved`).
_STEADY_SCANS = """\
def {name}(controller, cycles{arguments}):
    ctx = controller.ctx
    hooks_before, hooks_after = list(controller.before_hooks), list(controller.after_hooks)
    tasks = list(controller.tasks)
    primary = tasks[0]
    programs = list(primary.programs)
{programs_before}    append_time = controller.task_times[primary.name].append
    limit_ps = (controller.time_limit_ns or primary.period_ns) * 1000
    period = controller.period_ns
    dt = period * 1e-9
    epoch = task._epoch
    unobserved = not controller.observers
{constants}    for done in range(1, cycles + 1):
        index = controller.scan_count
        ctx.scan = scan = index + 1
        ctx.now_ns = index * period
        ctx.budget = limit_ps
        try:
            try:
                try:
{programs}                except ScanOverrun as overrun:
                    controller._overran(primary, limit_ps, overrun)
                finally:
                    append_time(limit_ps - ctx.budget)
            except BaseException:
                task._published = False
                raise
            try:
{lanes}
            except BaseException as exception:
                task._published = task._continuing = False
                if not isinstance(exception, STFault):
                    raise
                controller._hook_fault(after_programs, exception)
        except StopRun as stop:
            controller.stopped = stop.record
        controller.scan_count = scan
        if unobserved:
            if controller.stopped is not None or not task._continuing:
                return done
            continue
        for observer in controller.observers:
            observer(controller)
        if controller.stopped is not None:
            return done
        if len(controller.observers) != controller._reading_observers:
            ctx.resumed = False
            return done
        if not (task._continuing and controller.before_hooks == hooks_before
                and controller.after_hooks == hooks_after and controller.tasks == tasks
                and primary.programs == programs):
            return done
    return cycles
"""

# The programs' runs in a scan, any number of them as `Controller._scans` runs them, and the
# one program of most controllers with its name and instance in locals: no iterator made and
# no pair unpacked a scan.  The task's programs are those `programs` holds while the loop runs
# (the end of a scan with observers compares them), as in the general loop.
_ANY_PROGRAMS = ("", """\
for name, instance in programs:
    instance.execute(ctx)
    if ctx.budget < 0:
        raise ScanOverrun(controller._program_place(name))
""")
_ONE_PROGRAM = ("(name, instance), = programs\n", """\
instance.execute(ctx)
if ctx.budget < 0:
    raise ScanOverrun(controller._program_place(name))
""")

# The loop a call takes: the one-program loop for a task of one program.
_DISPATCH = """\
def steady_scans(controller, cycles):
    if len(controller.tasks[0].programs) == 1:
        return steady_scans_one(controller, cycles)
    return steady_scans_any(controller, cycles)
"""

_VALUES = {"ScanOverrun": ScanOverrun, "StopRun": StopRun, "STFault": STFault}


def source(constants: str, lanes: str, names: dict) -> tuple[str, dict]:
    """(the source of the loop `steady_scans`, which takes the one-program loop or the loop of
    any programs, and the values it names) for `lanes`, the lane steps' source at no
    indentation, and `constants`, statements run once a call before the scans; both name the
    entries of `names` (the task under `task`)."""
    arguments = "".join(f", {name}={name}" for name in names)
    constants, lanes = textwrap.indent(constants, " " * 4), textwrap.indent(lanes, " " * 16) or " " * 16 + "pass\n"
    loops = (_STEADY_SCANS.format(name=name, arguments=arguments, constants=constants, lanes=lanes,
                                  programs_before=textwrap.indent(before, " " * 4),
                                  programs=textwrap.indent(run, " " * 20))
             for name, (before, run) in (("steady_scans_any", _ANY_PROGRAMS), ("steady_scans_one", _ONE_PROGRAM)))
    return "".join(loops) + _DISPATCH, {**_VALUES, **names}


def offer(task, controller):
    """The task's steady loop while `controller` has the shape it needs and its next scan is a
    steady one (the previous scan of this run ended with the motion processing publishing the
    axes, no observer but read-only ones since); else None."""
    ctx = controller.ctx
    hooks, tasks = controller.before_hooks, controller.tasks
    if (ctx.resumed and task._published and task._continuing and controller.stopped is None
            and len(hooks) == 1 and hooks[0] is task._before_hook
            and len(after := controller.after_hooks) == 1 and after[0] is task._after_programs
            and controller._quiet_hooks == 2 and len(tasks) == 1 and tasks[0].every == 1
            and tasks[0].period_ns == controller.period_ns):
        return task._steady_scans
    return None
