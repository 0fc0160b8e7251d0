"""Wire pixel formats -> raw mosaic codes (uint8/uint16 with a bit depth), vectorised with numpy.

A polarization camera streams its 2x2 polarizer mosaic as a monochrome image: a standard GenICam PFNC Mono
format, or a vendor code that means the same bytes. Codes are 32 bit: bit 31 set = vendor-specific,
bits 16..23 = bits per pixel on the wire, low 16 bits = the format's id.

Packings:
    u8           one byte per pixel (Mono8).
    u16          little-endian 16-bit words, the code in the low ``bit_depth`` bits (Mono10/12/14/16).
    lsb          PFNC "p" packing (Mono10p, Mono12p): one little-endian bit stream, pixel i in bits
                 [i*bits, (i+1)*bits), no padding between pixels.
    gvsp10       GigE Vision "Packed" (Mono10Packed): 2 pixels in 3 bytes, b0 = p0[9:2], b1 = p0[1:0] | p1[1:0]<<4,
                 b2 = p1[9:2].
    gvsp12       GigE Vision "Packed" (Mono12Packed): 2 pixels in 3 bytes, b0 = p0[11:4], b1 = p0[3:0] | p1[3:0]<<4,
                 b2 = p1[11:4].

Vendor codes: LUCID PolarizeMono* as published in third-party copies of LUCID's Arena SDK PFNC header
(``LUCID_PolarizeMono8 0x81080001`` ...), not verified on hardware. FLIR Polarized8/10p/12p/16 are known by name
only: their wire codes were not found, so a FLIR camera is matched through its PixelFormat string
(Aravis gives both). An unknown code or name raises ``PixelFormatError`` naming it (hex for codes).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from drivers.errors import PixelFormatError


@dataclass(frozen=True)
class PixelFormat:
    name: str
    code: int | None  # None: known by name only
    wire_bits: int  # bits per pixel on the wire
    bit_depth: int  # significant bits of the decoded code
    packing: str  # u8, u16, lsb, gvsp10, gvsp12
    verified: bool = True  # False: code published by third parties, not checked on hardware

    @property
    def dtype(self) -> type[np.unsignedinteger]:
        return np.uint8 if self.bit_depth <= 8 else np.uint16

    def payload_bytes(self, width: int, height: int) -> int:
        """Bytes of a ``width`` x ``height`` image without line padding."""
        return -(-width * height * self.wire_bits // 8)


_FORMATS = [
    # GenICam PFNC / GigE Vision standard codes
    PixelFormat("Mono8", 0x01080001, 8, 8, "u8"),
    PixelFormat("Mono10", 0x01100003, 16, 10, "u16"),
    PixelFormat("Mono10Packed", 0x010C0004, 12, 10, "gvsp10"),
    PixelFormat("Mono10p", 0x010A0046, 10, 10, "lsb"),
    PixelFormat("Mono12", 0x01100005, 16, 12, "u16"),
    PixelFormat("Mono12Packed", 0x010C0006, 12, 12, "gvsp12"),
    PixelFormat("Mono12p", 0x010C0047, 12, 12, "lsb"),
    PixelFormat("Mono14", 0x01100025, 16, 14, "u16"),
    PixelFormat("Mono16", 0x01100007, 16, 16, "u16"),
    # LUCID (Phoenix/Triton polarized, IMX250MZR): third-party copies of the Arena SDK header; unverified
    PixelFormat("PolarizeMono8", 0x81080001, 8, 8, "u8", verified=False),
    PixelFormat("PolarizeMono12", 0x81100008, 16, 12, "u16", verified=False),
    PixelFormat("PolarizeMono12Packed", 0x810C0006, 12, 12, "gvsp12", verified=False),
    PixelFormat("PolarizeMono12p", 0x810C0047, 12, 12, "lsb", verified=False),
    PixelFormat("PolarizeMono16", 0x81100007, 16, 16, "u16", verified=False),
    # FLIR (Blackfly S polarized): names only, codes unknown
    PixelFormat("Polarized8", None, 8, 8, "u8", verified=False),
    PixelFormat("Polarized10p", None, 10, 10, "lsb", verified=False),
    PixelFormat("Polarized12p", None, 12, 12, "lsb", verified=False),
    PixelFormat("Polarized16", None, 16, 16, "u16", verified=False),
]

FORMATS: dict[str, PixelFormat] = {f.name: f for f in _FORMATS}
"""Every format the decoder knows, by its GenICam PixelFormat name."""

BY_CODE: dict[int, PixelFormat] = {f.code: f for f in _FORMATS if f.code is not None}


def lookup(fmt: str | int | PixelFormat) -> PixelFormat:
    """A format by name (case-sensitive, as GenICam spells it) or 32-bit code; ``PixelFormatError`` if unknown."""
    if isinstance(fmt, PixelFormat):
        return fmt
    if isinstance(fmt, str):
        if fmt in FORMATS:
            return FORMATS[fmt]
        raise PixelFormatError(f"unknown pixel format {fmt!r}; known: {', '.join(FORMATS)}")
    if fmt in BY_CODE:
        return BY_CODE[fmt]
    raise PixelFormatError(
        f"unknown pixel format code 0x{fmt:08X} ({(fmt >> 16) & 0xFF} bits per pixel"
        f"{', vendor-specific' if fmt & 0x80000000 else ''}); known codes: "
        + ", ".join(f"{f.name}=0x{f.code:08X}" for f in _FORMATS if f.code is not None))


def decode(data: bytes | bytearray | memoryview | np.ndarray, width: int, height: int,
           fmt: str | int | PixelFormat, row_stride_bytes: int | None = None) -> tuple[np.ndarray, int]:
    """Wire bytes -> ((height, width) uint8/uint16 mosaic, bit depth).

    ``row_stride_bytes`` is the length of one line including padding (None: lines are packed back to back).
    Bytes after the image (chunk data) are ignored; too few bytes raise ``PixelFormatError``. Mono8/Mono16 are
    returned as a read-only view of ``data`` when it is already an immutable ``bytes`` object (no copy).
    """
    pf = lookup(fmt)
    buf = np.frombuffer(data, dtype=np.uint8) if not isinstance(data, np.ndarray) else data.reshape(-1).view(np.uint8)
    n = width * height
    row_bytes = width * pf.wire_bits / 8
    if row_stride_bytes is not None and row_stride_bytes != row_bytes:
        if row_bytes != int(row_bytes) or row_stride_bytes < row_bytes:
            raise PixelFormatError(f"{pf.name}: row stride {row_stride_bytes} B does not fit width {width}")
        if buf.size < row_stride_bytes * (height - 1) + row_bytes:
            raise PixelFormatError(f"{pf.name} {width}x{height}: buffer of {buf.size} B is too short for "
                                   f"row stride {row_stride_bytes} B")
        padded = np.lib.stride_tricks.as_strided(buf, (height, int(row_bytes)), (row_stride_bytes, 1))
        buf = np.ascontiguousarray(padded).reshape(-1)
    need = pf.payload_bytes(width, height)
    if buf.size < need:
        raise PixelFormatError(f"{pf.name} {width}x{height}: buffer of {buf.size} B, need {need} B")
    buf = buf[:need]
    if pf.packing == "u8":
        out = buf
    elif pf.packing == "u16":
        out = buf.view("<u2").astype(np.uint16, copy=False)
    elif pf.packing == "lsb":
        out = _unpack_lsb(buf, pf.wire_bits, n)
    elif pf.packing == "gvsp12":
        out = _unpack_gvsp(buf, n, 4)
    elif pf.packing == "gvsp10":
        out = _unpack_gvsp(buf, n, 2)
    else:  # pragma: no cover - table error
        raise PixelFormatError(f"{pf.name}: packing {pf.packing!r} not implemented")
    return out[:n].reshape(height, width), pf.bit_depth


def encode(mosaic: np.ndarray, fmt: str | int | PixelFormat) -> bytes:
    """(H, W) codes -> wire bytes of ``fmt`` (the inverse of ``decode``); codes above the bit depth are an error."""
    pf = lookup(fmt)
    codes = np.ascontiguousarray(mosaic).reshape(-1)
    if codes.size and int(codes.max()) >= 2**pf.bit_depth:
        raise PixelFormatError(f"{pf.name}: code {int(codes.max())} exceeds {pf.bit_depth} bits")
    if pf.packing == "u8":
        return codes.astype(np.uint8).tobytes()
    if pf.packing == "u16":
        return codes.astype("<u2").tobytes()
    if pf.packing == "lsb":
        return _pack_lsb(codes.astype(np.uint64), pf.wire_bits).tobytes()
    low_bits = 4 if pf.packing == "gvsp12" else 2
    return _pack_gvsp(codes.astype(np.uint16), low_bits).tobytes()


def _groups(bits: int) -> tuple[int, int]:
    """(pixels, bytes) of the smallest whole-byte group of ``bits``-bit pixels."""
    px = 8 // np.gcd(bits, 8)
    return px, px * bits // 8


def _unpack_lsb(buf: np.ndarray, bits: int, n: int) -> np.ndarray:
    """LSB-first bit stream of ``bits``-bit pixels -> uint16 codes."""
    px, nbytes = _groups(bits)
    groups = -(-n // px)
    if buf.size < groups * nbytes:  # last group incomplete: pad with zeros
        buf = np.concatenate([buf, np.zeros(groups * nbytes - buf.size, np.uint8)])
    g = buf[: groups * nbytes].reshape(groups, nbytes)
    if bits == 12:  # the common case, done with 16-bit arithmetic
        b0, b1, b2 = (g[:, i].astype(np.uint16) for i in range(3))
        out = np.empty((groups, 2), np.uint16)
        out[:, 0] = b0 | ((b1 & 0x0F) << 8)
        out[:, 1] = (b1 >> 4) | (b2 << 4)
        return out.reshape(-1)
    word = np.zeros(groups, np.uint64)  # a group is at most 8 bytes for bits <= 16
    for i in range(nbytes):
        word |= g[:, i].astype(np.uint64) << np.uint64(8 * i)
    shifts = np.arange(px, dtype=np.uint64) * np.uint64(bits)
    mask = np.uint64((1 << bits) - 1)
    return ((word[:, None] >> shifts[None, :]) & mask).astype(np.uint16).reshape(-1)


def _pack_lsb(codes: np.ndarray, bits: int) -> np.ndarray:
    px, nbytes = _groups(bits)
    n = codes.size
    padded = np.zeros(-(-n // px) * px, np.uint64)
    padded[:n] = codes
    shifts = np.arange(px, dtype=np.uint64) * np.uint64(bits)
    word = np.bitwise_or.reduce(padded.reshape(-1, px) << shifts[None, :], axis=1)
    out = ((word[:, None] >> (np.arange(nbytes, dtype=np.uint64) * np.uint64(8))[None, :]) & np.uint64(0xFF))
    return out.astype(np.uint8).reshape(-1)[: -(-n * bits // 8)]


def _unpack_gvsp(buf: np.ndarray, n: int, low_bits: int) -> np.ndarray:
    """GigE Vision Mono10Packed (``low_bits`` 2) / Mono12Packed (4): 2 pixels in 3 bytes, MSBs in bytes 0 and 2."""
    groups = -(-n // 2)
    if buf.size < groups * 3:
        buf = np.concatenate([buf, np.zeros(groups * 3 - buf.size, np.uint8)])
    g = buf[: groups * 3].reshape(groups, 3).astype(np.uint16)
    mask = (1 << low_bits) - 1
    out = np.empty((groups, 2), np.uint16)
    out[:, 0] = (g[:, 0] << low_bits) | (g[:, 1] & mask)
    out[:, 1] = (g[:, 2] << low_bits) | ((g[:, 1] >> 4) & mask)
    return out.reshape(-1)


def _pack_gvsp(codes: np.ndarray, low_bits: int) -> np.ndarray:
    n = codes.size
    p = np.zeros(-(-n // 2) * 2, np.uint16)
    p[:n] = codes
    p = p.reshape(-1, 2)
    mask = (1 << low_bits) - 1
    out = np.empty((p.shape[0], 3), np.uint8)
    out[:, 0] = p[:, 0] >> low_bits
    out[:, 1] = (p[:, 0] & mask) | ((p[:, 1] & mask) << 4)
    out[:, 2] = p[:, 1] >> low_bits
    return out.reshape(-1)[: -(-n * 12 // 8)]
