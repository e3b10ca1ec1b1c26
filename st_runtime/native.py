"""Native POUs: FBs and types written in Python, declared in ST.

A native FB is a Python class whose interface is declared as ST text
(`DECLARATION`: a FUNCTION_BLOCK with its VAR blocks and an empty body).  The
checker parses every registered declaration as a built-in prelude, so a native
FB presents exactly the same interface to the checker and the compiler as an FB
written in ST.  Native data types (e.g. the axis reference) are registered the
same way as ST `TYPE` text.

The contract between a native FB and the compiled code (`NativeFB`):

* Every declared variable is an instance attribute named `mangle(name)`
  (`PT` -> `v_PT`).  Values: BOOL as bool, integers/enums as int, REAL and
  LREAL as float, TIME/DATE/TOD/DT as int nanoseconds, STRING as str, arrays
  as flat Python lists (row-major, index 0 is the lower bound of every
  dimension), structs and FB instances as objects with `v_` attributes.
* `__init__(self)` gives every variable its declared initial value (the base
  class does it from the checked declaration); VAR_IN_OUT variables start as
  None.
* `execute(self, ctx)` runs one call.  Before it, the compiled caller stores
  the inputs given in the call (inputs not given keep their previous value);
  after it, the caller reads the outputs.  VAR_IN_OUT variables hold the
  caller's object itself for arrays, structs and FB instances, and a `Ref`
  (`.get()`, `.set(value)`) for elementary values.
* `ctx` gives at least `ctx.now_ns` (simulated clock, int ns), `ctx.scan`
  (scan number, 1 for the first scan) and `ctx.period_ns` (period of the task
  that runs the caller).  A native FB that detects an instruction error raises
  `st_runtime.faults.STFault(code, message)`; the caller records it.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from .dialects import DIALECTS

NATIVE_FBS: dict[str, type] = {}       # upper-case FB name -> Python class
NATIVE_TYPE_SOURCES: list[str] = []    # ST TYPE ... END_TYPE texts


def mangle(name: str) -> str:
    """The Python attribute/local name of an ST identifier (case-insensitive).

    Every ST identifier becomes `v_` + its upper-case spelling, so no ST name
    can collide with a Python keyword, builtin or a name of the runtime.
    """
    return "v_" + name.upper()


def fb_declaration(name: str, *, inputs: str = "", outputs: str = "", in_outs: str = "",
                   memory: str = "") -> str:
    """The ST declaration of a native FB from its variable lists
    (`"IN : BOOL; PT : TIME;"`): VAR_IN_OUT, VAR_INPUT, VAR_OUTPUT, VAR."""
    blocks = [(keyword, names) for keyword, names in
              (("VAR_IN_OUT", in_outs), ("VAR_INPUT", inputs), ("VAR_OUTPUT", outputs),
               ("VAR", memory)) if names]
    body = "".join(f"{keyword}\n    {names}\nEND_VAR\n" for keyword, names in blocks)
    return f"\nFUNCTION_BLOCK {name}\n{body}END_FUNCTION_BLOCK\n"


def native_fb(cls: type) -> type:
    """Class decorator: register a native FB (its `NAME` and `DECLARATION`).

    A pin that a dialect names differently (`dialects.Dialect.pins`, e.g.
    OMRON's `Reset` for CTU's `R`) becomes an alias attribute of the class,
    so `execute` reads `v_R` whichever name the compiled caller stores to.
    """
    NATIVE_FBS[cls.NAME.upper()] = cls
    for dialect in DIALECTS.values():
        for iec_pin, renamed in dialect.pins.get(cls.NAME.upper(), {}).items():
            setattr(cls, mangle(renamed), _alias(mangle(iec_pin)))
    return cls


def _alias(attr: str) -> property:
    return property(lambda self: getattr(self, attr), lambda self, value: setattr(self, attr, value))


def _renamed_pins(declaration: str, renames: dict[str, str]) -> str:
    """The declaration text with each `Pin :` renamed (fb_declaration writes `Name : Type;`)."""
    for iec_pin, renamed in renames.items():
        declaration = re.sub(rf"(?<![A-Za-z0-9_]){iec_pin}(?=\s*:)", renamed, declaration,
                             flags=re.IGNORECASE)
    return declaration


def native_types(source: str) -> None:
    """Register ST TYPE declarations that native FBs rely on."""
    if source not in NATIVE_TYPE_SOURCES:
        NATIVE_TYPE_SOURCES.append(source)


def prelude_source(dialect: str = "iec") -> str:
    """All native declarations as one ST text, types first, with the dialect's pin names."""
    pins = DIALECTS[dialect].pins if dialect in DIALECTS else {}
    parts = list(NATIVE_TYPE_SOURCES)
    parts.extend(_renamed_pins(cls.DECLARATION, pins.get(key, {})) for key, cls in NATIVE_FBS.items())
    return "\n".join(parts)


class RestTest(NamedTuple):
    """`NativeFB.REST`: Python of the instance `{fb}` and the caller's `_ctx`.  `awake` is false
    only while the FB is known to be at rest (an earlier CALL_NEEDED test was false and nothing
    has touched the FB since: `ScanContext.seal`); `note` is the statement that records it,
    `forget` one that drops it; `unnoted`, the part of `awake` false while the note holds.
    `group`: an attribute of the instance free for its caller's note of a group of call sites
    (optimise/dormant.py: the FB and the others of its group found at rest under a seal)."""

    awake: str
    note: str
    forget: str
    unnoted: str
    group: str


class NativeFB:
    """Base class of FBs written in Python (see the module docstring).

    Subclasses set `NAME` and `DECLARATION` and implement `execute(self, ctx)`.
    The initial values come from the checked declaration; the compiler installs
    them when it compiles a program (`set_initializers`); a class used on its
    own (a unit test) needs `st_runtime.compiler.install_native_layouts()` first.
    """

    NAME: str = ""
    DECLARATION: str = ""
    # A Python expression of the instance `{fb}`, or None: when it is false, a call with the
    # inputs as they are stored changes nothing (no variable, no state of the FB or of what it
    # drives) and raises nothing, so the compiled caller may leave the call out.
    CALL_NEEDED: str | None = None
    # None, or an object whose `inline(fb, temp)` gives (test, statements): when the test holds,
    # the statements (new locals named by `temp()`) do what the call would do, so the compiled
    # caller runs them instead of the call (motion.fbs.HotPath).
    HOT_PATH = None
    # None, or a RestTest: the compiled caller makes the CALL_NEEDED test only when `awake` is
    # true, and when that test is false notes the FB at rest (`note`), for the scans to come.
    REST: "RestTest | None" = None

    def __init__(self) -> None:
        init = type(self).__dict__.get("_st_initializers")
        if init is None:
            raise RuntimeError(f"native FB {self.NAME or type(self).__name__} has no layout yet: compile a"
                               " program first, or call st_runtime.compiler.install_native_layouts()")
        for attr, make in init:
            setattr(self, attr, make())

    def execute(self, ctx) -> None:  # pragma: no cover - abstract
        raise NotImplementedError(f"native FB {self.NAME} has no execute()")

    @classmethod
    def set_initializers(cls, initializers: list[tuple[str, object]]) -> None:
        """Install (attribute, zero-argument factory) pairs for `__init__`."""
        cls._st_initializers = tuple(initializers)
