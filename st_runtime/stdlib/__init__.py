"""The IEC 61131-3 standard library of the runtime.

* `functions.FUNCTIONS` / `STRICT_FUNCTIONS`: standard functions by
  upper-case name (ABS ... MID), see `functions` for calling conventions;
* `conversions.CONVERSIONS` and `conversion(src, dst)`: every `<A>_TO_<B>`;
* `fbs`: TON, TOF, TP, R_TRIG, F_TRIG, CTU, CTD, CTUD, SR, RS as native FBs,
  registered with `st_runtime.native` when this package is imported.
"""

from . import fbs  # noqa: F401  (registers the standard FBs)
from .conversions import CONVERSIONS, conversion, split_conversion_name
from .functions import FUNCTIONS, STRICT_FUNCTIONS, WIDTH_ARGUMENT

__all__ = [
    "CONVERSIONS", "FUNCTIONS", "STRICT_FUNCTIONS", "WIDTH_ARGUMENT",
    "conversion", "split_conversion_name",
]
