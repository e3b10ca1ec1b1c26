"""BCD conversions of IEC 61131-3 (2nd edition BCD_TO_INT / INT_TO_BCD, 3rd
edition WORD_BCD_TO_UINT / UINT_TO_BCD_WORD, Table 23).

A BCD value holds one decimal digit per nibble (16#1234 is 1234).  A nibble
above 9, a negative number or one with more digits than the bit string holds
is an F-CONVERT fault (the standard leaves them an error; the NJ's BCD_TO_*
instructions set an error too, W502 "BCD_TO_***").
"""

from __future__ import annotations

from ..faults import STFault

# Integer type -> the bit string of its width, as the 2nd edition pairs them.
BITS_OF = {"SINT": "BYTE", "USINT": "BYTE", "INT": "WORD", "UINT": "WORD",
           "DINT": "DWORD", "UDINT": "DWORD", "LINT": "LWORD", "ULINT": "LWORD"}
WIDTH = {"BYTE": 8, "WORD": 16, "DWORD": 32, "LWORD": 64}


def from_bcd(name: str, value: int) -> int:
    result, scale, rest = 0, 1, value
    while rest:
        digit = rest & 0xF
        if digit > 9:
            raise STFault("F-CONVERT", f"{name}(16#{value:X}): nibble {digit:X} is not a BCD digit")
        result += digit * scale
        scale *= 10
        rest >>= 4
    return result


def to_bcd(name: str, value: int, bits: int) -> int:
    if value < 0 or value >= 10 ** (bits // 4):
        raise STFault("F-CONVERT", f"{name}({value}): expected 0..{10 ** (bits // 4) - 1}, "
                      f"the digits a {bits}-bit BCD value holds")
    result, shift = 0, 0
    while value:
        value, digit = divmod(value, 10)
        result |= digit << shift
        shift += 4
    return result


def _decoder(name: str):
    def decode(value):
        return from_bcd(name, value)
    decode.__name__ = name
    return decode


def _encoder(name: str, bits: int):
    def encode(value):
        return to_bcd(name, value, bits)
    encode.__name__ = name
    return encode


def _table() -> dict[str, tuple[str, str, object]]:
    """Function name -> (parameter category or type, result type, callable)."""
    table = {}
    for integer, bits in BITS_OF.items():
        name = f"BCD_TO_{integer}"
        table[name] = ("ANY_BITS", integer, _decoder(name))
        name = f"{integer}_TO_BCD"
        table[name] = ("ANY_INT", bits, _encoder(name, WIDTH[bits]))
    for bits, integer in (("BYTE", "USINT"), ("WORD", "UINT"), ("DWORD", "UDINT"), ("LWORD", "ULINT")):
        name = f"{bits}_BCD_TO_{integer}"
        table[name] = (bits, integer, _decoder(name))
        name = f"{integer}_TO_BCD_{bits}"
        table[name] = (integer, bits, _encoder(name, WIDTH[bits]))
    return table


BCD_FUNCTIONS = _table()
