"""The CheckedProgram the compiler reads: types, POUs, globals, name_refs,
call_targets, constants, for_vars."""

from __future__ import annotations

from st_runtime import ast
from st_runtime import types as T
from st_runtime.stdlib import fbs
from checker_helpers import checked, nodes, statement

SOURCE = """
TYPE Dist : LREAL; END_TYPE
TYPE Vec6 : ARRAY[1..6] OF Dist; END_TYPE
TYPE Color : (Red, Green := 5, Blue); END_TYPE
TYPE Pose : STRUCT
    p : ARRAY[1..3] OF LREAL;
    tag : Color := Blue;
END_STRUCT; END_TYPE
VAR_GLOBAL CONSTANT
    LEGS : INT := 6;
END_VAR
VAR_GLOBAL
    gPose : Pose;
END_VAR
FUNCTION Norm2 : LREAL
VAR_INPUT a : LREAL; b : LREAL; END_VAR
VAR_OUTPUT sq : LREAL; END_VAR
VAR t : LREAL; END_VAR
t := a * a + b * b;
sq := t;
Norm2 := SQRT(t);
END_FUNCTION
FUNCTION_BLOCK Leg
VAR_INPUT length : Dist; END_VAR
VAR_OUTPUT ok : BOOL; END_VAR
VAR_IN_OUT q : Vec6; END_VAR
VAR timer : TON; END_VAR
timer(IN := TRUE, PT := T#10ms);
ok := timer.Q AND length > 0.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    q : Vec6;
    units : ARRAY[1..LEGS] OF Leg;
    i : INT;
    c : Color := Green;
    n : LREAL;
    s : LREAL;
END_VAR
FOR i := 1 TO LEGS DO
    units[i](length := 1.0, q := q);
END_FOR;
n := Norm2(3.0, 4.0, sq => s);
CASE c OF
    Red: i := 0;
    Green, Blue: i := LEGS;
END_CASE;
gPose.p[1] := q[LEGS];
END_PROGRAM
"""


def test_types_are_resolved():
    p = checked(SOURCE)
    assert p.types["DIST"] is T.LREAL                      # alias -> its target
    vec6 = p.types["VEC6"]
    assert isinstance(vec6, T.ArrayType) and vec6.dims == ((1, 6),) and vec6.element is T.LREAL
    color = p.types["COLOR"]
    assert isinstance(color, T.EnumType)
    assert color.values == {"RED": ("Red", 0), "GREEN": ("Green", 5), "BLUE": ("Blue", 6)}
    pose = p.types["POSE"]
    assert isinstance(pose, T.StructType)
    assert list(pose.fields) == ["P", "TAG"] and pose.fields["TAG"][1] is color
    assert isinstance(p.types["LEG"], T.FBType)


def test_pous_and_variables_in_declaration_order():
    p = checked(SOURCE)
    norm = p.pous["NORM2"]
    assert norm.kind == "FUNCTION" and norm.return_type is T.LREAL
    assert [(s.name, s.kind) for s in norm.variables.values()] == [
        ("Norm2", "RETURN"), ("a", "VAR_INPUT"), ("b", "VAR_INPUT"), ("sq", "VAR_OUTPUT"), ("t", "VAR")]
    leg = p.pous["LEG"]
    assert [s.name for s in leg.inputs] == ["length"] and [s.name for s in leg.in_outs] == ["q"]
    assert p.types["LEG"].variables is leg.variables
    main = p.pous["MAIN"]
    units = main.variables["UNITS"]
    assert units.type.dims == ((1, 6),) and units.type.element is p.types["LEG"]
    assert main.variables["C"].init is not None


def test_native_fbs_from_the_prelude():
    p = checked(SOURCE)
    ton = p.pous["TON"]
    assert ton.native is fbs.TON and p.types["TON"].native is fbs.TON
    assert {"IN", "PT", "Q", "ET"} <= set(p.types["TON"].variables)


def test_globals_and_constants():
    p = checked(SOURCE)
    assert p.globals["LEGS"].constant and p.globals["LEGS"].type is T.INT
    assert isinstance(p.globals["GPOSE"].type, T.StructType)
    last = statement(p, 3)                     # gPose.p[1] := q[LEGS];
    legs_name = last.value.indices[0]
    assert p.name_refs[id(legs_name)] is p.globals["LEGS"]
    assert p.constants[id(legs_name)] == 6


def test_name_refs_calls_and_loops():
    p = checked(SOURCE)
    main = p.pous["MAIN"]
    loop = statement(p, 0)
    assert p.for_vars[id(loop)] is main.variables["I"]
    fb_call = loop.body[0].call
    target = p.call_targets[id(fb_call)]
    assert target.kind == "fb" and target.pou is p.pous["LEG"]
    fn_call = statement(p, 1).value
    target = p.call_targets[id(fn_call)]
    assert target.kind == "function" and target.name == "NORM2" and target.pou is p.pous["NORM2"]
    assert p.expr_types[id(fn_call)] is T.LREAL
    case = statement(p, 2)
    red, green, blue = (lab for clause in case.clauses for lab in clause.labels)
    assert (p.name_refs[id(red)], p.name_refs[id(green)], p.name_refs[id(blue)]) == (0, 5, 6)
    assert p.expr_types[id(red)] is p.types["COLOR"]
    for name in nodes(main.node.body, ast.Name):
        is_callee = any(c.callee is name for c in nodes(main.node.body, ast.Call))
        assert is_callee or id(name) in p.name_refs, name


def test_function_name_inside_its_body_is_the_result():
    p = checked(SOURCE)
    assign = statement(p, 2, pou="Norm2")
    assert p.name_refs[id(assign.target)] is p.pous["NORM2"].variables["NORM2"]


def test_external_variables_refer_to_a_local_symbol_of_kind_var_external():
    p = checked("VAR_GLOBAL g : DINT; END_VAR\nPROGRAM Main\nVAR_EXTERNAL g : DINT; END_VAR\n"
                "g := g + 1;\nEND_PROGRAM\n")
    sym = p.name_refs[id(statement(p, 0).target)]
    assert sym.kind == "VAR_EXTERNAL" and sym.type is T.DINT


def test_global_used_without_var_external():
    p = checked("VAR_GLOBAL g : DINT; END_VAR\nPROGRAM Main\ng := 1;\nEND_PROGRAM\n")
    assert p.name_refs[id(statement(p, 0).target)] is p.globals["G"]


def test_array_initializers_with_repetition_and_nesting():
    p = checked("PROGRAM Main\nVAR\n a : ARRAY[1..6] OF LREAL := [2(1.0), 4(0.0)];\n"
                " m : ARRAY[1..2, 1..2] OF INT := [[1, 2], [3, 4]];\n"
                " s : ARRAY[0..2] OF STRING[4] := ['a', 'b'];\nEND_VAR\nEND_PROGRAM\n")
    assert p.pous["MAIN"].variables["M"].type.dims == ((1, 2), (1, 2))


def test_bare_enum_value_shared_by_two_enums_is_resolved_by_its_context():
    p = checked("TYPE Mode : (Idle, Run); END_TYPE\nTYPE Pump : (Idle, Pumping); END_TYPE\n"
                "PROGRAM Main\nVAR m : Mode; q : Pump; b : BOOL; END_VAR\n"
                "m := Idle;\nq := Idle;\nb := q = Idle;\nEND_PROGRAM\n")
    assert p.expr_types[id(statement(p, 0).value)] is p.types["MODE"]
    assert p.expr_types[id(statement(p, 1).value)] is p.types["PUMP"]
    assert p.expr_types[id(statement(p, 2).value.right)] is p.types["PUMP"]


def test_types_may_use_global_constants_declared_anywhere():
    p = checked("VAR_GLOBAL gLegs : Legs; END_VAR\n"
                "TYPE Legs : ARRAY[1..N_LEGS] OF LREAL; END_TYPE\n"
                "VAR_GLOBAL CONSTANT N_LEGS : INT := 6; END_VAR\n")
    assert p.types["LEGS"].dims == ((1, 6),)
    assert p.globals["GLEGS"].type is p.types["LEGS"]
