"""The JONSWAP sea state of the playback tests: now in stgen.scenarios.sea_state (the demo plays it too)."""

from stgen.scenarios.sea_state import jonswap_motion, write_csv

__all__ = ["jonswap_motion", "write_csv"]
