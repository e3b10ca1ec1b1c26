"""The `seal` pass (st_runtime/compiler/optimise/seal.py): a body whose idle Execute FBs' call
sites test and note the controller's seal reads `_ctx.seal` once, into `_seal`, at its start.
The seal is replaced only between the programs' runs, so every test and note sees the same
object: each FB and the axis end every scan as they do with every call made, with the pass on
and off, through Execute edges inside runs and outputs written from outside between them.
"""

from __future__ import annotations

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.motion import fbs
from stgen.scenarios.program import controller_sources

from test_motion_rest import _run_in_runs
from test_motion_idle_calls import counted_calls


def test_the_controller_reads_the_seal_once_a_scan():
    program = api.load_sources(dict(controller_sources(None))).program
    source = compile_program(program, optimise=Optimisations()).python_sources["SP_CONTROLLER"]
    plain = compile_program(program, optimise=Optimisations.only("inline")).python_sources["SP_CONTROLLER"]
    assert source.splitlines()[1] == "    _seal = _ctx.seal" and source.count("_ctx.seal") == 1
    assert plain.count("_ctx.seal") == 24 and "_seal" not in plain.replace("_ctx.seal", "")
    # twelve rest tests, twelve `dormant` tests around the sites (the sole writers of their FBs)
    # and twelve in the line after the group of them (dormant.Groups), whose own test is one
    assert source.count("._at_rest is not _seal") == 36 and source.count("._at_rest = _seal") == 12
    assert source.count("._group_at_rest is not _seal") == 1


def test_fbs_at_rest_end_every_scan_as_with_every_call(monkeypatch):
    calls = counted_calls(monkeypatch, fbs.MC_Home, fbs.MC_MoveAbsolute, fbs.MC_SyncMoveAbsolute,
                          fbs.MC_Stop, fbs.MC_Reset)
    every_call = _run_in_runs(monkeypatch, "none", calls)
    outcomes = []
    for optimise in ("inline,seal", "all"):
        calls.clear()
        outcomes.append(_run_in_runs(monkeypatch, optimise, calls))
        assert len(calls) < len(every_call) * 5 // 2          # the rest tests ran, under `_seal`
    for noted in outcomes:
        assert [s[:4] for s in noted] == [s[:4] for s in every_call]


def test_a_string_that_spells_the_seal_is_left_as_written():
    """ST text is data: a STRING literal '_ctx.seal' is a value, not a read of the seal, so
    the pass neither rewrites it nor counts it (it did both: s held '_seal')."""
    source = """
PROGRAM Main
VAR s : STRING; t : STRING; END_VAR
s := '_ctx.seal';
t := CONCAT(s, '_ctx.seal');
END_PROGRAM
"""
    project = api.load_text(source)
    plc = project.controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["s"] == "_ctx.seal" and main["t"] == "_ctx.seal_ctx.seal"
    assert "_seal = " not in project.compiled.python_sources["MAIN"]
