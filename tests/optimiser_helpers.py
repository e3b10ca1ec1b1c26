"""One scan of a program's Main, compiled with a given set of optimiser passes: what the
optimiser tests compare with the passes on and off."""

from __future__ import annotations

from st_runtime.api import Plc, load_text
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller


def run_main(source: str, optimise: Optimisations, inputs: dict, outputs: tuple[str, ...],
             stop: bool = False, dialect: str = "iec"):
    """Main's `outputs` after one scan with `inputs` set first, the faults (code, POU, line,
    column, scan) and the NJ time charged per scan."""
    compiled = compile_program(load_text(source, "t.st", dialect=dialect).program, optimise=optimise)
    plc = Plc(Controller(compiled, 1_000_000, None, stop))
    main = plc.add_program("Main")
    for name, value in inputs.items():
        main[name] = value
    plc.run(1)
    faults = [(f.code, f.pou, f.line, f.col, f.scan) for f in plc.controller.faults]
    return tuple(main[name] for name in outputs), faults, list(plc.controller.task_times["Primary"])
