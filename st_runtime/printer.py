"""Print the AST back as clean, conventionally indented Structured Text.

`parse(format_source(f))` equals `f` for every file the parser produces: the
printer adds parentheses only where IEC precedence needs them, writes literals
in a form that decodes to the same value, and ends every structured statement
with `END_xxx;`.

    format_source(file)  the whole file
    format_stmt(stmt)    one statement (possibly several lines)
    format_expr(expr)    one expression
"""

from __future__ import annotations

from . import ast
from .literals import (
    encode_date,
    encode_date_and_time,
    encode_duration,
    encode_string,
    encode_time_of_day,
)

INDENT = "    "

# Binding strength, loosest first.  `**` binds tighter than the unary
# operators: `-a ** b` is `-(a ** b)`.
_BINARY_LEVEL = {
    "OR": 1, "XOR": 2, "AND": 3, "&": 3, "=": 4, "<>": 4,
    "<": 5, ">": 5, "<=": 5, ">=": 5, "+": 6, "-": 6,
    "*": 7, "/": 7, "MOD": 7, "**": 9,
}
_UNARY_LEVEL = 8
_ATOM_LEVEL = 10


def _level(expr) -> int:
    kind = type(expr)
    if kind is ast.Binary:
        return _BINARY_LEVEL[expr.op]
    if kind is ast.Unary:
        return _UNARY_LEVEL
    if kind is ast.IntLiteral and expr.value < 0 and expr.type_prefix is None:
        return _UNARY_LEVEL  # printed as `-5`, which reads back as a unary minus
    if kind is ast.RealLiteral and _is_negative(expr.value) and expr.type_prefix is None:
        return _UNARY_LEVEL
    return _ATOM_LEVEL


def _is_negative(value: float) -> bool:
    return value < 0 or (value == 0 and str(value).startswith("-"))


def _wrap(expr, parenthesise: bool) -> str:
    text = format_expr(expr)
    return f"({text})" if parenthesise else text


# --------------------------------------------------------------- expressions


def format_expr(expr) -> str:
    """One expression, parenthesised only where precedence requires."""
    kind = type(expr)
    if kind is ast.Name:
        return expr.name
    if kind is ast.Binary:
        return _format_binary(expr)
    if kind is ast.Unary:
        operand = _wrap(expr.operand, _level(expr.operand) < _UNARY_LEVEL)
        if expr.op == "NOT":
            return f"NOT {operand}"
        if operand[:1] in "+-":
            operand = f"({operand})"
        return f"{expr.op}{operand}"
    if kind is ast.IntLiteral:
        prefix = f"{expr.type_prefix}#" if expr.type_prefix else ""
        return f"{prefix}{expr.value}"
    if kind is ast.RealLiteral:
        return _format_real(expr)
    if kind is ast.BoolLiteral:
        word = "TRUE" if expr.value else "FALSE"
        return f"{expr.type_prefix}#{word}" if expr.type_prefix else word
    if kind is ast.StringLiteral:
        return encode_string(expr.value, expr.wide)
    if kind is ast.TimeLiteral:
        return encode_duration(expr.nanoseconds)
    if kind is ast.DateTimeLiteral:
        return {"DATE": encode_date, "TOD": encode_time_of_day,
                "DT": encode_date_and_time}[expr.kind](expr.nanoseconds)
    if kind is ast.EnumLiteral:
        return f"{expr.type_name}#{expr.value_name}"
    if kind is ast.Member:
        return f"{_postfix_base(expr.base)}.{expr.name}"
    if kind is ast.Index:
        indices = ", ".join(format_expr(i) for i in expr.indices)
        return f"{_postfix_base(expr.base)}[{indices}]"
    if kind is ast.Call:
        comma = "," if expr.trailing_comma else ""
        return f"{_postfix_base(expr.callee)}({_format_args(expr.args)}{comma})"
    if kind is ast.Deref:
        return f"{_postfix_base(expr.base)}^"
    if kind is ast.BitAccess:
        size = f"%{expr.size}" if expr.size else ""
        return f"{_postfix_base(expr.base)}.{size}{expr.bit}"
    if kind is ast.NullLiteral:
        return "NULL"
    if kind is ast.DirectVar:
        return expr.address
    raise TypeError(f"not an expression node: {kind.__name__}")


def _format_binary(expr: ast.Binary) -> str:
    """`a + b - c ...`: the left spine of one precedence level is walked in a
    loop, so a generated sum of thousands of terms does not exhaust the stack."""
    level = _BINARY_LEVEL[expr.op]
    tail = []
    node = expr
    while type(node) is ast.Binary and _BINARY_LEVEL[node.op] == level:
        # Left-associative: an equal-level right operand needs parentheses.
        right = _wrap(node.right, _level(node.right) <= level)
        tail.append(f" {'AND' if node.op == '&' else node.op} {right}")
        node = node.left
    head = _wrap(node, _level(node) < level)
    return head + "".join(reversed(tail))


def _postfix_base(expr) -> str:
    text = format_expr(expr)
    return text if type(expr) in (ast.Name, ast.Member, ast.Index, ast.Deref, ast.BitAccess, ast.DirectVar) else f"({text})"


def _format_real(expr: ast.RealLiteral) -> str:
    value = expr.value
    if value != value or value in (float("inf"), float("-inf")):
        raise ValueError(f"REAL value {value} has no ST literal")
    text = repr(abs(value)) if expr.type_prefix is None else repr(value)
    if "e" in text or "E" in text:
        mantissa, _, exponent = text.partition("e")
        if "." not in mantissa:
            mantissa += ".0"
        text = f"{mantissa}E{exponent}"
    elif "." not in text:
        text += ".0"
    if expr.type_prefix:
        return f"{expr.type_prefix}#{text}"
    return f"-{text}" if _is_negative(value) else text


def _format_args(args) -> str:
    parts = []
    for arg in args:
        if arg.name is None:
            parts.append(format_expr(arg.value))
        elif arg.direction == "out":
            target = "" if arg.value is None else " " + format_expr(arg.value)
            parts.append(f"{'NOT ' if arg.negated else ''}{arg.name} =>{target}")
        else:
            parts.append(f"{arg.name} := {format_expr(arg.value)}")
    return ", ".join(parts)


# ---------------------------------------------------------------- statements


def format_stmt(stmt, indent: str = "") -> str:
    """One statement; nested statements indented by four spaces per level."""
    return "\n".join(_stmt_lines(stmt, indent))


def _body(stmts, indent: str) -> list[str]:
    lines: list[str] = []
    for stmt in stmts:
        lines.extend(_stmt_lines(stmt, indent))
    return lines


def _stmt_lines(stmt, indent: str) -> list[str]:
    kind = type(stmt)
    inner = indent + INDENT
    if kind is ast.Assign:
        return [f"{indent}{format_expr(stmt.target)} {stmt.mode} {format_expr(stmt.value)};"]
    if kind is ast.CallStmt:
        return [f"{indent}{format_expr(stmt.call)};"]
    if kind is ast.If:
        lines = []
        for number, branch in enumerate(stmt.branches):
            keyword = "IF" if number == 0 else "ELSIF"
            lines.append(f"{indent}{keyword} {format_expr(branch.condition)} THEN")
            lines.extend(_body(branch.body, inner))
        if stmt.else_body is not None:
            lines.append(f"{indent}ELSE")
            lines.extend(_body(stmt.else_body, inner))
        lines.append(f"{indent}END_IF;")
        return lines
    if kind is ast.Case:
        lines = [f"{indent}CASE {format_expr(stmt.selector)} OF"]
        for clause in stmt.clauses:
            labels = ", ".join(_format_label(label) for label in clause.labels)
            lines.append(f"{inner}{labels}:")
            lines.extend(_body(clause.body, inner + INDENT))
        if stmt.else_body is not None:
            lines.append(f"{indent}ELSE")
            lines.extend(_body(stmt.else_body, inner))
        lines.append(f"{indent}END_CASE;")
        return lines
    if kind is ast.For:
        step = f" BY {format_expr(stmt.step)}" if stmt.step is not None else ""
        lines = [f"{indent}FOR {stmt.variable} := {format_expr(stmt.start)} TO "
                 f"{format_expr(stmt.end)}{step} DO"]
        lines.extend(_body(stmt.body, inner))
        lines.append(f"{indent}END_FOR;")
        return lines
    if kind is ast.While:
        lines = [f"{indent}WHILE {format_expr(stmt.condition)} DO"]
        lines.extend(_body(stmt.body, inner))
        lines.append(f"{indent}END_WHILE;")
        return lines
    if kind is ast.Repeat:
        lines = [f"{indent}REPEAT"]
        lines.extend(_body(stmt.body, inner))
        lines.append(f"{indent}UNTIL {format_expr(stmt.condition)}")
        lines.append(f"{indent}END_REPEAT;")
        return lines
    if kind is ast.Exit:
        return [f"{indent}EXIT;"]
    if kind is ast.Continue:
        return [f"{indent}CONTINUE;"]
    if kind is ast.Return:
        return [f"{indent}RETURN;"]
    if kind is ast.Empty:
        return [f"{indent};"]
    raise TypeError(f"not a statement node: {kind.__name__}")


def _format_label(label) -> str:
    if type(label) is ast.CaseRange:
        return f"{format_expr(label.lo)}..{format_expr(label.hi)}"
    return format_expr(label)


# -------------------------------------------------------------- declarations


def format_type(type_ref) -> str:
    kind = type(type_ref)
    if kind is ast.NamedType:
        return type_ref.name
    if kind is ast.StringType:
        word = "WSTRING" if type_ref.wide else "STRING"
        if type_ref.length is None:
            return word
        return f"{word}[{format_expr(type_ref.length)}]"
    if kind is ast.ArrayType:
        ranges = ", ".join("*" if r is None else f"{format_expr(r.lo)}..{format_expr(r.hi)}"
                           for r in type_ref.ranges)
        return f"ARRAY[{ranges}] OF {format_type(type_ref.element)}"
    if kind is ast.RefType:
        return ("POINTER TO " if type_ref.pointer else "REF_TO ") + format_type(type_ref.target)
    if kind is ast.SubrangeType:
        return f"{type_ref.base} ({format_expr(type_ref.range.lo)}..{format_expr(type_ref.range.hi)})"
    raise TypeError(f"not a type reference: {kind.__name__}")


def format_initializer(init) -> str:
    kind = type(init)
    if kind is ast.ArrayInit:
        return "[" + ", ".join(_format_init_item(item) for item in init.items) + "]"
    if kind is ast.StructInit:
        fields = ", ".join(f"{f.name} := {format_initializer(f.value)}" for f in init.fields)
        return f"({fields})"
    return format_expr(init)


def _format_init_item(item: ast.ArrayInitItem) -> str:
    value = "" if item.value is None else format_initializer(item.value)
    if item.count is None:
        return value
    return f"{format_expr(item.count)}({value})"


def _decl_line(decl: ast.VarDecl, indent: str) -> str:
    init = "" if decl.init is None else f" := {format_initializer(decl.init)}"
    edge = "" if decl.edge is None else f" {decl.edge}"
    at = "" if decl.location is None else f" AT {decl.location}"
    if not decl.name:                      # an unnamed located variable
        return f"{indent}AT {decl.location} : {format_type(decl.type)}{init};"
    return f"{indent}{decl.name}{at} : {format_type(decl.type)}{edge}{init};"


def _var_block_lines(block: ast.VarBlock, indent: str) -> list[str]:
    qualifiers = (" CONSTANT" if block.constant else "") + (" RETAIN" if block.retain else "")
    lines = [f"{indent}{block.kind}{qualifiers}"]
    lines.extend(_decl_line(decl, indent + INDENT) for decl in block.decls)
    lines.append(f"{indent}END_VAR")
    return lines


def _type_spec(spec, indent: str) -> str:
    kind = type(spec)
    if kind is ast.StructType:
        members = [_decl_line(m, indent + INDENT) for m in spec.members]
        word = "UNION" if spec.union else "STRUCT"
        return "\n".join([word, *members, f"{indent}END_{word}"])
    if kind is ast.EnumType:
        values = []
        for value in spec.values:
            values.append(value.name if value.value is None
                          else f"{value.name} := {format_expr(value.value)}")
        return "(" + ", ".join(values) + ")"
    return format_type(spec)


def _type_decl_lines(decl: ast.TypeDecl, indent: str) -> list[str]:
    init = "" if decl.init is None else f" := {format_initializer(decl.init)}"
    return [f"{indent}{decl.name} : {_type_spec(decl.spec, indent)}{init};"]


def _pou_lines(pou: ast.Pou) -> list[str]:
    header = " ".join([pou.kind, *pou.modifiers, pou.name])
    if pou.return_type is not None:
        header += f" : {format_type(pou.return_type)}"
    if pou.extends:
        header += " EXTENDS " + ", ".join(pou.extends)
    if pou.implements:
        header += " IMPLEMENTS " + ", ".join(pou.implements)
    lines = [header]
    for block in pou.var_blocks:
        lines.extend(_var_block_lines(block, ""))
    lines.extend(_access_lines(pou.access, ""))
    methods = list(pou.methods)
    while methods:
        method = methods.pop(0)
        if "GET" in method.modifiers or "SET" in method.modifiers:
            pair = [method]
            if methods and "SET" in methods[0].modifiers and "GET" in method.modifiers \
                    and methods[0].name == method.name:
                pair.append(methods.pop(0))
            lines.extend(_property_lines(pair, INDENT))
        else:
            lines.extend(_method_lines(method, INDENT))
    lines.extend(_body(pou.body, INDENT))
    if pou.sfc is not None:
        lines.extend(_sfc_lines(pou.sfc, INDENT))
    lines.append(f"END_{pou.kind}")
    return lines


def _sfc_lines(sfc: ast.Sfc, indent: str) -> list[str]:
    """Steps, then transitions, then actions (the chart does not depend on their order)."""
    lines = []
    for step in sfc.steps:
        lines.append(f"{indent}{'INITIAL_STEP' if step.initial else 'STEP'} {step.name}:")
        for a in step.actions:
            args = [a.qualifier] + ([format_expr(a.time)] if a.time is not None else []) \
                + ([a.indicator] if a.indicator else [])
            lines.append(f"{indent}{INDENT}{a.action}({', '.join(args)});")
        lines.append(f"{indent}END_STEP")
    for t in sfc.transitions:
        steps = [s[0] if len(s) == 1 else f"({', '.join(s)})" for s in (t.sources, t.targets)]
        name = f" {t.name}" if t.name else ""
        lines.append(f"{indent}TRANSITION{name} FROM {steps[0]} TO {steps[1]} := "
                     f"{format_expr(t.condition)};")
        lines.append(f"{indent}END_TRANSITION")
    for action in sfc.actions:
        lines.extend(_method_lines(action, indent))
    return lines


def _property_lines(accessors: list, indent: str) -> list[str]:
    first = accessors[0]
    words = ["PROPERTY", *([first.access] if first.access else []),
             *[m for m in first.modifiers if m not in ("GET", "SET")], first.name]
    prop_type = first.return_type if "GET" in first.modifiers else first.var_blocks[0].decls[0].type
    lines = [f"{indent}{' '.join(words)} : {format_type(prop_type)}"]
    for accessor in accessors:
        word = "GET" if "GET" in accessor.modifiers else "SET"
        blocks = accessor.var_blocks if word == "GET" else accessor.var_blocks[1:]
        lines.append(f"{indent}{word}")
        for block in blocks:
            lines.extend(_var_block_lines(block, indent + INDENT))
        lines.extend(_body(accessor.body, indent + INDENT + INDENT))
        lines.append(f"{indent}END_{word}")
    lines.append(f"{indent}END_PROPERTY")
    return lines


def _method_lines(method: ast.Method, indent: str) -> list[str]:
    if "ACTION" in method.modifiers:
        return [f"{indent}ACTION {method.name}:", *_body(method.body, indent + INDENT),
                f"{indent}END_ACTION"]
    words = ["METHOD", *([method.access] if method.access else []), *method.modifiers, method.name]
    header = indent + " ".join(words)
    if method.return_type is not None:
        header += f" : {format_type(method.return_type)}"
    lines = [header]
    for block in method.var_blocks:
        lines.extend(_var_block_lines(block, indent))
    lines.extend(_body(method.body, indent + INDENT))
    lines.append(f"{indent}END_METHOD")
    return lines


def _access_lines(paths, indent: str) -> list[str]:
    if not paths:
        return []
    lines = [f"{indent}VAR_ACCESS"]
    for a in paths:
        lines.append(f"{indent}{INDENT}{a.name} : {format_expr(a.path)} : {format_type(a.type)}"
                     f"{' READ_WRITE' if a.read_write else ' READ_ONLY'};")
    return lines + [f"{indent}END_VAR"]


def _configuration_lines(config: ast.Configuration) -> list[str]:
    lines = [f"CONFIGURATION {config.name}"]
    for block in config.globals:
        lines.extend(_var_block_lines(block, INDENT))
    for task in config.tasks:
        params = []
        if task.interval is not None:
            params.append(f"INTERVAL := {format_expr(task.interval)}")
        if task.priority is not None:
            params.append(f"PRIORITY := {format_expr(task.priority)}")
        lines.append(f"{INDENT}TASK {task.name}({', '.join(params)});")
    for program in config.programs:
        with_task = f" WITH {program.task}" if program.task else ""
        connections = f" ({_format_args(program.connections)})" if program.connections else ""
        lines.append(f"{INDENT}PROGRAM {program.name}{with_task} : {program.program_type}"
                     f"{connections};")
    if config.config_inits:
        lines.append(f"{INDENT}VAR_CONFIG")
        for init in config.config_inits:
            at = f" AT {init.location}" if init.location else ""
            value = f" := {format_initializer(init.init)}" if init.init is not None else ""
            lines.append(f"{INDENT}{INDENT}{'.'.join(init.path)}{at} : {format_type(init.type)}{value};")
        lines.append(f"{INDENT}END_VAR")
    lines.extend(_access_lines(config.access, INDENT))
    lines.append("END_CONFIGURATION")
    return lines


def format_source(file: ast.SourceFile) -> str:
    """The whole file: items separated by a blank line, ending in a newline."""
    chunks: list[str] = []
    pending_types: list[str] = []

    def flush_types() -> None:
        if pending_types:
            chunks.append("\n".join(["TYPE", *pending_types, "END_TYPE"]))
            pending_types.clear()

    for item in file.items:
        kind = type(item)
        if kind is ast.TypeDecl and item.namespace:
            flush_types()
            chunks.append("\n".join([f"NAMESPACE {item.namespace}", "TYPE",
                                     *_type_decl_lines(item, INDENT), "END_TYPE", "END_NAMESPACE"]))
            continue
        if kind is ast.TypeDecl:
            pending_types.extend(_type_decl_lines(item, INDENT))
            continue
        flush_types()
        if kind is ast.Pou and item.namespace:
            chunks.append("\n".join([f"NAMESPACE {item.namespace}", *_pou_lines(item), "END_NAMESPACE"]))
        elif kind is ast.Pou:
            chunks.append("\n".join(_pou_lines(item)))
        elif kind is ast.VarBlock:
            chunks.append("\n".join(_var_block_lines(item, "")))
        elif kind is ast.Configuration:
            chunks.append("\n".join(_configuration_lines(item)))
        else:
            raise TypeError(f"not a top-level item: {kind.__name__}")
    flush_types()
    return "\n\n".join(chunks) + "\n" if chunks else ""
