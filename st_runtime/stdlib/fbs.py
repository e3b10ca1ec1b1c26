"""Standard function blocks of IEC 61131-3 as native FBs.

Timers (TON, TOF, TP) read the simulated clock `ctx.now_ns` only, never the
wall clock: the elapsed time ET of a call is `now - start`, where `start` is
the clock value of the call that started the timing.  With a 1 ms task a
TON with PT = T#5ms started at the call of time t sees ET = 0, 1, 2, 3, 4,
5 ms on its first six calls, so Q turns TRUE on the sixth call, exactly PT
after the call that saw IN rise.

Edge detectors, counters and bistables follow the bodies given in IEC
61131-3 (3rd ed., tables 43-46); counters count on the rising edge of CU/CD
and saturate at the limits of INT (PVmax = 32767, PVmin = -32768).
F_TRIG's memory M has no initial value in the standard (it starts FALSE), so
a CLK that is FALSE on the first call gives Q = TRUE once: see F_TRIG.
"""

from __future__ import annotations

from ..native import NativeFB, fb_declaration, native_fb

INT_MAX = 32767
INT_MIN = -32768


def _time_up(timer, now: int) -> bool:
    """Set a timer's ET to the time since its StartTime, capped at PT;
    TRUE once PT has elapsed (the one rule TON, TOF and TP share)."""
    elapsed = now - timer.v_STARTTIME
    if elapsed >= timer.v_PT:
        timer.v_ET = timer.v_PT
        return True
    timer.v_ET = elapsed
    return False


TIMER_INPUTS = "IN : BOOL; PT : TIME;"
TIMER_OUTPUTS = "Q : BOOL; ET : TIME;"


@native_fb
class TON(NativeFB):
    """On-delay: Q rises once IN has been TRUE for PT; IN FALSE resets."""

    NAME = "TON"
    DECLARATION = fb_declaration("TON", inputs=TIMER_INPUTS, outputs=TIMER_OUTPUTS,
                                 memory="StartTime : TIME; Running : BOOL;")

    def execute(self, ctx) -> None:
        if not self.v_IN:
            self.v_RUNNING = False
            self.v_Q = False
            self.v_ET = 0
            return
        now = ctx.now_ns
        if not self.v_RUNNING:
            self.v_RUNNING = True
            self.v_STARTTIME = now
        self.v_Q = _time_up(self, now)


@native_fb
class TOF(NativeFB):
    """Off-delay: Q follows IN up, and falls PT after IN fell."""

    NAME = "TOF"
    DECLARATION = fb_declaration("TOF", inputs=TIMER_INPUTS, outputs=TIMER_OUTPUTS,
                                 memory="StartTime : TIME; Running : BOOL; PrevIN : BOOL;")

    def execute(self, ctx) -> None:
        now = ctx.now_ns
        if self.v_IN:
            self.v_Q = True
            self.v_ET = 0
            self.v_RUNNING = False
        else:
            if self.v_PREVIN:               # falling edge of IN: start timing
                self.v_RUNNING = True
                self.v_STARTTIME = now
            if self.v_RUNNING and _time_up(self, now):
                self.v_Q = False
                self.v_RUNNING = False
        self.v_PREVIN = self.v_IN


@native_fb
class TP(NativeFB):
    """Pulse: a rising edge of IN gives Q for exactly PT; not retriggerable.

    After the pulse ET holds PT while IN stays TRUE and returns to 0 once IN
    is FALSE.
    """

    NAME = "TP"
    DECLARATION = fb_declaration("TP", inputs=TIMER_INPUTS, outputs=TIMER_OUTPUTS,
                                 memory="StartTime : TIME; PrevIN : BOOL;")

    def execute(self, ctx) -> None:
        now = ctx.now_ns
        inp = self.v_IN
        if not self.v_Q:
            if inp and not self.v_PREVIN:      # rising edge starts a pulse
                self.v_Q = True
                self.v_STARTTIME = now
            elif not inp:
                self.v_ET = 0
        if self.v_Q and _time_up(self, now):
            self.v_Q = False
        self.v_PREVIN = inp


@native_fb
class R_TRIG(NativeFB):
    NAME = "R_TRIG"
    DECLARATION = fb_declaration(
        "R_TRIG",
        inputs="CLK : BOOL;",
        outputs="Q : BOOL;",
        memory="M : BOOL;")

    def execute(self, ctx) -> None:
        clk = self.v_CLK
        self.v_Q = clk and not self.v_M
        self.v_M = clk


@native_fb
class F_TRIG(NativeFB):
    """Falling edge: the standard's body, `Q := NOT CLK AND NOT M; M := NOT CLK;`
    with `VAR M : BOOL; END_VAR` (no initial value, so M starts FALSE).

    Consequence: a CLK that is FALSE on the very first call pulses Q once.
    Sources: IEC 61131-3 2nd ed. table 35 / 3rd ed. table 44 (edge
    detection), whose ST text MATIEC's library reproduces verbatim
    ("taken directly from the IEC 61131.3 draft standard", lib
    edge_detection.txt); CODESYS Safety documentation of SF_F_TRIG: "In the
    first cycle, SF_F_TRIG recognizes a falling edge when FALSE is applied
    and sets the output Q to TRUE. This behavior conforms to the F_TRIG of
    IEC 61131-3 from Edition 2" (content.helpme-codesys.com, CODESYS Safety
    Extension, SF_F_TRIG), which adds that CODESYS's standard F_TRIG keeps
    edition 1's behaviour (no first pulse).  Fernhill Software declares
    `M : BOOL := TRUE` and notes that this follows the recommendation of
    IEC 61131-8 (guidelines), i.e. not part 3's text
    (fernhillsoftware.com/help/iec-61131/common-elements/standard-function-blocks/edge.html).
    """

    NAME = "F_TRIG"
    DECLARATION = fb_declaration(
        "F_TRIG",
        inputs="CLK : BOOL;",
        outputs="Q : BOOL;",
        memory="M : BOOL;")

    def execute(self, ctx) -> None:
        low = not self.v_CLK
        self.v_Q = low and not self.v_M
        self.v_M = low


@native_fb
class CTU(NativeFB):
    NAME = "CTU"
    DECLARATION = fb_declaration(
        "CTU",
        inputs="CU : BOOL; R : BOOL; PV : INT;",
        outputs="Q : BOOL; CV : INT;",
        memory="CUMemory : BOOL;")

    def execute(self, ctx) -> None:
        edge = self.v_CU and not self.v_CUMEMORY
        self.v_CUMEMORY = self.v_CU
        if self.v_R:
            self.v_CV = 0
        elif edge and self.v_CV < INT_MAX:
            self.v_CV += 1
        self.v_Q = self.v_CV >= self.v_PV


@native_fb
class CTD(NativeFB):
    NAME = "CTD"
    DECLARATION = fb_declaration(
        "CTD",
        inputs="CD : BOOL; LD : BOOL; PV : INT;",
        outputs="Q : BOOL; CV : INT;",
        memory="CDMemory : BOOL;")

    def execute(self, ctx) -> None:
        edge = self.v_CD and not self.v_CDMEMORY
        self.v_CDMEMORY = self.v_CD
        if self.v_LD:
            self.v_CV = self.v_PV
        elif edge and self.v_CV > INT_MIN:
            self.v_CV -= 1
        self.v_Q = self.v_CV <= 0


@native_fb
class CTUD(NativeFB):
    NAME = "CTUD"
    DECLARATION = fb_declaration(
        "CTUD",
        inputs="CU : BOOL; CD : BOOL; R : BOOL; LD : BOOL; PV : INT;",
        outputs="QU : BOOL; QD : BOOL; CV : INT;",
        memory="CUMemory : BOOL; CDMemory : BOOL;")

    def execute(self, ctx) -> None:
        up = self.v_CU and not self.v_CUMEMORY
        down = self.v_CD and not self.v_CDMEMORY
        self.v_CUMEMORY = self.v_CU
        self.v_CDMEMORY = self.v_CD
        if self.v_R:
            self.v_CV = 0
        elif self.v_LD:
            self.v_CV = self.v_PV
        elif not (up and down):
            if up and self.v_CV < INT_MAX:
                self.v_CV += 1
            elif down and self.v_CV > INT_MIN:
                self.v_CV -= 1
        self.v_QU = self.v_CV >= self.v_PV
        self.v_QD = self.v_CV <= 0


@native_fb
class SR(NativeFB):
    """Set-dominant bistable: Q1 := S1 OR (NOT R AND Q1)."""

    NAME = "SR"
    DECLARATION = fb_declaration(
        "SR",
        inputs="S1 : BOOL; R : BOOL;",
        outputs="Q1 : BOOL;")

    def execute(self, ctx) -> None:
        self.v_Q1 = bool(self.v_S1 or (not self.v_R and self.v_Q1))


@native_fb
class RS(NativeFB):
    """Reset-dominant bistable: Q1 := NOT R1 AND (S OR Q1)."""

    NAME = "RS"
    DECLARATION = fb_declaration(
        "RS",
        inputs="S : BOOL; R1 : BOOL;",
        outputs="Q1 : BOOL;")

    def execute(self, ctx) -> None:
        self.v_Q1 = bool(not self.v_R1 and (self.v_S or self.v_Q1))


STANDARD_FBS = (TON, TOF, TP, R_TRIG, F_TRIG, CTU, CTD, CTUD, SR, RS)
