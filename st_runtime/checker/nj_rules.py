"""OMRON NJ identifier rules (Sysmac Studio variable and POU names).

* at most 127 bytes in UTF-8;
* no leading or trailing underscore, no two consecutive underscores;
* no 'P_' prefix, in any case (system-defined variables such as P_On; NJ
  Software User's Manual W501, 6-3-12);
* not equal (case-insensitively) to an instruction name.

Errors (`E-NJ-...`) under `--dialect nj`, warnings (`W-NJ-...`) otherwise.
The built-in prelude (native FB declarations) is exempt.

The instruction table holds the NJ instructions a generated or hand-written
ST program is most likely to collide with: the IEC standard functions and
FBs, their conversions, and the common NJ math, string, bit, timer, counter
and motion instructions.  It is not the complete NJ instruction list.
"""

from __future__ import annotations

import functools

from .. import ast
from ..ast import key
from . import builtins as B
from .context import BUILTIN_FILE, Context

MAX_IDENTIFIER_BYTES = 127

NJ_INSTRUCTIONS: frozenset[str] = frozenset(key(n) for n in """
    ABS ACOS ASIN ATAN COS SIN TAN EXP EXPT LN LOG SQRT
    ADD SUB MUL DIV MOD EQ NE LT LE GT GE
    MIN MAX LIMIT SEL MUX MOVE TRUNC ROUND RoundUp RoundDown Fraction
    SHL SHR ROL ROR NOT AND OR XOR Inc Dec
    LEN CONCAT LEFT RIGHT MID FIND INSERT DELETE REPLACE
    TON TOF TP AccumulationTimer
    R_TRIG F_TRIG CTU CTD CTUD SR RS
    Clear Exchange AryMove AryExchg ArySearch AryMax AryMin AryMean AryShiftReg ScaleTrans
    MC_Power MC_Reset MC_Home MC_Stop MC_ImmediateStop MC_MoveAbsolute MC_MoveRelative
    MC_MoveVelocity MC_MoveJog MC_SyncMoveAbsolute MC_SyncMoveVelocity MC_GearIn MC_GearOut
    MC_CamIn MC_CamOut MC_SetPosition MC_ReadAxisParameter MC_Phasing MC_TorqueControl
    GetTime DtToSec SecToDt
""".split())


def is_instruction(name: str) -> bool:
    k = key(name)
    return k in NJ_INSTRUCTIONS or B.conversion(k) is not None


def identifier_problems(name: str) -> list[tuple[str, str]]:
    """(rule number, message) for every NJ rule the identifier breaks."""
    problems = []
    size = len(name.encode("utf-8"))
    if size > MAX_IDENTIFIER_BYTES:
        problems.append(("001", f"identifier '{name[:32]}...' is {size} bytes long: expected at "
                                f"most {MAX_IDENTIFIER_BYTES} bytes (UTF-8) on an OMRON NJ"))
    if name.startswith("_") or name.endswith("_"):
        problems.append(("002", f"identifier '{name}' starts or ends with '_': not allowed on an "
                                f"OMRON NJ"))
    if "__" in name:
        problems.append(("003", f"identifier '{name}' contains '__': not allowed on an OMRON NJ"))
    if is_instruction(name):
        problems.append(("004", f"identifier '{name}' is the name of an NJ instruction: choose "
                                f"another name"))
    if name[:2].upper() == "P_":
        problems.append(("005", f"identifier '{name}' starts with 'P_', which the NJ reserves for "
                                f"system-defined variables"))
    return problems


def check_identifiers(ctx: Context, files) -> None:
    """Report each NJ rule broken by an identifier the user declares (POUs, types,
    members, variables), in the order they are declared: each node's name asked of
    `_problems_of` where it is met (no list of the names made first)."""
    for f in files:
        if f.path == BUILTIN_FILE:
            continue
        for item in f.items:
            if item.pos.file == BUILTIN_FILE:
                continue
            if isinstance(item, ast.Pou):
                _check_names(ctx, (item,))
                for block in item.var_blocks:
                    _check_names(ctx, block.decls)
            elif isinstance(item, ast.TypeDecl):
                _check_names(ctx, (item,))
                if isinstance(item.spec, ast.StructType):
                    _check_names(ctx, item.spec.members)
                elif isinstance(item.spec, ast.EnumType):
                    _check_names(ctx, item.spec.values)
            elif isinstance(item, ast.VarBlock):
                _check_names(ctx, item.decls)
            elif isinstance(item, ast.Configuration):
                for block in item.globals:
                    _check_names(ctx, block.decls)


def _check_names(ctx: Context, nodes) -> None:
    """Report the NJ rules the names of `nodes` (each with a name and a position) break."""
    for node in nodes:
        problems = _problems_of(node.name)
        if problems:
            for rule, message in problems:
                ctx.nj_rule(rule, message, node.pos)


@functools.lru_cache(maxsize=4096)   # a pure function of the name, asked on every load (Main, x, ...)
def _problems_of(name: str) -> tuple[tuple[str, str], ...]:
    return tuple(identifier_problems(name))
