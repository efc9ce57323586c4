"""The special-file and size cases of scripts/check_bounded_inputs.sh, made in
a scratch folder: inputs no loader may read in full, hang on or crash on.
Standard library only."""

import os
import struct
import zlib

GIB = 1 << 30
VOCABULARY_EXTENSIONS = (".bin", ".txt", ".dbow3", ".yml", ".bowgvoc")


def _special(folder, stem, ext):
    """FIFO, directory, /dev/zero link and sparse 3 GiB file named *ext."""
    cases = []
    fifo = os.path.join(folder, stem + "_fifo" + ext)
    os.mkfifo(fifo)
    cases.append(("fifo" + ext, fifo))
    directory = os.path.join(folder, stem + "_dir" + ext)
    os.mkdir(directory)
    cases.append(("directory" + ext, directory))
    zero = os.path.join(folder, stem + "_devzero" + ext)
    os.symlink("/dev/zero", zero)
    cases.append(("/dev/zero link" + ext, zero))
    sparse = os.path.join(folder, stem + "_sparse3g" + ext)
    with open(sparse, "wb") as f:
        f.truncate(3 * GIB)  # no block written: 3 GiB of zeros for the reader
    cases.append(("sparse 3 GiB" + ext, sparse))
    return cases


def _gzip_bomb(path, decompressed=3 * GIB):
    """A gzip YAML header then zeros: ~3 MB on disk, `decompressed` bytes."""
    header = b"%YAML:1.0\n---\nvocabulary:\n   k: 10\n   L: 6\n   nodes: [\n"
    comp = zlib.compressobj(9, zlib.DEFLATED, 31)  # 31: gzip container
    chunk = b"\0" * (16 << 20)
    with open(path, "wb") as f:
        f.write(comp.compress(header))
        left = decompressed - len(header)
        while left > 0:
            piece = chunk if left >= len(chunk) else chunk[:left]
            f.write(comp.compress(piece))
            left -= len(piece)
        f.write(comp.flush())


def _png_chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def _huge_png(path, side=30000):
    """A valid grey PNG of side x side pixels (900 MB decoded), ~1 MB on disk."""
    row = b"\0" * (side + 1)  # filter byte + pixels
    comp = zlib.compressobj(9)
    idat = []
    rows_per_piece = 512
    piece = row * rows_per_piece
    done = 0
    while done < side:
        n = min(rows_per_piece, side - done)
        idat.append(comp.compress(piece if n == rows_per_piece else row * n))
        done += n
    idat.append(comp.flush())
    ihdr = struct.pack(">IIBBBBB", side, side, 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(_png_chunk(b"IHDR", ihdr))
        f.write(_png_chunk(b"IDAT", b"".join(idat)))
        f.write(_png_chunk(b"IEND", b""))


def _small_png(path, side=64):
    row = b"\0" + bytes((x * 3) % 256 for x in range(side))
    ihdr = struct.pack(">IIBBBBB", side, side, 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(_png_chunk(b"IHDR", ihdr))
        f.write(_png_chunk(b"IDAT", zlib.compress(row * side)))
        f.write(_png_chunk(b"IEND", b""))


def make_cases(folder):
    """Returns (vocabulary_cases, database_cases, image_folders, small_images):
    lists of (case name, path); small_images is a folder of one valid image,
    for the evaluator's vocabulary cases."""
    vocabulary = []
    for ext in VOCABULARY_EXTENSIONS:
        vocabulary += _special(folder, "voc", ext)
    bomb = os.path.join(folder, "voc_bomb.yml.gz")
    _gzip_bomb(bomb)
    vocabulary.append(("gzip bomb %.0f MB.yml.gz" % (os.path.getsize(bomb) / 1e6), bomb))
    database = _special(folder, "db", ".bowgdb")
    huge = os.path.join(folder, "huge_images")
    os.mkdir(huge)
    _huge_png(os.path.join(huge, "000000.png"))
    images = [("30000x30000 PNG in --images", huge)]
    small = os.path.join(folder, "small_images")
    os.mkdir(small)
    _small_png(os.path.join(small, "000000.png"))
    return vocabulary, database, images, small
