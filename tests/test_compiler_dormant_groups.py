"""Groups of dormant call sites (st_runtime/compiler/optimise/dormant.py, `Groups`): two or more
dormant sites apart only by other call statements are skipped under one test a scan, while each
X is FALSE and a note on the group's first instance says that all were found at rest.

Each row runs 8 scans of one program (Poke TRUE in scan 5 only) and reads after every scan
`Resets[1].Done` or `Stops[1].Deceleration`, with all passes and none.  By hand: MC_Reset on an
axis without error is Done in the call of Execute's rising edge, and Done is TRUE for that one
call when Execute falls in the next (PLCopen's output rules, st_runtime/motion/fbs.py's
docstrings; docs/nj501.md), so a reset asked for in scan 5 alone shows Done in scan 5 only;
MC_Stop never writes its inputs, so the call's Deceleration 50.0 is what every scan ends with.
Where something between two sites writes an X (a store, an output, a VAR_IN_OUT, a reference,
another POU through a global) the sites keep their own tests; where something outside the program
writes an instance (a hook, the API), the seal is new and the group runs again.
"""

from __future__ import annotations

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from stgen.scenarios.program import controller_sources

from test_compiler_dormant import run_8_scans
from test_motion_st import AXIS, make_plc

PROGRAM = """
FUNCTION_BLOCK Setter
VAR_IN_OUT B : BOOL; END_VAR
VAR_INPUT V : BOOL; END_VAR
B := V;
END_FUNCTION_BLOCK

FUNCTION_BLOCK ViaRef
VAR_INPUT P : REF_TO BOOL; V : BOOL; END_VAR
P^ := V;
END_FUNCTION_BLOCK

FUNCTION_BLOCK Echo
VAR_INPUT V : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
Q := V;
END_FUNCTION_BLOCK

FUNCTION_BLOCK GlobalWriter
VAR_INPUT V : BOOL; END_VAR
VAR_EXTERNAL GReset : BOOL; END_VAR
GReset := V;
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    Stops : ARRAY[1..2] OF MC_Stop;
    Resets : ARRAY[1..2] OF MC_Reset;
    Count : INT;
    Poke, DoStop, DoReset : BOOL;
    S : Setter;
    P : ViaRef;
    E : Echo;
    W : GlobalWriter;
    R : REF_TO BOOL;
    Seen : BOOL;
END_VAR
Count := Count + 1;
Poke := Count = 5;
{before}
Stops[1](Axis := Cyl1, Execute := DoStop AND NOT Cyl1.Status.ErrorStop, Deceleration := 50.0);
{between}
Resets[1](Axis := Cyl1, Execute := {reset});
(* read often enough that the body keeps them in Python locals (scope.CACHE_THRESHOLD) *)
Seen := (DoStop AND DoReset AND GReset) OR (DoStop AND DoReset AND GReset) OR (DoStop AND DoReset AND GReset);
END_PROGRAM
"""

GLOBALS = "VAR_GLOBAL GReset : BOOL; END_VAR\n"

# The writers of Resets[1]'s Execute in scan 5: (before the first site, between the sites, X).
WRITERS = {
    "a call between, X stored before": ("DoReset := Poke;", "E(V := Poke);", "DoReset"),
    "a store between": ("", "DoReset := Poke;", "DoReset"),
    "an output between": ("", "E(V := Poke, Q => DoReset);", "DoReset"),
    "a VAR_IN_OUT between": ("", "S(B := DoReset, V := Poke);", "DoReset"),
    "a reference": ("R := REF(DoReset);", "P(P := R, V := Poke);", "DoReset"),
    "another POU through a global": ("", "W(V := Poke);", "GReset"),
}

# Whether the two sites form a group: only where nothing between them can write an X.
GROUPED = {"a call between, X stored before"}


def _program(before: str = "", between: str = "E(V := Poke);", reset: str = "DoReset") -> str:
    return GLOBALS + PROGRAM.replace("{before}", before).replace("{between}", between).replace("{reset}", reset)


def _run(monkeypatch, optimise: str, program: str, read, outside=None) -> list:
    """`read(instance)` after each of 8 scans of one run (`run_8_scans`: a hook or the API
    sets Stops[1].Deceleration to 10.0 before scan 5 for `outside`)."""
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, _ = make_plc(program, AXIS, dialect="iec")
    instance = plc.controller.instances["Main"]
    seen = []
    plc.controller.add_observer(lambda _c: seen.append(read(instance)), reads_only=True)
    run_8_scans(plc, main, instance.v_STOPS, outside)
    return seen


def _done(instance) -> bool:
    return instance.v_RESETS[0].v_DONE


def _deceleration(instance) -> float:
    return instance.v_STOPS[0].v_DECELERATION


def _source(program: str) -> str:
    from st_runtime.motion.motion_task import MotionTask

    axes = MotionTask.from_tables([AXIS]).globals_source()
    project = api.load_sources({"axes.st": axes, "main.st": program}, dialect="iec")
    return compile_program(project.program, optimise=Optimisations()).python_sources["MAIN"]


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_an_execute_written_in_scan_5_resets_in_scan_5_only(monkeypatch, writer):
    before, between, x = WRITERS[writer]
    program = _program(before, between, x)
    assert ("_dormant1 = True" in _source(program)) == (writer in GROUPED)
    expected = [False] * 4 + [True] + [False] * 3
    assert _run(monkeypatch, "all", program, _done) == _run(monkeypatch, "none", program, _done) == expected


@pytest.mark.parametrize("outside", ["hook", "api"])
def test_a_write_from_outside_renews_the_seal_and_the_group_stores_again(monkeypatch, outside):
    program = _program()
    assert "_dormant1 = True" in _source(program)
    for optimise in ("all", "none"):
        assert _run(monkeypatch, optimise, program, _deceleration, outside) == [50.0] * 8


def test_the_controller_tests_its_twelve_idle_sites_once_a_scan():
    program = api.load_sources(dict(controller_sources(None))).program
    source = compile_program(program, optimise=Optimisations()).python_sources["SP_CONTROLLER"]
    assert source.count("if v_STOPEXECUTE is not False or v_RESETEXECUTE is not False or "
                        "v_AXISSTOP[0]._group_at_rest is not _seal:") == 1
    for k in range(6):
        assert f"if _dormant1 and (v_STOPEXECUTE is not False or v_AXISSTOP[{k}]._at_rest is not _seal):" in source
        assert f"if _dormant1 and (v_RESETEXECUTE is not False or v_AXISRESET[{k}]._at_rest is not _seal):" in source
    off = compile_program(program, optimise=Optimisations(dormant=False)).python_sources["SP_CONTROLLER"]
    assert "_dormant" not in off and "_group_at_rest" not in off


SECOND_GROUP = """
Stops[2](Axis := Cyl1, Execute := DoStop AND NOT Cyl1.Status.ErrorStop, Deceleration := 50.0);
E(V := Poke);
Resets[2](Axis := Cyl1, Execute := DoReset);
END_PROGRAM"""


def test_two_groups_in_one_body_each_have_their_own_flag(monkeypatch):
    """A store (Seen) parts the two pairs of sites: two groups, each skipped under its own
    `_dormantN` (one shared flag would let the second group's test stand for the first's).
    By hand, as above: each reset is Done in scan 5 only."""
    program = _program("DoReset := Poke;", "E(V := Poke);", "DoReset").replace("END_PROGRAM", SECOND_GROUP)
    source = _source(program)
    assert "_dormant1 = True" in source and "_dormant2 = True" in source

    def both_done(instance) -> tuple:
        return instance.v_RESETS[0].v_DONE, instance.v_RESETS[1].v_DONE

    expected = [(False, False)] * 4 + [(True, True)] + [(False, False)] * 3
    assert _run(monkeypatch, "all", program, both_done) == _run(monkeypatch, "none", program, both_done) == expected
