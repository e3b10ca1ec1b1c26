"""examples/plc: the README's Python API example runs as written (values by hand)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from st_runtime import load

PLC = str(Path(__file__).resolve().parent.parent / "examples" / "plc")
MS = 1_000_000


def test_readme_python_api_on_examples_plc():
    project = load([PLC])
    plc = project.controller(period="1ms")
    main = plc.add_program("Main")
    main["Setpoint"] = 12.5
    plc.globals["Gain"] = 2.0
    trace = plc.trace(["Count", "Timer.ET"], program="Main")
    plc.run(1000)
    assert main["Count"] == 1000 and plc.faults == []
    assert main.to_json()["Pose"] == [25.0, 0.0, 0.0, 0.0, 0.0, 0.0]      # 12.5 * 2.0
    data = trace.to_numpy()
    # the TON is called at t = 0, 1, ... 999 ms: ET = t, capped at PT = 500 ms
    np.testing.assert_array_equal(data["Timer.ET"], np.minimum(np.arange(1000), 500) * MS)
    assert project.call("Hyp", {"a": 3, "b": 4})["outputs"]["return"] == 5.0
    ramp = project.call("Ramp", {"target": 2.0}, until="done", max_cycles=100)
    # 0.5 per scan from 0: 0.5, 1.0, 1.5, 2.0
    assert ramp["outputs"] == {"Done": True, "Value": 2.0, "cycles": 4} and ramp["reached"]
