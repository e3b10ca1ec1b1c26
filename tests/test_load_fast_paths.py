"""The load's shortcuts do what the long way did (docs/load.md, "Less work per load").

* A PROGRAM's and the globals' `__init__`, and one that sets nothing, are not
  compiled: `_store_members` makes the stores the kept source spells, in its order.
* The process image allocates an area when it is first used.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from st_runtime.compiler import compile_program
from st_runtime.compiler import _plain, _store_members
from st_runtime.loader import load_texts
from st_runtime.process_image import ProcessImage, parse_address
from tree_order import walk_order

ROOT = Path(__file__).resolve().parent.parent
ACCEPT = sorted((ROOT / "tests" / "corpus" / "accept").glob("*.st"))


def _state(value, depth: int = 0):
    """A value, deep: instances by type and attributes, lists by elements."""
    if depth > 8:
        return "..."
    if isinstance(value, (list, tuple)):
        return [type(value).__name__] + [_state(v, depth + 1) for v in value]
    attrs = list(getattr(type(value), "__slots__", ())) + list(getattr(value, "__dict__", {}))
    if attrs and not isinstance(value, (str, int, float)):
        return (type(value).__name__, {a: _state(getattr(value, a, "<unset>"), depth + 1) for a in attrs})
    return (type(value).__name__, repr(value))


@pytest.mark.parametrize("path", ACCEPT[::3], ids=lambda p: p.stem)
def test_an_uncompiled_init_stores_what_its_source_says(path: Path):
    result = load_texts({path.name: path.read_text(encoding="utf-8")})
    if result.program is None:
        pytest.skip("a file the loader refuses")
    compiled = compile_program(result.program)
    for key, cls in list(compiled.classes.items()) + [("<GLOBALS>", type(compiled.globals))]:
        if cls.__init__.__name__ != "__init__" or cls.__init__.__qualname__.split(".")[0] != "_store_members":
            continue
        source = compiled.python_sources["init:" + key]
        namespace = dict(compiled.namespace)
        exec(compile(source, "<test>", "exec"), namespace)       # the kept source, compiled here
        by_source = object.__new__(cls)
        namespace[source.split()[1].split("(")[0]](by_source)
        assert _state(cls()) == _state(by_source)


def test_programs_and_globals_are_initialised_without_compiling():
    text = """
    VAR_GLOBAL g : INT := 7; h : ARRAY[1..3] OF REAL := [1.5, 2.5, 3.5]; END_VAR
    PROGRAM Main VAR x : LREAL := -0.0; s : STRING := 'it$'s'; t : TON; b : BOOL := TRUE; END_VAR
    x := x + 1.0;
    END_PROGRAM
    """
    compiled = compile_program(load_texts({"m.st": text}).program)
    main = compiled.new("Main")
    assert type(main).__init__.__qualname__.startswith("_store_members")
    assert math.copysign(1.0, main.v_X) == -1.0 and main.v_S == "it's" and main.v_B is True
    assert type(main.v_T).__name__ == "TON" and main.v_T is not compiled.new("Main").v_T
    g = compiled.globals
    assert g.v_G == 7 and list(g.v_H) == [1.5, 2.5, 3.5]
    assert "self.v_G = 7" in compiled.python_sources["init:<GLOBALS>"]


def test_plain_values_are_those_of_the_literals():
    class Small(int):
        pass

    assert type(_plain(Small(3))) is int and _plain(True) is True
    assert math.isnan(_plain(float("nan"))) and _plain(float("-inf")) == -math.inf
    assert _plain((Small(1), "a", None)) == (1, "a", None) and type(_plain((Small(1),))[0]) is int
    made = []
    init = _store_members((("a", None, 1), ("b", lambda: made.append(1) or [0], None)))

    class Obj:
        pass

    one, two = Obj(), Obj()
    init(one)
    init(two)
    assert one.a == 1 and one.b == [0] and one.b is not two.b and made == [1, 1]


def test_process_image_areas_appear_on_first_use():
    image = ProcessImage()
    assert dict(image.areas) == {}
    address = parse_address("%QW4")[0]
    image.set(address, "int", 513)
    assert image.get(address, "int") == 513 and set(image.areas) == {"Q"}
    assert image.get(parse_address("%IX1.2")[0], "bool") is False
    assert len(image.areas["I"]) == len(image.areas["Q"])
    with pytest.raises(KeyError):
        image.areas["Z"]
    image.clear()
    assert image.get(address, "int") == 0


def test_a_body_walked_again_gives_the_same_nodes():
    """scope.walk keeps a body's node list for the next pass of the same compile:
    the same nodes in the same order as walking it afresh, never another tuple's."""
    from st_runtime import ast
    from st_runtime.compiler import scope
    from st_runtime.parser import parse_body

    bodies = [parse_body(f"x := {i} + y[{i}]; IF a THEN b := NOT c; END_IF;", "w.st")[0] for i in range(40)]
    fresh = [[id(n) for n in walk_order(body)] for body in bodies]
    for _ in range(2):
        for body, nodes in zip(bodies, fresh):
            assert [id(n) for n in scope.walk(body)] == nodes
    twin = tuple(bodies[0])                      # equal, but another tuple: its own nodes
    assert [id(n) for n in scope.walk(twin)] == fresh[0]
    assert len(scope._WALKED) <= scope._WALKED_ENTRIES
    assert [type(n) for n in scope.walk(bodies[0][0])][0] is ast.Assign    # (a node: walked afresh)


def test_the_walk_lists_every_node_of_the_corpus_in_its_order():
    """scope.walk over every POU of the accept corpus (a whole item, each body, each
    statement alone as the passes ask) gives the reference order; a one-leaf tuple,
    which it returns as it is, holds a node with no child node."""
    from st_runtime import ast
    from st_runtime.compiler import scope
    from st_runtime.parser import parse

    leaves = 0
    for path in ACCEPT:
        parsed, _ = parse(path.read_text(encoding="utf-8"), str(path))
        for item in parsed.items:
            assert [id(n) for n in scope.walk(item)] == [id(n) for n in walk_order(item)]
            for body in [getattr(item, "body", ())] + [m.body for m in getattr(item, "methods", ())]:
                assert [id(n) for n in scope.walk(body)] == [id(n) for n in walk_order(body)]
                for node in walk_order(body):
                    one = (node,)
                    assert [id(n) for n in scope.walk(one)] == [id(n) for n in walk_order(one)]
                    if type(node) in scope._LEAVES:
                        leaves += 1
                        assert not any(isinstance(getattr(node, f), (ast.Node, tuple))
                                       for f in ast.fields_of(type(node)))
    assert leaves > 1000


def test_usage_counts_a_name_once_an_occurrence_and_ten_times_inside_a_loop():
    """`scope.Usage` (a variable is cached in a local from CACHE_THRESHOLD occurrences): each
    occurrence of a name counts 1, whatever its case; inside a loop 10, and a FOR's variable
    10 more (stored every iteration).  Counted by hand from the two bodies."""
    from types import SimpleNamespace

    from st_runtime.compiler.scope import Usage
    from st_runtime.parser import parse_body

    program = SimpleNamespace(call_targets={})
    straight = Usage(program, parse_body("a := b + B; c := a * 2;", "u.st")[0], None)
    assert straight.count == {"A": 2, "B": 2, "C": 1}
    assert straight.used == {"A", "B", "C"} and straight.assigned == {"A", "C"}
    looped = Usage(program, parse_body("a := b; FOR i := 1 TO 3 DO c := a + b; END_FOR;", "u.st")[0], None)
    assert looped.count == {"A": 11, "B": 11, "C": 10, "I": 10}
    assert looped.used == {"A", "B", "C", "I"} and looped.assigned == {"A", "C", "I"}


def test_a_field_the_walks_pass_by_never_holds_a_node():
    """The walks read only `ast.CHILD_FIELDS` (fields annotated as names, flags or
    numbers are passed by): in every .st file of the repository, parsed, and in the
    checked files (SFC charts lowered to statements), no other field holds a node."""
    from st_runtime import ast
    from st_runtime.checker import check
    from st_runtime.parser import parse

    def nodes(node):
        stack = [node]
        while stack:
            n = stack.pop()
            if isinstance(n, tuple):
                stack.extend(n)
            elif isinstance(n, ast.Node):
                yield n
                stack.extend(getattr(n, name) for name in ast.fields_of(type(n)))

    def holds_node(value) -> bool:
        return isinstance(value, ast.Node) or isinstance(value, tuple) and any(map(holds_node, value))

    seen = 0
    for path in sorted({*ROOT.glob("tests/**/*.st"), *ROOT.glob("examples/**/*.st"), *ROOT.glob("generated/**/*.st")}):
        parsed, _ = parse(path.read_text(encoding="utf-8", errors="replace"), str(path))
        if parsed is None:
            continue
        program, _ = check([parsed])
        for source in [parsed, *program.files]:
            for node in nodes(source):
                passed_by = set(ast.fields_of(type(node))) - set(ast.CHILD_FIELDS[type(node)])
                assert not any(holds_node(getattr(node, name)) for name in passed_by), type(node)
                seen += 1
    assert seen > 100_000


def test_a_compile_takes_the_leading_prelude_at_once_as_one_by_one(monkeypatch):
    """When a program's types and POUs begin with the shared prelude's (most loads),
    compile_program adds their classes, __init__ sources and makers at once: the same
    sources, in the same order, the same classes as going through them one by one."""
    from st_runtime.compiler import SharedPrelude

    def compiled(path):
        result = compile_program(load_texts({str(path): path.read_text(encoding="utf-8")}).program)
        return list(result.python_sources.items()), [(k, c.__qualname__) for k, c in result.classes.items()]

    loads = [p for p in ACCEPT if load_texts({str(p): p.read_text(encoding="utf-8")}).program is not None]
    at_once = [compiled(p) for p in loads]
    led = [SharedPrelude.leads]
    taken = []

    def leads(self, program, table):
        taken.append(led[0](self, program, table))
        return False

    monkeypatch.setattr(SharedPrelude, "leads", leads)
    one_by_one = [compiled(p) for p in loads]
    assert at_once == one_by_one
    assert taken.count(True) > len(loads) and taken.count(False) > 0     # (both cases occur)


def test_each_compile_installs_its_dialects_native_layouts():
    """A native FB's class serves every dialect: after each compile it holds that
    dialect's layout (CTU's reset pin is R under iec, Reset under nj), also when
    the previous compile left another dialect's, or a full compile its own."""
    from st_runtime.native import NATIVE_FBS
    from st_runtime.checker import check
    from st_runtime.loader import parse_texts

    text = {"c.st": "PROGRAM P VAR c : CTU; END_VAR c(CU := TRUE, PV := 3); END_PROGRAM"}
    ctu = NATIVE_FBS["CTU"]
    for dialect, pin, other in [("iec", "R", "RESET"), ("nj", "RESET", "R"), ("nj", "RESET", "R"),
                                ("iec", "R", "RESET"), ("iec", "R", "RESET")]:
        compile_program(load_texts(text, dialect).program)
        assert pin in ctu._st_vars and other not in ctu._st_vars
        if dialect == "nj":        # a full compile (no shared prelude) sets its own layout
            _, parsed, _ = parse_texts(text, "iec")
            program, _ = check([f for _, f in parsed], "iec", share_prelude=False)
            compile_program(program)
            assert "R" in ctu._st_vars and "RESET" not in ctu._st_vars


def test_programs_without_globals_share_one_empty_globals_class():
    """A program without globals gets the one shared Globals class, which holds
    nothing of any program and is not changed by a compile; a program with globals
    gets its own class, and its values stay its own."""
    import st_runtime.compiler as compiler

    bare = [compile_program(load_texts({f"p{i}.st": f"PROGRAM P VAR x : INT := {i}; END_VAR x := x + 1; "
                                                    "END_PROGRAM"}).program) for i in range(2)]
    assert type(bare[0].globals) is type(bare[1].globals) is compiler._NO_GLOBALS
    assert compiler._NO_GLOBALS.__slots__ == () and compiler._NO_GLOBALS._st_vars == {}
    assert compiler._NO_GLOBALS.__dict__["__init__"] is compiler._NO_GLOBALS_INIT
    assert bare[0].python_sources["init:<GLOBALS>"].endswith("(self):\n    pass\n")    # (kept for reading)
    with_globals = compile_program(load_texts({"g.st": "VAR_GLOBAL g : INT := 7; END_VAR "
                                               "PROGRAM P VAR_EXTERNAL g : INT; END_VAR g := g + 1; "
                                               "END_PROGRAM"}).program)
    assert type(with_globals.globals) is not compiler._NO_GLOBALS
    assert with_globals.globals.v_G == 7 and compiler._NO_GLOBALS._st_vars == {}


def _as_dataclass_made_it(cls: type) -> type:
    """What @dataclass(frozen=True, slots=True) makes of a class with cls's fields
    (in order, with their defaults, compare, repr and kw_only) and its name."""
    import dataclasses

    fields = [(f.name, f.type, dataclasses.field(default=f.default, compare=f.compare, repr=f.repr,
                                                 kw_only=f.kw_only))
              for f in dataclasses.fields(cls)]
    return dataclasses.make_dataclass(cls.__name__, fields, frozen=True, slots=True)


def test_a_node_class_behaves_as_its_frozen_dataclass():
    """Every AST class (and Pos) takes the parameters a frozen slotted dataclass of
    its fields takes, with the same defaults and annotations, stores the same
    fields, and has the same repr, equality, hash, match arguments, refusal of
    stores, pickled round trip and generated docstring (frozen_dataclasses.make_methods)."""
    import dataclasses
    import inspect
    import pickle

    from st_runtime import ast

    classes = [ast.Pos] + [c for c in vars(ast).values() if isinstance(c, type) and issubclass(c, ast.Node)]
    assert len(classes) > 60
    for cls in classes:
        reference = _as_dataclass_made_it(cls)
        assert inspect.signature(cls.__init__) == inspect.signature(reference.__init__)
        assert cls.__match_args__ == reference.__match_args__
        if cls.__doc__.startswith(cls.__name__ + "("):     # no docstring of its own: dataclass's
            assert cls.__doc__ == reference.__doc__
        assert not hasattr(cls(*[None] * len(cls.__match_args__)), "__dict__")   # slotted
        fields = dataclasses.fields(cls)
        values = {f.name: f"v_{f.name}" for f in fields}
        args = [values[f.name] for f in fields if not f.kw_only]
        kwargs = {f.name: values[f.name] for f in fields if f.kw_only}
        made, by_dataclass = cls(*args, **kwargs), reference(*args, **kwargs)
        assert all(getattr(made, f.name) is values[f.name] for f in fields)
        assert repr(made) == repr(by_dataclass) and hash(made) == hash(by_dataclass)
        required = [values[f.name] for f in fields if not f.kw_only and f.default is dataclasses.MISSING]
        defaults, by_dataclass_defaults = cls(*required), reference(*required)
        assert all(getattr(defaults, f.name) is getattr(by_dataclass_defaults, f.name) for f in fields)
        assert (made == defaults) == (by_dataclass == by_dataclass_defaults)
        assert (made == cls(*args, **kwargs)) and made.__eq__(by_dataclass) is NotImplemented
        for f in fields:     # equal but for one field: unequal exactly when that field is compared
            other = dataclasses.replace(made, **{f.name: f"w_{f.name}"})
            other_ref = dataclasses.replace(by_dataclass, **{f.name: f"w_{f.name}"})
            assert (made == other) == (by_dataclass == other_ref) == (not f.compare)
            assert (hash(made) == hash(other)) == (hash(by_dataclass) == hash(other_ref))
            refusals = []
            for node in (made, by_dataclass):
                with pytest.raises(dataclasses.FrozenInstanceError) as stored:
                    setattr(node, f.name, 1)
                with pytest.raises(dataclasses.FrozenInstanceError) as deleted:
                    delattr(node, f.name)
                refusals.append((str(stored.value), str(deleted.value)))
            assert refusals[0] == refusals[1]
        copy = pickle.loads(pickle.dumps(made))
        assert type(copy) is cls and all(getattr(copy, f.name) == values[f.name] for f in fields)
        assert made.__getstate__() == by_dataclass.__getstate__()


def test_the_prelude_text_is_made_again_when_a_native_is_registered(monkeypatch):
    """prelude_text keeps the text per dialect until the registered natives change:
    always the text native.prelude_source makes of them."""
    from st_runtime import native, prelude

    for dialect in ("iec", "nj", "codesys"):
        assert prelude.prelude_text(dialect) == native.prelude_source(dialect)

    class Probe:
        NAME = "PROBE_FB"
        DECLARATION = native.fb_declaration("PROBE_FB", inputs="A : BOOL;")

    monkeypatch.setitem(native.NATIVE_FBS, "PROBE_FB", Probe)
    assert prelude.prelude_text("iec") == native.prelude_source("iec")
    assert "FUNCTION_BLOCK PROBE_FB" in prelude.prelude_text("iec")
    monkeypatch.setattr(native, "NATIVE_TYPE_SOURCES", native.NATIVE_TYPE_SOURCES + ["TYPE PROBE_T : INT; END_TYPE"])
    assert "PROBE_T" in prelude.prelude_text("nj") and prelude.prelude_text("nj") == native.prelude_source("nj")
    monkeypatch.undo()
    assert "PROBE" not in prelude.prelude_text("iec") and "PROBE" not in prelude.prelude_text("nj")


def test_charges_join_along_a_level_until_a_barrier():
    """charges.merge reads the code between a taker and each later charge of its level
    once (not again from the taker): the same joins as reading it whole.  By the rule:
    a charge joins the one before it in its level when no line between is less
    indented and none can raise, check the budget or leave (`return`).  Then (session 15)
    the joined charge 1 + 2 + 3 + 4 = 10, which the IF follows with nothing between that can
    raise, sinks into the chain: its branch charges 10 + 30 = 40, and an ELSE it did not
    have charges 10, so each path pays what it paid before (40 or 10)."""
    from st_runtime.compiler.optimise import charges

    body = ["def f(self, _ctx):", "    _spent = 0", "    try:",
            "        _spent += 1", "        x = 1", "        _spent += 2", "        y = 2",
            "        _spent += 3", "        if x:", "            _spent += 10", "            z = 3",
            "            _spent += 20", "        _spent += 4", "        return x",
            "        _spent += 5", "        w = 1", "        _spent += 6",
            "    finally:", "        _ctx.budget -= _spent"]
    charges.merge(body, 0)
    assert body == ["def f(self, _ctx):", "    _spent = 0", "    try:",
                    "        x = 1", "        y = 2", "        if x:",
                    "            _spent += 40", "            z = 3",
                    "        else:", "            _spent += 10", "        return x",
                    "        _spent += 11", "        w = 1",
                    "    finally:", "        _ctx.budget -= _spent"]


class _Holding(dict):
    """Empty, but true: a `ranges.Flow` whose variables are none is kept as if it had some."""

    def __bool__(self) -> bool:
        return True


class _EveryClass:
    """`scope.Usage.kinds` holding every node class: no gate of it closes (`real`: the body's)."""

    def __init__(self, real: set) -> None:
        self.real = real

    def __contains__(self, cls) -> bool:
        return True


def test_the_passes_gates_leave_the_code_as_running_every_pass_makes_it(monkeypatch):
    """A pass whose subject a body lacks is not run on it (`optimise.branched`,
    `optimise.may_reuse`, `scope.Usage.kinds`, no `ranges.Flow` without a variable to
    follow): with every gate open, each pass run on every body, every file of the
    accept corpus and the generated platform program compiles to the same Python, and the
    gates did close for most bodies."""
    from st_runtime.compiler import statements
    from st_runtime.compiler.optimise import ranges
    from st_runtime.compiler.scope import Usage

    def compiled(paths):
        result = compile_program(load_texts({str(p): p.read_text(encoding="utf-8") for p in paths}).program)
        return list(result.python_sources.items())

    loads = [[p] for p in ACCEPT if load_texts({str(p): p.read_text(encoding="utf-8")}).program is not None]
    loads.append(sorted((ROOT / "generated" / "iec").rglob("*.st")))
    gated = [compiled(p) for p in loads]
    closed = {"branched": 0, "may_reuse": 0, "flow": 0}
    real = {"branched": statements.branched, "may_reuse": statements.may_reuse}

    def opened(name):
        def gate(arg):
            usage = getattr(getattr(arg, "scope", None), "usage", None)     # (may_reuse's compiler)
            if usage is not None:
                usage.kinds = usage.kinds.real
            closed[name] += not real[name](arg)
            if usage is not None:
                usage.kinds = _EveryClass(usage.kinds)
            return True
        return gate

    usage_init, flow_init = Usage.__init__, ranges.Flow.__init__

    def every_class(self, *args):
        usage_init(self, *args)
        self.kinds = _EveryClass(self.kinds)

    def holding(self, *args):
        flow_init(self, *args)
        closed["flow"] += not self.bounds
        self.bounds = _Holding(self.bounds)

    monkeypatch.setattr(statements, "branched", opened("branched"))
    monkeypatch.setattr(statements, "may_reuse", opened("may_reuse"))
    monkeypatch.setattr(Usage, "__init__", every_class)
    monkeypatch.setattr(ranges.Flow, "__init__", holding)
    assert [compiled(p) for p in loads] == gated
    assert all(count > len(loads) // 2 for count in closed.values()), closed


def test_a_compiled_init_source_is_one_store_a_member_in_declaration_order():
    # `_install_init` writes an FB's `__init__` as `def _init_<n>(self):` and one line a
    # member at one indentation (four spaces): a constant as its literal, an aggregate from
    # its maker `_mk<n>()`; an FB without a variable stores nothing (`pass`, kept for reading).
    text = """
    FUNCTION_BLOCK F
    VAR_INPUT x : INT := 3; END_VAR
    VAR r : LREAL; a : ARRAY[1..2] OF INT; b : BOOL := TRUE; END_VAR
    END_FUNCTION_BLOCK
    FUNCTION_BLOCK Empty
    END_FUNCTION_BLOCK
    PROGRAM Main VAR f : F; e : Empty; END_VAR f(); e(); END_PROGRAM
    """
    compiled = compile_program(load_texts({"m.st": text}).program)
    source = compiled.python_sources["init:F"]
    lines = source.split("\n")
    assert lines[0].startswith("def _init_") and lines[0].endswith("(self):")
    maker = lines[3].split(" = ")[1]
    assert lines[1:] == ["    self.v_X = 3", "    self.v_R = 0.0", f"    self.v_A = {maker}",
                         "    self.v_B = True", ""]
    assert maker.startswith("_mk") and maker.endswith("()")
    assert type(compiled.namespace[maker[:-2]]()) is list
    cls = compiled.classes["F"]
    assert cls.__init__.__name__ == lines[0][4:].split("(")[0]        # compiled, not `_store_members`
    one, two = cls(), cls()
    assert (one.v_X, one.v_R, one.v_A, one.v_B) == (3, 0.0, [0, 0], True) and one.v_A is not two.v_A
    empty = compiled.python_sources["init:EMPTY"]
    assert empty.startswith("def _init_") and empty.endswith("(self):\n    pass\n") and empty.count("\n") == 2


@pytest.mark.parametrize("decl, expected", [
    ("BOOL", False), ("INT", 0), ("UDINT", 0), ("LREAL", 0.0), ("REAL", 0.0), ("WORD", 0),
    ("TIME", 0), ("INT (5..10)", 5), ("INT (-3..4)", -3), ("STRING", ""),
])
def test_a_variable_without_an_initializer_takes_its_types_default(decl: str, expected):
    # IEC 61131-3:2013 table 11: FALSE, 0, 0.0, T#0s (0 ns), the empty string; a subrange
    # starts at its lower limit (6.4.4.4).  The elementary defaults are made once a kind
    # (`initial._elementary_default`), a subrange's by its own bounds, each load of a
    # variable of another kind, before and after, its own.
    text = f"""
    FUNCTION_BLOCK F
    VAR before : LREAL; v : {decl}; after : BOOL; END_VAR
    END_FUNCTION_BLOCK
    PROGRAM Main VAR f : F; END_VAR f(); END_PROGRAM
    """
    for _ in range(2):
        fb = compile_program(load_texts({"m.st": text}).program).classes["F"]()
        assert type(fb.v_V) is type(expected) and fb.v_V == expected
        assert type(fb.v_BEFORE) is float and fb.v_AFTER is False


def test_type_and_member_initializers_are_read_from_every_file_in_one_pass():
    # IEC 61131-3:2013 table 11 (and 6.4.4.1): a derived type's initial value is the default of
    # every variable and STRUCT member of that type without its own; a member's own value wins.
    # `initial._initializers` reads both tables in one pass over the items of every file.
    first = """
    TYPE Pair : STRUCT a : Speed; b : Speed := 1.25; c : Count; END_STRUCT; END_TYPE
    PROGRAM Main VAR p : Pair; s : Speed; n : Count; q : Speed := 4.0; END_VAR
    p.a := p.a; END_PROGRAM
    """
    second = """
    TYPE Speed : LREAL := 2.5; END_TYPE
    TYPE Count : INT := 7; END_TYPE
    """
    compiled = compile_program(load_texts({"a.st": first, "b.st": second}).program)
    main = compiled.new("Main")
    assert (main.v_P.v_A, main.v_P.v_B, main.v_P.v_C) == (2.5, 1.25, 7)
    assert (main.v_S, main.v_N, main.v_Q) == (2.5, 7, 4.0)


def test_each_function_blocks_init_sets_its_own_variables_and_edge_inputs():
    # `_make_classes` lays out each FB's instance variables and edge inputs once, and
    # `_make_initializers` initialises from that layout: each FB its own (a derived FB its own
    # and the ones it inherits), an edge input's previous value FALSE (IEC 61131-3 6.5.1.2:
    # R_EDGE as an R_TRIG whose memory starts FALSE).
    text = """
    FUNCTION_BLOCK Base
    VAR_INPUT go : BOOL R_EDGE; END_VAR
    VAR a : INT := 1; END_VAR
    END_FUNCTION_BLOCK
    FUNCTION_BLOCK Child EXTENDS Base
    VAR b : LREAL := 2.5; END_VAR
    END_FUNCTION_BLOCK
    FUNCTION_BLOCK Other
    VAR_INPUT up : BOOL F_EDGE; END_VAR
    VAR c : DINT := -4; END_VAR
    END_FUNCTION_BLOCK
    PROGRAM Main VAR x : Base; y : Child; z : Other; END_VAR x(); y(); z(); END_PROGRAM
    """
    compiled = compile_program(load_texts({"m.st": text}).program)
    base, child, other = (compiled.classes[k]() for k in ("BASE", "CHILD", "OTHER"))
    assert (base.v_A, base.v_GO, base._edgev_GO) == (1, False, False) and not hasattr(base, "v_B")
    assert (child.v_A, child.v_B, child.v_GO, child._edgev_GO) == (1, 2.5, False, False)
    assert (other.v_C, other.v_UP, other._edgev_UP) == (-4, False, False) and not hasattr(other, "v_A")
