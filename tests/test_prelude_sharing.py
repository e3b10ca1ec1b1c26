"""The checked and compiled native prelude is shared by every load of a process
(checker/prelude_base.py, compiler SharedPrelude): the result of a load must be
exactly that of checking the prelude again with the user's files, nothing of
one load may reach the next, and no two programs share instance state."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from st_runtime import api
from st_runtime.checker import check
from st_runtime.checker.prelude_base import prelude_base
from st_runtime.compiler import CompileError, compile_program
from st_runtime.loader import BUILTIN, _ordered, load_texts, parse_texts

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "tests" / "corpus"


def _both_ways(texts: dict[str, str], dialect: str, memory_limit: int | None = None):
    """(shared, full): the diagnostics and the checked program of a load with the
    shared prelude and of one that checks the prelude again."""
    out = []
    for share in (True, False):
        prelude, parsed, diagnostics = parse_texts(dict(texts), dialect)
        program, found = check([f for _, f in parsed], dialect, memory_limit, share_prelude=share)
        everything = diagnostics + found
        rendered = [d.render(texts.get(d.pos.file)) for d in _ordered(everything, [BUILTIN, *texts])]
        out.append((rendered, None if any(d.is_error for d in everything) else program))
    return out


def _layout(program) -> dict:
    """What the compiler and the tools see of a checked program, in its order."""
    return {
        "types": [(k, str(t)) for k, t in program.types.items()],
        "pous": [(k, p.kind, [(n, s.kind, str(s.type)) for n, s in p.variables.items()])
                 for k, p in program.pous.items()],
        "globals": [(k, str(s.type)) for k, s in program.globals.items()],
    }


CASES = [(p, "iec") for p in sorted((CORPUS / "accept").glob("*.st"))] + \
        [(p, "iec") for p in sorted((CORPUS / "reject").glob("*.st"))] + \
        [(p, "nj") for p in sorted((CORPUS / "accept").glob("*.st"))[::4]] + \
        [(p, "nj") for p in sorted((ROOT / "tests" / "st_dialects").glob("*.st"))]


@pytest.mark.parametrize("path,dialect", CASES, ids=lambda c: getattr(c, "stem", c))
def test_shared_prelude_checks_like_a_full_check(path: Path, dialect: str):
    texts = {path.name: path.read_text(encoding="utf-8")}
    (shared, program), (full, again) = _both_ways(texts, dialect)
    assert shared == full
    if program is not None:
        assert _layout(program) == _layout(again)
        assert _compiled(program) == _compiled(again)


@pytest.mark.parametrize("limit", [1, 8, 16, 40, 2**20])
@pytest.mark.parametrize("dialect", ["iec", "nj"])
def test_memory_limits_report_the_prelude_as_a_full_check_does(limit: int, dialect: str):
    """A limit below a prelude FB's bytes reports it (at "<builtin>") as the full check did."""
    texts = {"m.st": "PROGRAM MAIN VAR t : TON; p : MC_Power; a : AXIS_REF; s : STRING[10]; END_VAR END_PROGRAM"}
    (shared, _), (full, _) = _both_ways(texts, dialect, limit)
    assert shared == full


def _compiled(program):
    """The classes and the POUs' Python of a compiled program, or why it did not compile."""
    try:
        compiled = compile_program(program)
    except CompileError as exc:
        return exc.message, exc.pos
    return list(compiled.classes), {k: v for k, v in compiled.python_sources.items()
                                    if not k.startswith("init:")}


# Two programs with the same names and different types: B would see anything A
# left behind (a type, a POU, a global, an enumeration value), and B replaces
# the standard TON with its own FB (a project's own TON: W-DECL-001).
PROGRAM_A = """
TYPE Pair : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE
TYPE Mode : (Idle, Busy); END_TYPE
FUNCTION_BLOCK Counter
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
total := total + step;
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR
    p : Pair := (x := 3, y := 4);
    m : Mode := Busy;
    c : Counter;
    t : TON;
    n : INT;
END_VAR
c(step := p.x);
t(IN := TRUE, PT := T#3ms);
n := n + 1;
END_PROGRAM
"""

PROGRAM_B = """
TYPE Pair : STRUCT x : REAL; END_STRUCT; END_TYPE
TYPE Mode : (Off, Idle); END_TYPE
FUNCTION_BLOCK TON
VAR_INPUT IN : BOOL; PT : TIME; END_VAR
VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
Q := IN;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Counter
VAR_INPUT step : REAL; END_VAR
VAR_OUTPUT total : REAL; END_VAR
total := total + step * 0.5;
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR
    p : Pair := (x := 2.5);
    m : Mode := Idle;
    c : Counter;
    t : TON;
END_VAR
c(step := p.x);
t(IN := TRUE, PT := T#3ms);
END_PROGRAM
"""

# B again, without its own TON: it shares the prelude, and must not see A's types.
PROGRAM_C = PROGRAM_B.replace("""FUNCTION_BLOCK TON
VAR_INPUT IN : BOOL; PT : TIME; END_VAR
VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
Q := IN;
END_FUNCTION_BLOCK
""", "")


def _run(text: str, scans: int) -> dict:
    """Load, run `scans` scans of 1 ms, and report what a user sees."""
    project = api.load_text(text, "main.st")
    plc = project.controller(period="1ms")
    main = plc.add_program("MAIN")
    plc.run(scans)
    warnings = sorted(d.code for d in project.diagnostics)
    return {"warnings": warnings, "main": main.to_json(), "mode": main.raw("m")}


FRESH = """
import json, sys
sys.path.insert(0, sys.argv[1])
from tests.test_prelude_sharing import PROGRAM_A, PROGRAM_B, PROGRAM_C, _run
print(json.dumps(_run({"A": PROGRAM_A, "B": PROGRAM_B, "C": PROGRAM_C}[sys.argv[2]], 5)))
"""


def _fresh(name: str) -> dict:
    child = subprocess.run([sys.executable, "-c", FRESH, str(ROOT), name],
                           capture_output=True, text=True, check=True)
    return json.loads(child.stdout)


def test_loads_in_a_row_do_not_leak_into_each_other():
    first_a = _run(PROGRAM_A, 5)
    b = _run(PROGRAM_B, 5)
    c = _run(PROGRAM_C, 5)
    second_a = _run(PROGRAM_A, 5)
    # By hand: 5 scans of 1 ms.  A: c.total = 5 * 3, TON(PT 3 ms) on since scan 1:
    # ET stops at PT (3 ms, reached on scan 4), Q TRUE; Mode#Busy = 1.
    assert first_a["main"]["c"]["total"] == 15
    assert first_a["main"]["t"] == {"IN": True, "PT": "T#3ms", "Q": True, "ET": "T#3ms"}
    assert first_a["main"]["n"] == 5 and first_a["mode"] == 1 and first_a["warnings"] == []
    # B: its own TON (Q := IN, ET never set) and REAL totals 5 * 1.25; Mode#Idle = 1.
    assert b["main"]["c"]["total"] == 6.25
    assert b["main"]["t"] == {"IN": True, "PT": "T#3ms", "Q": True, "ET": "T#0s"}
    assert b["mode"] == 1 and b["warnings"] == ["W-DECL-001", "W-NJ-004"]   # TON is an NJ instruction name
    # C: the standard TON again, B's types.
    assert c["main"]["t"] == first_a["main"]["t"] and c["main"]["c"]["total"] == 6.25
    assert c["warnings"] == []
    assert second_a == first_a
    for name, seen in (("A", first_a), ("B", b), ("C", c)):
        assert seen == _fresh(name), name


def test_no_two_programs_share_instance_state():
    one, two = api.load_text(PROGRAM_A, "a.st"), api.load_text(PROGRAM_A, "a.st")
    first, second = one.controller(), two.controller()
    a, b = first.add_program("MAIN"), second.add_program("MAIN")
    first.run(4)
    assert a["t"]["Q"] is True and a["t"]["ET"] == "T#3ms"
    assert b["t"] == {"IN": False, "PT": "T#0s", "Q": False, "ET": "T#0s"}     # not run yet
    a["t.PT"] = "T#7ms"
    second.run(1)
    assert b["t"] == {"IN": True, "PT": "T#3ms", "Q": False, "ET": "T#0s"}
    assert a["t"]["PT"] == "T#7ms"
    # Two instances of a prelude STRUCT (AXIS_REF) are two objects.
    axis = api.load_text("PROGRAM MAIN VAR a, b : AXIS_REF; END_VAR a.Cfg.AxNo := 3; END_PROGRAM", "ax.st")
    plc = axis.controller()
    main = plc.add_program("MAIN")
    plc.run(1)
    assert main["a.Cfg.AxNo"] == 3 and main["b.Cfg.AxNo"] == 0
    assert main.raw("a") is not main.raw("b") and main.raw("a.Cfg") is not main.raw("b.Cfg")


def _fingerprint(base) -> str:
    """Everything of the shared prelude a load could change, as text."""
    parts = [repr(sorted(base.names.items())), repr(list(base.types.items()))]
    for k, info in base.pous.items():
        parts.append(repr((k, info.kind, [(n, s.kind, str(s.type), s.init, s.constant)
                                          for n, s in info.variables.items()],
                           list(info.methods), info.parent, info.interfaces, info.modifiers)))
    for name, table in sorted(base.program_tables.items()) + sorted(base.context_tables.items()):
        parts.append(f"{name}:{len(table)}")
    parts.append(repr(sorted(base.type_events.items())))
    return "\n".join(parts)


def test_loads_leave_the_shared_prelude_as_it_was():
    prelude, parsed, _ = parse_texts({}, "iec")
    base = prelude_base([f for _, f in parsed], "iec", False)
    assert base is not None
    before = _fingerprint(base)
    shared = 0
    for path in sorted((CORPUS / "accept").glob("*.st")) + sorted((CORPUS / "reject").glob("*.st")):
        result = load_texts({path.name: path.read_text(encoding="utf-8")})
        if result.program is not None:
            assert result.program.prelude in (base, None)   # None: the file declares its own TON
            shared += result.program.prelude is base
            compile_program(result.program)
    assert shared > 200
    for text in (PROGRAM_A, PROGRAM_B, PROGRAM_C):
        load_texts({"m.st": text})
    assert _fingerprint(base) == before
