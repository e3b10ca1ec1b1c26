"""A CONFIGURATION's program connections and VAR_CONFIG (IEC 61131-3 3rd ed. 6.8.2).

Both are checked, not applied: st_runtime checks configurations but does not
run them (`stgen run --program` picks the program), so a connection or a
VAR_CONFIG value changes nothing at run time.
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
    instance of this configuration (leading resource names are skipped), of that type."""
    ctx = decls.ctx
    instances = {key(p.name): p for p in config.programs}
    for init in config.config_inits:
        what = f"VAR_CONFIG {'.'.join(init.path)}"
        start = next((i for i, part in enumerate(init.path[:-1]) if key(part) in instances), None)
        if start is None:
            names = ", ".join(p.name for p in config.programs) or "none"
            ctx.error("E-DECL-001", f"{what}: the path names no program instance of "
                      f"{config.name} (instances: {names})", init.pos)
            continue
        info = decls.program.pous.get(key(instances[key(init.path[start])].program_type))
        if info is None or info.kind != "PROGRAM":
            continue                                    # reported with the instance
        found = _variable_type(ctx, info, init.path[start + 1:], what, init.pos)
        if found is None:
            continue
        declared = decls.resolve(init.type, ex)
        if declared is ts.ERROR:
            continue
        if not ts.same_type(T.resolve_alias(declared), T.resolve_alias(found)):
            ctx.error("E-TYPE-004", f"{what}: declared {declared}, the variable is {found}", init.pos)
        elif init.init is not None:
            decls.initializer(init.init, declared, ex, what)


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
