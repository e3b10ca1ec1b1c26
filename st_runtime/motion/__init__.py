"""Simulated PLCopen servo axes for the ST runtime.

* `axis_config` -- one axis's settings, loaded from a dict / TOML table;
* `axis` -- the simulation of one axis (PLCopen states, limits, servo lag);
* `error_ids` -- the ErrorID table of the axes and motion FBs.
"""
