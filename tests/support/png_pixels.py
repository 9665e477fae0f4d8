"""Reads an 8-bit RGB, RGBA or indexed PNG (no interlace) into rows of pixels, for the command-line
tests. Indexed images come back as RGB (the palette applied).

    rows, channels = read_png(path)          # rows[y][channels * x + c]
    rows, channels, colour_type = read_png(path, with_type=True)
"""
import struct
import zlib


def read_png(path, with_type=False):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat, width, height, colour, palette = 8, b"", 0, 0, 0, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 3, 6), path + ": expected 8-bit RGB, RGBA or indexed"
        elif kind == b"PLTE":
            palette = body
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    bpp = {2: 3, 3: 1, 6: 4}[colour]
    raw, stride, rows, prev = zlib.decompress(idat), bpp * width, [], bytearray(bpp * width)
    for y in range(height):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        f, cur = line[0], bytearray(line[1:])
        for x in range(stride if f else 0):  # the five PNG filters
            a = cur[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1: cur[x] = (cur[x] + a) & 255
            elif f == 2: cur[x] = (cur[x] + b) & 255
            elif f == 3: cur[x] = (cur[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                cur[x] = (cur[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(cur)
        prev = cur
    if colour == 3:
        rows = [bytearray(b"".join(palette[3 * i:3 * i + 3] for i in row)) for row in rows]
    channels = 3 if colour in (2, 3) else 4
    return (rows, channels, colour) if with_type else (rows, channels)
