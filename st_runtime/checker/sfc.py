"""Sequential Function Charts (IEC 61131-3 3rd ed. 6.7, textual form) lowered to statements.

A POU whose body is a chart is checked and compiled as the equivalent
statement list, built here from the chart (the positions stay the chart's, so
a fault in a transition condition points at it).  One scan of a chart:

1. the transitions are evaluated in their textual order on the steps active
   at the start of the scan; one that fires clears its source steps (so a
   later transition from the same step does not fire: the standard's
   left-to-right priority of a divergence, 6.7.3.2) and marks its targets;
2. the steps are updated (`S.X`; `S.T` the time since the step became
   active, kept when it is left, restarting from T#0s on activation);
3. each action's control (6.7.4.5, table 60) computes Q from its
   associations: N while the step is active, S / R stored and reset (R wins),
   P and P1 one scan on the step's activation, P0 one scan on its
   deactivation, L while active for at most the time, D after the time;
   SD stored at activation and on after the time, DS on after the time if
   the step is still active and then stored, SL stored at activation and on
   for the time (a flip-flop and a TON each, as the standard's
   ACTION_CONTROL body; CODESYS's help, "Qualifiers for Actions in SFC",
   words the same rules); R is reset-dominant over every stored kind; an
   action's body runs while Q is TRUE and once more on Q's falling edge
   (the standard's final scan; PLCnext's help, "Action and Action Qualifier
   in SFC", quotes the rule), so a P, P1 or P0 action's body runs on two
   scans, the second with Q FALSE.  An association naming no ACTION is a
   Boolean variable set to Q.

The order (transitions, steps, then actions) is MATIEC's.  `S.T` counts up
to T#24d (a TON's preset), where it stops.  Each L, D, SD, DS and SL
association has its own timer: an action associated with two steps, each
with its own time, times each association separately.
"""

from __future__ import annotations

from dataclasses import replace

from .. import ast
from ..ast import key

STEP_TYPE = "__SFC_STEP"
_FOREVER_NS = 24 * 86_400 * 10**9


def step_type_decl() -> ast.TypeDecl:
    """TYPE __SFC_STEP : STRUCT X : BOOL; T : TIME; END_STRUCT (a step's flag and time)."""
    members = (ast.VarDecl("X", ast.NamedType("BOOL")), ast.VarDecl("T", ast.NamedType("TIME")))
    return ast.TypeDecl(STEP_TYPE, ast.StructType(members))


def lower_charts(ctx, files: list[ast.SourceFile], chartless=None) -> list[ast.SourceFile]:
    """`files` with every chart body replaced by its statements (and the step type added);
    `chartless`: a file known to hold no chart (the shared prelude), not searched."""
    out, charts = [], False
    for f in files:
        if f is chartless or not any(isinstance(item, ast.Pou) and item.sfc is not None for item in f.items):
            out.append(f)
            continue
        charts = True
        out.append(replace(f, items=tuple(
            _Lowering(ctx, item).lowered() if isinstance(item, ast.Pou) and item.sfc is not None
            else item for item in f.items)))
    if charts:
        out.append(ast.SourceFile("<builtin>", (step_type_decl(),)))
    return out


class _Lowering:
    def __init__(self, ctx, pou: ast.Pou) -> None:
        self.ctx, self.pou, self.chart = ctx, pou, pou.sfc
        self.decls: list[ast.VarDecl] = []
        self.steps = {key(s.name): s for s in self.chart.steps}

    # ------------------------------------------------------------ helpers
    def _var(self, name: str, type_name: str, pos, init=None) -> None:
        self.decls.append(ast.VarDecl(name, ast.NamedType(type_name), init, pos=pos))

    @staticmethod
    def _name(text: str, pos) -> ast.Name:
        return ast.Name(text, pos=pos)

    def _flag(self, step: str, pos) -> ast.Member:
        return ast.Member(self._name(step, pos), "X", pos=pos)

    @staticmethod
    def _set(target, value, pos) -> ast.Assign:
        return ast.Assign(target, value, pos=pos)

    @staticmethod
    def _if(condition, body, pos) -> ast.If:
        return ast.If((ast.IfBranch(condition, tuple(body), pos=pos),), pos=pos)

    def _ton(self, instance: str, signal, preset, pos) -> ast.CallStmt:
        call = ast.Call(self._name(instance, pos), (ast.Arg("IN", signal, pos=pos),
                                                    ast.Arg("PT", preset, pos=pos)), pos=pos)
        return ast.CallStmt(call, pos=pos)

    @staticmethod
    def _and(*terms):
        result = terms[0]
        for t in terms[1:]:
            result = ast.Binary("AND", result, t, pos=result.pos)
        return result

    @staticmethod
    def _or(a, b):
        return ast.Binary("OR", a, b, pos=a.pos)

    @staticmethod
    def _not(e):
        return ast.Unary("NOT", e, pos=e.pos)

    def _false(self, pos):
        return ast.BoolLiteral(False, pos=pos)

    # ----------------------------------------------------------- checks
    def _well_formed(self) -> bool:
        ok = True
        seen: dict[str, ast.Step] = {}
        for s in self.chart.steps:
            if key(s.name) in seen:
                self.ctx.error("E-SFC-002", f"step '{s.name}' is declared twice in "
                               f"{self.pou.name}", s.pos)
                ok = False
            seen[key(s.name)] = s
        if not any(s.initial for s in self.chart.steps):
            self.ctx.error("E-SFC-002", f"the chart of {self.pou.name} has no INITIAL_STEP",
                           self.chart.pos)
            ok = False
        for t in self.chart.transitions:
            for name in (*t.sources, *t.targets):
                if key(name) not in self.steps:
                    self.ctx.error("E-SFC-002", f"transition from {', '.join(t.sources)} to "
                                   f"{', '.join(t.targets)}: no step '{name}' in "
                                   f"{self.pou.name}", t.pos)
                    ok = False
        return ok

    # ------------------------------------------------------------ body
    def lowered(self) -> ast.Pou:
        if not self._well_formed():
            return replace(self.pou, sfc=None, body=())
        pos = self.chart.pos
        body: list = []
        for s in self.chart.steps:
            init = ast.StructInit((ast.FieldInit("X", ast.BoolLiteral(True, pos=s.pos), pos=s.pos),),
                                  pos=s.pos) if s.initial else None
            self._var(s.name, STEP_TYPE, s.pos, init)
            for hidden, type_name in (("__X_", "BOOL"), ("__N_", "BOOL"), ("__W_", "BOOL"),
                                      ("__T_", "TON")):
                self._var(hidden + s.name, type_name, s.pos)
            body.append(self._set(self._name("__X_" + s.name, s.pos), self._flag(s.name, s.pos), s.pos))
            body.append(self._set(self._name("__N_" + s.name, s.pos), self._false(s.pos), s.pos))
        for t in self.chart.transitions:
            enabled = self._and(*(self._name("__X_" + n, t.pos) for n in t.sources), t.condition)
            fire = [self._set(self._name("__X_" + n, t.pos), self._false(t.pos), t.pos)
                    for n in t.sources]
            fire += [self._set(self._name("__N_" + n, t.pos), ast.BoolLiteral(True, pos=t.pos), t.pos)
                     for n in t.targets]
            body.append(self._if(enabled, fire, t.pos))
        forever = ast.TimeLiteral(_FOREVER_NS, pos=pos)
        for s in self.chart.steps:
            p = s.pos
            body.append(self._set(self._name("__W_" + s.name, p), self._flag(s.name, p), p))
            body.append(self._set(self._flag(s.name, p), self._or(self._name("__X_" + s.name, p),
                                                                    self._name("__N_" + s.name, p)), p))
            body.append(self._ton("__T_" + s.name, self._flag(s.name, p), forever, p))
            body.append(self._if(self._flag(s.name, p), [self._set(
                ast.Member(self._name(s.name, p), "T", pos=p),
                ast.Member(self._name("__T_" + s.name, p), "ET", pos=p), p)], p))
        body += self._actions()
        blocks = self.pou.var_blocks + (ast.VarBlock("VAR", tuple(self.decls), pos=pos),)
        return replace(self.pou, var_blocks=blocks, body=tuple(body), sfc=None)

    def _actions(self) -> list:
        coded = {key(a.name): a for a in self.chart.actions}
        uses: dict[str, list] = {k: [] for k in coded}
        names: dict[str, str] = {k: a.name for k, a in coded.items()}
        for s in self.chart.steps:
            for a in s.actions:
                uses.setdefault(key(a.action), []).append((s, a))
                names.setdefault(key(a.action), a.action)
        out: list = []
        for k, associations in uses.items():
            name = names[k]
            pos = coded[k].pos if k in coded else associations[0][1].pos
            q, stored, reset, final = (self._name(f"__{h}_{name}", pos) for h in "QSRF")
            for hidden in (q, stored, reset, final):
                self._var(hidden.name, "BOOL", pos)
            out += [self._set(q, self._false(pos), pos), self._set(reset, self._false(pos), pos)]
            # Resets first: every stored kind is reset-dominant (an RS flip-flop).
            numbered = sorted(enumerate(associations), key=lambda ia: ia[1][1].qualifier != "R")
            for i, (s, a) in numbered:
                out += self._association(s, a, i, q, stored, reset)
            out.append(self._set(stored, self._and(stored, self._not(reset)), pos))
            out.append(self._set(q, self._and(self._or(q, stored), self._not(reset)), pos))
            if k in coded:
                out.append(self._if(self._or(q, final), coded[k].body, pos))
            else:               # a Boolean action: the variable follows Q
                out.append(self._set(self._name(name, pos), q, pos))
            out.append(self._set(final, q, pos))
        return out

    def _association(self, s: ast.Step, a: ast.ActionAssociation, i: int, q, stored, reset) -> list:
        p = a.pos
        active = self._flag(s.name, p)
        was = self._name("__W_" + s.name, p)
        kind = a.qualifier
        if kind == "N":
            return [self._set(q, self._or(q, active), p)]
        if kind == "S":
            return [self._if(active, [self._set(stored, ast.BoolLiteral(True, pos=p), p)], p)]
        if kind == "R":
            return [self._if(active, [self._set(reset, ast.BoolLiteral(True, pos=p), p)], p)]
        if kind in ("P", "P1"):
            return [self._set(q, self._or(q, self._and(active, self._not(was))), p)]
        if kind == "P0":
            return [self._set(q, self._or(q, self._and(was, self._not(active))), p)]
        timer = f"__{kind}{i}_{a.action}"
        self._var(timer, "TON", p)
        done = ast.Member(self._name(timer, p), "Q", pos=p)
        if kind in ("L", "D"):
            term = self._and(active, self._not(done)) if kind == "L" else done
            return [self._ton(timer, active, a.time, p), self._set(q, self._or(q, term), p)]
        # SD, DS, SL: a reset-dominant flip-flop (RS) and a TON, as ACTION_CONTROL's body
        flag = self._name(f"__{kind}F{i}_{a.action}", p)
        self._var(flag.name, "BOOL", p)
        not_reset = self._not(reset)
        if kind == "DS":        # timed while the step is active, then stored
            return [self._ton(timer, active, a.time, p),
                    self._set(flag, self._and(self._or(flag, done), not_reset), p),
                    self._set(q, self._or(q, flag), p)]
        term = done if kind == "SD" else self._and(flag, self._not(done))      # SL: on for the time
        return [self._set(flag, self._and(self._or(flag, active), not_reset), p),
                self._ton(timer, flag, a.time, p),
                self._set(q, self._or(q, term), p)]
