#!/usr/bin/env python3
# make_files.py: writes the binary and byte-exact files of the hostile-input catalogue
# (catalogue.json): PNG headers that lie, bad CRCs, binary garbage, a UTF-8 BOM, CRLF line
# ends and a polygon with 1,000 vertices. Only the standard library. The files are committed;
# run this from any folder only to write them again (the same bytes every time):
#   python3 tests/hostile/make_files.py
# Files too large to commit (a 100 KB line, JSON nested 100,000 deep, a level of 10,001
# things) are written by tests/game/hostile_test.cpp when it runs.
import os
import random
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    path = os.path.join(HERE, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def chunk(kind, data, crc=None):
    body = kind + data
    value = zlib.crc32(body) & 0xFFFFFFFF if crc is None else crc
    return struct.pack(">I", len(data)) + body + struct.pack(">I", value)


def png(width, height, raw, ihdr_crc=None):
    ihdr = chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0), ihdr_crc)
    return b"\x89PNG\r\n\x1a\n" + ihdr + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def rgba_rows(width, height, pixel):
    return b"".join(b"\x00" + bytes(pixel) * width for _ in range(height))


# A good 2x2 PNG to compare the bad ones with.
ok = png(2, 2, rgba_rows(2, 2, (10, 20, 30, 255)))
write("png/ok.png", ok)
# A valid header (CRCs right) that claims 100000 x 100000 pixels (40 GB of RGBA): refused from
# the header, before any pixel memory is allocated.
write("png/claims_100000x100000.png", png(100000, 100000, b"\x00" * 16))
# The good PNG with its IHDR chunk's CRC off by one.
ihdr_crc = zlib.crc32(ok[12:29]) & 0xFFFFFFFF
write("png/bad_crc.png", png(2, 2, rgba_rows(2, 2, (10, 20, 30, 255)), ihdr_crc ^ 1))
# Cut in the middle of the IDAT chunk.
write("png/truncated.png", ok[:ok.index(b"IDAT") + 6])
write("png/empty.png", b"")
rng = random.Random(8)
garbage = bytes(rng.randrange(256) for _ in range(512))
write("png/garbage.png", garbage)
# Sprites: one that claims 100000 x 100000 pixels, one readable but wider than a collision
# mask may be (4096 pixels).
write("sprite_assets/sprites/huge.png", png(100000, 100000, b"\x00" * 16))
write("mask_assets/sprites/wide.png", png(5000, 1, rgba_rows(5000, 1, (255, 255, 255, 255))))

# Binary garbage where text is expected.
write("assets/levels/binary.level", garbage)
write("scenarios/binary.scn", garbage)
write("scripts/binary.script", garbage)
write("queries/binary.jsonl", garbage + b"\n")
write("assets/levels/empty.level", b"")
write("scenarios/empty.scn", b"")

# A UTF-8 byte order mark and CRLF line ends: accepted (README, "File formats").
level = b"jostle-level 1\nsize 200 100\nplayer 100 50 0\nwall floor 0 92 200 100\n"
write("ok_assets/levels/bom.level", b"\xef\xbb\xbf" + level)
write("ok_assets/levels/crlf.level", level.replace(b"\n", b"\r\n"))
# A carriage return in the middle of a line is not a line end: refused.
write("assets/levels/lone_cr.level", b"jostle-level 1\nsize 200 100\rplayer 100 50 0\n")

# A polygon rock with 1,000 vertices (a regular 1000-gon of radius 40): convex, but over
# kMaxPolygonVertices (16).
import math
points = []
for i in range(1000):
    a = 2 * math.pi * i / 1000
    points.append("%.3f %.3f" % (40 * math.cos(a), 40 * math.sin(a)))
write("assets/levels/polygon_1000_vertices.level",
      b"jostle-level 1\nsize 200 100\nplayer 100 50 0\nrock r1 poly 100 50 " + " ".join(points).encode() + b"\n")
poly = ",".join("[%.3f,%.3f]" % tuple(40 * f(2 * math.pi * i / 1000) for f in (math.cos, math.sin)) for i in range(1000))
write("queries/polygon_1000_vertices.jsonl",
      ('{"op":"collide","a":{"type":"polygon","points":[' + poly + ']},"b":{"type":"circle","center":[0,0],"radius":1}}\n').encode())

# A scenario with a BOM and CRLF line ends (accepted), on the good level, with an expectation.
scenario = (b"jostle-scenario 1\nengine 0.1.0\nlevel ok\nseed 1\ntick-rate 60\nlevel-hash 238c4785c60662f2\n\n"
            b"0-9 left\nat 9 expect player in 99 49 101 51\nat 10 end\n")
write("scenarios/bom_crlf.scn", b"\xef\xbb\xbf" + scenario.replace(b"\n", b"\r\n"))

# A byte order mark after the start of a file (a file pasted after one that had its own): an
# invisible U+FEFF, refused at its line and column, not shown inside a word.
write("scenarios/bom_inside.scn", scenario.replace(b"0-9 left", b"\xef\xbb\xbf0-9 left"))
write("scripts/bom_inside.script", b"wait 2\n\xef\xbb\xbfwait 3\n")
# A NUL byte in a query line, where the parser would take it for the end of the input.
write("queries/nul_byte.jsonl", b'{"op":"lines"\x00,"a":[[0,0],[1,1]],"b":[[0,1],[1,0]]}\n')
