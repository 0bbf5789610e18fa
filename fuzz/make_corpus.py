#!/usr/bin/env python3
"""Writes the seed corpora and dictionaries of the fuzz targets (run from the
repository root; the output is committed, so this runs only when the seeds
should change):

  fuzz/corpus/scene/  the example scenes of scenes/ and the bad scenes of tests/scene/bad/
  fuzz/corpus/nrrd/   tiny hand-made NRRD files: every voxel type, both byte orders, raw and gzip
  fuzz/corpus/nifti/  tiny hand-made NIfTI-1 and NIfTI-2 files, .nii and .nii.gz
  fuzz/corpus/metaimage/  tiny hand-made MetaImage files (.mha): types, byte orders, zlib
  fuzz/corpus/dicom/  tiny hand-made DICOM slices (explicit VR little endian): types, a
                      rescale, an oblique one, pixel data short, a header cut short
  fuzz/corpus/nhdr/   detached NRRD headers naming the data files of fuzz/nhdr_data/
  fuzz/corpus/gltf/   the example scenes' tool models (scenes/meshes/)
  fuzz/nhdr_data/     the data files those headers name: raw, gzip, with lines to skip
  fuzz/scene.dict     the keys and enum strings of scenes/scene.schema.json
  fuzz/nrrd.dict      NRRD magic, field names and values
  fuzz/metaimage.dict MetaImage keys and values
  fuzz/nhdr.dict      the same, and data file names (fuzz/nhdr_data/'s, a folder, a device)
  fuzz/gltf.dict      glTF keys, enums and component types

Deterministic: gzip streams carry no time stamp, files are written in order.
"""
import gzip
import zlib
import json
import shutil
import struct
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"


def gz(data: bytes) -> bytes:
    return gzip.compress(data, compresslevel=6, mtime=0)


def fresh(name: str) -> Path:
    folder = CORPUS / name
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    return folder


def scene_seeds() -> None:
    out = fresh("scene")
    for src in sorted((ROOT / "scenes").glob("*.json")) + sorted(
        (ROOT / "tests" / "scene" / "bad").glob("*.json")
    ):
        if src.name != "scene.schema.json":
            shutil.copyfile(src, out / src.name)


def nrrd(fields: str, data: bytes, magic: str = "NRRD0004") -> bytes:
    return (magic + "\n" + fields + "\n").encode() + data


def nrrd_seeds() -> None:
    out = fresh("nrrd")
    u8 = bytes(range(8))
    seeds = {
        "uint8-raw.nrrd": nrrd(
            "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\nspacings: 1 1 2.5\n", u8
        ),
        "int8-raw-comments.nrrd": nrrd(
            "# a comment\ntype: signed char\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"
            "content: seed\nkinds: domain domain domain\n",
            bytes([0x80, 0xFF, 0, 1, 2, 3, 4, 0x7F]),
            "NRRD0001",
        ),
        "int16-big-directions.nrrd": nrrd(
            "type: short\ndimension: 3\nsizes: 2 2 1\nendian: big\nencoding: raw\n"
            "space: left-posterior-superior\n"
            "space directions: (0.5,0,0) (0,0.5,0) (0,0,1.5)\nspace origin: (-1,-2,-3)\n",
            struct.pack(">4h", -1024, 0, 40, 3071),
        ),
        "uint16-little-gzip.nrrd": nrrd(
            "type: unsigned short\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: gzip\n",
            gz(struct.pack("<8H", *range(0, 8000, 1000))),
        ),
        "int32-gz-byteskip.nrrd": nrrd(
            "type: int32\ndimension: 3\nsizes: 1 2 2\nendian: little\nencoding: gz\nbyte skip: 4\n",
            gz(b"skip" + struct.pack("<4i", -5, 0, 5, 1 << 20)),
        ),
        "uint32-lineskip.nrrd": nrrd(
            "type: uint\ndimension: 3\nsizes: 2 1 1\nendian: little\nencoding: raw\nline skip: 1\n",
            b"a line to skip\n" + struct.pack("<2I", 0, 4000000000),
        ),
        "float-4d-scaled.nrrd": nrrd(
            "type: float\ndimension: 4\nsizes: 1 2 1 2\nendian: little\nencoding: raw\n"
            "space directions: none (1,0,0) (0,1,0) (0,0,1)\n"
            "cutaway_slope:=2\ncutaway_inter:=-1\n",
            struct.pack("<4f", 0.0, 1.5, float("nan"), -2.0),
            "NRRD0005",
        ),
        "double-byteskip-end.nrrd": nrrd(
            "type: double\ndimension: 3\nsizes: 1 1 2\nendian: big\nencoding: raw\n"
            "byte skip: -1\n",
            b"padding" + struct.pack(">2d", 1e-3, 1e3),
        ),
        "float-gzip-two-members.nrrd": nrrd(
            "type: float\ndimension: 3\nsizes: 2 1 1\nendian: little\nencoding: gzip\n",
            gz(struct.pack("<f", 1.0)) + gz(struct.pack("<f", 2.0)),
        ),
        "detached-header.nhdr": nrrd(
            "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: data.raw\n", b""
        ),
    }
    for name, content in seeds.items():
        (out / name).write_bytes(content)


def nhdr_seeds() -> None:
    data = ROOT / "fuzz" / "nhdr_data"
    shutil.rmtree(data, ignore_errors=True)
    data.mkdir(parents=True)
    (data / "u8.raw").write_bytes(bytes(range(8)))
    (data / "i16-big.raw").write_bytes(struct.pack(">4h", -1024, 0, 40, 3071))
    (data / "f32.gz").write_bytes(gz(struct.pack("<4f", 0.0, 0.5, float("nan"), -2.0)))
    (data / "skip.raw").write_bytes(b"a line to skip\n" + bytes(range(8)))
    out = fresh("nhdr")
    u8 = "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"
    seeds = {
        "u8.nhdr": nrrd(u8 + "data file: u8.raw\n", b""),
        "i16-big.nhdr": nrrd(
            "type: short\ndimension: 3\nsizes: 2 2 1\nendian: big\nencoding: raw\n"
            "space: left-posterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,2)\n"
            "data file: i16-big.raw\n",
            b"",
        ),
        "f32-gzip.nhdr": nrrd(
            "type: float\ndimension: 3\nsizes: 2 2 1\nendian: little\nencoding: gzip\n"
            "data file: f32.gz\n",
            b"",
        ),
        "line-skip.nhdr": nrrd(u8 + "line skip: 1\ndata file: skip.raw\n", b""),
        "byte-skip-end.nhdr": nrrd(u8 + "byte skip: -1\ndata file: skip.raw\n", b""),
        "comments.nhdr": nrrd("# detached\n" + u8 + "content: seed\ndata file: ./u8.raw\n", b"",
                              "NRRD0005"),
    }
    for name, content in seeds.items():
        (out / name).write_bytes(content)


def gltf_seeds() -> None:
    out = fresh("gltf")
    for src in sorted((ROOT / "scenes" / "meshes").iterdir()):
        shutil.copyfile(src, out / src.name)


def nifti(
    dims, datatype: int, bitpix: int, data: bytes, *, big=False, pixdim=(1, 1, 1),
    vox_offset=352.0, slope=0.0, inter=0.0, qform=0, sform=0, extension=b"\0\0\0\0",
) -> bytes:
    e = ">" if big else "<"
    h = bytearray(348)
    struct.pack_into(e + "i", h, 0, 348)
    full = list(dims) + [1] * (7 - len(dims))
    struct.pack_into(e + "8h", h, 40, len(dims), *full)
    struct.pack_into(e + "2h", h, 70, datatype, bitpix)
    struct.pack_into(e + "8f", h, 76, 1.0, *pixdim, 1, 1, 1, 1)
    struct.pack_into(e + "3f", h, 108, vox_offset, slope, inter)
    struct.pack_into(e + "2h", h, 252, qform, sform)
    struct.pack_into(e + "3f", h, 268, 1.0, 2.0, 3.0)  # quatern_x/y/z (the qform's offsets)
    for row, offset in enumerate((280, 296, 312)):  # srow_x/y/z
        struct.pack_into(e + "4f", h, offset, *[1.0 if c == row else 0.0 for c in range(3)], -10)
    h[344:348] = b"n+1\0"
    return bytes(h) + extension + data


def nifti2(dims, datatype: int, bitpix: int, data: bytes, *, big=False, slope=0.0, sform=0) -> bytes:
    e = ">" if big else "<"
    h = bytearray(540)
    struct.pack_into(e + "i", h, 0, 540)
    h[4:12] = b"n+2\0\r\n\x1a\n"
    struct.pack_into(e + "2h", h, 12, datatype, bitpix)
    full = list(dims) + [1] * (7 - len(dims))
    struct.pack_into(e + "8q", h, 16, len(dims), *full)
    struct.pack_into(e + "8d", h, 104, 1.0, 0.5, 0.75, 2.0, 1, 1, 1, 1)
    struct.pack_into(e + "q2d", h, 168, 544, slope, 0.0)
    struct.pack_into(e + "2i", h, 344, 0, sform)
    for row, offset in enumerate((400, 432, 464)):  # srow_x/y/z
        struct.pack_into(e + "4d", h, offset, *[-1.0 if c == row else 0.0 for c in range(3)], 7)
    return bytes(h) + b"\0\0\0\0" + data


def nifti_seeds() -> None:
    out = fresh("nifti")
    seeds = {
        "uint8.nii": nifti((2, 2, 2), 2, 8, bytes(range(8))),
        "int16-big-scaled.nii": nifti(
            (2, 2, 1), 4, 16, struct.pack(">4h", -1024, 0, 40, 3071), big=True,
            pixdim=(0.5, -0.5, 2.0), slope=0.5, inter=-10.0, qform=1,
        ),
        "float32.nii.gz": gz(
            nifti((2, 1, 2), 16, 32, struct.pack("<4f", 0.0, 0.25, float("inf"), -1.0), sform=1)
        ),
        "uint16-4d.nii.gz": gz(nifti((2, 2, 1, 1), 512, 16, struct.pack("<4H", 0, 1, 2, 65535))),
        "int32-old-offset.nii": nifti(
            (1, 1, 2), 8, 32, struct.pack("<2i", -7, 7), vox_offset=0.0, pixdim=(0, 0, 0)
        ),
        "float64-extension.nii": nifti(
            (1, 2, 1), 64, 64, struct.pack("<2d", 1.0, 2.0), vox_offset=368.0,
            extension=b"\1\0\0\0" + struct.pack("<2i", 16, 0) + b"cutaway!",
        ),
        "int8-big.nii.gz": gz(nifti((2, 1, 1), 256, 8, bytes([0x80, 0x7F]), big=True)),
        "uint32.nii": nifti((1, 1, 1), 768, 32, struct.pack("<I", 123456)),
        "nifti2-int16-sform.nii": nifti2((2, 1, 2), 4, 16, struct.pack("<4h", -5, 0, 5, 9),
                                         slope=2.0, sform=1),
        "nifti2-float-big.nii.gz": gz(nifti2((1, 2, 1), 16, 32, struct.pack(">2f", 1.5, -2.0),
                                             big=True)),
    }
    for name, content in seeds.items():
        (out / name).write_bytes(content)


def metaimage(dims, element: str, data: bytes, extra: str = "", big=False) -> bytes:
    header = (f"ObjectType = Image\nNDims = {len(dims)}\nBinaryData = True\n"
              f"BinaryDataByteOrderMSB = {'True' if big else 'False'}\n"
              f"DimSize = {' '.join(str(d) for d in dims)}\nElementType = {element}\n"
              f"{extra}ElementDataFile = LOCAL\n")
    return header.encode() + data


def metaimage_seeds() -> None:
    out = fresh("metaimage")
    seeds = {
        "uchar.mha": metaimage((2, 2, 2), "MET_UCHAR", bytes(range(8))),
        "short-big-placed.mha": metaimage(
            (2, 1, 2), "MET_SHORT", struct.pack(">4h", -1000, 0, 1, 3000), big=True,
            extra="Offset = -1 2 3\nTransformMatrix = 0 1 0 -1 0 0 0 0 1\n"
                  "ElementSpacing = 0.5 0.5 2\n"),
        "float-zlib.mha": metaimage(
            (2, 2, 1), "MET_FLOAT", zlib.compress(struct.pack("<4f", 0.0, 0.25, 1.0, -1.0)),
            extra="CompressedData = True\nCompressedDataSize = 24\n"),
        "ushort-2d.mha": metaimage((3, 2), "MET_USHORT", struct.pack("<6H", 0, 1, 2, 3, 4, 65535)),
        "double-headersize.mha": metaimage(
            (1, 1, 1), "MET_DOUBLE", b"xxxx" + struct.pack("<d", 2.5), extra="HeaderSize = 4\n"),
        "char-at-end.mha": metaimage((2, 1, 1), "MET_CHAR", b"junk" + bytes([0x80, 0x7F]),
                                     extra="HeaderSize = -1\n"),
    }
    for name, content in seeds.items():
        (out / name).write_bytes(content)


def metaimage_dict() -> None:
    keys = ["ObjectType", "NDims", "DimSize", "ElementType", "ElementSpacing", "ElementDataFile",
            "BinaryData", "BinaryDataByteOrderMSB", "ElementByteOrderMSB", "CompressedData",
            "CompressedDataSize", "HeaderSize", "Offset", "Origin", "Position", "TransformMatrix",
            "Rotation", "Orientation", "AnatomicalOrientation", "ElementNumberOfChannels"]
    values = ["MET_UCHAR", "MET_CHAR", "MET_USHORT", "MET_SHORT", "MET_UINT", "MET_INT",
              "MET_FLOAT", "MET_DOUBLE", "MET_LONG_LONG", "LOCAL", "LIST", "True", "False", "-1",
              "Image", "RAI", "\n", "nan", "1e308"]
    dictionary(ROOT / "fuzz" / "metaimage.dict", [k + " = " for k in keys] + values)


def dicom_element(group: int, element: int, vr: str, value: bytes) -> bytes:
    """One data element in explicit VR little endian, padded to an even length."""
    if len(value) % 2:
        value += b"\0" if vr in ("UI", "OB", "OW") else b" "
    head = struct.pack("<HH", group, element) + vr.encode()
    if vr in ("OB", "OW", "UN", "SQ", "UT"):
        return head + b"\0\0" + struct.pack("<I", len(value)) + value
    return head + struct.pack("<H", len(value)) + value


def dicom(rows: int, cols: int, bits: int, signed: bool, pixels: bytes, *, z=0.0,
          orientation="1\\0\\0\\0\\1\\0", spacing="0.5\\0.75", rescale=None) -> bytes:
    """A CT slice as a scanner writes it, the least a reader needs."""
    ct = b"1.2.840.10008.5.1.4.1.1.2"
    meta = dicom_element(0x0002, 0x0010, "UI", b"1.2.840.10008.1.2.1")
    meta = dicom_element(0x0002, 0x0000, "UL", struct.pack("<I", len(meta))) + meta
    data = [
        (0x0008, 0x0016, "UI", ct),
        (0x0008, 0x0018, "UI", b"1.2.3.4.5.6.%d" % int(z * 10)),
        (0x0008, 0x0060, "CS", b"CT"),
        (0x0020, 0x000E, "UI", b"1.2.3.4.5"),
        (0x0020, 0x0011, "IS", b"1"),
        (0x0020, 0x0032, "DS", b"-10\\20\\%g" % z),
        (0x0020, 0x0037, "DS", orientation.encode()),
        (0x0028, 0x0002, "US", struct.pack("<H", 1)),
        (0x0028, 0x0004, "CS", b"MONOCHROME2"),
        (0x0028, 0x0010, "US", struct.pack("<H", rows)),
        (0x0028, 0x0011, "US", struct.pack("<H", cols)),
        (0x0028, 0x0030, "DS", spacing.encode()),
        (0x0028, 0x0100, "US", struct.pack("<H", bits)),
        (0x0028, 0x0101, "US", struct.pack("<H", bits)),
        (0x0028, 0x0102, "US", struct.pack("<H", bits - 1)),
        (0x0028, 0x0103, "US", struct.pack("<H", 1 if signed else 0)),
    ]
    if rescale:
        data += [(0x0028, 0x1052, "DS", b"%g" % rescale[1]),
                 (0x0028, 0x1053, "DS", b"%g" % rescale[0])]
    data.append((0x7FE0, 0x0010, "OW" if bits > 8 else "OB", pixels))
    body = b"".join(dicom_element(*d) for d in data)
    return b"\0" * 128 + b"DICM" + meta + body


def dicom_seeds() -> None:
    out = fresh("dicom")
    u8 = bytes(range(12))
    i16 = struct.pack("<12h", *range(-1000, 1400, 200))
    seeds = {
        "uint8.dcm": dicom(3, 4, 8, False, u8),
        "int16-rescale.dcm": dicom(3, 4, 16, True, i16, z=1.5, rescale=(1.0, -1024.0)),
        "oblique.dcm": dicom(3, 4, 16, False, i16, orientation="0.8660254\\0.5\\0\\-0.5\\0.8660254\\0"),
        "pixels-short.dcm": dicom(5, 4, 16, True, i16),
        "spacing-nan.dcm": dicom(3, 4, 8, False, u8, spacing="nan\\nan"),
        "header-cut.dcm": dicom(3, 4, 16, True, i16)[:200],
        "preamble-only.dcm": b"\0" * 128 + b"DICM",
    }
    for name, data in seeds.items():
        (out / name).write_bytes(data)


def dictionary(path: Path, words) -> None:
    def quoted(word: str) -> str:  # libFuzzer's escapes: \\ \" \xAB
        return '"' + "".join(
            "\\" + c if c in '\\"' else c if " " <= c <= "~" else f"\\x{ord(c):02X}" for c in word
        ) + '"'

    lines = [f"w{i:03d}={quoted(w)}" for i, w in enumerate(words)]
    path.write_text("# Generated by fuzz/make_corpus.py\n" + "\n".join(lines) + "\n")


def scene_dict() -> None:
    schema = json.loads((ROOT / "scenes" / "scene.schema.json").read_text())
    keys, values = set(), set()

    def walk(node):
        if isinstance(node, dict):
            for k, v in node.items():
                if k == "properties" and isinstance(v, dict):
                    keys.update(v)
                if k in ("enum", "const"):
                    values.update(x for x in (v if isinstance(v, list) else [v]) if isinstance(x, str))
                walk(v)
        elif isinstance(node, list):
            for x in node:
                walk(x)

    walk(schema)
    words = [f'"{k}":' for k in sorted(keys)] + [f'"{v}"' for v in sorted(values)]
    words += ["/camera/orbit/azimuth", "/operators/0/params/", "true", "false", "null", "1e400",
              "-0", "[", "]", "{", "}"]
    dictionary(ROOT / "fuzz" / "scene.dict", words)


def nrrd_dict() -> None:
    fields = ["type", "dimension", "sizes", "endian", "encoding", "spacings", "space directions",
              "space origin", "data file", "byte skip", "line skip", "kinds", "space"]
    values = ["NRRD0004", "uint8", "short", "unsigned short", "int", "float", "double", "block",
              "int64", "raw", "gzip", "bzip2", "big", "little", "none", "(1,0,0)", "LIST",
              "cutaway_slope:=", "cutaway_inter:=", "\n\n", "-1", "nan", "inf"]
    dictionary(ROOT / "fuzz" / "nrrd.dict", [f + ": " for f in fields] + values)


def nhdr_dict() -> None:
    words = ["data file: ", "u8.raw", "i16-big.raw", "f32.gz", "skip.raw", ".", "..", "/dev/zero",
             "/dev/stdin", "LIST", "%03d", "byte skip: ", "line skip: ", "encoding: ", "gzip",
             "raw", "sizes: ", "type: ", "NRRD0004", "\n"]
    dictionary(ROOT / "fuzz" / "nhdr.dict", words)


def gltf_dict() -> None:
    keys = ["asset", "version", "buffers", "bufferViews", "accessors", "meshes", "primitives",
            "attributes", "indices", "nodes", "children", "scenes", "scene", "matrix",
            "translation", "rotation", "scale", "uri", "byteLength", "byteOffset", "byteStride",
            "componentType", "count", "type", "mode", "material", "materials", "mesh",
            "pbrMetallicRoughness", "baseColorFactor", "sparse", "images", "textures", "extras",
            "extensions", "normalized", "min", "max", "buffer", "bufferView"]
    values = ['"2.0"', '"POSITION"', '"NORMAL"', '"COLOR_0"', '"SCALAR"', '"VEC3"', '"VEC4"',
              '"MAT4"', "5120", "5121", "5122", "5123", "5125", "5126", '"forceps.gltf"',
              '"retractor.glb"', '"."', '"/dev/zero"', '"data:application/octet-stream;base64,',
              "glTF", "JSON", "BIN\0", "[", "]", "{", "}"]
    dictionary(ROOT / "fuzz" / "gltf.dict", [f'"{k}":' for k in keys] + values)


if __name__ == "__main__":
    scene_seeds()
    nrrd_seeds()
    nifti_seeds()
    metaimage_seeds()
    dicom_seeds()
    nhdr_seeds()
    gltf_seeds()
    scene_dict()
    nrrd_dict()
    metaimage_dict()
    nhdr_dict()
    gltf_dict()
