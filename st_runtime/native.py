"""Registry of native POUs: FBs and types written in Python, declared in ST.

A native FB is a Python class whose interface is declared as ST text
(`DECLARATION`: a FUNCTION_BLOCK with its VAR blocks and an empty body).  The
checker parses every registered declaration as a built-in prelude, so a native
FB presents exactly the same interface to the checker and the compiler as an FB
written in ST.  Native data types (e.g. the axis reference) are registered the
same way as ST `TYPE` text.

The runtime owns how instances are created and called (see compiler/runtime).
"""

from __future__ import annotations

NATIVE_FBS: dict[str, type] = {}       # upper-case FB name -> Python class
NATIVE_TYPE_SOURCES: list[str] = []    # ST TYPE ... END_TYPE texts


def native_fb(cls: type) -> type:
    """Class decorator: register a native FB (its `NAME` and `DECLARATION`)."""
    NATIVE_FBS[cls.NAME.upper()] = cls
    return cls


def native_types(source: str) -> None:
    """Register ST TYPE declarations that native FBs rely on."""
    if source not in NATIVE_TYPE_SOURCES:
        NATIVE_TYPE_SOURCES.append(source)


def prelude_source() -> str:
    """All native declarations as one ST text, types first."""
    parts = list(NATIVE_TYPE_SOURCES)
    parts.extend(cls.DECLARATION for cls in NATIVE_FBS.values())
    return "\n".join(parts)
