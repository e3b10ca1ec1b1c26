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

from .api import CallError, Instance, LoadError, Plc, Project, load, load_sources, load_text
from .controller import Controller
from .faults import FaultRecord, STFault

__all__ = [
    "CallError", "Controller", "FaultRecord", "Instance", "LoadError", "Plc", "Project",
    "STFault", "load", "load_sources", "load_text",
]
