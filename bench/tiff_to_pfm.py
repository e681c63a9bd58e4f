#!/usr/bin/env python3
"""Float RGB TIFF (uncompressed, one strip, as `oiiotool -d float --compression none
--attrib tiff:RowsPerStrip H` writes it) to PFM, for encoders that read PFM but not EXR
(Debian's cjxl 0.7). Standard library only. Usage: tiff_to_pfm.py in.tif out.pfm"""
import struct
import sys


def main(src, dst):
    data = open(src, "rb").read()
    end = "<" if data[:2] == b"II" else ">"
    (ifd,) = struct.unpack(end + "I", data[4:8])
    (count,) = struct.unpack(end + "H", data[ifd:ifd + 2])
    tags = {}
    for k in range(count):
        tag, typ, n, value = struct.unpack(end + "HHII", data[ifd + 2 + 12 * k:ifd + 14 + 12 * k])
        if typ == 3 and n <= 2:  # SHORTs stored in the value field itself: the first one
            value = struct.unpack(end + "H", data[ifd + 10 + 12 * k:ifd + 12 + 12 * k])[0]
        elif typ == 3:  # SHORTs stored elsewhere: the first one
            value = struct.unpack(end + "H", data[value:value + 2])[0]
        tags[tag] = (n, value)
    width, height = tags[256][1], tags[257][1]
    assert tags[277][1] == 3 and tags[259][1] == 1 and tags[339][1] == 3, "needs uncompressed float RGB"
    assert tags[273][0] == 1, "needs one strip"
    offset = tags[273][1]
    row = width * 3 * 4
    with open(dst, "wb") as out:
        out.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        for y in reversed(range(height)):  # PFM rows run bottom to top
            line = data[offset + y * row:offset + (y + 1) * row]
            if end == ">":
                line = b"".join(struct.pack("<f", v) for v in struct.unpack(">%df" % (width * 3), line))
            out.write(line)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
