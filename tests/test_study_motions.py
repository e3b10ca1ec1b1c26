"""docs/mathematics.md section 6.2's two motions: analytic rates against central differences, and the study's claim
that both stay inside every limit (stroke 0..150 mm, universal joint 24.25°, tilt 24.25°)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stgen.config import load_config
from stgen.reference.study_motions import fixed_base_upper, moving_base_base, moving_base_upper, study_reports

MOVING = load_config(Path(__file__).resolve().parent.parent / "examples" / "moving_base_platform.toml")


@pytest.mark.parametrize("trajectory", [moving_base_upper, moving_base_base, fixed_base_upper])
def test_analytic_rates_against_central_differences(trajectory):
    t, h = np.linspace(0.0, 10.0, 101), 1e-4
    value, rate, acceleration = trajectory(t)
    ahead, behind = trajectory(t + h)[0], trajectory(t - h)[0]
    assert np.abs(rate - (ahead - behind) / (2 * h)).max() < 1e-6
    assert np.abs(acceleration - (ahead - 2 * value + behind) / h**2).max() < 1e-3


def test_study_start_values_in_this_projects_frame():
    # pU(0) = (4.5, 0, 415.706) in the study: z from h0 is 0 here; pB(0) = (0, 0, -3).
    assert moving_base_upper(np.array([0.0]))[0][0] == pytest.approx([4.5, 0, 0, 0, 0, 0])
    assert moving_base_base(np.array([0.0]))[0][0] == pytest.approx([0, 0, -3.0, 0, 0, 0])


def test_both_motions_keep_every_limit_as_the_study_claims():
    reports = study_reports(MOVING)
    assert len(reports) == 3
    for report in reports:
        assert report.feasible, (report.name, report.first_violation)
        assert report.samples == 10001
        assert 0.0 <= report.extension_range[0] and report.extension_range[1] <= 150.0
        assert report.max_tilt <= 24.25 and max(report.max_universal_gamma, report.max_universal_psi) <= 24.25
