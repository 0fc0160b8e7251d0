"""Pixel format decoding against hand-made bit patterns, round trips, and clear errors."""

from __future__ import annotations

import numpy as np
import pytest

from drivers.errors import PixelFormatError
from drivers.pixel_formats import BY_CODE, FORMATS, decode, encode, lookup


def test_mono12p_known_bytes() -> None:
    # PFNC Mono12p: p0 = b0 | (b1 & 0xF) << 8, p1 = b1 >> 4 | b2 << 4
    raw, bits = decode(bytes([0x21, 0x43, 0x65, 0xFF, 0x0F, 0x00]), 4, 1, "Mono12p")
    assert bits == 12 and raw.dtype == np.uint16
    assert raw.tolist() == [[0x321, 0x654, 0xFFF, 0x000]]


def test_mono10p_known_bytes() -> None:
    # LSB-first stream: 0x3FF, 0x000, 0x155, 0x2AA -> FF 03 50 95 AA (worked out bit by bit)
    raw, bits = decode(bytes([0xFF, 0x03, 0x50, 0x95, 0xAA]), 2, 2, "Mono10p")
    assert bits == 10 and raw.tolist() == [[0x3FF, 0x000], [0x155, 0x2AA]]


def test_gvsp_mono12packed_known_bytes() -> None:
    # GigE Vision Mono12Packed: p0 = b0 << 4 | b1 & 0xF, p1 = b2 << 4 | b1 >> 4
    raw, _ = decode(bytes([0xAB, 0x4C, 0xDE]), 2, 1, "Mono12Packed")
    assert raw.tolist() == [[0xABC, 0xDE4]]


def test_gvsp_mono10packed_known_bytes() -> None:
    raw, _ = decode(bytes([0xAB, 0x21, 0xDE]), 2, 1, "Mono10Packed")
    assert raw.tolist() == [[0xAB << 2 | 1, 0xDE << 2 | 2]]


def test_mono16_little_endian_and_mono8_zero_copy() -> None:
    raw, bits = decode(bytes([0x34, 0x12, 0xFF, 0xFF]), 2, 1, "Mono16")
    assert bits == 16 and raw.tolist() == [[0x1234, 0xFFFF]]
    data = bytes(range(16))
    raw8, _ = decode(data, 4, 4, 0x01080001)
    assert raw8.dtype == np.uint8 and np.shares_memory(raw8, np.frombuffer(data, np.uint8))


@pytest.mark.parametrize("name", sorted(FORMATS))
@pytest.mark.parametrize("shape", [(4, 6), (3, 5), (2, 1)])
def test_round_trip(name: str, shape: tuple[int, int]) -> None:
    pf = FORMATS[name]
    rng = np.random.default_rng(0)
    codes = rng.integers(0, 2**pf.bit_depth, size=shape).astype(pf.dtype)
    wire = encode(codes, name)
    assert len(wire) == pf.payload_bytes(shape[1], shape[0])
    raw, bits = decode(wire, shape[1], shape[0], name)
    assert bits == pf.bit_depth and raw.dtype == pf.dtype
    np.testing.assert_array_equal(raw, codes)


def test_lucid_polarized_codes_decode_like_mono() -> None:
    codes = np.arange(24, dtype=np.uint16).reshape(4, 6) * 170
    wire = encode(codes, "Mono12p")
    raw, bits = decode(wire, 6, 4, 0x810C0047)  # LUCID PolarizeMono12p
    assert bits == 12
    np.testing.assert_array_equal(raw, codes)
    assert lookup(0x81080001).name == "PolarizeMono8" and not lookup(0x81080001).verified


def test_row_stride_padding() -> None:
    codes = np.arange(8, dtype=np.uint8).reshape(2, 4)
    padded = bytes([0, 1, 2, 3, 99, 99, 4, 5, 6, 7])  # 2 padding bytes after the first line
    raw, _ = decode(padded, 4, 2, "Mono8", row_stride_bytes=6)
    np.testing.assert_array_equal(raw, codes)


def test_unknown_code_names_it_in_hex() -> None:
    with pytest.raises(PixelFormatError, match=r"0x8123ABCD.*35 bits.*vendor"):
        lookup(0x8123ABCD)
    with pytest.raises(PixelFormatError, match="'Mono9'"):
        lookup("Mono9")


def test_short_buffer_is_an_error() -> None:
    with pytest.raises(PixelFormatError, match=r"Mono12p 4x4: buffer of 23 B, need 24 B"):
        decode(bytes(23), 4, 4, "Mono12p")


def test_code_table_is_consistent() -> None:
    for code, pf in BY_CODE.items():
        assert (code >> 16) & 0xFF == pf.wire_bits, pf.name
