"""What every command that reads ST shares before loading anything: the
check of its FILE_OR_DIR arguments and the help of `--dialect`.  Light on
purpose (no runtime import): `stgen check` starts with this alone.
"""

from __future__ import annotations

import os

#: One help text for `--dialect` in every command that loads ST.
DIALECT_HELP = ("rules to check against: iec (IEC 61131-3; OMRON NJ identifier rules are"
                " warnings, the default), nj (OMRON NJ/Sysmac Studio: those rules are errors)"
                " or codesys (CODESYS/TwinCAT extensions: POINTER TO, x.3, S=, PROPERTY, ...)")


def source_problem(paths: list[str]) -> str | None:
    """Why `paths` give nothing to load (a missing path, no .st file at all)."""
    from st_runtime.loader import expand

    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        return f"no such file or directory: '{missing[0]}'"
    files, _ = expand(list(paths))
    if not files:
        where = ", ".join(f"'{p}'" for p in paths)
        return f"no .st file in {where}"
    return None
