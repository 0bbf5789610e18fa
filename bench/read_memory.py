"""Peak memory of reading a gzip'd volume, against the bound docs/reliability.md states.

For each voxel type, writes a gzip'd NIfTI-1 of N^3 voxels (default 1024;
the data a ramp along x, so the stream really holds every byte) and runs
`cutaway info` on it under /usr/bin/time, whose "Maximum resident set size"
is the process's peak. The bound is the declared size plus the reader's
1 MiB chunk, plus what `cutaway info` holds besides the volume (its
baseline: the same command on an 8^3 file). Prints one row per type: the
declared size, the peak, the peak less the baseline, and whether it is
within the bound.

Usage: python3 bench/read_memory.py [--size N] [--types uint8,int16,...]
       [--cutaway BINARY] [--keep DIR]
"""
import argparse
import gzip
import os
import re
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TYPES = {  # name: (NIfTI datatype, bytes per voxel, struct code)
    "uint8": (2, 1, "B"),
    "int16": (4, 2, "h"),
    "int32": (8, 4, "i"),
    "float32": (16, 4, "f"),
    "float64": (64, 8, "d"),
}
CHUNK = 1 << 20


def nifti_header(n, datatype, size):
    h = bytearray(352)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, 3, n, n, n, 1, 1, 1, 1)
    struct.pack_into("<hh", h, 70, datatype, size * 8)
    struct.pack_into("<8f", h, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", h, 108, 352.0)
    h[344:348] = b"n+1\0"
    return bytes(h)


def write_volume(path, n, type_name):
    datatype, size, code = TYPES[type_name]
    row = struct.pack("<%d%s" % (n, code), *[(x % 100) for x in range(n)])
    with gzip.open(path, "wb", compresslevel=1) as out:
        out.write(nifti_header(n, datatype, size))
        for _ in range(n * n):
            out.write(row)
    return n ** 3 * size


def peak_kib(binary, path):
    r = subprocess.run(["/usr/bin/time", "-v", binary, "info", path],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("cutaway info %s failed: %s" % (path, r.stderr[-2000:]))
    return int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", type=int, default=1024)
    p.add_argument("--types", default=",".join(TYPES))
    p.add_argument("--cutaway", default=os.path.join(ROOT, "build", "cutaway"))
    p.add_argument("--keep", help="write the volumes here and keep them")
    a = p.parse_args()
    folder = a.keep or tempfile.mkdtemp(prefix="cutaway-read-memory-")
    small = os.path.join(folder, "small.nii.gz")
    write_volume(small, 8, "uint8")
    baseline = peak_kib(a.cutaway, small)
    print("baseline (8^3 uint8): %d MiB" % (baseline // 1024))
    print("%-8s %10s %10s %14s %s" % ("type", "declared", "peak", "peak-baseline", "within"))
    for name in a.types.split(","):
        path = os.path.join(folder, "%s_%d.nii.gz" % (name, a.size))
        declared = write_volume(path, a.size, name)
        peak = peak_kib(a.cutaway, path)
        extra = (peak - baseline) * 1024
        within = extra <= declared + CHUNK
        print("%-8s %7d MiB %7d MiB %10d MiB %s" % (name, declared >> 20, peak // 1024,
                                                    extra >> 20, "yes" if within else "NO"))
        if not a.keep:
            os.remove(path)
    if not a.keep:
        os.remove(small)
        os.rmdir(folder)


if __name__ == "__main__":
    main()
