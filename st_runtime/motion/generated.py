"""Python that the motion layer writes for itself (hot paths, idle calls, the motion step).

Only this package's own templates, filled with Python names it checked, ever reach
`define`: never ST text.
"""

from __future__ import annotations


def define(source: str, label: str, values: dict | None = None) -> dict:
    """Run `source` in a namespace holding `values`; the namespace, with what it defined.
    `label` names the source in tracebacks (`<label>`)."""
    namespace = dict(values or {})
    exec(compile(source, f"<{label}>", "exec"), namespace)
    return namespace
