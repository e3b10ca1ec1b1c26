"""st_runtime: an IEC 61131-3 Structured Text toolchain in Python.

Parse, check, compile to Python, and run scan by scan in a simulated
controller.  The Python API (see `api`):

    from st_runtime import load
    project = load(["plc/"])
    plc = project.controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(100)
    print(main.to_json(), plc.faults)
"""

__all__ = [
    "CallError", "Controller", "FaultRecord", "Instance", "LoadError", "Plc", "Project",
    "STFault", "load", "load_sources", "load_text",
]

#: Where each public name lives. Imported on first use (PEP 562), so that a
#: tool needing one stage (`stgen check`: the loader) does not import them all.
_HOMES = {"Controller": "controller", "FaultRecord": "faults", "STFault": "faults"}


def __getattr__(name: str):
    if name not in __all__:
        raise AttributeError(f"module 'st_runtime' has no attribute {name!r}")
    from importlib import import_module

    value = getattr(import_module(f".{_HOMES.get(name, 'api')}", __name__), name)
    globals()[name] = value
    return value
