"""Standard FBs driven directly from Python on a simulated 1 ms clock.

Expected values are worked out by hand from the IEC definitions; each test
states the reasoning.
"""

import re
from types import SimpleNamespace

import pytest

from st_runtime.native import NATIVE_FBS, NativeFB
from st_runtime.stdlib import fbs

MS = 1_000_000


def make(cls):
    """An instance with its declared initial values.

    Uses the real constructor when the checker/compiler are available; until
    then (they are written in parallel) the defaults are read from the
    declaration with a regex: BOOL FALSE unless `:= TRUE`, numbers 0.
    The native layouts are installed first, so that this file passes when
    run on its own (as the mutation tool runs it), before any compilation.
    """
    try:
        from st_runtime.compiler import install_native_layouts
        install_native_layouts()
        return cls()
    except ImportError:
        inst = cls.__new__(cls)
        for name, type_, init in re.findall(r"(\w+)\s*:\s*(\w+)\s*(?::=\s*(\w+))?;", cls.DECLARATION):
            value = (init == "TRUE") if type_ == "BOOL" else 0
            setattr(inst, "v_" + name.upper(), value)
        return inst


class Clock:
    """A 1 ms task: every `step` is one scan at the next millisecond."""

    def __init__(self, period_ns=MS):
        self.ctx = SimpleNamespace(now_ns=0, scan=0, period_ns=period_ns)

    def step(self, fb, **inputs):
        self.ctx.scan += 1
        for name, value in inputs.items():
            setattr(fb, "v_" + name.upper(), value)
        fb.execute(self.ctx)
        self.ctx.now_ns += self.ctx.period_ns
        return fb


def test_all_standard_fbs_are_registered_native_fbs():
    for name in ("TON", "TOF", "TP", "R_TRIG", "F_TRIG", "CTU", "CTD", "CTUD", "SR", "RS"):
        cls = NATIVE_FBS[name]
        assert issubclass(cls, NativeFB) and cls.NAME == name
        assert f"FUNCTION_BLOCK {name}" in cls.DECLARATION
        assert "END_FUNCTION_BLOCK" in cls.DECLARATION


# --- timers -----------------------------------------------------------------

# TON, TOF and TP as an ST user calls them: tests/st_unit/test_standard_timers.st
# (run by tests/test_st_unit_files.py).  The period-dependent case stays here.


def test_ton_with_period_of_two_ms():
    # 2 ms scans, PT = 5 ms: ET = 0, 2, 4, 5(capped at PT) -> Q on call 4.
    clock, ton = Clock(period_ns=2 * MS), make(fbs.TON)
    qs = [clock.step(ton, IN=True, PT=5 * MS).v_Q for _ in range(4)]
    assert qs == [False, False, False, True]
    assert ton.v_ET == 5 * MS


# --- edges ------------------------------------------------------------------

def test_r_trig_single_scan_pulse_on_rising_edges():
    clock, trig = Clock(), make(fbs.R_TRIG)
    clk = [False, True, True, False, True, False]
    assert [clock.step(trig, CLK=c).v_Q for c in clk] == [False, True, False, False, True, False]


def test_r_trig_input_true_from_the_start_is_an_edge():
    clock, trig = Clock(), make(fbs.R_TRIG)
    assert clock.step(trig, CLK=True).v_Q is True


def test_f_trig_single_scan_pulse_on_falling_edges():
    # IEC 61131-3 (tables 35/44): M has no initial value, so it starts FALSE
    # and Q := NOT CLK AND NOT M is TRUE on a first call with CLK FALSE;
    # after that only TRUE -> FALSE changes of CLK pulse.
    clock, trig = Clock(), make(fbs.F_TRIG)
    assert trig.v_M is False
    clk = [False, True, False, False, True, True, False]
    assert [clock.step(trig, CLK=c).v_Q for c in clk] == [True, False, True, False, False, False, True]
    held = make(fbs.F_TRIG)
    assert [clock.step(held, CLK=c).v_Q for c in (True, True, False)] == [False, False, True]


# --- counters ---------------------------------------------------------------

def test_ctu_counts_rising_edges_and_resets():
    # CU = 1,0,1,1,1: rising edges only on calls 1 and 3 (calls 3-5 are one
    # held level) -> CV 1,1,2,2,2; Q needs CV >= PV = 3.
    clock, ctu = Clock(), make(fbs.CTU)
    cu = [True, False, True, True, True]
    cvs, qs = [], []
    for c in cu:
        clock.step(ctu, CU=c, PV=3)
        cvs.append(ctu.v_CV)
        qs.append(ctu.v_Q)
    assert cvs == [1, 1, 2, 2, 2]
    assert qs == [False] * 5
    clock.step(ctu, CU=False)
    clock.step(ctu, CU=True)
    assert (ctu.v_CV, ctu.v_Q) == (3, True)
    clock.step(ctu, CU=False, R=True)      # R wins
    assert (ctu.v_CV, ctu.v_Q) == (0, False)


def test_ctu_saturates_at_int_max():
    clock, ctu = Clock(), make(fbs.CTU)
    ctu.v_CV = 32767
    clock.step(ctu, CU=True, PV=1)
    assert ctu.v_CV == 32767


def test_ctd_counts_down_from_loaded_pv():
    # LD loads PV = 2; edges of CD then give 1, 0 (Q TRUE at CV <= 0), -1.
    clock, ctd = Clock(), make(fbs.CTD)
    clock.step(ctd, LD=True, PV=2)
    assert (ctd.v_CV, ctd.v_Q) == (2, False)
    ctd.v_LD = False
    cvs = []
    for c in [True, False, True, False, True]:
        clock.step(ctd, CD=c)
        cvs.append((ctd.v_CV, ctd.v_Q))
    assert cvs == [(1, False), (1, False), (0, True), (0, True), (-1, True)]


def test_ctud_up_down_and_simultaneous_edges():
    clock, c = Clock(), make(fbs.CTUD)
    clock.step(c, CU=True, PV=2)                  # up edge: 1
    clock.step(c, CU=False)
    clock.step(c, CU=True)                        # 2 -> QU
    assert (c.v_CV, c.v_QU, c.v_QD) == (2, True, False)
    clock.step(c, CU=False, CD=True)              # down edge: 1
    assert c.v_CV == 1
    clock.step(c, CU=True, CD=False)
    clock.step(c, CU=False, CD=False)
    clock.step(c, CU=True, CD=True)               # both edges together: no count
    assert c.v_CV == 2
    clock.step(c, LD=True, PV=5)                  # load
    assert (c.v_CV, c.v_QU) == (5, True)
    clock.step(c, LD=True, R=True)                # R has priority over LD
    assert (c.v_CV, c.v_QU, c.v_QD) == (0, False, True)


# --- bistables --------------------------------------------------------------

# (set, reset, Q1 before, Q1 after), from the standard's bodies:
# SR: Q1 := S1 OR (NOT R AND Q1); RS: Q1 := NOT R1 AND (S OR Q1).
BISTABLE_TABLES = {
    "SR": ("S1", "R", [(False, False, False, False), (False, False, True, True),
                       (True, False, False, True), (False, True, True, False),
                       (True, True, False, True), (True, True, True, True)]),      # set dominates
    "RS": ("S", "R1", [(False, False, False, False), (False, False, True, True),
                       (True, False, False, True), (False, True, True, False),
                       (True, True, False, False), (True, True, True, False)]),    # reset dominates
}


@pytest.mark.parametrize("name, set_value, reset_value, before, after", [
    (name, *row) for name, (_, _, rows) in BISTABLE_TABLES.items() for row in rows])
def test_bistable_truth_tables(name, set_value, reset_value, before, after):
    set_pin, reset_pin, _ = BISTABLE_TABLES[name]
    fb = make(getattr(fbs, name))
    fb.v_Q1 = before
    Clock().step(fb, **{set_pin: set_value, reset_pin: reset_value})
    assert fb.v_Q1 is after
