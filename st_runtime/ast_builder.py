"""Builds the AST while Lark's LALR parser reduces (no parse tree is built).

Each method is named after a grammar rule (or its `-> alias`) and receives the
rule's kept children inline.  Positions: a node's `pos` is its first token,
except `Binary`, whose pos is its operator (so a caret points at the `+`
whose operands do not fit), and `VarDecl`, whose pos is the variable's name.

Literal texts that the lexer accepts but that have no valid value (`2#102`,
`T#5x`) are reported through `errors` instead of raising, so one bad literal
does not stop the parse.
"""

from __future__ import annotations

import dataclasses
from bisect import bisect_right

from lark import Transformer, v_args

from . import ast
from .ast import Pos
from .diagnostics import Diagnostic
from .literals import (
    BOOL_TYPES,
    REAL_TYPES,
    LiteralError,
    abridged,
    decode_based,
    decode_date,
    decode_date_and_time,
    decode_duration,
    decode_int,
    decode_number,
    decode_real,
    decode_string,
    decode_time_of_day,
)

BAD_LITERAL = "E-PARSE-009"
MISPLACED_CASE_STATEMENT = "E-PARSE-010"
TOP_LEVEL_VAR = "E-PARSE-011"
BAD_TASK_PARAMETER = "E-PARSE-012"

_OPERATORS = {
    "OR": "OR", "XOR": "XOR", "AND": "AND", "AMP": "AND", "EQ": "=", "NE": "<>",
    "LT": "<", "GT": ">", "LE": "<=", "GE": ">=", "PLUS": "+", "MINUS": "-",
    "STAR": "*", "SLASH": "/", "MOD": "MOD", "POW": "**", "NOT": "NOT",
}
_STRUCTURED = (ast.If, ast.Case, ast.For, ast.While, ast.Repeat)


class _Labels(tuple):
    """The labels of one CASE clause, before the clause is assembled."""

    pos: ast.Pos


class _Resource(list):
    """The elements of a RESOURCE, flattened into its CONFIGURATION."""


def _statements(items) -> tuple:
    """Statements in order, without the `;` that customarily follows END_IF etc."""
    out = []
    previous = None
    for stmt in items:
        if type(stmt) is ast.Empty and isinstance(previous, _STRUCTURED):
            previous = None  # only the first `;` after END_xxx belongs to it
            continue
        out.append(stmt)
        previous = stmt
    return tuple(out)


_TRAILING = object()          # the marker of a trailing comma in an argument list


class _ArgsWithComma(tuple):
    """Arguments written with a trailing comma (`F(a, b,)`)."""


@v_args(inline=True)
class AstBuilder(Transformer):
    def __init__(self) -> None:
        super().__init__()
        self.path = "<input>"
        self.errors: list[Diagnostic] = []

    def reset(self, path: str) -> None:
        self.path = path
        self.errors = []

    def _pos(self, token) -> ast.Pos:
        try:        # a token of the fast loop: its text's line starts (lalr_fast._Token)
            starts, offset = token.lines.starts, token.start_pos
        except AttributeError:      # a token of Lark's own loop: counted as it lexed
            return Pos(self.path, token.line, token.column)
        # (lalr_fast._Lines.at, inline: a call less for each of a parse's thousands of nodes)
        line = bisect_right(starts, offset)
        return Pos(self.path, line, offset - starts[line - 1] + 1)

    def _error(self, code: str, message: str, pos: ast.Pos) -> None:
        self.errors.append(Diagnostic(code, message, pos))

    # ------------------------------------------------------------ file, POUs

    def start(self, *items):
        flat = []
        for item in items:
            if isinstance(item, list):
                flat.extend(item)
            else:
                if type(item) is ast.VarBlock and item.kind != "VAR_GLOBAL":
                    self._error(TOP_LEVEL_VAR, f"{item.kind} block outside a POU: only "
                                "VAR_GLOBAL may stand at the top level", item.pos)
                flat.append(item)
        return ast.SourceFile(self.path, tuple(flat), pos=ast.Pos(self.path, 1, 1))

    def program_decl(self, kw, name, *rest):
        body, sfc = _body_or_sfc(rest[-1])
        blocks = tuple(r for r in rest[:-1] if type(r) is ast.VarBlock)
        access = tuple(a for r in rest[:-1] if type(r) is _Access for a in r)
        return ast.Pou("PROGRAM", str(name), blocks, body, sfc=sfc, access=access, pos=self._pos(kw))

    def function_decl(self, kw, name, return_type, *rest):
        return ast.Pou("FUNCTION", str(name), tuple(rest[:-1]), rest[-1],
                       return_type, pos=self._pos(kw))

    def fb_decl(self, kw, *items):
        modifiers = tuple(i[1] for i in items if isinstance(i, tuple) and i and i[0] == "modifier")
        rest = [i for i in items if not (isinstance(i, tuple) and i and i[0] == "modifier")]
        name, extends, implements = rest[0], rest[1], rest[2]
        parts = [p for i in rest[3:-1] for p in (i if isinstance(i, list) else [i])]
        blocks = tuple(i for i in parts if type(i) is ast.VarBlock)
        methods = tuple(i for i in parts if type(i) is ast.Method)
        body, sfc = _body_or_sfc(rest[-1])
        return ast.Pou("FUNCTION_BLOCK", str(name), blocks, body, None,
                       extends or (), implements or (), methods, modifiers, sfc=sfc, pos=self._pos(kw))

    # ------------------------------------------------------------------ SFC
    def sfc(self, *elements):
        return ast.Sfc(tuple(e for e in elements if type(e) is ast.Step),
                       tuple(e for e in elements if type(e) is ast.Transition),
                       tuple(e for e in elements if type(e) is ast.Method), pos=elements[0].pos)

    def sfc_step(self, kw, name, *actions):
        return ast.Step(str(name), kw.type == "INITIAL_STEP", tuple(actions), pos=self._pos(kw))

    def action_association(self, action, qualifier=None, *rest):
        word = str(qualifier).upper() if qualifier is not None else "N"
        pos = self._pos(action)
        if word not in SFC_QUALIFIERS:
            self._error("E-PARSE-014", f"unknown action qualifier '{qualifier}' (IEC 61131-3: "
                        f"{', '.join(SFC_QUALIFIERS)})", self._pos(qualifier))
        timed = word in SFC_TIMED_QUALIFIERS
        time = rest[0] if timed and rest else None
        more = rest[1:] if timed else rest
        if timed and time is None:
            self._error("E-PARSE-014", f"action qualifier {word} needs a duration: "
                        f"{action}({word}, T#5s)", pos)
        indicator = None
        if len(more) == 1 and type(more[0]) is ast.Name:
            indicator = more[0].name
        elif more:
            self._error("E-PARSE-014", f"action {action}({word}, ...): expected "
                        + ("a duration and " if timed else "") + "at most an indicator variable", pos)
        return ast.ActionAssociation(str(action), word, time, indicator, pos=pos)

    def sfc_transition(self, kw, name, sources, targets, condition):
        return ast.Transition(sources, targets, condition, str(name) if name is not None else None,
                              pos=self._pos(kw))

    def sfc_steps(self, *names):
        return tuple(str(n) for n in names)

    def interface_decl(self, kw, name, extends, *methods):
        return ast.Pou("INTERFACE", str(name), (), (), None, extends or (), (), tuple(methods),
                       pos=self._pos(kw))

    def extends_clause(self, *names):
        return tuple(str(n) for n in names)

    implements_clause = extends_clause

    def pou_modifier(self, token):
        return ("modifier", str(token).upper())

    def qualified_name(self, *parts):
        return ".".join(str(p) for p in parts)

    def qualified_type(self, *parts):
        return ast.NamedType(".".join(str(p) for p in parts), pos=self._pos(parts[0]))

    def namespace_decl(self, kw, *rest):
        rest = [r for r in rest if r is not None and not (hasattr(r, "type") and r.type == "INTERNAL")]
        name, items = rest[0], rest[1:]
        out = []
        for item in items:
            for one in (item if isinstance(item, list) else [item]):
                if type(one) in (ast.Pou, ast.TypeDecl):
                    inner = f"{name}.{one.namespace}" if one.namespace else name
                    one = dataclasses.replace(one, namespace=inner)
                out.append(one)
        return out

    def using_directive(self, *names):
        return []          # names stay reachable by their short names (flattened)

    def property_decl(self, kw, *items):
        """A PROPERTY becomes up to two Methods: the getter (its result is the
        property) and the setter (its one input is the property)."""
        words = [i[1] for i in items if isinstance(i, tuple) and i and i[0] == "modifier"]
        rest = [i for i in items if not (isinstance(i, tuple) and i and i[0] == "modifier")]
        name, type_ref, getter, setter = rest
        access = next((w for w in words if w in ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL")), None)
        modifiers = tuple(w for w in words if w not in ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL"))
        methods = []
        if getter is not None:
            methods.append(ast.Method(str(name), getter[0], getter[1], type_ref, access,
                                      modifiers + ("GET",), pos=self._pos(name)))
        if setter is not None:
            value = ast.VarBlock("VAR_INPUT", (ast.VarDecl(str(name), type_ref, pos=self._pos(name)),),
                                 pos=self._pos(name))
            methods.append(ast.Method(str(name), (value,) + setter[0], setter[1], None, access,
                                      modifiers + ("SET",), pos=self._pos(name)))
        return methods

    def property_get(self, kw, *rest):
        return tuple(rest[:-1]), rest[-1]

    property_set = property_get

    def action_decl(self, kw, name, body):
        return ast.Method(str(name), (), body, None, "PUBLIC", ("ACTION",), pos=self._pos(name))

    def method_modifier(self, token):
        return ("modifier", str(token).upper())

    def method_decl(self, kw, *items):
        words = [i[1] for i in items if isinstance(i, tuple) and i and i[0] == "modifier"]
        rest = [i for i in items if not (isinstance(i, tuple) and i and i[0] == "modifier")]
        access = next((w for w in words if w in ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL")), None)
        modifiers = tuple(w for w in words if w not in ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL"))
        name, return_type = rest[0], rest[1]
        return ast.Method(str(name), tuple(rest[2:-1]), rest[-1], return_type, access, modifiers,
                          pos=self._pos(name))

    # ---------------------------------------------------------- declarations

    def var_block(self, kind, *rest):
        decls = []
        constant = retain = False
        for item in rest:
            if isinstance(item, str):
                if item == "CONSTANT":
                    constant = True
                elif item in ("RETAIN", "PERSISTENT"):
                    retain = True
            else:
                decls.extend(item)
        return ast.VarBlock(kind.type, tuple(decls), constant, retain, pos=self._pos(kind))

    def var_qualifier(self, token):
        return token.type

    def var_decl(self, *args):
        location, type_ref, edge, init = args[-4:]
        location = None if location is None else str(location).upper()
        return [ast.VarDecl(str(tok), type_ref, init, edge, location, pos=self._pos(tok))
                for tok in args[:-4]]

    def edge(self, token):
        return str(token).upper()

    def bare_array_init(self, *items):
        items = tuple(i if type(i) is ast.ArrayInitItem else ast.ArrayInitItem(i, pos=i.pos)
                      for i in items)
        return ast.ArrayInit(items, pos=items[0].pos)

    def array_init(self, *items):
        return ast.ArrayInit(items, pos=items[0].pos)

    def init_item(self, value):
        if type(value) is ast.ArrayInitItem:
            return value
        return ast.ArrayInitItem(value, pos=value.pos)

    def repeat_item(self, count, value):
        count_node = self.int_literal(count)
        return ast.ArrayInitItem(value, count_node, pos=count_node.pos)

    def struct_init(self, *fields):
        return ast.StructInit(fields, pos=fields[0].pos)

    def field_init(self, name, value):
        return ast.FieldInit(str(name), value, pos=self._pos(name))

    def named_type(self, name):
        return ast.NamedType(str(name), pos=self._pos(name))

    def string_type(self, kw, length):
        return ast.StringType(length, False, pos=self._pos(kw))

    def wstring_type(self, kw, length):
        return ast.StringType(length, True, pos=self._pos(kw))

    def string_length(self, expr):
        return expr

    def array_type(self, kw, *rest):
        return ast.ArrayType(tuple(rest[:-1]), rest[-1], pos=self._pos(kw))

    def open_range(self, star):
        return None

    def subrange(self, lo, hi):
        return ast.Subrange(lo, hi, pos=lo.pos)

    def type_block(self, *decls):
        return list(decls)

    def type_decl(self, name, spec, init):
        return ast.TypeDecl(str(name), spec, init, pos=self._pos(name))

    def struct_decl(self, name, spec):
        return ast.TypeDecl(str(name), spec, None, pos=self._pos(name))

    def struct_type(self, kw, *decls):
        members = []
        for group in decls:
            members.extend(group)
        return ast.StructType(tuple(members), pos=self._pos(kw))

    def union_type(self, kw, *decls):
        return ast.StructType(tuple(m for group in decls for m in group), True, pos=self._pos(kw))

    def enum_type(self, *args):
        values = args[:-1]  # the last child is the optional base type (ignored)
        return ast.EnumType(tuple(values), pos=values[0].pos)

    def enum_value(self, name, value):
        return ast.EnumValue(str(name), value, pos=self._pos(name))

    # --------------------------------------------------------- configuration

    def configuration(self, kw, name, *elements):
        globals_, tasks, programs, inits, access = [], [], [], [], []
        stack = list(elements)
        while stack:
            element = stack.pop(0)
            if isinstance(element, _Resource):
                stack[0:0] = element
            elif type(element) is ast.VarBlock:
                globals_.append(element)
            elif type(element) is ast.TaskDecl:
                tasks.append(element)
            elif isinstance(element, _Access):       # VAR_ACCESS ... END_VAR
                access.extend(element)
            elif isinstance(element, list):          # VAR_CONFIG ... END_VAR
                inits.extend(element)
            else:
                programs.append(element)
        return ast.Configuration(str(name), tuple(globals_), tuple(tasks), tuple(programs),
                                 tuple(inits), tuple(access), pos=self._pos(kw))

    def var_access(self, *paths):
        return _Access(paths)

    def access_path(self, name, path, type_ref, direction):
        return ast.AccessPath(str(name), path, type_ref,
                              direction is not None and direction.type == "READ_WRITE",
                              pos=self._pos(name))

    def var_config(self, *inits):
        return list(inits)

    def config_init(self, *parts):
        *path, location, type_ref, init = parts
        return ast.ConfigInit(tuple(str(p) for p in path), type_ref, init,
                              str(location) if location is not None else None, pos=self._pos(path[0]))

    def resource(self, kw, name, processor, *elements):
        return _Resource(elements)

    def task_decl(self, kw, name, *params):
        values = {"INTERVAL": None, "PRIORITY": None}
        for param in params:
            if param is None:
                continue
            key, value = param
            if key.upper() in values:
                values[key.upper()] = value
            elif key.upper() != "SINGLE":
                self._error(BAD_TASK_PARAMETER, f"unknown TASK parameter '{key}': expected "
                            "INTERVAL, PRIORITY or SINGLE", value.pos)
        return ast.TaskDecl(str(name), values["INTERVAL"], values["PRIORITY"], pos=self._pos(kw))

    def task_param(self, name, value):
        return (str(name), value)

    def program_config(self, kw, name, task, program_type, connections=None):
        return ast.ProgramInstance(str(name), str(task) if task is not None else None,
                                   str(program_type), tuple(connections or ()), pos=self._pos(kw))

    # ------------------------------------------------------------ statements

    def stmt_list(self, *stmts):
        return _statements(stmts)

    def assign_stmt(self, target, value):
        return ast.Assign(target, value, pos=target.pos)

    def set_reset_stmt(self, target, op, value):
        return ast.Assign(target, value, str(op).upper(), pos=target.pos)

    def call_stmt(self, callee, args):
        call = ast.Call(callee, tuple(args or ()), type(args) is _ArgsWithComma, pos=callee.pos)
        return ast.CallStmt(call, pos=callee.pos)

    def if_stmt(self, kw, condition, body, *rest):
        pos = self._pos(kw)
        branches = [ast.IfBranch(condition, body, pos=pos)]
        branches.extend(rest[:-1])
        return ast.If(tuple(branches), rest[-1], pos=pos)

    def elsif_branch(self, kw, condition, body):
        return ast.IfBranch(condition, body, pos=self._pos(kw))

    def else_part(self, body):
        return body

    def case_stmt(self, kw, selector, *parts):
        clauses = []
        labels = None
        body: list = []
        for part in parts[:-1]:
            if type(part) is _Labels:
                if labels is not None:
                    clauses.append(ast.CaseClause(tuple(labels), _statements(body), pos=labels.pos))
                labels, body = part, []
            elif labels is None:
                self._error(MISPLACED_CASE_STATEMENT, "expected a CASE label (e.g. '1:') "
                            "before the first statement of the CASE", part.pos)
            else:
                body.append(part)
        if labels is not None:
            clauses.append(ast.CaseClause(tuple(labels), _statements(body), pos=labels.pos))
        return ast.Case(selector, tuple(clauses), parts[-1], pos=self._pos(kw))

    def case_labels(self, *labels):
        result = _Labels(labels)
        result.pos = labels[0].pos
        return result

    def case_range(self, lo, hi):
        return ast.CaseRange(lo, hi, pos=lo.pos)

    def for_stmt(self, kw, variable, start, end, step, body):
        return ast.For(str(variable), start, end, step, body, pos=self._pos(kw))

    def while_stmt(self, kw, condition, body):
        return ast.While(condition, body, pos=self._pos(kw))

    def repeat_stmt(self, kw, body, condition):
        return ast.Repeat(body, condition, pos=self._pos(kw))

    def exit_stmt(self, kw):
        return ast.Exit(pos=self._pos(kw))

    def continue_stmt(self, kw):
        return ast.Continue(pos=self._pos(kw))

    def return_stmt(self, kw):
        return ast.Return(pos=self._pos(kw))

    def empty_stmt(self, semi):
        return ast.Empty(pos=self._pos(semi))

    # ----------------------------------------------------------- expressions

    def binary(self, left, op, right):
        return ast.Binary(_OPERATORS[op.type], left, right, pos=self._pos(op))

    def unary(self, op, operand):
        return ast.Unary(_OPERATORS[op.type], operand, pos=self._pos(op))

    def call(self, callee, args):
        return ast.Call(callee, tuple(args or ()), type(args) is _ArgsWithComma, pos=callee.pos)

    def subrange_type(self, base, subrange):
        return ast.SubrangeType(str(base), subrange, pos=self._pos(base))

    def ref_type(self, kw, target):
        return ast.RefType(target, pos=self._pos(kw))

    def pointer_type(self, kw, target):
        return ast.RefType(target, True, pos=self._pos(kw))

    def deref(self, base, caret):
        return ast.Deref(base, pos=base.pos)

    def bit_access(self, base, bit):
        return ast.BitAccess(base, int(str(bit).replace("_", "")), pos=base.pos)

    def partial_access(self, base, token):
        text = str(token)
        return ast.BitAccess(base, int(text[2:]), text[1].upper(), pos=base.pos)

    def direct_var(self, token):
        return ast.DirectVar(str(token).upper(), pos=self._pos(token))

    def unnamed_located(self, address, type_ref, init):
        """`AT %IX1.1 : BOOL;` (no name: the code writes %IX1.1 itself)."""
        return [ast.VarDecl("", type_ref, init, None, str(address).upper(), pos=self._pos(address))]

    def null_literal(self, token):
        return ast.NullLiteral(pos=self._pos(token))

    def keyword_callee(self, token):
        return ast.Name(str(token), pos=self._pos(token))

    def name(self, token):
        return ast.Name(str(token), pos=self._pos(token))

    def member(self, base, name):
        return ast.Member(base, str(name), pos=base.pos)

    def index(self, base, *indices):
        return ast.Index(base, indices, pos=base.pos)

    def arg_list(self, *args):
        if args and args[-1] is None:
            return args[:-1]
        if args and args[-1] is _TRAILING:
            return _ArgsWithComma(args[:-1])
        return args

    def trailing_comma(self):
        return _TRAILING

    def positional_arg(self, value):
        return ast.Arg(None, value, pos=value.pos)

    def input_arg(self, name, value):
        return ast.Arg(str(name), value, "in", pos=self._pos(name))

    def output_arg(self, name, target):
        return ast.Arg(str(name), target, "out", pos=self._pos(name))

    def negated_output_arg(self, kw, name, target):
        return ast.Arg(str(name), target, "out", True, pos=self._pos(kw))

    # -------------------------------------------------------------- literals

    def _decode(self, decoder, token, fallback):
        try:
            return decoder(str(token))
        except (LiteralError, ValueError, OverflowError) as exc:
            self._error(BAD_LITERAL, f"invalid literal {abridged(str(token))}: {exc}", self._pos(token))
            return fallback

    def int_literal(self, token):
        text = str(token)
        if len(text) < 20 and text.isdigit() and text.isascii():    # (`0`, `42`: most literals)
            value = int(text)       # what decode_int gives plain digits: no `_`, far in bounds
        else:
            value = self._decode(decode_int, token, 0)
        return ast.IntLiteral(value, pos=self._pos(token))

    def based_literal(self, token):
        return ast.IntLiteral(self._decode(decode_based, token, 0), pos=self._pos(token))

    def real_literal(self, token):
        return ast.RealLiteral(self._decode(decode_real, token, 0.0), pos=self._pos(token))

    def time_literal(self, token):
        return ast.TimeLiteral(self._decode(decode_duration, token, 0), pos=self._pos(token))

    def date_literal(self, token):
        return ast.DateTimeLiteral("DATE", self._decode(decode_date, token, 0),
                                   pos=self._pos(token))

    def tod_literal(self, token):
        return ast.DateTimeLiteral("TOD", self._decode(decode_time_of_day, token, 0),
                                   pos=self._pos(token))

    def dt_literal(self, token):
        return ast.DateTimeLiteral("DT", self._decode(decode_date_and_time, token, 0),
                                   pos=self._pos(token))

    def string_literal(self, token):
        return ast.StringLiteral(self._decode(decode_string, token, ""), pos=self._pos(token))

    def wstring_literal(self, token):
        return ast.StringLiteral(self._decode(decode_string, token, ""), True,
                                 pos=self._pos(token))

    def typed_string_literal(self, token):
        """STRING#'ABC' is 'ABC'; WSTRING#"ABC" is "ABC" (the prefix only repeats the type)."""
        prefix, _, body = str(token).partition("#")
        quoted = token.update(value=body)
        wide = prefix.upper() == "WSTRING"
        if wide != body.startswith('"'):
            self._error(BAD_LITERAL, f"{prefix.upper()}# takes a string in "
                        + ('"double quotes"' if wide else "'single quotes'"), self._pos(token))
        return self.wstring_literal(quoted) if wide else self.string_literal(quoted)

    def bool_literal(self, token):
        return ast.BoolLiteral(token.type == "TRUE", pos=self._pos(token))

    def typed_literal(self, token):
        pos = self._pos(token)
        prefix, _, body = str(token).partition("#")
        type_name = prefix.upper()
        if body[:1].isalpha() or body[:1] == "_":
            if type_name in BOOL_TYPES and body.upper() in ("TRUE", "FALSE"):
                return ast.BoolLiteral(body.upper() == "TRUE", type_name, pos=pos)
            return ast.EnumLiteral(prefix, body, pos=pos)
        try:
            value = decode_number(body)
        except (LiteralError, ValueError, OverflowError) as exc:
            self._error(BAD_LITERAL, f"invalid literal {abridged(str(token))}: {exc}", pos)
            value = 0
        if type_name in REAL_TYPES:
            return ast.RealLiteral(float(value), type_name, pos=pos)
        if isinstance(value, float):
            self._error(BAD_LITERAL, f"invalid literal '{token}': {type_name} needs an "
                        "integer value", pos)
            value = 0
        if type_name in BOOL_TYPES:
            if value not in (0, 1):
                self._error(BAD_LITERAL, f"invalid literal '{token}': BOOL# takes 0 or 1", pos)
            return ast.BoolLiteral(bool(value), type_name, pos=pos)
        return ast.IntLiteral(value, type_name, pos=pos)

    # ------------------------------------------------------------ test files
    # (grammar.lark, block "test files"; parser.parse_tests)

    def test_file(self, *items):
        return self.start(*items)

    def test_setup(self, kw, *rest):
        return ast.TestSetup(tuple(rest[:-1]), rest[-1], pos=self._pos(kw))

    def test_teardown(self, kw, body):
        return ast.TestTeardown(body, pos=self._pos(kw))

    def test_case(self, kw, name, *rest):
        title = self._decode(decode_string, name, "")
        return ast.TestCase(title, tuple(rest[:-1]), rest[-1], pos=self._pos(kw))


# IEC 61131-3 3rd ed. table 60 (action qualifiers); the timed ones take a duration.
SFC_QUALIFIERS = ("N", "R", "S", "P", "L", "D", "SD", "DS", "SL", "P1", "P0")
SFC_TIMED_QUALIFIERS = frozenset({"L", "D", "SD", "DS", "SL"})


def _body_or_sfc(body):
    """(statements, None) for a statement body, ((), Sfc) for a chart."""
    return ((), body) if type(body) is ast.Sfc else (body, None)


class _Access(tuple):
    """The paths of one VAR_ACCESS block, until the POU or configuration takes them."""
