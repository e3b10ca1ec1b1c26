"""JSON of references, interfaces, native FBs and NJ strings: what a whole run of
st_runtime/values.py's mutants found unchecked in session 8 (issue 16, docs/mutation.md).
Expected values by hand: NJ STRING[n] counts bytes (docs/nj501.md: myOMRON knowledge base 1668;
UTF-8 assumed there), IEC counts characters; a native FB shows its inputs and outputs."""

from __future__ import annotations

import pytest

from st_runtime import types as T
from st_runtime.api import load_text
from st_runtime.values import JsonValueError, from_json, to_json

E = T.ELEMENTARY
S4 = T.StringType(4)
EEE = "\u00e9\u00e9\u00e9"            # three characters, six bytes in UTF-8


def test_a_ref_is_null_or_shown_as_ref():
    ref = T.RefType(E["INT"])
    assert to_json(None, ref) is None
    assert to_json(object(), ref) == "REF"


def test_an_interface_variable_shows_the_type_of_the_instance_it_refers_to():
    class Motor:
        _st_name = "Motor"

    itf = T.InterfaceType("IDrive")
    assert to_json(None, itf) is None
    assert to_json(Motor(), itf) == "Motor"


def test_a_native_fb_instance_shows_its_inputs_and_outputs():
    # TON called with IN TRUE in three scans of 1 ms (at 0, 1 and 2 ms): ET 2 ms, Q FALSE.
    plc = load_text("PROGRAM Main\nVAR t : TON; END_VAR\nt(IN := TRUE, PT := T#5s);\nEND_PROGRAM\n").controller()
    main = plc.add_program("Main")
    plc.run(3)
    assert main.to_json() == {"t": {"IN": True, "PT": "T#5s", "Q": False, "ET": "T#2ms"}}


def test_an_nj_string_is_measured_in_bytes_an_iec_one_in_characters():
    assert from_json(EEE, S4) == EEE                                   # 3 characters fit STRING[4]
    with pytest.raises(JsonValueError) as error:
        from_json(EEE, S4, dialect="nj")
    assert str(error.value) == "value: string of 6 bytes exceeds STRING[4]"
    assert from_json("\u00e9\u00e9", S4, dialect="nj") == "\u00e9\u00e9"   # 4 bytes fit


@pytest.mark.parametrize("data, t, where", [
    (["ab", EEE], T.ArrayType(((1, 2),), S4), "value[2]"),
    ([["ab"], [EEE]], T.ArrayType(((0, 1), (0, 0)), S4), "value[1, 0]"),
    ({"s": EEE}, T.StructType("Named", {"S": ("s", S4)}), "value.s"),
])
def test_an_nj_string_inside_an_array_or_a_struct_is_measured_in_bytes(data, t, where):
    assert from_json(data, t)                                          # IEC: 3 characters fit
    with pytest.raises(JsonValueError) as error:
        from_json(data, t, dialect="nj")
    assert str(error.value) == f"{where}: string of 6 bytes exceeds STRING[4]"
