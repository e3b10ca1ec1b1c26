"""The scenario figure names each excursion of the point-to-point run (stgen.figures)."""

from __future__ import annotations

import numpy as np
import pytest

from stgen.figures import excursions
from stgen.scenarios.definitions import AIRY_WAVE, POINT_TO_POINT, SYNCHRONISED_MOVE
from stgen.scenarios.runner import ScenarioResult


def _result(scenario, command_scans, scans):
    """A run's timeline without its data: what excursions() reads."""
    empty = np.zeros((scans, 6))
    flags = np.zeros(scans, dtype=np.int64)
    return ScenarioResult(scenario, 0.001, tuple(command_scans), empty, empty, empty, empty,
                          flags, flags, flags, flags.astype(bool), empty)


def test_each_out_and_back_pair_is_one_named_span():
    # Edges 5 ms apart from the timeline of the real run: moves of 10,001 scans (10 s + the edge)
    # and 500 scans of standstill; the 6 s moves take 6,001. Edge of move k+1 = edge k + calls + 1 + 500.
    steps = [10_501] * 6 + [6_501] * 4 + [10_501] * 2
    edges = [5]
    for step in steps[:-1]:
        edges.append(edges[-1] + step)
    scans = edges[-1] + steps[-1] - 1
    spans = excursions(_result(POINT_TO_POINT, edges, scans))
    assert [label for _, _, label in spans] == ["x +100 mm", "y +100 mm", "z +100 mm", "α +6°", "β +6°", "γ +10°"]
    # x out and back: from the first edge scan (it begins at 4 ms) to the start of the third move's edge scan.
    assert spans[0][:2] == pytest.approx((0.004, (5 + 2 * 10_501 - 1) * 0.001))
    assert spans[-1][1] == pytest.approx(scans * 0.001)  # the last span runs to the end of the run
    for (_, end, _), (begin, _, _) in zip(spans, spans[1:]):
        assert end == begin  # the spans tile the run


def test_a_single_move_or_a_wave_has_no_spans():
    assert excursions(_result(SYNCHRONISED_MOVE, [5], 10_510)) == []
    assert excursions(_result(AIRY_WAVE, [5], 1_000)) == []
