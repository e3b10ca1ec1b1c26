"""`stgen generate --tests`: test benches with vectors from the NumPy reference.

They pass under `stgen test` and `stgen check --dialect nj`; a template broken
on purpose (a wrong l0, a lost sign in the LU determinant) makes the benches
of the POUs it breaks fail, and only those.
"""

from __future__ import annotations

import dataclasses

import pytest

from stgen.cli import main
from stgen.config import PlatformConfig
from stgen.exports import iec, sysmac
from stgen.render import BENCH_TEST_FILE, RenderOptions, render_program
from st_runtime.testing import run_tests

BENCHES = ("TB_InverseKinematics", "TB_ForwardKinematics", "TB_Determinant", "TB_LuSolve")


@pytest.fixture(scope="module")
def program():
    return render_program(options=RenderOptions(tests=True))


def _with(program, pou):
    """The program with `pou` in place of the POU of the same name."""
    return dataclasses.replace(program, pous=tuple(pou if p.name == pou.name else p
                                                   for p in program.pous))


def _wrong_l0_constants():
    """SP_Constants rendered with l0 half a millimetre too long."""
    config = PlatformConfig.default()
    geometry = dataclasses.replace(config.geometry, l0=config.geometry.l0 + 0.5)
    return render_program(dataclasses.replace(config, geometry=geometry)).pou("SP_Constants")


def _statuses(program, folder) -> dict[str, str]:
    iec.write(program, folder)
    run = run_tests([str(folder)])
    assert run.loaded, run.render_diagnostics()
    return {r.name.split()[0]: r.status for r in run.results}


def test_generated_benches_pass_and_are_nj_clean(tmp_path, capsys):
    out = tmp_path / "iec"
    assert main(["generate", "--target", "iec", "--tests", "--out", str(out)]) == 0
    assert (out / BENCH_TEST_FILE).is_file()
    assert main(["check", "--dialect", "nj", str(out)]) == 0
    assert "0 error(s), 0 warning(s)" in capsys.readouterr().err
    assert main(["test", str(out), "--junit", str(tmp_path / "benches.xml")]) == 0
    report = capsys.readouterr().out
    for bench in BENCHES:
        assert f"PASS: {bench} matches the NumPy reference" in report


def test_a_wrong_l0_fails_the_kinematics_benches_only(program, tmp_path):
    statuses = _statuses(_with(program, _wrong_l0_constants()), tmp_path)
    assert statuses == {"TB_InverseKinematics": "failed", "TB_ForwardKinematics": "failed",
                        "TB_Determinant": "passed", "TB_LuSolve": "passed"}


def test_a_lost_sign_fails_the_lu_bench_only(program, tmp_path):
    lu = program.pou("SP_LuSolve")
    assert "Determinant := -Determinant;" in lu.body
    broken_lu = dataclasses.replace(lu, body=lu.body.replace("Determinant := -Determinant;",
                                                             "Determinant := Determinant;"))
    statuses = _statuses(_with(program, broken_lu), tmp_path)
    assert statuses == {"TB_InverseKinematics": "passed", "TB_ForwardKinematics": "passed",
                        "TB_Determinant": "passed", "TB_LuSolve": "failed"}


def test_a_failed_bench_reports_its_failures(program, tmp_path):
    iec.write(_with(program, _wrong_l0_constants()), tmp_path)
    run = run_tests([str(tmp_path)], pattern="TB_InverseKinematics")
    [result] = run.results
    # the first assert after the scans that fails: some case differs by the 0.5 mm of l0
    assert "ASSERT_EQ(TbIkFailures, 0" in result.detail and "right = 0" in result.detail


def test_vectors_cover_the_error_paths(program):
    ik = program.pou("TB_InverseKinematics")
    ids = next(v for v in ik.variables if v.name == "EXPECTED_ERROR_ID").initial
    assert "16#0000" in ids and "16#1004" in ids          # inside and outside the stroke
    lu = program.pou("TB_LuSolve")
    solved = next(v for v in lu.variables if v.name == "EXPECTED_SOLVED").initial
    assert "TRUE" in solved and "FALSE" in solved         # singular systems too


def test_nj_export_says_how_to_run_the_benches(program):
    readme = sysmac.files(program)["README.md"]
    assert "## Test benches" in readme and "TbIkPass" not in readme.split("## Test benches")[0]
    plain = sysmac.files(render_program())
    assert "## Test benches" not in plain["README.md"]
    assert not any(name.startswith("TB_") for name in plain)
    assert BENCH_TEST_FILE not in iec.files(render_program())


@pytest.mark.parametrize("bench, done", [("TB_InverseKinematics", "TbIkDone"),
                                         ("TB_ForwardKinematics", "TbFkDone"),
                                         ("TB_Determinant", "TbDetDone"), ("TB_LuSolve", "TbLuDone")])
def test_every_scan_of_a_bench_fits_the_task_period(program, tmp_path_factory, bench, done):
    """By the NJ501 execution-time estimate (st_runtime/compiler/cost.py), each
    scan of a bench stays under OMRON's 80 % load guideline of a 1 ms task."""
    from st_runtime import load

    folder = tmp_path_factory.mktemp("benches")
    iec.write(program, folder)
    project = load([p for p in folder.glob("*.st") if p.name != BENCH_TEST_FILE])
    plc = project.controller(period="1ms")
    plc.add_program(bench)
    for _ in range(200):
        plc.controller.scan()
        if plc.globals[done]:
            break
    assert plc.globals[done] and not plc.controller.faults
    [timing] = plc.controller.time_report()
    assert timing.max_ns < 0.8 * 1_000_000, timing
