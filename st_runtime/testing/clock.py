"""ADVANCE_TIME: the simulated clock of a test, moved by hand.

STruC++'s convention (its docs/TESTING.md, "Time Advancement"): calling a
program or FB instance does not move the clock; `ADVANCE_TIME(d)` adds `d`
(a TIME, or an integer count of nanoseconds) to the time every timer and
motion FB reads (`ctx.now_ns`).  The test lowering turns each
`ADVANCE_TIME(d)` into a call of one instance of this native FB.
"""

from __future__ import annotations

from ..faults import STFault
from ..native import NativeFB, fb_declaration, native_fb

CLOCK_FB = "STGEN_TEST_CLOCK"


@native_fb
class TestClock(NativeFB):
    """Adds D (TIME) plus NS (LINT nanoseconds) to the test's clock, then clears both."""

    __test__ = False   # not a pytest class
    NAME = CLOCK_FB
    DECLARATION = fb_declaration(CLOCK_FB, inputs="D : TIME; NS : LINT;")

    def execute(self, ctx) -> None:
        step = self.v_D + self.v_NS
        self.v_D = 0
        self.v_NS = 0
        if step < 0:
            raise STFault("F-TEST-TIME", f"ADVANCE_TIME by a negative duration ({step} ns)")
        ctx.now_ns += step
