"""MIN and MAX of two integers or two reals as a conditional expression, `(b if a > b else a)`
(MAX with `<`), under the `inline` switch (compiler/calls.py `_selected_pair`), in place of a
call of Python's min or max.

Expected values: IEC 61131-3's MIN and MAX (the least and the greatest input), and where the
standard says nothing (a NaN, -0.0 against 0.0) the library's own definition
(stdlib/functions.py: Python's min/max of the inputs, which keeps the first input unless the
second compares less, resp. greater, and IEEE-754 comparisons with a NaN are false):
MIN(NaN, 1.0) is NaN, MIN(1.0, NaN) is 1.0, MIN(0.0, -0.0) is 0.0 and MIN(-0.0, 0.0) is -0.0.
Each input is evaluated once, the first before the second (IEC 61131-3: inputs in order).
"""

from __future__ import annotations

import itertools
import math
import struct
from dataclasses import replace

import pytest

from st_runtime.api import Plc, load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

PROGRAM = """
VAR_GLOBAL Trail : DINT; END_VAR
FUNCTION Tag : DINT
VAR_INPUT v, d : DINT; END_VAR
Trail := Trail * 10 + d;
Tag := v;
END_FUNCTION
PROGRAM Main
VAR x, y, mn, mx : LREAL; i, j, imn, imx, tmn, tmx, trail_min, trail_max : DINT; END_VAR
mn := MIN(x, y);
mx := MAX(x, y);
imn := MIN(i + 1, j);
imx := MAX(i, j - 1);
Trail := 0;
tmn := MIN(Tag(i, 1), Tag(j, 2));
trail_min := Trail;
Trail := 0;
tmx := MAX(Tag(i, 3), j + Tag(0, 4));
trail_max := Trail;
END_PROGRAM
"""

VALUES = [math.nan, math.inf, -math.inf, 0.0, -0.0, 1.0, -2.5, 1e308, -5e-324]
ON = Optimisations()
OFF = replace(ON, inline=False)


def bits(value: float) -> bytes:
    return struct.pack("<d", value)


@pytest.fixture(scope="module")
def builds():
    program = load_text(PROGRAM, dialect="codesys").program
    return {name: compile_program(program, optimise=o) for name, o in (("on", ON), ("off", OFF))}


def test_the_pairs_are_conditional_expressions(builds):
    on, off = builds["on"].python_sources["MAIN"], builds["off"].python_sources["MAIN"]
    assert "min(" not in on and "max(" not in on
    assert "(_t2 if (_t1 := self.v_X) > (_t2 := self.v_Y) else _t1)" in on      # MIN(x, y)
    assert "(_t2 if (_t1 := self.v_X) < (_t2 := self.v_Y) else _t1)" in on      # MAX(x, y)
    assert "(v_J if (_t1 := (v_I + 1)) > v_J else _t1)" in on                  # a local read as it is
    assert "(_t1 if v_I < (_t1 := (v_J - 1)) else v_I)" in on
    assert off.count("_sf_MIN(") == off.count("_sf_MAX(") == 3                # the library's


def test_ordinary_values_by_hand(builds):
    plc = Plc(Controller(builds["on"], 1_000_000))
    main = plc.add_program("Main")
    main["x"], main["y"], main["i"], main["j"] = 2.5, -4.0, 6, 3
    plc.run(1)
    assert (main["mn"], main["mx"], main["imn"], main["imx"]) == (-4.0, 2.5, 3, 6)
    assert (main["tmn"], main["trail_min"]) == (3, 12)      # Tag(6, 1), then Tag(3, 2): each once
    assert (main["tmx"], main["trail_max"]) == (6, 34)


@pytest.mark.parametrize("build", ["on", "off"])
def test_every_pair_of_special_values(builds, build):
    plc = Plc(Controller(builds[build], 1_000_000))
    main = plc.add_program("Main")
    for x, y in itertools.product(VALUES, VALUES):
        main["x"], main["y"] = x, y
        plc.run(1)
        least = x if not y < x else y             # the first kept unless the second is less
        greatest = x if not y > x else y
        assert (bits(main["mn"]), bits(main["mx"])) == (bits(least), bits(greatest)), (x, y)
    for i, j in itertools.product((-2147483647, -1, 0, 5, 2147483646), repeat=2):
        main["i"], main["j"] = i, j
        plc.run(1)
        assert (main["imn"], main["imx"]) == (min(i + 1, j), max(i, j - 1)), (i, j)
        assert (main["tmn"], main["tmx"], main["trail_min"], main["trail_max"]) == (min(i, j), max(i, j), 12, 34)
