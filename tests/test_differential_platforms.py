"""The variants' generated ST (crank platform, moving base) against the NumPy reference.

Seeded samples here (1,000 IK poses with angles, 100 rate cases, 50 FK solves at
Tolerance 1e-9); `stgen verify --config examples/<variant>.toml` runs the full
size (10,000 / 500).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stgen.config import load_config
from stgen.error_codes import ErrorCode, LegLimitError
from stgen.render import RenderError, render_program
from stgen.verify import run_verification
from stgen.verify_variants import VariantRuntime, check_variant_fk, check_variant_ik, check_variant_rates, variant_poses

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CRANK = load_config(EXAMPLES / "crank_platform.toml")
MOVING = load_config(EXAMPLES / "moving_base_platform.toml")


@pytest.fixture(scope="module")
def crank_runtime():
    return VariantRuntime(CRANK)


@pytest.fixture(scope="module")
def moving_runtime():
    return VariantRuntime(MOVING)


@pytest.mark.parametrize("name", ["crank", "moving"])
def test_ik_angles_and_rates_of_1000_poses(name, crank_runtime, moving_runtime):
    runtime = crank_runtime if name == "crank" else moving_runtime
    upper, base = variant_poses(runtime.config, 1000, seed=7)
    checks = check_variant_ik(runtime, upper, base)
    checks.append(check_variant_rates(runtime, upper[:100], base[:100], seed=8))
    for check in checks:
        assert check.passed, (check.what, check.max_error, check.problems)


def test_the_sample_holds_feasible_and_infeasible_poses_of_every_limit():
    upper, base = variant_poses(MOVING, 1000, seed=7)
    from stgen.reference.feasibility import error_ids, feasibility

    ids, _ = error_ids(feasibility(MOVING, upper, base))
    kinds = {i & 0xFFF0 for i in ids}
    assert {0, LegLimitError.STROKE, LegLimitError.SPHERICAL_TILT} <= kinds


@pytest.mark.parametrize("name", ["crank", "moving"])
def test_fk_of_50_poses_at_1e_9(name, crank_runtime, moving_runtime):
    runtime = crank_runtime if name == "crank" else moving_runtime
    upper, base = variant_poses(runtime.config, 50, seed=9, feasible_share=1.0)
    check = check_variant_fk(runtime, upper, base)
    assert check.cases == 50
    assert check.passed, (check.max_error, check.problems)


def test_error_ids_name_limit_and_leg(crank_runtime, moving_runtime):
    # Straight up by 160 mm: every leg beyond the 150 mm stroke; the lowest leg is named.
    run = moving_runtime.inverse_kinematics([[0, 0, 160, 0, 0, 0], [0, 0, 75, 0, 0, 0], [0, 0, np.nan, 0, 0, 0]])
    assert [hex(i) for i in run["ErrorIDs"]] == ["0x1041", "0x0", hex(ErrorCode.NON_FINITE.error_id)]
    assert list(run["ErrorLegs"]) == [1, 0, 0]
    # The crank platform 600 mm up: no rod reaches (16#1051 = no solution, leg 1).
    run = crank_runtime.inverse_kinematics([[0, 0, 600, 0, 0, 0]])
    assert hex(run["ErrorIDs"][0]) == "0x1051"


def test_verify_dispatches_to_the_variant_checks():
    checks = run_verification(MOVING, poses=20, fk_poses=5)
    assert [c.pou for c in checks] == ["SP_InverseKinematics", "SP_InverseKinematics", "reference rates",
                                       "SP_ForwardKinematics"]
    assert all(c.passed for c in checks)


def test_a_kind_not_rendered_is_refused():
    from dataclasses import replace

    both = replace(CRANK, platform=replace(CRANK.platform, base="moving"))
    with pytest.raises(RenderError, match="is not rendered"):
        render_program(both)


def test_default_output_has_no_variant_constants():
    constants = render_program().pou("SP_Constants")
    assert not [v for v in constants.variables if v.name.startswith(("ERR_LEG_", "SP_CRANK", "SP_TILT"))]


@pytest.mark.parametrize("name", ["crank", "moving"])
def test_the_harness_st_files_check_clean_with_the_variant_folder(name, tmp_path, capsys):
    """stgen/harnesses/*.st are ST files (not Python strings): with VERIFY_CASES and the generated
    folder they pass `stgen check --dialect nj` without an error or a warning."""
    from stgen.cli import main
    from stgen.verify_variants import variant_harness_sources

    config = CRANK if name == "crank" else MOVING
    for file, text in variant_harness_sources(config, 10).items():
        (tmp_path / file).write_text(text, encoding="utf-8")
    folder = EXAMPLES.parent / "generated" / ("crank_iec" if name == "crank" else "moving_base_iec")
    assert main(["check", "--dialect", "nj", str(tmp_path), str(folder)]) == 0
    out = capsys.readouterr()
    assert "0 error(s), 0 warning(s)" in out.out + out.err


def test_the_default_harness_st_files_check_clean_with_generated_iec(tmp_path, capsys):
    """The default platform's harnesses (VerifyIk, VerifyLinalg, VerifyFk) are ST files too:
    with VERIFY_CASES and generated/iec they pass `stgen check --dialect nj` clean."""
    from stgen.cli import main
    from stgen.verify import harness_sources

    for file, text in harness_sources(10).items():
        (tmp_path / file).write_text(text, encoding="utf-8")
    assert main(["check", "--dialect", "nj", str(tmp_path), str(EXAMPLES.parent / "generated" / "iec")]) == 0
    out = capsys.readouterr()
    assert "0 error(s), 0 warning(s)" in out.out + out.err
