"""Optimisation passes of the ST-to-Python compiler, each exact by construction.

Each pass has its own switch (`Optimisations`), so the equivalence tests can
run a program with and without it and compare results, faults and instance
states bit for bit:

* `fold` (fold.py): reads of `VAR CONSTANT` array elements at constant
  indices become literals, and IF conditions made only of constants choose
  their branch at compile time.
* `unroll` (unroll.py): a FOR with constant bounds, a body that cannot leave
  early and a control variable no one else can see is unrolled (up to
  `UNROLL_CAP` statements), its variable a constant in each copy.
* `cse` (cse.py): in an unrolled loop whose body stores only plain locals and
  calls nothing, array elements read at constant indices are read once,
  before the loop, and a `+ - *` of such values, literals or earlier shared
  results is computed once and reused.  Operands keep their order and
  grouping (no reassociation), so every result is the same float.  In a
  FOR loop's body of assignments to Python names that calls nothing but
  the numeric library (reads.py), an element `v_A[_tN]` read again in the
  same iteration is kept by its first read (`(_tM := v_A[_tN])`) where that
  read always runs, and read by name after.
* `fuse` (fuse.py): in a CSE region's straight code, a store that no one
  can see before the variable is set again is put into its one use, runs of
  `D := D + x` become one expression (same operations, same order), and
  temporaries share Python names (fewer than 256 locals).
* `gather` (gather.py, off unless asked for): a body's prologue loads its
  variables with one `operator.attrgetter` call per run instead of one load
  each.  Fewer bytecodes, but slower on CPython 3.11: a specialised slot load
  beats attrgetter's generic lookup, whose type-cache slot depends on
  PYTHONHASHSEED (measured in gather.py's docstring).
* `inline` (calls.py, `_GUARDED`): SIN, COS, TAN and SQRT call Python's
  math function directly where the library's wrapper would only call it
  (a finite argument, tested as `t < 1e309 and t > -1e309`; SQRT: not below zero, with no
  test for a REAL sum of squares of variables), the wrapper otherwise; MIN and
  MAX of two or more inputs are Python's min/max (the library's MIN is min of
  the tuple: the same comparisons in the same order); `ABS(x) <= B` and
  `ABS(x) < B` are chained comparisons without the call, `ABS(x) <= ` the
  largest LREAL that finite test of a local x (absolute.py).
* `vector` (vector.py): in a CSE region, a straight run of at least
  `vector.MIN_OPERATIONS` float `+ - *` (the unrolled Leibniz determinant:
  1,950 products and 720 sums) is one call that computes the products depth
  by depth and each `D := D +- term` chain with `np.add.accumulate` (left to
  right); inputs that are not finite or could overflow take the same run in
  Python, so the results are Python's bit for bit.  Each run's call is one
  generated function (no loop over the levels; its input check by `argmax`).
* `ranges` (ranges.py): the values an integer local can hold are followed
  through the code as it is written (assignments, IF/CASE joins, loops), so
  a bounds check that can never fail is left out (`Matrix[PivotRow, K]`
  after `PivotRow := K` and `PivotRow := Row` in the LU's pivot search).
  A FOR with step 1 whose end is data (`FOR C := 1 TO Count`) and whose body
  checks bounds on its variable comes in two versions: one without those
  checks, run when the range (`range.stop`, tested once) lies inside every
  array so indexed, and the loop as before otherwise.
* `unguard` (unguard.py): no `try` around an assignment whose Python code
  cannot raise: a local set from locals and literals with `+ - *`, or a
  store into the POU's own elementary variable (a local or a `self.` slot;
  not located, whose attribute is a process-image property, nor VAR_IN_OUT,
  REF_TO or global) of an expression that cannot fault by the branches
  pass's rule (owned reads, literals, comparisons, logic, unary minus,
  `+ - *`; no division, power, shift or call), or a store of such an
  expression at a literal index (in range) into the POU's own array of
  elementary elements.  The handler catches
  `_FAULTS` only, so where nothing can raise one it never runs: same
  results, faults and charges.
* `branches` (branches.py): an IF whose conditions cannot fault (owned
  variables, comparisons, logic, `+ - *`, no call that may raise) is a plain
  `if/elif/else` instead of a guarded branch index compared with each
  branch's number; a CASE selector that cannot fault is read without a
  guard.
* `aliases` (aliases.py): an array, struct or FB instance of the instance or
  a global that a body names inside one IF branch or CASE clause only is
  aliased by its local at the start of that branch, not in the prologue of
  every call (the same load of the same object, before any use).
* `fastpath` (fastpath.py): a POU body, or an iteration of a FOR that may
  leave early, whose worst-case NJ time is bounded at compile time (constant
  loop counts, callees bounded too, no METHOD or PROPERTY) and whose exact
  code has at least `fastpath.WORTH` budget checks is compiled a second time
  without the checks and with one charge per straight run of blocks; it runs
  when the time left covers the worst case, the exact code otherwise.  A
  FUNCTION's in-out arrays are owned storage in that copy, which runs only
  when each is a Python list (not an unconnected in-out's NullRef passed on),
  so `unguard` and `branches` apply to their reads and stores there.
* `chains` (chains.py): in a fast copy, two adjacent stores of one array
  element, neither guarded (so neither can raise), the second of the form
  `X[k] = (X[k] op rest)` where `rest` reads nothing at index k, are one
  store of `(first op rest)`: the same operations in the same order.

* `sets` (sets.py): in an OR chain, a run of `X = c` comparisons of one
  plain integer variable with constants is `X in (c1, c2, ...)`; in an AND
  chain a run of `X <> c` is `X not in (...)`: the same bool, X read once.
* `stores` (stores.py): a cached variable whose stores are all in one IF
  branch or CASE clause is stored back to its slot in a `finally` around
  that branch, not at the end of every call, and loaded at the branch's
  start when every use is there too.
* `unused` (aliases.py `drop_unused`): a load `v_X = self.v_X` or
  `v_X = _G.v_X` whose local the compiled function never names again (a
  constant table every read of which was folded) is left out.
* `offsets` (exprs.py `index_lvalue`): in the body of a range-based FOR,
  the flat index `i - lo` of a one-dimensional array indexed by the loop's
  variable is computed once per iteration into a temporary when the body
  uses it twice or more (TRJ_OceanWave's `Wavenumber[Component]` and four
  more arrays: `Component - 1` seven times an iteration), as `i * k` was.
* `reuse` (reuse.py): across the statements of a body, a float value
  computed again over unchanged operands (an own array's element at a
  literal index, `+ - *` of such values and plain variables, SIN, COS, TAN
  or SQRT of one) is set once, before the statement that first computes
  it, and read by name after; a value used once keeps its text.
* `charges` (charges.py): a charge `_spent += N` of a block is added by the
  charge before it in the same block level when nothing between them can
  raise, check the budget or leave the level (assignments and IF tests that
  cannot raise): the same total at every read of `_spent`.
* `settle` (charges.py `settled`): a charge where the value of `_spent` is
  known (from the body's `_spent = 0` on, into IF branches and on after a chain
  whose paths end with one total, through `try` statements that charge nothing)
  stores that value plus its amount: the same int, no addition.  Where paths
  join with different totals, each keeps its own with the literals its
  locals hold, and a test of such a local (`IF NewFault = 0`) lets into a
  branch only the paths that reach it, whose total may then be one.
* `spread` (aliases.py `spread_branches`, with `aliases` and `stores`): a
  variable every use of which lies in branches of one IF or CASE, no use at
  their common level, is loaded at the start of each such branch (and stored
  back in a `finally` around each that stores it), not once around them all:
  SP_Controller's CASE loads its FB instances and flags in the clause that
  names them.  A call runs one of those branches at most.
* `halves` (halves.py): a CASE of at least `halves.MIN_CLAUSES` clauses with
  integer labels and no ELSE tests `selector < P` first, P a value no clause's
  labels lie on both sides of, and so on by halves down to groups of
  `halves.LEAF` clauses tested in the order written: the same clause for
  every selector, with the same charges.
* `shortcut` (shortcut.py): an IF condition tested in place (`branches`)
  tests its AND and OR of BOOLs as Python's `and` and `or`: the same truth,
  and the operand left out reads, stores and raises nothing.
* `finite` (reuse.py `finite`, with `reuse`): the finite test (pysrc.finite_test)
  of inline SIN, COS and TAN of a float local is a value of `reuse`: SIN(Psi)
  and COS(Psi) of one unchanged Psi test it once; of an own slot too (`self.v_X`,
  IK's Alpha, Beta and Gamma).
* `deferred` (aliases.py `drop_unread`, with `unused`): the load of a cached variable
  the body sets before it reads it is left out also when budget checks come before
  the set; each such check loads it in its branch, before `_overrun` (IK's U, V, W,
  LegX, LegY and LegZ): an overrun stores back the same value, a call that passes
  the checks loads nothing.
* `wraps` (wraps.py): a store of MIN or MAX of integers is not wrapped when their
  range (an input's declared type, a literal, `+ -` of such) lies inside the
  target's type: `SyncCalls := MIN(SyncCalls + 1, 2)` is at most 2.
* `stores_read` (reuse.py `stored`, with `reuse`): after `X[k] := v`, v a value of
  `reuse` stored as it is into an own array at a literal index, a read of `X[k]` is
  that value while X and what v reads are unchanged: IK's `Position[Leg]`, stored
  and read back by three tests, is computed into a name once.
* `temps` (statements.py `_statement_with_values`): the temporaries `_tN` of a
  statement are its own (its guards, walrus operands, ranges, the motion FBs' call
  sites), so once it is compiled the next statement takes the same numbers again;
  a loop's hoisted and per-iteration temps, set where other statements run too, take
  a number no statement had and keep it (`lasting_temp`), and a CSE region's temps
  are not given again inside the region.  Fewer local slots: a
  call creates and clears each one (SP_Controller 116 -> 59, TRJ_OceanWave 165 -> 110).
* `seal` (seal.py): a body that reads the controller's seal twice or more (the
  idle Execute FBs' rest tests and notes) reads it once, `_seal = _ctx.seal` at its
  start: the seal is replaced only between the programs' runs.
* `scalars` (scalars.py): in a FUNCTION's fast copy, the elements of an in-out array read
  and stored at literal indices live in Python locals (`v_MATRIX_e6`), loaded with one
  unpack of the list and written back before anything else may look at the list (a read at
  a data index or of a list that may be the same, a return, a fault handler's start, the
  copy's end): the LU's elimination and substitutions on locals, the same operations in the
  same order.
* `sums` (sums.py): in a fast copy, a run of finite tests of REAL or LREAL elements at
  literal indices (`IF NOT (ABS(J[r, c]) <= SP_LREAL_MAX) THEN AllFinite := FALSE`), with
  the same body and only stores of `+ - *` that cannot change what they read between them,
  runs where its last test stood and only when the sum of the tested elements is not finite:
  SP_ForwardKinematics' 42 tests of the Jacobian and the residual are one sum when all pass.
* `pivots` (pivots.py): in a fast copy, a pivot search unrolled (`IF ABS(M[Row, K]) >
  ABS(M[PivotRow, K]) THEN PivotRow := Row`) keeps the best `abs` in a local, set again where
  the pivot row moves, and the zero-pivot test after it reads that local: SP_LuSolve's 15
  candidate tests and 5 zero tests read the pivot's element once a column.
* `native` (native.py, with `vector`): a `vector` run is computed by machine code LLVM
  compiles from its graph (llvmlite, MCJIT; one `fmul`/`fadd`/`fsub` an operation, no
  fast-math, no FMA), compiled by the run's first call and kept per process by its IR;
  an output that is not finite takes the run in Python, as NumPy's kernel does.  Off
  without llvmlite (the `native` extra) or with `ST_RUNTIME_NATIVE=0`: NumPy's kernel.
* `kernels` (kernels.py): a body's run of at least `kernels.MIN_OPERATIONS` float
  operations in consecutive assignments of plain names (`+ - *`, unary minus, float
  literals, list elements at literal indices, SQRT as `math.sqrt`: IK's legs) is one call
  of machine code LLVM compiles from it (native.py, by its first call), which returns the
  values only when every argument is a float and every value computed is finite, else
  None, and then the lines run in Python as written.  One call spans runs separated by
  finite tests of its values (not taken where it answers) and statements that cannot
  raise (stores of its values or tests into list elements, tests, int charges), which
  then run after it in their order (IK's six legs: one call).  Off as `native` is.
* `loops` (loops.py): in a fast copy, a FOR loop of float sums over `L[i]` elements with SIN
  and COS (TRJ_OceanWave's components) is one call of machine code LLVM compiles from its
  body, `sin` and `cos` the C library's functions math.sin and math.cos call; the values
  only when the range, lists, elements and every value are as the kernel needs (floats,
  finite), else None and the loop runs in Python as written.  Off as `native` is.
* `elements` (elements.py): in an IF chain tested in place (`branches`), an element of a
  local array at a literal index that two or more conditions read is read once, into a
  temp, where its first read runs whenever its condition does; the later reads read the
  temp: nothing between the conditions can store into the array.
* `dormant` (dormant.py, with `inline`): the call site of an idle Execute FB (MC_Stop,
  MC_Reset) that is the only code of the program writing its instance runs under one test,
  `X or <the rest note does not hold>`, X the BOOL its Execute is given: at rest it would
  store what the instance holds (constants, the same AXIS_REF, FALSE) and call nothing.
  Two or more such sites apart only by other call statements naming none of their X form a
  group (`dormant.Groups`): one test a scan of each X and a note of the group, each site's
  test only when that one is true.
* `threads` (threads.py): an IF chain whose first test reads a local alone (`IF NewFault = 0`)
  right after an IF chain every path of which tells that test's answer (a branch set the
  local to a literal, or tested it) is not tested: each path runs the branch it would take
  at its end (jump threading); SP_Controller's axes, five tests a scan fewer.
* `early` (aliases.py `store_early`): a method's cached variable set once at the top level
  before any line names it is stored into its slot by that line, not loaded at the start
  and stored back at the end (SP_Controller's SyncExecute, StopExecute, ResetExecute).

None of them changes the NJ execution-time charges (cost.py): those come from
the ST text, and an unrolled loop charges what the loop charged, at the same
checks; the fast path charges the same total, and leaves out only checks
that cannot fire.  `ST_RUNTIME_OPTIMISE` (environment) picks the default: `none`, `all`
(every pass on by default, so not `gather`) or a comma-separated list of
pass names; unset means all.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, fields

from ... import ast
from ...types import ElementaryType

#: A temporary `_tN` named in a line of generated code (a whole word).  Spelled with the
#: literal `_` first and the look-behind after it (the matches of `\b_t\d+\b`): the regex
#: engine then skips to each `_` instead of testing the boundary at every character (4x).
TEMP_NAME = re.compile(r"_(?<!\w_)t\d+\b")

_UNASKED = object()


def remembered(answer):
    """`answer`, a pure function of one text (a line, an expression's code, a name), with its
    answers kept by that text: for one body's compile or one pass over a region's lines, where
    the same text comes again (an unrolled loop's copies, the fast path's and the exact)."""
    answers: dict = {}

    def remembered_answer(text: str):
        found = answers.get(text, _UNASKED)
        if found is _UNASKED:
            found = answers[text] = answer(text)
        return found
    return remembered_answer


def kept(compiler, name: str, make):
    """What `make()` builds, made once per body's compile: kept on `compiler` (one
    BodyCompiler) under `name` (a pass's memo or its `remembered` judge)."""
    found = compiler.__dict__.get(name)
    if found is None:
        found = make()
        setattr(compiler, name, found)
    return found


# ------------------------------------------------------------------ gates
# A pass whose subject a body does not hold is not run on it: each gate below is true
# whenever the pass could change the body's code, so the code is the same either way.
# They read the body's node classes and nodes, listed once by `scope.Usage`.

def branched(body) -> bool:
    """Whether `body` has an IF or CASE among its own statements.  `aliases.late_loads`
    and `stores.late_stores` move a line into an IF branch or CASE clause only: a name
    met in a statement outside every branch (a loop is one statement) stays put."""
    for stmt in body:
        if type(stmt) is ast.If or type(stmt) is ast.Case:
            return True
    return False


def may_reuse(compiler) -> bool:
    """Whether `reuse` may find a value in the body: its values are array elements
    (`ast.Index`), float `+ - *`, and SIN, COS, TAN and SQRT (their finite tests too)."""
    usage = compiler.scope.usage
    kinds = usage.kinds
    if ast.Index in kinds:
        return True
    if ast.Binary not in kinds and ast.Call not in kinds:
        return False
    from ..scope import of_classes      # (scope imports exprs, which imports this package)

    targets = compiler.program.call_targets
    for node in of_classes(usage.nodes, _MAY_REUSE):
        cls = type(node)        # (a Binary or a Call)
        if cls is ast.Binary:
            if node.op in _REUSED_OPERATORS:
                t = compiler.ty(node)
                if isinstance(t, ElementaryType) and t.kind == "real":
                    return True
        elif cls is ast.Call:
            target = targets.get(id(node))
            if target is None or (target.name or "").upper() in _REUSED_FUNCTIONS:
                return True
    return False


_MAY_REUSE = frozenset({ast.Binary, ast.Call})
_REUSED_OPERATORS = frozenset(("+", "-", "*"))
_REUSED_FUNCTIONS = frozenset(("SIN", "COS", "TAN", "SQRT"))


UNROLL_CAP = 8000   # statements unrolled loops may produce in one POU (iterations x body statements)


@dataclass(frozen=True)
class Optimisations:
    fold: bool = True
    unroll: bool = True
    cse: bool = True
    unguard: bool = True
    fuse: bool = True
    gather: bool = False     # off by default: slower than the loads it replaces (gather.py)
    inline: bool = True
    vector: bool = True
    ranges: bool = True
    branches: bool = True
    aliases: bool = True
    fastpath: bool = True
    chains: bool = True
    sets: bool = True
    stores: bool = True
    unused: bool = True
    offsets: bool = True
    reuse: bool = True
    charges: bool = True
    settle: bool = True
    spread: bool = True
    halves: bool = True
    shortcut: bool = True
    finite: bool = True
    deferred: bool = True
    wraps: bool = True
    stores_read: bool = True
    temps: bool = True
    seal: bool = True
    scalars: bool = True
    sums: bool = True
    pivots: bool = True
    native: bool = True
    kernels: bool = True
    loops: bool = True
    elements: bool = True
    dormant: bool = True
    threads: bool = True
    early: bool = True

    @classmethod
    def none(cls) -> "Optimisations":
        return cls(**{f.name: False for f in fields(cls)})

    @classmethod
    def only(cls, *names: str) -> "Optimisations":
        known = {f.name for f in fields(cls)}
        unknown = set(names) - known
        if unknown:
            raise ValueError(f"unknown optimisation(s) {sorted(unknown)}; known: {sorted(known)}")
        return cls(**{name: name in names for name in known})

    @classmethod
    def from_environment(cls) -> "Optimisations":
        value = os.environ.get("ST_RUNTIME_OPTIMISE", "all").strip().lower()
        if value in ("", "all"):
            return cls()
        if value == "none":
            return cls.none()
        return cls.only(*(name.strip() for name in value.split(",") if name.strip()))
