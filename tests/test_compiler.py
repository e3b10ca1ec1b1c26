"""The compiler's own promises: code kept and compiled once, optimizations
that never change a result (bounds checks skipped only where proven, loop
hoisting, variables cached in locals), and clear errors."""

from __future__ import annotations

import pytest

from st_runtime.api import LoadError, _compiled, load_text
from st_runtime.compiler import compile_program


def run(src: str, cycles: int = 1, program: str = "Main"):
    plc = load_text(src, "t.st").controller()
    inst = plc.add_program(program)
    plc.run(cycles)
    return inst, plc


def test_each_pou_is_compiled_once_and_its_source_kept():
    src = """
    FUNCTION_BLOCK Inc
    VAR_OUTPUT n : INT; END_VAR
    n := n + 1;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR a, b : Inc; END_VAR
    a(); b(); b();
    END_PROGRAM
    """
    project = load_text(src)
    sources = project.compiled.python_sources
    assert "def _body_INC(self, _ctx):" in sources["INC"]
    assert "def _body_MAIN(self, _ctx):" in sources["MAIN"]
    a, b = project.compiled.new("Inc"), project.compiled.new("Inc")
    assert a.execute.__func__ is b.execute.__func__      # one code object for every instance
    plc = project.controller()
    main = plc.add_program("Main")
    plc.run(2)
    assert main["a"] == {"n": 2} and main["b"] == {"n": 4}


def test_index_checks_stay_where_the_loop_range_is_outside_the_bounds():
    main, plc = run("""PROGRAM Main
    VAR a : ARRAY[1..5] OF INT; i : INT; END_VAR
    FOR i := 1 TO 5 DO a[i + 3] := i; END_FOR;
    END_PROGRAM""")
    assert main["a"] == [0, 0, 0, 1, 2]
    assert [f.code for f in plc.faults] == ["F-INDEX"] * 3


def test_index_checks_stay_when_loop_bounds_are_variables():
    main, plc = run("""PROGRAM Main
    VAR m : ARRAY[0..2, -1..1] OF INT; i, j, hi : INT := 3; END_VAR
    FOR i := 0 TO hi DO FOR j := -1 TO 1 DO m[i, j] := m[i, j] + i * 10 + j; END_FOR; END_FOR;
    END_PROGRAM""")
    assert main["m"] == [[-1, 0, 1], [9, 10, 11], [19, 20, 21]]
    assert [f.code for f in plc.faults] == ["F-INDEX"] * 3          # i = 3, three times
    assert "index 3 (dimension 1)" in plc.faults[0].message


def test_loop_variable_passed_to_an_in_out_is_refused_before_compiling():
    # IEC: the control variable is not written in the loop; handing it to a
    # VAR_IN_OUT (which may write it) is a checker error.  The compiler's
    # testing FOR loop for a variable a callee can change is exercised by
    # test_global_loop_variable_changed_by_a_callee_is_seen_by_the_loop.
    src = """
    FUNCTION Bump : BOOL
    VAR_IN_OUT v : INT; END_VAR
    v := v + 10; Bump := TRUE;
    END_FUNCTION
    PROGRAM Main
    VAR a : ARRAY[1..5] OF INT; i : INT; END_VAR
    FOR i := 1 TO 5 DO Bump(i); a[i] := 1; END_FOR;
    END_PROGRAM"""
    with pytest.raises(LoadError) as info:
        load_text(src)
    assert [(d.code, d.pos.line) for d in info.value.diagnostics] == [("E-CALL-007", 8)]


def test_hoisted_row_offsets_follow_the_outer_loop():
    main, _ = run("""PROGRAM Main
    VAR m, t : ARRAY[1..3, 1..4] OF INT; tt : ARRAY[1..4, 1..3] OF INT; i, j, k : INT; END_VAR
    FOR i := 1 TO 3 DO FOR j := 1 TO 4 DO m[i, j] := i * 10 + j; END_FOR; END_FOR;
    k := 2;
    FOR j := 1 TO 4 DO t[k, j] := m[k, j] * 2; END_FOR;
    FOR i := 1 TO 3 DO FOR j := 1 TO 4 DO tt[j, i] := m[i, j]; END_FOR; END_FOR;
    END_PROGRAM""")
    assert main["m"] == [[11, 12, 13, 14], [21, 22, 23, 24], [31, 32, 33, 34]]
    assert main["t"][1] == [42, 44, 46, 48] and main["t"][0] == [0] * 4
    assert main["tt"] == [[11, 21, 31], [12, 22, 32], [13, 23, 33], [14, 24, 34]]


def test_constant_tables_skip_checks_but_variable_tables_do_not(monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "none")   # the loop as written (unrolled, no index is left)
    src = """PROGRAM Main
    VAR CONSTANT perm : ARRAY[1..3] OF INT := [3, 1, 2]; END_VAR
    VAR table : ARRAY[1..3] OF INT := [3, 1, 7]; v : ARRAY[1..3] OF INT := [10, 20, 30];
        a, b : ARRAY[1..3] OF INT; i : INT; END_VAR
    FOR i := 1 TO 3 DO a[i] := v[perm[i]]; b[i] := v[table[i]]; END_FOR;
    END_PROGRAM"""
    project = load_text(src)
    source = project.compiled.python_sources["MAIN"]
    assert source.count("_index_fault") == 1                   # only v[table[i]] is checked
    plc = project.controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["a"] == [30, 10, 20]
    assert main["b"] == [30, 10, 0]
    assert [f.code for f in plc.faults] == ["F-INDEX"]


def test_for_to_the_type_maximum_ends_and_wraps_the_variable():
    main, _ = run("""PROGRAM Main
    VAR i : INT; n : INT; END_VAR
    FOR i := 32765 TO 32767 DO n := n + 1; END_FOR;
    END_PROGRAM""")
    # A PLC would loop forever here (i wraps before the test); the runtime
    # runs the three iterations the range holds and wraps the final value.
    assert main["n"] == 3 and main["i"] == -32768


def test_aggregate_inputs_are_copied_into_the_instance():
    src = """
    FUNCTION_BLOCK Keep
    VAR_INPUT v : ARRAY[1..3] OF LREAL; END_VAR
    VAR_OUTPUT first : LREAL; END_VAR
    first := v[1];
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR a : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; k : Keep; END_VAR
    k(v := a); a[1] := 99.0;
    END_PROGRAM"""
    main, _ = run(src)
    assert main["k"] == {"v": [1.0, 2.0, 3.0], "first": 1.0}
    assert main["a"] == [99.0, 2.0, 3.0]


def test_function_outputs_inside_a_condition():
    src = """
    FUNCTION Split : BOOL
    VAR_INPUT x : DINT; END_VAR
    VAR_OUTPUT hi, lo : DINT; END_VAR
    hi := x / 100; lo := x MOD 100; Split := lo = 0;
    END_FUNCTION
    PROGRAM Main
    VAR h, l, n : DINT; END_VAR
    IF Split(1234, hi => h, lo => l) OR h > 0 THEN n := 1; END_IF;
    END_PROGRAM"""
    main, _ = run(src)
    assert (main["h"], main["l"], main["n"]) == (12, 34, 1)


def test_arrays_of_fb_instances_and_fb_initializers():
    src = """PROGRAM Main
    VAR t : ARRAY[1..3] OF TON; slow : TON := (PT := T#3ms); i : INT; q : ARRAY[1..3] OF BOOL; END_VAR
    FOR i := 1 TO 3 DO t[i](IN := TRUE, PT := INT_TO_TIME(i) * 1000000); q[i] := t[i].Q; END_FOR;
    slow(IN := TRUE);
    END_PROGRAM"""
    main, _ = run(src, cycles=3)
    # Third scan at t = 2 ms: timers of 1 ms and 2 ms are done, 3 ms is not.
    assert main["q"] == [True, True, False]
    assert main["slow"]["PT"] == "T#3ms" and main["slow"]["Q"] is False


def test_unguarded_compilation_gives_the_same_results():
    src = """PROGRAM Main
    VAR s : LREAL; i : INT; END_VAR
    FOR i := 1 TO 10 DO s := s + i / 2; END_FOR;
    END_PROGRAM"""
    project = load_text(src)
    for compiled in (project.compiled, compile_program(project.program, guard_statements=False)):
        main = compiled.new("Main")
        ctx = project.controller().controller.ctx
        main.execute(ctx)
        assert main.v_S == 25.0           # 0+1+1+2+2+3+3+4+4+5: INT / INT truncates
    assert "except _FAULTS" not in compile_program(project.program, guard_statements=False).python_sources["MAIN"]


def test_native_fb_works_outside_a_compiled_program():
    from st_runtime.compiler import install_native_layouts
    from st_runtime.stdlib.fbs import TON

    install_native_layouts()
    t = TON()
    assert t.v_IN is False and t.v_PT == 0 and t.v_Q is False


def test_compile_errors_become_diagnostics():
    from st_runtime import loader

    result = loader.load_texts({"x.st": "PROGRAM Main\nVAR x : INT; END_VAR\nx := ABS(x);\nEND_PROGRAM\n"})
    result.program.call_targets.clear()        # a call the checker left unresolved
    with pytest.raises(LoadError) as info:
        _compiled(result)
    assert info.value.diagnostics[-1].code == "E-COMPILE-001"
    assert "x.st:3:6: error[E-COMPILE-001]" in info.value.render()


def test_global_loop_variable_changed_by_a_callee_is_seen_by_the_loop():
    src = """
    VAR_GLOBAL k : INT; END_VAR
    FUNCTION Skip : BOOL
    VAR_EXTERNAL k : INT; END_VAR
    k := k + 2; Skip := TRUE;
    END_FUNCTION
    PROGRAM Main
    VAR_EXTERNAL k : INT; END_VAR
    VAR a : ARRAY[1..9] OF INT; END_VAR
    FOR k := 1 TO 9 DO a[k] := 1; Skip(); END_FOR;
    END_PROGRAM"""
    main, plc = run(src)
    assert main["a"] == [1, 0, 0, 1, 0, 0, 1, 0, 0]      # k = 1, 4, 7
    assert plc.faults == []


def test_a_fault_in_a_condition_or_bound_abandons_that_statement():
    main, plc = run("""PROGRAM Main
    VAR a : ARRAY[1..3] OF INT; i : INT := 9; n, k : INT; r : ARRAY[1..6] OF INT; END_VAR
    IF a[i] > 0 THEN r[1] := 1; ELSE r[1] := 2; END_IF;
    IF n > 0 THEN r[2] := 1; ELSIF a[i] = 0 THEN r[2] := 2; ELSE r[2] := 3; END_IF;
    CASE a[i] OF 0: r[3] := 1; ELSE r[3] := 2; END_CASE;
    FOR k := 1 TO a[i] DO r[4] := r[4] + 1; END_FOR;
    WHILE a[i] = 0 DO r[5] := r[5] + 1; END_WHILE;
    REPEAT r[6] := r[6] + 1; UNTIL a[i] = 0 END_REPEAT;
    n := 7;
    END_PROGRAM""")
    assert main["r"] == [0, 0, 0, 0, 0, 1]       # REPEAT runs its body once, then the test faults
    assert main["n"] == 7 and main["k"] == 0
    assert [(f.code, f.line) for f in plc.faults] == [("F-INDEX", line) for line in range(3, 9)]


def test_deeply_nested_statements_compile():
    depth = 40
    body = "".join(f"IF x < {100 + i} THEN\n" for i in range(depth)) + "x := x + 1;\n" + "END_IF;\n" * depth
    loops = "".join(f"FOR i{k} := 1 TO 2 DO\n" for k in range(12)) + "n := n + 1;\n" + "END_FOR;\n" * 12
    decls = " ".join(f"i{k} : INT;" for k in range(12))
    main, _ = run(f"PROGRAM Main\nVAR x : INT; n : DINT; {decls} END_VAR\n{body}{loops}END_PROGRAM\n")
    assert main["x"] == 1 and main["n"] == 2 ** 12


def test_nesting_beyond_python_limits_is_a_diagnostic(monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "none")   # unrolling would take the inner loops away
    loops = "".join(f"FOR i{k} := 1 TO 2 DO\n" for k in range(25)) + "n := n + 1;\n" + "END_FOR;\n" * 25
    decls = " ".join(f"i{k} : INT;" for k in range(25))
    with pytest.raises(LoadError) as info:
        load_text(f"PROGRAM Main\nVAR n : DINT; {decls} END_VAR\n{loops}END_PROGRAM\n", "deep.st")
    # The checker refuses it (st_runtime/checker/limits.py) at the 13th loop: lines 3..27 hold the FORs.
    diagnostic = info.value.diagnostics[-1]
    assert diagnostic.code == "E-LIMIT-004" and "loops nested more than 12 levels deep" in diagnostic.message
    assert diagnostic.pos.file == "deep.st" and diagnostic.pos.line == 3 + 12
