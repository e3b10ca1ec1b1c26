"""Run the TEST blocks of ST test files (what `stgen test` does).

    run = run_tests(["src/", "tests/test_counter.st"], dialect="iec", pattern="reset")
    print(run.render()); run.ok

A file is a test file when a line starts with `TEST 'name'` or `TEST "name"`;
the others are the code under test, loaded with it as one program.  The
semantics follow STruC++ (docs/TESTING.md of Autonomy-Logic/STruCpp):

* every test starts from fresh instances: a new instance of the lowered test
  FB (its SETUP and own variables) and fresh global variables;
* SETUP runs before each test of its file, TEARDOWN after each (also after a
  failed assert);
* a failed assert ends its test; the report names file:line:column of the
  assert and both values;
* the clock starts at 0 and moves only by ADVANCE_TIME; calling a program or
  an FB instance runs it once (one scan of that program), at the current time;
* a runtime fault (division by zero, index out of bounds, ...) is an error
  of the test, reported with its place.

Lowering to ordinary FBs is in `lowering.py`; JUnit XML in `junit.py`.
"""

from __future__ import annotations

import fnmatch
import time
from dataclasses import dataclass, field

from .. import ast, loader, native
from ..checker import check
from ..controller import Controller, DEFAULT_PERIOD_NS
from ..diagnostics import Diagnostic, register
from ..faults import ScanOverrun, StopRun
from ..parser import parse, parse_tests
from ..values import to_json
from . import clock as _clock  # noqa: F401  (registers the clock FB)
from .detect import is_test_source
from .lowering import FAILED, NEAR, TEARDOWN, Lowering, LoweredTest, TestProblem

CODES = register({
    "E-TEST-001": "an assert or ADVANCE_TIME is called with the wrong arguments",
    "E-TEST-002": "no TEST block in the files given to `stgen test`",
})

# Estimated NJ501 time (controller.py, compiler/cost.py) a whole test may
# spend: a test is one call of its FB and may run a program for many scans,
# so it gets 2 s, a thousand fully loaded 1 ms scans; beyond it the test is
# an error (a loop that never ends stops there).
TEST_TIME_LIMIT_PS = 2_000_000_000_000
LABELS = {"passed": "PASS", "failed": "FAIL", "error": "ERROR"}
@dataclass
class TestResult:
    name: str
    file: str
    line: int
    status: str                  # "passed" | "failed" | "error"
    message: str = ""            # one line
    detail: str = ""             # the full report (file:line: ...)
    seconds: float = 0.0

    __test__ = False   # not a pytest class


@dataclass
class TestRun:
    results: list[TestResult] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    sources: dict[str, str] = field(default_factory=dict)

    __test__ = False   # not a pytest class

    @property
    def loaded(self) -> bool:
        return not any(d.is_error for d in self.diagnostics)

    @property
    def ok(self) -> bool:
        return self.loaded and all(r.status == "passed" for r in self.results)

    def count(self, status: str) -> int:
        return sum(r.status == status for r in self.results)

    def render_diagnostics(self) -> str:
        return "\n".join(d.render(self.sources.get(d.pos.file)) for d in self.diagnostics)

    def render(self) -> str:
        """STruC++'s report: per file PASS/FAIL lines, the failure under it, a total."""
        lines, current = [], None
        for r in self.results:
            if r.file != current:
                current = r.file
                lines.append(f"[{r.file}]")
            lines.append(f"  {LABELS[r.status]}: {r.name}")
            lines.extend("    " + part for part in r.detail.splitlines())
        lines.append(f"Results: {self.count('passed')} passed, {self.count('failed')} failed, "
                     f"{self.count('error')} error(s)")
        return "\n".join(lines)


def run_tests(paths, dialect: str = "iec", pattern: str | None = None,
              period_ns: int = DEFAULT_PERIOD_NS, execute: bool = True,
              time_limit_ps: int = TEST_TIME_LIMIT_PS) -> TestRun:
    """Load the files, run every TEST (whose name matches `pattern`), report.

    `execute=False` stops after the check (what `stgen check` does with test
    files); `time_limit_ps` is the estimated NJ501 time one test may use.
    """
    run = TestRun()
    names, problems = loader.expand([str(p) for p in paths])
    run.diagnostics.extend(problems)
    texts = {}
    for name in names:
        text, problem = loader.read_source(name)
        if problem is not None:
            run.diagnostics.append(problem)
        else:
            texts[name] = text
    run.sources = dict(texts)
    plain, tests = _parse_all(texts, dialect, run)
    if not run.loaded:
        return run
    if not any(isinstance(i, ast.TestCase) for f in tests for i in f.items):
        run.diagnostics.append(Diagnostic("E-TEST-002", "no TEST block found: a test file has "
                                          "lines `TEST 'name' ... END_TEST`",
                                          ast.Pos(names[0] if names else "<none>", 0, 0)))
        return run
    lowered = _lower_and_check(plain, tests, dialect, run)
    if lowered is None:
        return run
    lowering, checked = lowered
    if not execute:
        return run
    from ..compiler import CompileError, compile_program

    try:
        compiled = compile_program(checked)
    except CompileError as exc:
        run.diagnostics.append(Diagnostic("E-COMPILE-001", exc.message, exc.pos))
        return run
    for test in lowering.tests:
        if pattern is None or _matches(test.name, pattern):
            run.results.append(_run_one(compiled, test, period_ns, time_limit_ps))
    return run


def _matches(name: str, pattern: str) -> bool:
    if any(c in pattern for c in "*?["):
        return fnmatch.fnmatchcase(name.lower(), pattern.lower())
    return pattern.lower() in name.lower()


def _parse_all(texts: dict[str, str], dialect: str, run: TestRun):
    """Parse as `loader.load_texts` does (`loader.parse_texts`), test files
    with the test grammar: (plain files, test files)."""
    test_paths = set()

    def parser_for(path: str, text: str, from_xml: bool):
        if from_xml or not is_test_source(text):
            return parse
        test_paths.add(path)
        return parse_tests

    _prelude, parsed, found = loader.parse_texts(texts, dialect, parser_for)
    run.diagnostics.extend(found)
    plain = [file for path, file in parsed if path not in test_paths]
    tests = [file for path, file in parsed if path in test_paths]
    return plain, tests


def _lower_and_check(plain, tests, dialect: str, run: TestRun):
    """Pass 1 types the assert operands, pass 2 is what runs (see lowering.py)."""
    pous = [i for f in plain + tests for i in f.items if isinstance(i, ast.Pou)]
    programs = {p.name.upper(): p for p in pous if p.kind == "PROGRAM"}
    taken = {p.name for p in pous} | {i.name for f in plain + tests for i in f.items
                                      if isinstance(i, ast.TypeDecl)}
    types = None
    for _ in range(2):
        lowering = Lowering(taken, types)
        try:
            files = plain + [lowering.file(f, programs) for f in tests]
        except TestProblem as problem:
            run.diagnostics.append(Diagnostic("E-TEST-001", problem.message, problem.pos))
            return None
        twins = lowering.twins(programs)
        checked, found = check(files + ([twins] if twins else []), dialect, open_instances=True)
        if any(d.is_error for d in found):
            run.diagnostics.extend(found)
            return None
        types = checked.expr_types
    run.diagnostics.extend(found)
    return lowering, checked


def _run_one(compiled, test: LoweredTest, period_ns: int, limit_ps: int) -> TestResult:
    result = TestResult(test.name, test.file, test.pos.line, "passed")
    started = time.perf_counter()
    fresh_globals = type(compiled.globals)()
    compiled.globals = fresh_globals
    compiled.namespace["_G"] = fresh_globals
    controller = Controller(compiled, period_ns)
    ctx = controller.ctx
    ctx.scan, ctx.now_ns, ctx.budget, ctx.period_ns = 1, 0, limit_ps, period_ns
    instance = compiled.new(test.fb_name)
    problems = []
    for phase in (False, True):
        setattr(instance, native.mangle(TEARDOWN), phase)
        try:
            instance.execute(ctx)
        except ScanOverrun:
            problems.append(f"{test.file}:{test.pos.line}: the test used up its "
                            f"{limit_ps / 1e12:g} s of estimated NJ501 time "
                            "(a loop that never ends?)")
        except StopRun:
            pass
    failed = getattr(instance, native.mangle(FAILED))
    if failed:
        result.status = "failed"
        result.message, result.detail = _failure(compiled, test, instance, failed)
    for fault in controller.faults:
        problems.append(f"{fault.file}:{fault.line}:{fault.col}: runtime fault {fault.code}: "
                        f"{fault.message}")
    if problems and result.status == "passed":
        result.status = "error"
        result.message = problems[0]
    if problems:
        result.detail = "\n".join(([result.detail] if result.detail else []) + problems)
    result.seconds = time.perf_counter() - started
    return result


def _failure(compiled, test: LoweredTest, instance, index: int) -> tuple[str, str]:
    site = test.asserts[index]
    variables = compiled.checked.pous[test.fb_name.upper()].variables
    shown = []
    for letter in "ABT"[: len(site.operands)]:
        name = f"Stgen{letter}{index}"
        shown.append(_literal(getattr(instance, native.mangle(name)), variables[name.upper()].type))
    if site.kind == NEAR:
        a, b = (float(getattr(instance, native.mangle(f"Stgen{x}{index}"))) for x in "AB")
        values = (f"left = {shown[0]}, right = {shown[1]}, |left - right| = {abs(a - b):.6g} "
                  f"> tolerance {shown[2]}")
    elif len(shown) == 2:
        values = f"left = {shown[0]}, right = {shown[1]}"
    else:
        values = f"value = {shown[0]}"
    where = f"{site.pos.file}:{site.pos.line}:{site.pos.col}"
    message = f"{site.text} failed: {values}" + (f" ({site.message})" if site.message else "")
    return message, f"{where}: {message}"


def _literal(value, t) -> str:
    shown = to_json(value, t)
    if isinstance(shown, bool):
        return "TRUE" if shown else "FALSE"
    return repr(shown) if isinstance(shown, str) and not shown[:2].upper() in ("T#", "D#") else str(shown)
