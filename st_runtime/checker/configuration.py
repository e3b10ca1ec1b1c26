"""A CONFIGURATION's program connections, VAR_CONFIG and VAR_ACCESS (IEC 61131-3 3rd ed. 6.8.2).

They are checked, not applied: st_runtime checks configurations but does not
run them (`stgen run --program` picks the program), so a connection or a
VAR_CONFIG value changes nothing at run time, and an access path (a name
for remote access, also declared in a PROGRAM) is read by nothing.
"""

from __future__ import annotations

from .. import ast
from .. import types as T
from ..ast import key
from . import typesys as ts
from .stores import check_store


def check_connections(ctx, inst: ast.ProgramInstance, info, ex) -> None:
    """`PROGRAM G : P (In := source, Out => sink)`: an input fed by a value, an output
    written to a variable or a direct address, each of the program's type."""
    for arg in inst.connections:
        if arg.name is None:
            ctx.error("E-CALL-002", f"program instance {inst.name}: a connection names an input "
                      f"or output of {info.name} (In := %IX0.0, Out => %QX0.0)", arg.pos)
            continue
        what = f"connection {inst.name}.{arg.name}"
        sym = info.variables.get(key(arg.name))
        wanted = ("VAR_INPUT", "VAR_IN_OUT") if arg.direction == "in" else ("VAR_OUTPUT",)
        if sym is None or sym.kind not in ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT"):
            ctx.error("E-CALL-002", f"{what}: PROGRAM {info.name} has no input or output "
                      f"'{arg.name}'", arg.pos)
        elif sym.kind not in wanted:
            ctx.error("E-CALL-005", f"{what}: '{arg.name}' is a {sym.kind}: connect an input "
                      f"with :=, an output with =>", arg.pos)
        elif arg.direction == "in":
            ex.check_value(arg.value, sym.type, what)
        elif arg.value is not None:
            target = check_store(ex, arg.value, what)
            ex.require_assignable(sym.type, target, arg.value.pos, what)


def check_config_inits(decls, config: ast.Configuration, ex) -> None:
    """`Res.Prog.Inst.Var : TYPE := value;`: the path names a variable of a program
    instance of this configuration (leading resource names are skipped), of that type;
    VAR_ACCESS paths of the configuration likewise."""
    for init in config.config_inits:
        declared = _path_of_type(decls, config, init.path, init.type, ex,
                                 f"VAR_CONFIG {'.'.join(init.path)}", init.pos)
        if declared is not None and init.init is not None:
            decls.initializer(init.init, declared, ex, f"VAR_CONFIG {'.'.join(init.path)}")
    for access in config.access:
        parts = _parts(access.path)
        if parts is None:
            decls.ctx.error("E-TYPE-014", f"VAR_ACCESS {access.name}: expected a path "
                            f"Resource.Program.Variable", access.path.pos)
            continue
        _path_of_type(decls, config, parts, access.type, ex, f"VAR_ACCESS {access.name}", access.pos)


def check_program_access(decls, paths, ex) -> None:
    """A PROGRAM's VAR_ACCESS: each path is a variable of the program, of the declared
    type; a READ_WRITE path must be writable."""
    for access in paths:
        what = f"VAR_ACCESS {access.name}"
        found = check_store(ex, access.path, what) if access.read_write else ex.infer(access.path)
        declared = decls.resolve(access.type, ex)
        if found is ts.ERROR or declared is ts.ERROR:
            continue
        if not ts.same_type(T.resolve_alias(declared), T.resolve_alias(found)):
            decls.ctx.error("E-TYPE-004", f"{what}: declared {declared}, the variable is {found}",
                            access.pos)


def _parts(path) -> tuple[str, ...] | None:
    """`A.B.C` as ("A", "B", "C"), or None for any other expression."""
    parts = []
    while isinstance(path, ast.Member):
        parts.append(path.name)
        path = path.base
    if not isinstance(path, ast.Name):
        return None
    return (path.name, *reversed(parts))


def _path_of_type(decls, config, path, type_ref, ex, what: str, pos):
    """The declared type when `path` names a program instance's variable of that type,
    else None (after a report)."""
    ctx = decls.ctx
    instances = {key(p.name): p for p in config.programs}
    start = next((i for i, part in enumerate(path[:-1]) if key(part) in instances), None)
    if start is None:
        names = ", ".join(p.name for p in config.programs) or "none"
        ctx.error("E-DECL-001", f"{what}: the path names no program instance of "
                  f"{config.name} (instances: {names})", pos)
        return None
    info = decls.program.pous.get(key(instances[key(path[start])].program_type))
    if info is None or info.kind != "PROGRAM":
        return None                                     # reported with the instance
    found = _variable_type(ctx, info, path[start + 1:], what, pos)
    if found is None:
        return None
    declared = decls.resolve(type_ref, ex)
    if declared is ts.ERROR:
        return None
    if not ts.same_type(T.resolve_alias(declared), T.resolve_alias(found)):
        ctx.error("E-TYPE-004", f"{what}: declared {declared}, the variable is {found}", pos)
        return None
    return declared


def _variable_type(ctx, info, parts, what: str, pos):
    """The type at `Var.Member...` inside the program `info`, or None after a report."""
    owner, t = info.name, None
    for part in parts:
        if t is None:
            sym = info.variables.get(key(part))
            found = sym.type if sym is not None else None
        else:
            t = T.resolve_alias(t)
            if isinstance(t, T.FBType):
                sym = t.variables.get(key(part))
                found = sym.type if sym is not None else None
            elif isinstance(t, T.StructType):
                entry = t.fields.get(key(part))
                found = entry[1] if entry is not None else None
            else:
                found = None
        if found is None:
            ctx.error("E-DECL-001", f"{what}: {owner} has no variable '{part}'", pos)
            return None
        owner, t = part, found
    return t
