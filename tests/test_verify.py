"""`stgen verify`: the table, the exit status, bad configurations."""

from __future__ import annotations

import re

from stgen.cli import main
from stgen.commands import verify as verify_command
from stgen.verify import Check


def test_verify_passes_on_the_default_platform_with_a_small_sample(capsys):
    assert main(["verify", "--poses", "200", "--fk-poses", "20", "--seed", "3"]) == 0
    out = capsys.readouterr().out
    for pou in ("SP_InverseKinematics", "SP_LeibnizDeterminant", "SP_LuSolve", "SP_ForwardKinematics"):
        assert pou in out
    assert "FAIL" not in out and "all checks passed" in out
    assert "unrolled" in out and "error paths" in out and "1/scan" in out


def test_verify_runs_the_example_configuration(capsys):
    assert main(["verify", "--config", "examples/default_platform.toml", "--poses", "50", "--fk-poses", "5"]) == 0


def test_a_failed_check_is_shown_and_exits_1(monkeypatch, capsys):
    failing = [Check("SP_InverseKinematics", "q", 3, 2e-9, 1e-9, "mm"),
               Check("SP_ForwardKinematics", "error paths", 4, None, 0.0, "", problems=("NaN: ErrorID 0",))]
    monkeypatch.setattr(verify_command, "run_verification", lambda *args, **kwargs: failing)
    assert main(["verify"]) == 1
    out = capsys.readouterr().out
    assert len(re.findall(r"\bFAIL\b", out)) == 2 and "NaN: ErrorID 0" in out and "2 of 2 checks FAILED" in out


def test_bad_config_and_bad_arguments(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[stroke]\nmin = 10.0\nmax = 5.0\n")
    assert main(["verify", "--config", str(bad)]) == 1
    assert "stroke.min" in capsys.readouterr().err
    try:
        main(["verify", "--poses", "0"])
    except SystemExit as exit_info:
        assert exit_info.code == 2
    else:
        raise AssertionError("--poses 0 must be a usage error")


def test_workspace_box_spans_the_reachable_heights_of_the_level_platform():
    import numpy as np

    from stgen.config import PlatformConfig
    from stgen.reference import inverse_kinematics
    from stgen.verify import BOX_LINEAR_FRACTION, workspace_box

    config = PlatformConfig.default()
    centre, half = workspace_box(config)
    span = half[2] / BOX_LINEAR_FRACTION[2]
    low, high = centre[2] - span / 2, centre[2] + span / 2
    heights = np.array([low - 1.0, low, centre[2], high, high + 1.0])
    poses = np.zeros((5, 6))
    poses[:, 2] = heights
    reachable = inverse_kinematics(config.geometry, poses, config.stroke).reachable
    assert list(reachable) == [False, True, True, True, False]
    assert low < 0.0 < high  # the home pose lies inside


def _inject(monkeypatch, file_name: str, correct: str, bugged: str) -> None:
    """Make every rendering that verify loads carry a bug in one POU."""
    import stgen.verify as verify_module

    original = verify_module.kinematics_sources

    def tampered(*args, **kwargs):
        sources = original(*args, **kwargs)
        assert correct in sources[file_name]
        sources[file_name] = sources[file_name].replace(correct, bugged)
        return sources

    monkeypatch.setattr(verify_module, "kinematics_sources", tampered)


def _rows(out: str) -> dict[str, list[str]]:
    """Result column of every table row, by POU."""
    rows: dict[str, list[str]] = {}
    for line in out.splitlines():
        words = line.split()
        if words and words[-1] in ("PASS", "FAIL"):
            rows.setdefault(words[0], []).append(words[-1])
    return rows


def test_a_1e6_mm_bug_in_the_rendered_ik_fails_only_the_ik_row(monkeypatch, capsys):
    _inject(monkeypatch, "SP_InverseKinematics.st",
            "- SP_RETRACTED_LENGTH;", "- SP_RETRACTED_LENGTH + 1.0E-6;")
    assert main(["verify", "--poses", "60", "--fk-poses", "6", "--seed", "5"]) == 1
    rows = _rows(capsys.readouterr().out)
    assert rows["SP_InverseKinematics"] == ["FAIL"]
    assert set(rows["SP_ForwardKinematics"]) == {"PASS"} and set(rows["SP_LuSolve"]) == {"PASS"}


def test_a_wrong_jacobian_entry_fails_the_fk_rows(monkeypatch, capsys):
    # Newton still converges with a slightly wrong Jacobian, but in other iteration counts.
    _inject(monkeypatch, "SP_Jacobian.st",
            "Jacobian[Leg, 1] := 2.0 * (XBar + U);", "Jacobian[Leg, 1] := 2.2 * (XBar + U);")
    assert main(["verify", "--poses", "60", "--fk-poses", "6", "--seed", "5"]) == 1
    out = capsys.readouterr().out
    rows = _rows(out)
    assert rows["SP_InverseKinematics"] == ["PASS"]
    assert "FAIL" in rows["SP_ForwardKinematics"]
    assert "iterations, reference" in out and "checks FAILED" in out


def test_verify_estimates_the_fk_time_per_scan_and_the_iterations_that_fit(capsys):
    assert main(["verify", "--poses", "50", "--fk-poses", "5"]) == 0
    out = capsys.readouterr().out
    # 80 % of 1 ms at the study's 49.5 us per iteration: 800 / 49.5 = 16.2 -> 16.
    assert "IterationsPerScan <= 16 keeps a call within 80 % of the period" in out
    assert "49.6 us per Newton-Raphson iteration" in out or "49.5 us per Newton-Raphson iteration" in out


def test_fk_scan_time_follows_the_configured_period():
    import dataclasses

    import numpy as np

    from stgen.config import PlatformConfig
    from stgen.render import RenderOptions
    from stgen.verify import fk_scan_time, load_kinematics, random_poses

    config = PlatformConfig.default()
    slow = dataclasses.replace(config, task=dataclasses.replace(config.task, period_s=0.002))
    runtime = load_kinematics(config, RenderOptions("table"))
    poses = random_poses(config, 3, 7)
    fast = fk_scan_time(runtime.project, config, poses, config.solver.start_pose)
    two_ms = fk_scan_time(runtime.project, slow, poses, config.solver.start_pose)
    assert abs(fast.per_iteration_ns - 49_500) <= 0.01 * 49_500
    assert fast.fitting == 16 and two_ms.fitting == 32        # 1600 / 49.5 = 32.3
    # The worst call with the configured 4 iterations: about 4 x 49.5 us.
    assert fast.calls.max_ns == np.float64(fast.calls.max_ns) and 190_000 < fast.calls.max_ns < 205_000
    assert fast.calls.fits and fast.calls.load_ok
