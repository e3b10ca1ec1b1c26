"""The simulated controller: tasks, clock, scan loop, faults, NJ501 time per scan.

One call of `scan()` is one period of the primary task:

1. the `before` I/O hooks run (e.g. axis feedback in),
2. every task due in this scan runs its programs in the order they were
   added (the primary task every scan, a task with period k * primary every
   k-th scan, starting with the first),
3. the `after` I/O hooks run (e.g. motion processing), then the scan
   observers (trace).

The clock only advances by the primary period: during scan k (1-based)
`ctx.now_ns` is (k - 1) * period; wall-clock time never enters a result.

Runtime faults (instruction errors) are recorded as `FaultRecord`s in
`faults` and scanning goes on, unless `stop_on_fault` is set: then the first
fault ends the run (`stopped` holds it).

Execution time.  The compiled code charges the estimated NJ501 time of every
basic block it runs (st_runtime/compiler/cost.py) to `ctx.budget`, in
picoseconds.  Each task starts with its period (or `time_limit_ns` when
given) and `task_times[task]` keeps what each of its runs used.  A run whose
estimate exceeds that limit ends with F-PERIOD ("task period exceeded"): at
once inside a loop (so a runaway loop ends in its first iterations and the
simulator never hangs), otherwise after the program that overran; the rest
of that task's programs are skipped in this scan, the other tasks and the
`after` hooks still run.  The estimate covers the ST code only, not the
NJ's system services, I/O refresh or motion control processing.
"""

from __future__ import annotations

import warnings
from array import array
from dataclasses import dataclass, field
from typing import Callable

from .faults import FaultRecord, ScanOverrun, StopRun, STFault

DEFAULT_PERIOD_NS = 1_000_000
# Deprecated: the loop-iteration budget that the execution-time estimate
# replaced; kept so that old imports work (`budget=` only warns now).
DEFAULT_BUDGET = None
# OMRON's guideline for the NJ501: average task execution time below 80 % of
# the task period (NJ/NX-series CPU Unit Software User's Manual W501, quoted
# in the NX701 manual, section B-1-5: https://www.easymanua.ls/omron/nx701-1620/manual?p=285).
LOAD_GUIDELINE = 0.8
MAX_FAULT_RECORDS = 10_000       # kept in `faults`; `fault_count` counts them all


def _times() -> array:
    """A task's record of the picoseconds each run used: unsigned 64-bit integers.  A run's
    time is its limit less the budget left, the sum of the charges of what it ran (each a
    non-negative cost, cost.py), so never below zero.  CPython 3.11 stores an item of an
    `array("Q")` straight from the int, where `"q"` parses it with `PyArg_Parse` (twice an
    append: about 450 machine instructions a scan of the wave, against about 100)."""
    return array("Q")


class ScanContext:
    """What compiled code and native FBs see of the controller (`ctx`)."""

    __slots__ = ("now_ns", "scan", "period_ns", "budget", "controller", "pou", "resumed", "seal")

    def __init__(self, controller: "Controller"):
        self.controller = controller
        self.now_ns = 0
        self.scan = 0
        self.period_ns = controller.period_ns
        # True while a scan directly follows the previous one inside one `Controller.run`, with
        # no observer between them but those that only read (`add_observer(..., reads_only=True)`):
        # no code that could change anything has run since the previous scan's
        # `after` hooks (the motion task then need not publish the axes again before the programs).
        self.resumed = False
        # A new object whenever code other than the scans' own may have run since the previous
        # scan: a caller between `run` calls, an observer that writes, an I/O hook not added as
        # `quiet`.  While it stays the same, nothing but compiled ST (which cannot store into an
        # FB's outputs: the checker refuses it) and each FB's own calls has touched an FB, so a
        # fact an FB's caller noted under it still holds (`NativeFB.REST`: an idle FB at rest).
        self.seal = object()
        # Estimated NJ501 time (ps) the running task has left; each task run
        # starts from its limit (code run outside a scan gets one period).
        self.budget = (controller.time_limit_ns or controller.period_ns) * 1000

    def fault(self, exc: BaseException, where: tuple) -> None:
        """Record a fault raised by the statement at `where` (pou, file, line, col)."""
        self.controller.record_fault(exc, where)


@dataclass
class Task:
    name: str
    period_ns: int
    every: int                                   # runs every `every` primary scans
    programs: list = field(default_factory=list)  # (instance name, instance)


class Controller:
    def __init__(self, compiled, period_ns: int = DEFAULT_PERIOD_NS, budget=None,
                 stop_on_fault: bool = False, time_limit_ns: int | None = None):
        """`time_limit_ns`: the estimated NJ501 time a task may use per run
        before F-PERIOD (default: its period).  `budget` is deprecated."""
        if period_ns <= 0:
            raise ValueError("the task period must be positive")
        if budget is not None:
            warnings.warn("the loop-iteration budget is deprecated and ignored: a scan is now limited by"
                          " its estimated NJ501 time (the task period, or time_limit_ns)",
                          DeprecationWarning, stacklevel=2)
        if time_limit_ns is not None and time_limit_ns <= 0:
            raise ValueError("the time limit must be positive")
        self.compiled = compiled
        self.period_ns = period_ns
        self.time_limit_ns = time_limit_ns
        self.stop_on_fault = stop_on_fault
        self.tasks: list[Task] = [Task("Primary", period_ns, 1)]
        self.task_times: dict[str, array] = {"Primary": _times()}   # picoseconds used per run
        self.instances: dict[str, object] = {}
        self.before_hooks: list[Callable] = []
        self.after_hooks: list[Callable] = []
        self._quiet_hooks = 0            # of them, added as quiet
        self.observers: list[Callable] = []
        self._reading_observers = 0      # of them, added with reads_only
        self.faults: list[FaultRecord] = []
        self.fault_count = 0
        self.stopped: FaultRecord | None = None
        self.scan_count = 0
        self.motion = None               # set by a motion task (st_runtime.motion) when installed
        # `steady_scans(controller)`: a loop running the scans of a run fused with the I/O hooks,
        # `loop(controller, cycles) -> scans run`, while the controller's shape allows, else
        # None (the motion task's: st_runtime/motion/steady_scans.py).
        self.steady_scans: Callable | None = None
        self.ctx = ScanContext(self)

    # ------------------------------------------------------------ setup

    @property
    def globals(self):
        return self.compiled.globals

    @property
    def now_ns(self) -> int:
        """Simulated time after the scans run so far."""
        return self.scan_count * self.period_ns

    def add_task(self, name: str, period_ns: int) -> Task:
        """A periodic task; its period must be a multiple of the primary period."""
        if period_ns <= 0 or period_ns % self.period_ns:
            raise ValueError(f"task {name}: period must be a positive multiple of {self.period_ns} ns")
        task = Task(name, period_ns, period_ns // self.period_ns)
        self.tasks.append(task)
        self.task_times[name] = _times()
        return task

    def add_program(self, program: str, task: str | None = None, name: str | None = None):
        """Instantiate PROGRAM `program` and assign it to `task` (primary by default)."""
        pou = self.compiled.checked.pous.get(program.upper())
        if pou is None or pou.kind != "PROGRAM":
            raise KeyError(f"no PROGRAM named {program}")
        instance = self.compiled.new(program)
        target = self.tasks[0] if task is None else self._task(task)
        key = (name or pou.name)
        if key.upper() in {k.upper() for k in self.instances}:
            raise ValueError(f"a program instance named {key} already exists")
        target.programs.append((key, instance))
        self.instances[key] = instance
        return instance

    def _task(self, name: str) -> Task:
        for task in self.tasks:
            if task.name.upper() == name.upper():
                return task
        raise KeyError(f"no task named {name}")

    def add_io_hook(self, before: Callable | None = None, after: Callable | None = None,
                    quiet: bool = False) -> None:
        """Native code run each primary scan before / after the programs.

        Each hook is called as `hook(ctx)` (ctx.now_ns, ctx.scan, ctx.period_ns).
        `quiet`: the hooks store nothing into an FB instance (the motion task's), so the
        scans of a run keep their `ScanContext.seal`.
        """
        for hook, hooks in ((before, self.before_hooks), (after, self.after_hooks)):
            if hook is not None:
                hooks.append(hook)
                self._quiet_hooks += quiet

    def add_observer(self, observer: Callable, reads_only: bool = False) -> None:
        """Called as `observer(controller)` at the end of every scan (trace).

        `reads_only`: the observer changes nothing (no variable, no axis), so the
        next scan of a run may go on as if it had not run (`ScanContext.resumed`).
        """
        self.observers.append(observer)
        if reads_only:
            self._reading_observers += 1

    # ------------------------------------------------------------- run

    def scan(self) -> bool:
        """Run one primary period.  False when the run has stopped on a fault."""
        if self.stopped is not None:
            return False
        try:
            self._scans(1, False)
        finally:
            self.ctx.seal = object()         # the caller's code runs next
        return self.stopped is None

    def run(self, cycles: int) -> int:
        """Run up to `cycles` scans; returns the number run (fewer if stopped)."""
        if self.stopped is not None:
            return 0
        try:
            done = self._scans(min(cycles, 1), True)
            while done < cycles and self.stopped is None:
                steady = self.steady_scans and self.steady_scans(self)
                done += steady(self, cycles - done) if steady else self._scans(cycles - done, True)
            return done
        finally:
            self.ctx.resumed = False         # the caller's code runs next
            self.ctx.seal = object()

    def _scans(self, cycles: int, resume: bool) -> int:
        """Up to `cycles` scans, each as `scan` describes it, in one frame: the hooks, the
        tasks and their programs are read from the controller every scan (a hook may add
        one), only the calls of a method per scan and per task are gone.  `resume`: set
        ScanContext.resumed between the scans (inside one `run`).  Returns the scans run."""
        ctx = self.ctx
        done = 0
        for _ in range(cycles):
            done += 1
            index = self.scan_count
            ctx.scan = index + 1
            ctx.now_ns = index * self.period_ns
            ctx.period_ns = self.period_ns
            if not ctx.resumed or len(self.before_hooks) + len(self.after_hooks) != self._quiet_hooks:
                ctx.seal = object()
            try:
                for hook in self.before_hooks:
                    try:
                        hook(ctx)
                    except STFault as fault:
                        self._hook_fault(hook, fault)
                for task in self.tasks:
                    if index % task.every:
                        continue
                    # One run of the task's programs, charged against its time limit.
                    ctx.period_ns = task.period_ns
                    limit_ps = (self.time_limit_ns or task.period_ns) * 1000
                    ctx.budget = limit_ps
                    try:
                        for name, instance in task.programs:
                            instance.execute(ctx)
                            if ctx.budget < 0:      # straight-line code is checked after its program
                                raise ScanOverrun(self._program_place(name))
                    except ScanOverrun as overrun:
                        self._overran(task, limit_ps, overrun)
                    finally:
                        self.task_times[task.name].append(limit_ps - ctx.budget)
                ctx.period_ns = self.period_ns
                for hook in self.after_hooks:
                    try:
                        hook(ctx)
                    except STFault as fault:
                        self._hook_fault(hook, fault)
            except StopRun as stop:
                self.stopped = stop.record
            self.scan_count += 1
            for observer in self.observers:
                observer(self)
            if self.stopped is not None:
                break
            if resume:
                # Only the observers run before the next scan of this loop (see ScanContext.resumed).
                ctx.resumed = len(self.observers) == self._reading_observers
        return done

    def _overran(self, task: Task, limit_ps: int, overrun: ScanOverrun) -> None:
        self._record(FaultRecord("F-PERIOD", f"task period exceeded: the estimated NJ501 time of task "
                                 f"{task.name} passed {_ms(limit_ps)}", *overrun.where, self.ctx.scan))

    def _program_place(self, name: str) -> tuple:
        pou = self.compiled.checked.pous.get(name.upper())
        node = getattr(pou, "node", None)
        if node is None:
            return (name, "<task>", 0, 0)
        return (pou.name, node.pos.file, node.pos.line, node.pos.col)

    def time_report(self) -> list["TaskTime"]:
        """The estimated NJ501 time per run of each task that ran."""
        return [TaskTime.of(task, self.task_times[task.name]) for task in self.tasks
                if self.task_times[task.name]]

    def _hook_fault(self, hook: Callable, fault: STFault) -> None:
        """A fault an I/O hook raised, recorded against the hook."""
        name = getattr(hook, "__qualname__", type(hook).__name__)
        self.record_fault(fault, (name, "<io>", fault.line or 0, fault.col or 0))

    # ----------------------------------------------------------- faults

    def record_fault(self, exc: BaseException, where: tuple) -> None:
        if isinstance(exc, STFault):
            code, message = exc.code, exc.message
            line = exc.line if exc.line else where[2]
            col = exc.col if exc.col else (where[3] if not exc.line or exc.line == where[2] else 1)
        else:
            code, message = "F-MATH", f"{type(exc).__name__}: {exc}"
            line, col = where[2], where[3]
        self._record(FaultRecord(code, message, where[0], where[1], line, col, self.ctx.scan))

    def _record(self, record: FaultRecord) -> None:
        self.fault_count += 1
        if len(self.faults) < MAX_FAULT_RECORDS:
            self.faults.append(record)
        if self.stop_on_fault:
            raise StopRun(record)


def _ms(ps: int) -> str:
    return f"{ps / 1e9:.3f} ms"


@dataclass(frozen=True)
class TaskTime:
    """Estimated NJ501 time per run of one task (ns), against its period.

    `load_ok` applies OMRON's guideline (average below 80 % of the period,
    LOAD_GUIDELINE); `fits` says whether every run stayed within the period.
    """

    task: str
    period_ns: int
    runs: int
    max_ns: float
    p99_ns: float
    mean_ns: float

    @classmethod
    def of(cls, task: Task, times_ps) -> "TaskTime":
        ordered = sorted(times_ps)
        p99 = ordered[min(len(ordered) - 1, -(-99 * len(ordered) // 100) - 1)]   # nearest rank
        return cls(task.name, task.period_ns, len(ordered), ordered[-1] / 1000, p99 / 1000,
                   sum(ordered) / len(ordered) / 1000)

    @property
    def load_ok(self) -> bool:
        return self.mean_ns < LOAD_GUIDELINE * self.period_ns

    @property
    def fits(self) -> bool:
        return self.max_ns <= self.period_ns

    def to_json(self) -> dict:
        return {"task": self.task, "period_ns": self.period_ns, "runs": self.runs,
                "max_ns": self.max_ns, "p99_ns": self.p99_ns, "mean_ns": round(self.mean_ns, 3),
                "max_percent": round(100 * self.max_ns / self.period_ns, 4),
                "mean_percent": round(100 * self.mean_ns / self.period_ns, 4),
                "within_period": self.fits, "within_80_percent_rule": self.load_ok}

    def render(self) -> str:
        pct = 100 / self.period_ns
        rule = "meets" if self.load_ok else "BREAKS"
        over = "" if self.fits else "; some runs exceed the period (F-PERIOD)"
        return (f"estimated NJ501 time of task {self.task} ({self.period_ns / 1e3:g} us period, {self.runs} runs): "
                f"max {self.max_ns / 1e3:.1f} us ({self.max_ns * pct:.1f} %), "
                f"p99 {self.p99_ns / 1e3:.1f} us ({self.p99_ns * pct:.1f} %), "
                f"mean {self.mean_ns / 1e3:.1f} us ({self.mean_ns * pct:.1f} %); "
                f"{rule} OMRON's 80 % rule (average below 80 % of the period){over}")
