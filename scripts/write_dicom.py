#!/usr/bin/python3
"""Write a volume as a DICOM series, one CT image per slice, for cutaway's tests
and its DICOM example scene. Reads NRRD (attached header, raw or gzip) and
NIfTI-1 (.nii, .nii.gz) through its own few lines; writes through pydicom
(Debian's python3-pydicom) and, for a compressed series, GDCM's gdcmconv
(libgdcm-tools).

  scripts/write_dicom.py IN OUT_FOLDER [options]

The physical values are stored as int16 (or uint16 with --unsigned) through
RescaleSlope/Intercept: stored = round((value - intercept) / slope), by default
the file's own scaling (NIfTI scl_slope/scl_inter; 1 and 0 for NRRD), so its
stored numbers are kept. The series lies at --origin with rows along x,
columns along y (turned by --oblique), not at the file's own place.
"""
import argparse
import gzip
import os
import random
import struct
import subprocess
import sys

import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileDataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

NRRD_TYPES = {"uint8": "u1", "uchar": "u1", "unsigned char": "u1", "int8": "i1",
              "signed char": "i1", "uint16": "u2", "ushort": "u2", "unsigned short": "u2",
              "int16": "i2", "short": "i2", "signed short": "i2", "uint32": "u4",
              "int32": "i4", "int": "i4", "float": "f4", "double": "f8"}
NIFTI_TYPES = {2: "u1", 4: "i2", 8: "i4", 16: "f4", 64: "f8", 256: "i1", 512: "u2", 768: "u4"}


def read_nrrd(path):
    data = open(path, "rb").read()
    header, _, body = data.partition(b"\n\n")
    fields = {}
    for line in header.decode("latin-1").split("\n")[1:]:
        if ":" in line and not line.startswith("#"):
            key, value = line.split(":", 1)
            fields[key.strip()] = value.strip().lstrip("=").strip()
    sizes = [int(v) for v in fields["sizes"].split()]
    if fields.get("encoding", "raw") in ("gzip", "gz"):
        body = gzip.decompress(body)
    endian = ">" if fields.get("endian") == "big" else "<"
    values = np.frombuffer(body, endian + NRRD_TYPES[fields["type"]], count=int(np.prod(sizes)))
    spacing = [1.0, 1.0, 1.0]
    if "spacings" in fields:
        spacing = [float(v) for v in fields["spacings"].split()]
    elif "space directions" in fields:
        vectors = fields["space directions"].replace("(", " ").replace(")", " ").split()
        v = np.array([float(x) for x in " ".join(vectors).replace(",", " ").split()]).reshape(3, 3)
        spacing = list(np.linalg.norm(v, axis=1))
    return values.reshape(sizes[::-1]).astype(np.float64), spacing, 1.0, 0.0


def read_nifti(path):
    data = open(path, "rb").read()
    if path.endswith(".gz"):
        data = gzip.decompress(data)
    dims = struct.unpack_from("<8h", data, 40)
    datatype = struct.unpack_from("<h", data, 70)[0]
    pixdim = struct.unpack_from("<8f", data, 76)
    offset = int(struct.unpack_from("<f", data, 108)[0])
    slope, inter = struct.unpack_from("<2f", data, 112)
    nx, ny, nz = dims[1], dims[2], max(dims[3], 1)
    values = np.frombuffer(data, "<" + NIFTI_TYPES[datatype], count=nx * ny * nz, offset=offset)
    values = values.reshape(nz, ny, nx).astype(np.float64)
    if slope == 0.0 or np.isnan(slope):  # NIfTI: no scaling
        slope, inter = 1.0, 0.0
    return values, [abs(pixdim[1]), abs(pixdim[2]), abs(pixdim[3])], float(slope), float(inter)


def orientation(oblique_degrees):
    a = np.radians(oblique_degrees)
    row = np.array([np.cos(a), np.sin(a), 0.0])
    column = np.array([-np.sin(a) * np.cos(a), np.cos(a) * np.cos(a), np.sin(a)])
    column /= np.linalg.norm(column)
    return row, column


def slice_dataset(args, k, pixels, spacing, row, column, normal, uids):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"  # CT Image Storage
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = FileDataset(None, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.StudyInstanceUID, ds.SeriesInstanceUID, ds.FrameOfReferenceUID = uids
    ds.Modality = "CT"
    ds.PatientName = "Phantom^Test"
    ds.PatientID = "cutaway"
    ds.SeriesNumber = args.series_number
    ds.SeriesDescription = args.description
    ds.InstanceNumber = k + 1 if not args.shuffle else random.randint(1, 10000)
    position = np.array(args.origin) + normal * (k * spacing[2])
    if k >= args.slices // 2:
        position = position + normal * args.skew
    if args.tilt:
        position = position + row * (k * args.tilt)
    ds.ImagePositionPatient = [f"{v:.6f}" for v in position]
    ds.ImageOrientationPatient = [f"{v:.6f}" for v in list(row) + list(column)]
    ds.PixelSpacing = [f"{spacing[1]:.6f}", f"{spacing[0]:.6f}"]
    ds.SliceThickness = f"{spacing[2]:.6f}"
    ds.Rows, ds.Columns = pixels.shape
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated = ds.BitsStored = 16
    ds.HighBit = 15
    ds.PixelRepresentation = 0 if args.unsigned else 1
    ds.RescaleSlope = f"{args.slope:.10g}"
    ds.RescaleIntercept = f"{args.intercept:.10g}"
    stored = np.round((pixels - args.intercept) / args.slope)
    ds.PixelData = stored.astype("<u2" if args.unsigned else "<i2").tobytes()
    ds.is_little_endian, ds.is_implicit_VR = True, False
    return ds


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input")
    p.add_argument("out")
    p.add_argument("--series-number", type=int, default=1)
    p.add_argument("--description", default="volume")
    p.add_argument("--uid", help="SeriesInstanceUID (default: a new one)")
    p.add_argument("--unsigned", action="store_true", help="uint16 instead of int16")
    p.add_argument("--slope", type=float, help="RescaleSlope (default: the file's scaling)")
    p.add_argument("--intercept", type=float, help="RescaleIntercept (default: the file's)")
    p.add_argument("--oblique", type=float, default=0.0,
                   help="degrees the rows turn about z and the columns tip (an oblique stack)")
    p.add_argument("--origin", type=float, nargs=3, default=[-100.0, -80.0, 40.0])
    p.add_argument("--shuffle", action="store_true",
                   help="random file names and InstanceNumbers, unrelated to the slice order")
    p.add_argument("--jpeg-lossless", action="store_true", help="recompress with gdcmconv -J")
    p.add_argument("--skip-slice", type=int, help="leave this slice out (a missing slice)")
    p.add_argument("--skew", type=float, default=0.0,
                   help="mm the second half of the slices moves along the normal: uneven spacing")
    p.add_argument("--tilt", type=float, default=0.0, help="mm each slice shifts along rows")
    p.add_argument("--truncate-slice", type=int, help="cut this slice's file in half")
    p.add_argument("--media-names", action="store_true",
                   help="file names IM000001... as DICOM media (and gdcmgendir) want them")
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args()
    random.seed(args.seed)
    reader = read_nifti if args.input.endswith((".nii", ".nii.gz")) else read_nrrd
    raw, spacing, slope, inter = reader(args.input)
    values = raw * slope + inter
    if args.slope is None:
        args.slope = slope
    if args.intercept is None:
        args.intercept = inter
    row, column = orientation(args.oblique)
    normal = np.cross(row, column)
    study = generate_uid()
    uids = (study, args.uid or generate_uid(), generate_uid())
    os.makedirs(args.out, exist_ok=True)
    args.slices = values.shape[0]
    order = list(range(args.slices))
    if args.shuffle:
        random.shuffle(order)
    for k in range(values.shape[0]):
        if k == args.skip_slice:
            continue
        ds = slice_dataset(args, k, values[k], spacing, row, column, normal, uids)
        if args.media_names:
            name = f"IM{order[k] + 1:06d}"
        else:
            name = f"{random.getrandbits(48):012x}" if args.shuffle else f"slice{k:04d}.dcm"
        path = os.path.join(args.out, name)
        ds.save_as(path, write_like_original=False)
        if args.jpeg_lossless:
            subprocess.run(["gdcmconv", "-J", path, path], check=True)
        if k == args.truncate_slice:
            size = os.path.getsize(path)
            with open(path, "r+b") as f:
                f.truncate(size // 2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
