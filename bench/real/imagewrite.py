"""imagewrite.py: writes 8-bit greyscale TIFF pictures (Deflate-compressed, one strip) with the
Python standard library, as inputs to the scenes' MakeTexture requests."""
import struct
import zlib


def write_tiff_gray8(path, width, height, pixels):
    """pixels: width * height values in [0, 1], row by row from the top."""
    raw = bytes(max(0, min(255, int(round(p * 255)))) for p in pixels)
    assert len(raw) == width * height
    data = zlib.compress(raw, 9)
    tags = [
        (256, 4, 1, width),        # ImageWidth
        (257, 4, 1, height),       # ImageLength
        (258, 3, 1, 8),            # BitsPerSample
        (259, 3, 1, 8),            # Compression: Adobe Deflate
        (262, 3, 1, 1),            # PhotometricInterpretation: BlackIsZero
        (273, 4, 1, 0),            # StripOffsets (filled below)
        (277, 3, 1, 1),            # SamplesPerPixel
        (278, 4, 1, height),       # RowsPerStrip
        (279, 4, 1, len(data)),    # StripByteCounts
        (284, 3, 1, 1),            # PlanarConfiguration: contiguous
    ]
    ifd_offset = 8
    ifd_size = 2 + 12 * len(tags) + 4
    data_offset = ifd_offset + ifd_size
    out = bytearray(b"II*\x00" + struct.pack("<I", ifd_offset))
    out += struct.pack("<H", len(tags))
    for tag, kind, count, value in tags:
        if tag == 273:
            value = data_offset
        if kind == 3:
            out += struct.pack("<HHIHH", tag, kind, count, value, 0)
        else:
            out += struct.pack("<HHII", tag, kind, count, value)
    out += struct.pack("<I", 0)
    out += data
    with open(path, "wb") as f:
        f.write(out)


def box_blur(pixels, width, height, radius):
    """A separable box blur of the given radius, clamped at the borders."""
    def blur_rows(src, w, h):
        dst = [0.0] * (w * h)
        for y in range(h):
            row = src[y * w:(y + 1) * w]
            for x in range(w):
                lo, hi = max(0, x - radius), min(w - 1, x + radius)
                dst[y * w + x] = sum(row[lo:hi + 1]) / (hi - lo + 1)
        return dst

    def transpose(src, w, h):
        return [src[y * w + x] for x in range(w) for y in range(h)]

    p = blur_rows(pixels, width, height)
    p = transpose(p, width, height)
    p = blur_rows(p, height, width)
    return transpose(p, height, width)
