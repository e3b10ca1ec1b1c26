"""The simulated process image behind located variables (`AT %IX0.0`).

IEC 61131-3 (6.5.5) names three areas, inputs %I, outputs %Q and memory
%M, and a size prefix: X bit, B byte, W word (16 bits), D double word (32),
L long word (64); with no prefix the address is a bit.  How addresses of
different sizes overlap "is implementation dependent".  The choice here is
CODESYS's (byte-addressed areas, little-endian, each size numbered in its
own units):

    %IX<b>.<n>  bit n (0..7) of byte b        %IB<b>  byte b
    %IW<w>      bytes 2w, 2w+1                %ID<d>  bytes 4d .. 4d+3
    %IL<l>      bytes 8l .. 8l+7               %IX<n>  (one number) bit n mod 8 of byte n div 8

so %MW1 shares its bits with %MB2, %MB3, %MX2.0 .. %MX3.7 and half of %MD0,
and a store through one is seen at once through every other (a variable
located there has no storage of its own: it reads and writes the image).
A REAL at %MD is its IEEE-754 single-precision bit pattern; signed integers
are two's complement.  `%I*` / `%Q*` / `%M*` (a location left to the
configuration) is an ordinary variable: no VAR_CONFIG maps it yet.

One image per compiled program; the Python API reaches it as `Plc.image`
(`plc.image["%IX0.0"] = True`) and `stgen run --set %IW2=100`.
"""

from __future__ import annotations

import re
import struct
from dataclasses import dataclass

SIZES = {"X": 1, "B": 8, "W": 16, "D": 32, "L": 64}
# The type a bare address reads as (API, --set).
PLAIN_TYPES = {"X": "BOOL", "B": "BYTE", "W": "WORD", "D": "DWORD", "L": "LWORD"}
# Area size limit: a located address beyond it is refused by the checker.
AREA_BYTES = 1 << 16
AREAS = ("I", "Q", "M")

_ADDRESS = re.compile(r"%([IQM])([XBWDL]?)(\*|[0-9]+(?:\.[0-9]+)*)$", re.IGNORECASE)


@dataclass(frozen=True, slots=True)
class Address:
    area: str        # I | Q | M
    size: str        # X | B | W | D | L
    byte: int        # first byte
    bit: int         # bit in the byte (X only)
    text: str

    @property
    def bits(self) -> int:
        return SIZES[self.size]


def parse_address(text: str) -> tuple[Address | None, str | None]:
    """(Address, None), (None, None) for `%I*`, or (None, why it is not valid)."""
    m = _ADDRESS.match(text.strip())
    if not m:
        return None, f"'{text}' is not a direct address (%I, %Q or %M, a size X B W D L, numbers)"
    area, size, numbers = m.group(1).upper(), (m.group(2) or "X").upper(), m.group(3)
    if numbers == "*":
        return None, None
    parts = [int(p) for p in numbers.split(".")]
    if size == "X" and len(parts) == 1:      # %IX9: bits numbered on from bit 0 of byte 0
        parts = [parts[0] // 8, parts[0] % 8]
    if size == "X":
        if len(parts) != 2 or not 0 <= parts[1] <= 7:
            return None, f"'{text}': a bit address is <byte>.<bit> with bit 0..7"
        byte, bit = parts
    else:
        if len(parts) != 1:
            return None, f"'{text}': a {size} address is one number"
        byte, bit = parts[0] * SIZES[size] // 8, 0
    if byte + max(SIZES[size] // 8, 1) > AREA_BYTES:
        return None, f"'{text}' lies beyond the {AREA_BYTES}-byte %{area} area"
    return Address(area, size, byte, bit, f"%{area}{size}{numbers}"), None


class _Areas(dict):
    """Area letter -> its bytes, each zeroed on first use: every compile makes an
    image, and most programs locate nothing (three 64 KiB areas cost more than
    compiling a small program's initial values)."""

    def __missing__(self, area: str) -> bytearray:
        if area not in AREAS:
            raise KeyError(area)
        data = self[area] = bytearray(AREA_BYTES)
        return data


class ProcessImage:
    """The %I, %Q and %M areas as byte arrays."""

    def __init__(self) -> None:
        self.areas = _Areas()

    def clear(self) -> None:
        for data in self.areas.values():
            data[:] = bytes(len(data))

    def get(self, address: Address, kind: str, signed: bool = False):
        return decode(self.areas[address.area], address, kind, signed)

    def set(self, address: Address, kind: str, value) -> None:
        encode(self.areas[address.area], address, kind, value)


def decode(data: bytearray, address: Address, kind: str, signed: bool = False):
    """The value at `address` in `data` (little-endian, REAL as IEEE bits)."""
    if address.size == "X":
        return bool(data[address.byte] >> address.bit & 1)
    n = address.bits // 8
    raw = bytes(data[address.byte:address.byte + n])
    if kind == "real":
        return struct.unpack("<f" if n == 4 else "<d", raw)[0]
    value = int.from_bytes(raw, "little", signed=signed)
    return bool(value & 1) if kind == "bool" else value


def encode(data: bytearray, address: Address, kind: str, value) -> None:
    """Store `value` at `address` in `data`."""
    if address.size == "X":
        mask = 1 << address.bit
        data[address.byte] = data[address.byte] | mask if value else data[address.byte] & ~mask
        return
    n = address.bits // 8
    if kind == "real":
        raw = struct.pack("<f" if n == 4 else "<d", value)
    else:
        raw = (int(value) & ((1 << address.bits) - 1)).to_bytes(n, "little")
    data[address.byte:address.byte + n] = raw


def union_property(t) -> property:
    """A UNION member: its value lives at byte 0 of the object's shared bytes."""
    size = "X" if t.kind == "bool" else {8: "B", 16: "W", 32: "D", 64: "L"}[t.bits]
    address = Address("U", size, 0, 0, "")
    kind, signed = t.kind, bool(getattr(t, "signed", False))

    def read(self):
        return decode(self._bytes, address, kind, signed)

    def write(self, value):
        encode(self._bytes, address, kind, value)

    return property(read, write)


def located_property(image: ProcessImage, address: Address, t) -> property:
    """A class attribute that stores a located variable in the image."""
    kind, signed = t.kind, bool(getattr(t, "signed", False))

    def read(_self):
        return image.get(address, kind, signed)

    def write(_self, value):
        image.set(address, kind, value)

    return property(read, write)


def type_fits(address: Address, t) -> bool:
    """Whether an elementary type has the width of the address's size."""
    kind = getattr(t, "kind", None)
    if address.size == "X":
        return kind == "bool"
    if kind == "bool":
        return address.size == "B"
    return kind in ("int", "bits", "real") and t.bits == address.bits


class ImageCell:
    """One address of the image as a reference (`get`/`set`): `%QX0.1` in code."""

    __slots__ = ("image", "address", "kind", "signed")

    def __init__(self, image: ProcessImage, address: Address, t):
        self.image, self.address = image, address
        self.kind, self.signed = t.kind, bool(getattr(t, "signed", False))

    def get(self):
        return self.image.get(self.address, self.kind, self.signed)

    def set(self, value) -> None:
        self.image.set(self.address, self.kind, value)


class ImageView:
    """`plc.image["%IW2"]`: an address read or written as its plain type."""

    def __init__(self, image: ProcessImage):
        self.image = image

    def _address(self, text: str) -> Address:
        address, problem = parse_address(text)
        if address is None:
            raise KeyError(problem or f"'{text}': %I* has no place in the image")
        return address

    def __getitem__(self, text: str):
        address = self._address(text)
        return self.image.get(address, "bool" if address.size == "X" else "bits")

    def __setitem__(self, text: str, value) -> None:
        address = self._address(text)
        if address.size == "X":
            if not isinstance(value, bool):
                raise ValueError(f"{text}: expected true or false, found {value!r}")
        elif isinstance(value, bool) or not isinstance(value, int) \
                or not 0 <= value < 1 << address.bits:
            raise ValueError(f"{text}: expected an integer 0..{(1 << address.bits) - 1}, "
                             f"found {value!r}")
        self.image.set(address, "bool" if address.size == "X" else "bits", value)

