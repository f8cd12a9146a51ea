"""A picture's _repr_png_ is the library's PNG encoder (sylva/stream.h): decoded here by zlib
and the PNG filter rules (RFC 2083 §6), independently of libpng, it gives back the pixels."""
import os
import struct
import zlib

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def decode_png(data: bytes) -> np.ndarray:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, ihdr = 8, b"", None
    while at < len(data):
        n, tag = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        assert struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0] == zlib.crc32(tag + body) & 0xFFFFFFFF
        if tag == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        at += 12 + n
    w, h, depth, colour, _, _, interlace = ihdr
    assert (depth, colour, interlace) == (8, 6, 0)  # 8-bit RGBA, not interlaced
    raw, stride = zlib.decompress(idat), w * 4
    out = np.zeros((h, stride), np.int32)
    for y in range(h):
        f, line = raw[y * (stride + 1)], np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        up = out[y - 1] if y else np.zeros(stride, np.int32)
        row = out[y]
        for x in range(stride):
            a = row[x - 4] if x >= 4 else 0
            b, c = up[x], (up[x - 4] if x >= 4 else 0)
            if f == 0:
                pred = 0
            elif f == 1:
                pred = a
            elif f == 2:
                pred = b
            elif f == 3:
                pred = (a + b) // 2
            else:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
            row[x] = (line[x] + pred) & 255
    return out.astype(np.uint8).reshape(h, w, 4)


def test_repr_png_decodes_to_the_pixels():
    plant = sylva.load(os.path.join(ROOT, "examples", "abop", "fig1_25_bush3d.syl")).model.build()
    pic = plant.render(24, 16, transparent=True)
    assert (decode_png(pic._repr_png_()) == np.asarray(pic)).all()


def test_png_of_a_wrong_size_is_refused():
    with pytest.raises(ValueError):
        sylva._core.png_rgba(b"\0" * 7, 1, 2)
