"""The `dormant` pass (st_runtime/compiler/optimise/dormant.py): the call site of an idle
MC_Stop or MC_Reset that is the only code writing its instance skips its input stores while the
FB is at rest (`if X or <instance>._at_rest is not _seal:` around the site).

Skipped, the site would store what the instance holds; that holds only when nothing else
wrote the instance since the site last ran.  Each writer below (a direct store, a VAR_IN_OUT,
a reference, a whole-array copy, a second call site, another POU, a hook and the API from
outside) writes an input of `Stops[1]` before its call in one scan, once the FB is at rest:
the call stores Deceleration 50.0 again, so every scan ends with 50.0 (by hand: the call runs
after the writer in the scan's order, and MC_Stop never writes its inputs), with the
optimisations on and off, and the site keeps today's code where the writer is in the program.
"""

from __future__ import annotations

import re

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from stgen.scenarios.program import controller_sources

from test_motion_st import AXIS, make_plc

PROGRAM = """
FUNCTION_BLOCK Poker
VAR_IN_OUT S : MC_Stop; END_VAR
S.Deceleration := 10.0;
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    Stops : ARRAY[1..2] OF MC_Stop;
    Resets : ARRAY[1..2] OF MC_Reset;
    Spare : ARRAY[1..2] OF MC_Stop;
    Count : INT;
    Poke, DoStop, DoReset, Flag, Nope : BOOL;
    Decel : LREAL;
    P : Poker;
    R : REF_TO MC_Stop;
END_VAR
Count := Count + 1;
Poke := Count = 5;
{writer}
Stops[1](Axis := Cyl1, Execute := DoStop AND NOT Cyl1.Status.ErrorStop, Deceleration := 50.0);
Resets[1](Axis := Cyl1, Execute := DoReset);
Decel := Stops[1].Deceleration;
END_PROGRAM
"""

# The writers: ST before the call, run in the scans where Poke is TRUE.
WRITERS = {
    "direct store": "IF Poke THEN Stops[1].Deceleration := 10.0; END_IF;",
    "VAR_IN_OUT": "IF Poke THEN P(S := Stops[1]); END_IF;",
    "reference": "IF Poke THEN R := REF(Stops[1]); R^.Deceleration := 10.0; END_IF;",
    "whole-array copy": "Spare[1].Deceleration := 10.0; Spare[1](Axis := Cyl1, Execute := FALSE);\n"
                        "IF Poke THEN Stops := Spare; END_IF;",
    "second call site": "IF Poke THEN Stops[1](Axis := Cyl1, Execute := FALSE, Deceleration := 10.0); END_IF;",
}

OTHER_POU = """
PROGRAM Other
Main.Stops[1].Deceleration := 10.0;
END_PROGRAM
"""


def _decelerations(monkeypatch, optimise: str, writer: str = "", outside=None, extra: str = "") -> list:
    """Stops[1].Deceleration after each of 8 scans of one run (Poke TRUE in scan 5 only);
    `outside`: "hook", a hook (not quiet) writes the input before scan 5; "api", the API
    writes it between two runs of 4 scans."""
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, main, _ = make_plc(PROGRAM.replace("{writer}", writer) + extra, AXIS, dialect="iec")
    controller = plc.controller
    stops = controller.instances["Main"].v_STOPS       # (an array copy may put other FBs in it)
    seen = []
    controller.add_observer(lambda _c: seen.append(stops[0].v_DECELERATION), reads_only=True)
    run_8_scans(plc, main, stops, outside)
    return seen


def run_8_scans(plc, main, stops: list, outside=None) -> None:
    """8 scans of `plc`; `outside`: "hook", a hook (not quiet) sets Stops[1].Deceleration to
    10.0 before scan 5; "api", the API does between two runs of 4 scans."""
    if outside == "hook":
        def poke(ctx):
            if ctx.scan == 5:
                stops[0].v_DECELERATION = 10.0
        plc.controller.add_io_hook(before=poke)
    if outside == "api":
        plc.run(4)
        main["Stops[1].Deceleration"] = 10.0
        plc.run(4)
    else:
        plc.run(8)


def _source(writer: str, extra: str = "") -> str:
    project = api.load_sources({"axes.st": _axes(), "main.st": PROGRAM.replace("{writer}", writer) + extra},
                               dialect="iec")
    return compile_program(project.program, optimise=Optimisations()).python_sources["MAIN"]


def _axes() -> str:
    from st_runtime.motion.motion_task import MotionTask

    return MotionTask.from_tables([AXIS]).globals_source()


def _guarded(source: str, execute: str, instance: str) -> bool:
    """Whether `source` tests `execute` (a local or the program's slot) and the rest note of
    `instance` before the site."""
    return re.search(rf"if (self\.)?{execute} is not False or {re.escape(instance)}\._at_rest is not _seal:",
                     source) is not None


def test_the_sole_site_runs_under_one_test_and_ends_every_scan_as_with_every_call(monkeypatch):
    source = _source("")
    assert _guarded(source, "v_DOSTOP", "v_STOPS[0]") and _guarded(source, "v_DORESET", "v_RESETS[0]")
    assert _decelerations(monkeypatch, "all") == _decelerations(monkeypatch, "none") == [50.0] * 8


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_site_whose_instance_the_program_writes_elsewhere_keeps_its_code(monkeypatch, writer):
    source = _source(WRITERS[writer])
    assert not _guarded(source, "v_DOSTOP", "v_STOPS[0]") and _guarded(source, "v_DORESET", "v_RESETS[0]")
    for optimise in ("all", "none"):
        assert _decelerations(monkeypatch, optimise, WRITERS[writer]) == [50.0] * 8


def test_no_other_pou_names_a_programs_variable():
    """The census's premise for other POUs: a PROGRAM's VAR is named only by its own code (an
    access path is read by nothing at run time: checker/configuration.py)."""
    with pytest.raises(api.LoadError, match="E-TYPE-016"):
        _source("", OTHER_POU)


@pytest.mark.parametrize("outside", ["hook", "api"])
def test_a_write_from_outside_renews_the_seal_and_the_site_stores_again(monkeypatch, outside):
    assert _decelerations(monkeypatch, "all", outside=outside) == [50.0] * 8
    assert _decelerations(monkeypatch, "none", outside=outside) == [50.0] * 8


def test_the_controller_skips_its_twelve_idle_sites_under_one_test_each():
    program = api.load_sources(dict(controller_sources(None))).program
    source = compile_program(program, optimise=Optimisations()).python_sources["SP_CONTROLLER"]
    for k in range(6):      # (each under its group's test too: test_compiler_dormant_groups.py)
        assert f"(v_STOPEXECUTE is not False or v_AXISSTOP[{k}]._at_rest is not _seal):" in source
        assert f"(v_RESETEXECUTE is not False or v_AXISRESET[{k}]._at_rest is not _seal):" in source
    off = compile_program(program, optimise=Optimisations(dormant=False)).python_sources["SP_CONTROLLER"]
    assert "if v_STOPEXECUTE is not False or " not in off


def _executes(monkeypatch, optimise: str, writer: str, raw: dict) -> list:
    """(Stops[1].Execute, its type) after each of 8 scans of one run; `raw`: program variables
    given ints by Python before the run (a BOOL may hold 0 or 1)."""
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", optimise)
    plc, _, _ = make_plc(PROGRAM.replace("{writer}", writer), AXIS, dialect="iec")
    instance = plc.controller.instances["Main"]
    seen = []
    plc.controller.add_observer(lambda _c: seen.append((instance.v_STOPS[0].v_EXECUTE,
                                                        type(instance.v_STOPS[0].v_EXECUTE))), reads_only=True)
    for name, value in raw.items():
        setattr(instance, name, value)
    plc.run(8)
    return seen


def test_an_execute_of_0_is_stored_again_as_false_when_the_program_stores_false(monkeypatch):
    """`DoStop AND NOT ...ErrorStop` with DoStop 0 is 0 (`0 if not 0 else ...`, `0 & True`): the
    site stores 0 and finds the FB at rest; in scan 5 DoStop is FALSE and the site stores False:
    the FB ends scans 1-4 with the int 0 and scans 5-8 with the bool False, as with every call."""
    run = ("IF Poke THEN DoStop := FALSE; END_IF;", {"v_DOSTOP": 0})
    expected = [(0, int)] * 4 + [(False, bool)] * 4
    assert _executes(monkeypatch, "all", *run) == _executes(monkeypatch, "none", *run) == expected


def test_an_execute_of_false_is_stored_again_as_0_when_the_program_stores_0(monkeypatch):
    """The other way: DoStop FALSE (the FB at rest from scan 1), then in scan 5 `Flag AND Nope`
    of Flag 1 and Nope FALSE, `1 & False`, the int 0: the site stores it from scan 5 on."""
    run = ("IF Poke THEN DoStop := Flag AND Nope; END_IF;", {"v_FLAG": 1})
    expected = [(False, bool)] * 4 + [(0, int)] * 4
    assert _executes(monkeypatch, "all", *run) == _executes(monkeypatch, "none", *run) == expected


def test_a_word_spelt_like_the_instance_elsewhere_keeps_its_code():
    """The census counts the instance's spelling in the project's texts: a mention it cannot
    place (here a comment; a member or another POU's name would count the same) keeps the
    site's code, the sure side."""
    assert not _guarded(_source("(* Stops are cheap *)"), "v_DOSTOP", "v_STOPS[0]")
    assert _guarded(_source("(* Resets are not *)"), "v_DOSTOP", "v_STOPS[0]")


@pytest.mark.parametrize("texts, word, expected", [
    # by hand: whole words in any case, a member's and a comment's too; not inside another word
    (["Stops := STOPS; xStops stops_ (* stops *)", "s.Stops[1]"], "Stops", 4),
    (["aaa", "aa aa", "(aa)"], "aa", 3),
    (["Stop2 Stop_ _Stop", ""], "Stop", 0),
    # a text that is not ASCII: `re.IGNORECASE` folds the long s and the Kelvin sign into s and
    # k (the re docs), and `é` is a word character
    (["\u017ftops Stopsé", "\u212aick kick"], "stops", 1),
    (["\u212aick kick"], "KICK", 2),
])
def test_the_census_counts_a_word_as_the_pattern_does(texts, word, expected):
    from st_runtime.compiler.optimise.dormant import _Words
    assert _Words(texts).count(word) == expected
