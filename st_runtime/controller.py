"""The simulated controller: tasks, clock, scan loop, faults, scan budget.

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
fault ends the run (`stopped` holds it).  A scan that spends more than
`budget` loop iterations ends with F-PERIOD ("task period exceeded"): the
rest of that scan's programs are skipped, the `after` hooks still run.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from .faults import FaultRecord, ScanOverrun, StopRun, STFault

DEFAULT_PERIOD_NS = 1_000_000
# Loop iterations per scan before F-PERIOD.  An NJ501 runs a few ten thousand
# loop iterations in a 1 ms period, so a million is generous for any real
# program, and a runaway loop costs this simulator well under a second a scan.
DEFAULT_BUDGET = 1_000_000
MAX_FAULT_RECORDS = 10_000       # kept in `faults`; `fault_count` counts them all


class ScanContext:
    """What compiled code and native FBs see of the controller (`ctx`)."""

    __slots__ = ("now_ns", "scan", "period_ns", "budget", "controller", "pou")

    def __init__(self, controller: "Controller"):
        self.controller = controller
        self.now_ns = 0
        self.scan = 0
        self.period_ns = controller.period_ns
        self.budget = controller.budget

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
    def __init__(self, compiled, period_ns: int = DEFAULT_PERIOD_NS, budget: int = DEFAULT_BUDGET,
                 stop_on_fault: bool = False):
        if period_ns <= 0:
            raise ValueError("the task period must be positive")
        self.compiled = compiled
        self.period_ns = period_ns
        self.budget = budget
        self.stop_on_fault = stop_on_fault
        self.tasks: list[Task] = [Task("Primary", period_ns, 1)]
        self.instances: dict[str, object] = {}
        self.before_hooks: list[Callable] = []
        self.after_hooks: list[Callable] = []
        self.observers: list[Callable] = []
        self.faults: list[FaultRecord] = []
        self.fault_count = 0
        self.stopped: FaultRecord | None = None
        self.scan_count = 0
        self.motion = None               # set by a motion task (st_runtime.motion) when installed
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

    def add_io_hook(self, before: Callable | None = None, after: Callable | None = None) -> None:
        """Native code run each primary scan before / after the programs.

        Each hook is called as `hook(ctx)` (ctx.now_ns, ctx.scan, ctx.period_ns).
        """
        if before is not None:
            self.before_hooks.append(before)
        if after is not None:
            self.after_hooks.append(after)

    def add_observer(self, observer: Callable) -> None:
        """Called as `observer(controller)` at the end of every scan (trace)."""
        self.observers.append(observer)

    # ------------------------------------------------------------- run

    def scan(self) -> bool:
        """Run one primary period.  False when the run has stopped on a fault."""
        if self.stopped is not None:
            return False
        ctx = self.ctx
        index = self.scan_count
        ctx.scan = index + 1
        ctx.now_ns = index * self.period_ns
        ctx.budget = self.budget
        ctx.period_ns = self.period_ns
        try:
            self._hooks(self.before_hooks, ctx)
            try:
                for task in self.tasks:
                    if index % task.every:
                        continue
                    ctx.period_ns = task.period_ns
                    for _, instance in task.programs:
                        instance.execute(ctx)
            except ScanOverrun as overrun:
                self._record(FaultRecord("F-PERIOD", "task period exceeded: the scan used up its budget "
                                         f"of {self.budget} loop iterations", *_place(overrun.where),
                                         ctx.scan))
            ctx.period_ns = self.period_ns
            self._hooks(self.after_hooks, ctx)
        except StopRun as stop:
            self.stopped = stop.record
        self.scan_count += 1
        for observer in self.observers:
            observer(self)
        return self.stopped is None

    def run(self, cycles: int) -> int:
        """Run up to `cycles` scans; returns the number run (fewer if stopped)."""
        if self.stopped is not None:
            return 0
        done = 0
        scan = self.scan
        for _ in range(cycles):
            done += 1
            if not scan():
                break
        return done

    def _hooks(self, hooks: list, ctx) -> None:
        """Run I/O hooks; a fault they raise is recorded against the hook."""
        for hook in hooks:
            try:
                hook(ctx)
            except STFault as fault:
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


def _place(where: tuple) -> tuple:
    pou, file, line, col = where
    return pou, file, line, col
