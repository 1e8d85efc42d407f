#!/usr/bin/env python3
# make_pngs.py: writes the small PNG files the game tests read (query masks, png_io cases),
# with nothing but the standard library (zlib, struct). The PNGs are committed; run this
# from any folder only to regenerate them: python3 tests/data/make_pngs.py
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def ihdr(width, height, bit_depth, color_type, interlace=0):
    return chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, interlace))


def png(width, height, bit_depth, color_type, raw, extra=b"", interlace=0):
    """raw: the filtered scanlines (filter byte 0 + packed pixels per row)."""
    return (b"\x89PNG\r\n\x1a\n" + ihdr(width, height, bit_depth, color_type, interlace) + extra +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def rows_of(pixel_rows):
    return b"".join(b"\x00" + bytes(row) for row in pixel_rows)


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


# mask_4x4.png, RGBA8: opaque (alpha 255) 2x2 block at pixels (1,1)-(2,2); pixel (3,0) has
# alpha 100 (clear at the default threshold 127, set at threshold 50); the rest alpha 0.
alpha = [[0, 0, 0, 100], [0, 255, 255, 0], [0, 255, 255, 0], [0, 0, 0, 0]]
mask_rows = [[v for a in row for v in (200, 50, 25, a)] for row in alpha]
mask_png = png(4, 4, 8, 6, rows_of(mask_rows))
write("mask_4x4.png", mask_png)

# corrupt_crc.png: mask_4x4.png with one byte of the compressed IDAT data changed, so the
# IDAT chunk's CRC no longer matches.
idat = mask_png.index(b"IDAT")
corrupt = bytearray(mask_png)
corrupt[idat + 4 + 2] ^= 0x01
write("corrupt_crc.png", bytes(corrupt))

# truncated.png: mask_4x4.png cut off in the middle of the IDAT chunk.
write("truncated.png", mask_png[:idat + 10])

# not_png.png: text, not a PNG.
write("not_png.png", b"this is not a PNG file\n")

# palette_trns.png: 2x2, 2-bit palette [red, green, blue, white] with tRNS alphas
# [255, 128, 0] (white, the 4th entry, stays opaque); pixels (0,1 / 2,3).
palette = chunk(b"PLTE", bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255]))
trns = chunk(b"tRNS", bytes([255, 128, 0]))
write("palette_trns.png", png(2, 2, 2, 3, b"\x00" + bytes([0b00010000]) + b"\x00" + bytes([0b10110000]),
                              palette + trns))

# gray16.png: 3x1, 16-bit grey 0x0000, 0x8080, 0xFFFF (scaled to 0, 128, 255; alpha 255).
write("gray16.png", png(3, 1, 16, 0, b"\x00" + struct.pack(">HHH", 0x0000, 0x8080, 0xFFFF)))

# gray_alpha.png: 2x1, 8-bit grey + alpha (10, 20), (200, 255).
write("gray_alpha.png", png(2, 1, 8, 4, rows_of([[10, 20, 200, 255]])))

# rgb_adam7.png: 3x3 RGB8, Adam7-interlaced; pixel (x, y) = (10x + y, 100 + x, 200 + y).
def rgb(x, y):
    return [10 * x + y, 100 + x, 200 + y]


passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
raw = b""
for x0, y0, dx, dy in passes:
    xs = list(range(x0, 3, dx))
    for y in range(y0, 3, dy):
        if xs:
            raw += b"\x00" + bytes(v for x in xs for v in rgb(x, y))
write("rgb_adam7.png", png(3, 3, 8, 2, raw, interlace=1))

# too_wide.png and too_many_pixels.png: valid headers above read_png's limits (a side over
# 16384; 16384 x 8192 is over 64 Mi pixels). Their image data is not meant to be read.
write("too_wide.png", png(20000, 1, 8, 6, b"\x00" * 16))
write("too_many_pixels.png", png(16384, 8192, 8, 6, b"\x00" * 16))

# wide_5000x1.png: a valid 5000 x 1 RGBA image, readable but wider than a mask may be (4096).
write("wide_5000x1.png", png(5000, 1, 8, 6, b"\x00" + b"\xff" * (5000 * 4)))
