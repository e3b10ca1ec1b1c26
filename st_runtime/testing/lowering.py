"""Turn the TEST blocks of a test file into ordinary function blocks.

The checker and the compiler never see a TEST: each one becomes a
FUNCTION_BLOCK (`StgenTest<n>`) whose variables are the file's SETUP
variables, the test's own and a few of the runner's, and whose body is

    IF NOT StgenTeardown THEN <SETUP statements> <test statements>
    ELSE <TEARDOWN statements> END_IF

so a fresh instance of it is one fresh test.  Calls written as statements
are rewritten:

* `ASSERT_EQ(a, b [, 'message'])` (and NEQ, GT, LT, GE, LE, TRUE, FALSE,
  NEAR(a, b, tol)) becomes stores of its operands into variables of the
  runner, `StgenA<k> := a; StgenB<k> := b;`, then
  `IF NOT (StgenA<k> = StgenB<k>) THEN StgenFailed := k; RETURN; END_IF`:
  a failed assert ends the test (as in STruC++), and the runner reads both
  values from the instance.  The operand types come from a first check of
  the same code with each assert as a bare `IF a = b THEN END_IF` probe.
* `ADVANCE_TIME(d)` becomes a call of the clock FB (`clock.py`).

A PROGRAM named as a variable type in a test (STruC++ writes
`VAR uut : Adder; END_VAR ... uut();`) gets a FUNCTION_BLOCK twin
(`StgenProgram_<name>_<n>`) with the same variables and body.  The tests are
checked with `open_instances`, so they may set and read any variable of an
instance (`uut.a := 15`, `ASSERT_EQ(uut.result, 40)`), as STruC++'s tests
do.  Statement nodes are reused, so every diagnostic and fault points into
the user's files.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from .. import ast
from .. import types as T
from ..printer import format_expr
from .clock import CLOCK_FB

COMPARISONS = {"ASSERT_EQ": "=", "ASSERT_NEQ": "<>", "ASSERT_GT": ">", "ASSERT_LT": "<",
               "ASSERT_GE": ">=", "ASSERT_LE": "<="}
TRUTHS = {"ASSERT_TRUE": True, "ASSERT_FALSE": False}
NEAR = "ASSERT_NEAR"
ADVANCE = "ADVANCE_TIME"
OPERANDS = {**{k: 2 for k in COMPARISONS}, **{k: 1 for k in TRUTHS}, NEAR: 3}

FAILED = "StgenFailed"
TEARDOWN = "StgenTeardown"
CLOCK = "StgenClock"


@dataclass
class AssertSite:
    """One assert of a test: where it is and what it compares."""

    index: int
    kind: str
    pos: ast.Pos
    text: str                     # the call as written (printer form)
    operands: tuple               # the operand expressions
    message: str | None = None


@dataclass
class LoweredTest:
    name: str
    file: str
    pos: ast.Pos
    fb_name: str
    asserts: dict[int, AssertSite] = field(default_factory=dict)


class TestProblem(Exception):
    """A test file that cannot be lowered (a misused assert)."""

    __test__ = False   # not a pytest class

    def __init__(self, message: str, pos: ast.Pos):
        super().__init__(message)
        self.message = message
        self.pos = pos


def _name(text: str, pos: ast.Pos) -> ast.Name:
    return ast.Name(text, pos=pos)


def _decl(name: str, type_name: str, pos: ast.Pos) -> ast.VarDecl:
    return ast.VarDecl(name, ast.NamedType(type_name, pos=pos), pos=pos)


class Lowering:
    """Lowers every test file of one run; `types` (id(expr) -> Type) selects pass 2."""

    def __init__(self, taken_names: set[str], types: dict[int, object] | None = None):
        self.taken = {n.upper() for n in taken_names}
        self.types = types
        self.tests: list[LoweredTest] = []
        self.program_twins: dict[str, str] = {}     # PROGRAM upper name -> FB twin name
        self._count = 0

    # ---------------------------------------------------------------- files

    def file(self, source: ast.SourceFile, programs: dict[str, ast.Pou]) -> ast.SourceFile:
        """The file with its TEST/SETUP/TEARDOWN blocks replaced by FBs."""
        setup = next((i for i in source.items if isinstance(i, ast.TestSetup)), None)
        teardown = next((i for i in source.items if isinstance(i, ast.TestTeardown)), None)
        items = []
        for item in source.items:
            if isinstance(item, ast.TestCase):
                items.append(self._test(source.path, item, setup, teardown, programs))
            elif not isinstance(item, (ast.TestSetup, ast.TestTeardown)):
                items.append(item)
        return replace(source, items=tuple(items))

    def twins(self, programs: dict[str, ast.Pou]) -> ast.SourceFile | None:
        """FB twins of the PROGRAMs the tests instantiate, as one extra file."""
        if not self.program_twins:
            return None
        items = [self._twin(programs[key], name) for key, name in self.program_twins.items()]
        return ast.SourceFile("<test programs>", tuple(items))

    def _fresh(self, stem: str) -> str:
        n = 1
        while f"{stem}{n}".upper() in self.taken:
            n += 1
        name = f"{stem}{n}"
        self.taken.add(name.upper())
        return name

    # ---------------------------------------------------------------- tests

    def _test(self, path, case: ast.TestCase, setup, teardown, programs) -> ast.Pou:
        self._count += 1
        fb_name = self._fresh("StgenTest")
        test = LoweredTest(case.name, path, case.pos, fb_name)
        self.tests.append(test)
        self._sites = test.asserts
        self._temps: list[ast.VarDecl] = []
        pos = case.pos
        blocks = list(setup.var_blocks if setup else ()) + list(case.var_blocks)
        blocks = [self._with_twins(b, programs) for b in blocks]
        body = self._block((setup.body if setup else ()) + case.body)
        closing = self._block(teardown.body) if teardown else ()
        runner_vars = [_decl(FAILED, "DINT", pos), _decl(CLOCK, CLOCK_FB, pos)] + self._temps
        blocks.append(ast.VarBlock("VAR", tuple(runner_vars), pos=pos))
        blocks.append(ast.VarBlock("VAR_INPUT", (_decl(TEARDOWN, "BOOL", pos),), pos=pos))
        main = ast.If((ast.IfBranch(ast.Unary("NOT", _name(TEARDOWN, pos), pos=pos), body, pos=pos),),
                      closing or None, pos=pos)
        return ast.Pou("FUNCTION_BLOCK", fb_name, tuple(blocks), (main,), pos=pos)

    def _with_twins(self, block: ast.VarBlock, programs) -> ast.VarBlock:
        decls = []
        for decl in block.decls:
            if isinstance(decl.type, ast.NamedType) and decl.type.name.upper() in programs:
                key = decl.type.name.upper()
                if key not in self.program_twins:
                    self.program_twins[key] = self._fresh(f"StgenProgram_{programs[key].name}_")
                decl = replace(decl, type=replace(decl.type, name=self.program_twins[key]))
            decls.append(decl)
        return replace(block, decls=tuple(decls))

    @staticmethod
    def _twin(program: ast.Pou, name: str) -> ast.Pou:
        return replace(program, kind="FUNCTION_BLOCK", name=name)

    # ----------------------------------------------------------- statements

    def _block(self, stmts) -> tuple:
        out = []
        for stmt in stmts or ():
            out.extend(self._stmt(stmt))
        return tuple(out)

    def _stmt(self, s) -> list:
        if isinstance(s, ast.CallStmt) and isinstance(s.call.callee, ast.Name):
            name = s.call.callee.name.upper()
            if name in OPERANDS:
                return self._assert(s.call, name)
            if name == ADVANCE:
                return [self._advance(s.call)]
        if isinstance(s, ast.If):
            branches = tuple(replace(b, body=self._block(b.body)) for b in s.branches)
            return [replace(s, branches=branches,
                            else_body=None if s.else_body is None else self._block(s.else_body))]
        if isinstance(s, ast.Case):
            clauses = tuple(replace(c, body=self._block(c.body)) for c in s.clauses)
            return [replace(s, clauses=clauses,
                            else_body=None if s.else_body is None else self._block(s.else_body))]
        if isinstance(s, (ast.For, ast.While, ast.Repeat)):
            return [replace(s, body=self._block(s.body))]
        return [s]

    def _args(self, call: ast.Call, kind: str, count: int) -> tuple[tuple, str | None]:
        args = call.args
        if any(a.name is not None or a.direction != "in" for a in args):
            raise TestProblem(f"{kind} takes its operands by position", call.pos)
        message = None
        if len(args) == count + 1:
            last = args[-1].value
            if not isinstance(last, ast.StringLiteral):
                raise TestProblem(f"{kind}: the argument after the operands must be a string "
                                  "literal (the failure message)", last.pos)
            message = last.value
            args = args[:-1]
        if len(args) != count:
            raise TestProblem(f"{kind} takes {count} operand(s) and an optional message, "
                              f"found {len(call.args)} argument(s)", call.pos)
        return tuple(a.value for a in args), message

    def _assert(self, call: ast.Call, kind: str) -> list:
        operands, message = self._args(call, kind, OPERANDS[kind])
        k = len(self._sites) + 1
        pos = call.pos
        self._sites[k] = AssertSite(k, kind, pos, format_expr(call), operands, message)
        if self.types is None:      # pass 1: a probe that types the operands
            return [ast.If((ast.IfBranch(self._condition(kind, operands, pos), (), pos=pos),),
                           pos=pos)]
        stores, held = [], []
        for letter, operand in zip("ABT", operands):
            temp = f"Stgen{letter}{k}"
            self._temps.append(ast.VarDecl(temp, self._type_ref(operand, kind), pos=pos))
            stores.append(ast.Assign(_name(temp, pos), operand, pos=pos))
            held.append(_name(temp, pos))
        fail = (ast.Assign(_name(FAILED, pos), ast.IntLiteral(k, pos=pos), pos=pos),
                ast.Return(pos=pos))
        check = ast.If((ast.IfBranch(ast.Unary("NOT", self._condition(kind, held, pos), pos=pos),
                                     fail, pos=pos),), pos=pos)
        return stores + [check]

    @staticmethod
    def _condition(kind: str, operands, pos) -> ast.Node:
        if kind in COMPARISONS:
            return ast.Binary(COMPARISONS[kind], operands[0], operands[1], pos=pos)
        if kind in TRUTHS:
            return operands[0] if TRUTHS[kind] else ast.Unary("NOT", operands[0], pos=pos)
        a, b, tol = operands
        difference = ast.Binary("-", a, b, pos=pos)
        return ast.Binary("<=", ast.Call(_name("ABS", pos), (ast.Arg(None, difference, pos=pos),),
                                         pos=pos), tol, pos=pos)

    def _type_ref(self, operand, kind: str) -> ast.Node:
        t = T.resolve_alias(self.types.get(id(operand)))
        pos = getattr(operand, "pos", ast.NOWHERE)
        if isinstance(t, T.StringType):
            return ast.StringType(ast.IntLiteral(t.length, pos=pos), t.wide, pos=pos)
        if isinstance(t, (T.ElementaryType, T.EnumType)):
            return ast.NamedType(t.name, pos=pos)
        raise TestProblem(f"{kind} compares elementary values (numbers, BOOL, TIME, strings, "
                          f"enumerations), not {t}", pos)

    def _advance(self, call: ast.Call) -> ast.Node:
        if len(call.args) != 1 or call.args[0].name is not None:
            raise TestProblem("ADVANCE_TIME takes one operand: a TIME or a number of nanoseconds",
                              call.pos)
        value = call.args[0].value
        pos = call.pos
        if isinstance(value, (ast.IntLiteral, ast.TimeLiteral)):
            pin = "NS" if isinstance(value, ast.IntLiteral) else "D"
        elif self.types is None:    # pass 1: a probe that types the operand
            return ast.If((ast.IfBranch(ast.Binary("=", value, value, pos=pos), (), pos=pos),),
                          pos=pos)
        else:
            t = T.resolve_alias(self.types.get(id(value)))
            pin = "D" if isinstance(t, T.ElementaryType) and t.name in ("TIME", "LTIME") else "NS"
        clock = ast.Call(_name(CLOCK, pos), (ast.Arg(pin, value, pos=pos),), pos=pos)
        return ast.CallStmt(clock, pos=pos)
