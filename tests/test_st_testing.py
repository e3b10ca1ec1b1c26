"""`stgen test`: TEST blocks in ST (STruC++'s form), run in the simulated controller.

The ST lives in tests/st_testing/; expected values are worked by hand in
the comments of those files (IEC 61131-3 TON, integer arithmetic).
"""

from __future__ import annotations

import os

import pytest

from st_runtime.parser import parse, parse_tests
from st_runtime.testing import run_tests
from stgen.cli import main

HERE = os.path.join(os.path.dirname(__file__), "st_testing")
LIB = os.path.join(HERE, "lib.st")
PASSING = os.path.join(HERE, "test_pass.st")
FAILING = os.path.join(HERE, "test_fail.st")


def _by_name(run):
    return {r.name: r for r in run.results}


def test_every_passing_test_passes():
    run = run_tests([LIB, PASSING])
    assert run.loaded, run.render_diagnostics()
    assert [r.status for r in run.results] == ["passed"] * 5
    assert run.ok


def test_failures_name_the_assert_and_both_values():
    run = run_tests([LIB, FAILING])
    results = _by_name(run)
    equal = results["equal fails with both values"]
    assert equal.status == "failed"
    assert equal.detail.startswith(f"{FAILING}:7:5: ASSERT_EQ(C.Count, 3")
    assert "left = 1, right = 3" in equal.detail and "(one call counts one)" in equal.detail
    # the first failed assert ends the test: ASSERT_TRUE(FALSE) on line 8 never runs
    assert ":8:" not in equal.detail
    near = results["near fails"]
    assert near.status == "failed" and f"{FAILING}:16:5" in near.detail
    assert "tolerance 1e-12" in near.detail
    loop = results["asserts inside loops stop the test"]
    assert loop.status == "failed" and "left = 4, right = 4" in loop.detail
    assert not run.ok


def test_a_runtime_fault_is_an_error_with_its_place():
    result = _by_name(run_tests([LIB, FAILING]))["a runtime fault is an error"]
    assert result.status == "error"
    assert f"{LIB}:45:" in result.detail and "F-DIV-ZERO" in result.detail


def test_pattern_selects_tests():
    run = run_tests([LIB, PASSING], pattern="FRESH")
    assert [r.name for r in run.results] == ["each test starts from a fresh instance",
                                             "globals are fresh in every test"]
    run = run_tests([LIB, PASSING], pattern="counter*")
    assert [r.name for r in run.results] == ["counter counts calls"]


def test_cli_exit_codes_and_report(tmp_path, capsys):
    assert main(["test", LIB, PASSING]) == 0
    out = capsys.readouterr().out
    assert "PASS: counter counts calls" in out and "Results: 5 passed, 0 failed" in out
    assert main(["test", LIB, FAILING]) == 1
    out = capsys.readouterr().out
    assert "FAIL: equal fails with both values" in out and "ERROR: a runtime fault" in out
    assert main(["test", LIB, PASSING, "-k", "no such test"]) == 1
    assert main(["test", str(tmp_path / "missing.st")]) == 2


def test_test_keywords_stay_identifiers_outside_test_files():
    text = "PROGRAM P VAR Test, Setup, End_Test, Teardown : INT; END_VAR Test := Setup; END_PROGRAM"
    parsed, diagnostics = parse(text, "p.st")
    assert diagnostics == [] and parsed is not None
    _, diagnostics = parse_tests("TEST 'x' VAR Test : INT; END_VAR END_TEST", "t.st")
    assert diagnostics and diagnostics[0].pos.line == 1


@pytest.mark.parametrize("body, message", [
    ("ASSERT_EQ(1);", "ASSERT_EQ takes 2 operand(s)"),
    ("ASSERT_TRUE(TRUE, 5);", "must be a string literal"),
    ("ASSERT_EQ(IN1 := 1, IN2 := 1);", "by position"),
    ("ADVANCE_TIME();", "ADVANCE_TIME takes one operand"),
])
def test_misused_asserts_are_diagnostics(tmp_path, body, message):
    path = tmp_path / "test_bad.st"
    path.write_text(f"TEST 'bad'\n    {body}\nEND_TEST\n")
    run = run_tests([str(path)])
    assert not run.loaded
    [diagnostic] = [d for d in run.diagnostics if d.is_error]
    assert diagnostic.code == "E-TEST-001" and message in diagnostic.message
    assert (diagnostic.pos.file, diagnostic.pos.line) == (str(path), 2)


def test_type_errors_in_tests_point_into_the_test_file(tmp_path):
    path = tmp_path / "test_types.st"
    path.write_text("TEST 'types'\nVAR b : BOOL; END_VAR\n    ASSERT_EQ(b, T#1s);\nEND_TEST\n")
    run = run_tests([str(path)])
    assert not run.loaded
    assert any(d.pos.file == str(path) and d.pos.line == 3 for d in run.diagnostics if d.is_error)


def test_setup_and_teardown_run_around_each_test(tmp_path):
    path = tmp_path / "test_phases.st"
    # TEARDOWN runs after the test, also after a failed assert: its own
    # failing assert would replace nothing, so it records in a global instead.
    path.write_text(
        "VAR_GLOBAL Log : INT; END_VAR\n"
        "SETUP\nVAR n : INT; END_VAR\n    n := 10; Log := Log + 1;\nEND_SETUP\n"
        "TEARDOWN\n    ASSERT_EQ(Log, 100);\nEND_TEARDOWN\n"
        "TEST 'setup ran once'\n    ASSERT_EQ(n, 10);\n    ASSERT_EQ(Log, 1);\n    Log := 100;\nEND_TEST\n"
        "TEST 'teardown sees the test state'\n    Log := 7;\nEND_TEST\n")
    results = _by_name(run_tests([str(path)]))
    assert results["setup ran once"].status == "passed"
    failed = results["teardown sees the test state"]
    assert failed.status == "failed" and "left = 7, right = 100" in failed.detail


def test_files_without_a_test_are_refused():
    run = run_tests([LIB])
    assert not run.loaded
    assert [d.code for d in run.diagnostics if d.is_error] == ["E-TEST-002"]


def test_a_loop_that_never_ends_is_an_error(tmp_path):
    path = tmp_path / "test_forever.st"
    path.write_text("TEST 'forever'\nVAR I : DINT; END_VAR\n    WHILE TRUE DO\n        I := I + 1;\n"
                    "    END_WHILE;\nEND_TEST\n")
    [result] = run_tests([str(path)], time_limit_ps=10**10).results     # 10 ms of NJ501 time
    assert result.status == "error" and "estimated NJ501 time" in result.detail
