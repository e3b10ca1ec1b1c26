"""`ABS(x) <= B` and `ABS(x) < B` as chained comparisons, `ABS(x) > B` and `ABS(x) >= B` as
`x > B or x < -B` and `x >= B or x <= -B` (optimise/absolute.py, `inline` switch).

Expected values: the IEC meaning of ABS and IEEE-754 comparison, which Python's `abs(x) <= b`
on floats states (a NaN compares false, -0.0 equals 0.0); the compiled program must agree for
every pair of special values, with the pass on and off, and the pass must fire.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import replace

import pytest

from st_runtime.api import Plc, load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

PROGRAM = """
PROGRAM Main
VAR x, b : LREAL; i : DINT; le, lt, le_lit, lt_zero, ge, int_le, finite : BOOL; END_VAR
VAR gt_diff, ge_lit, gt_local, gt_neg, int_gt : BOOL; END_VAR
VAR_TEMP local : LREAL; END_VAR
local := b;
le := ABS(x) <= local;
lt := local > ABS(x);
le_lit := ABS(x) <= 2.5;
lt_zero := ABS(x) < 0.0;
ge := ABS(x) >= local;
int_le := ABS(i) <= 3;
finite := ABS(local) <= 1.7976931348623157E308;      (* the largest LREAL: finiteness *)
gt_diff := ABS(x - local) > 0.25;
ge_lit := 2.5 <= ABS(x);
gt_local := ABS(x) > local;
gt_neg := ABS(x) > -1.0;                              (* every number but NaN *)
int_gt := ABS(i) > 3;                                 (* a slot, not a name: set into a temp *)
END_PROGRAM
"""

VALUES = [math.nan, math.inf, -math.inf, 0.0, -0.0, 2.5, -2.5, -3.0, 1e308, -5e-324, -1.7976931348623157e308]
ON = Optimisations()
OFF = replace(ON, inline=False)


@pytest.fixture(scope="module")
def builds():
    program = load_text(PROGRAM).program
    return {name: compile_program(program, optimise=o) for name, o in (("on", ON), ("off", OFF))}


def test_the_calls_go_where_the_bound_allows(builds):
    on, off = builds["on"].python_sources["MAIN"], builds["off"].python_sources["MAIN"]
    assert off.count("abs(") == 12
    # a bound read from the instance (`self.v_B`) would keep its call; every one here goes
    assert on.count("abs(") == 0 and "(-v_LOCAL <= v_X <= v_LOCAL)" in on and "v_X < v_LOCAL)" in on
    assert "(v_X >= v_LOCAL or v_X <= -v_LOCAL)" in on and "(v_X >= 2.5 or v_X <= -2.5)" in on
    assert "(v_X > -1.0 or v_X < 1.0)" in on and re.search(r"\(\(_t\d+ := self\.v_I\) > 3 or _t\d+ < -3\)", on)
    assert re.search(r"\((\w+) > 0\.25 or \1 < -0\.25\)", on)      # X - Local: `reuse` names it
    assert "(-2.5 <= v_X <= 2.5)" in on and "(-0.0 < v_X < 0.0)" in on and "(-3 <= self.v_I <= 3)" in on
    assert "(v_LOCAL < 1e309 and v_LOCAL > -1e309)" in on          # a local against the largest double


@pytest.mark.parametrize("build", ["on", "off"])
def test_every_pair_of_special_values(builds, build):
    plc = Plc(Controller(builds[build], 1_000_000))
    main = plc.add_program("Main")
    for x, b in itertools.product(VALUES, VALUES):
        main["x"], main["b"] = x, b
        plc.run(1)
        expected = (abs(x) <= b, abs(x) < b, abs(x) <= 2.5, abs(x) < 0.0, abs(x) >= b, math.isfinite(b))
        assert (main["le"], main["lt"], main["le_lit"], main["lt_zero"], main["ge"], main["finite"]) == expected, (x, b)
        outside = (abs(x - b) > 0.25, abs(x) >= 2.5, abs(x) > b, not math.isnan(x))
        assert (main["gt_diff"], main["ge_lit"], main["gt_local"], main["gt_neg"]) == outside, (x, b)
    for i in (-2147483648, -4, -3, 0, 3, 4, 2147483647):
        main["i"] = i
        plc.run(1)
        assert main["int_le"] == (abs(i) <= 3) and main["int_gt"] == (abs(i) > 3)
