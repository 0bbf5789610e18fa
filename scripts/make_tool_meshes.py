#!/usr/bin/env python3
"""Writes the example surgical-tool models scenes/meshes/retractor.glb and
scenes/meshes/forceps.gltf (standard library only).

Both are built from closed convex blocks (boxes and tapered hexahedra) with
flat-shaded faces wound counter-clockwise seen from outside. Each tool's
working tip is at the origin and its handle extends along +z. Sizes are
written in millimetres below and stored in metres, glTF's unit.

Usage: python3 scripts/make_tool_meshes.py [output folder]
       (default: scenes/meshes next to this script's folder)
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path

MM = 0.001  # glTF positions are in metres


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


class Mesh:
    def __init__(self):
        self.positions, self.normals, self.indices = [], [], []

    def hexahedron(self, corners):
        """A convex block from 8 corners (in mm): corners[0:4] one end's
        quad and corners[4:8] the other's, in matching order around."""
        centre = [sum(c[i] for c in corners) / 8 for i in range(3)]
        a, b = corners[:4], corners[4:]
        faces = [a, b] + [[a[i], a[(i + 1) % 4], b[(i + 1) % 4], b[i]] for i in range(4)]
        for quad in faces:
            normal = unit(cross(sub(quad[2], quad[0]), sub(quad[3], quad[1])))
            mid = [sum(p[i] for p in quad) / 4 for i in range(3)]
            if dot(normal, sub(mid, centre)) < 0:  # wind counter-clockwise from outside
                quad = quad[::-1]
                normal = [-x for x in normal]
            base = len(self.positions)
            self.positions += [[x * MM for x in p] for p in quad]
            self.normals += [normal] * 4
            self.indices += [base, base + 1, base + 2, base, base + 2, base + 3]

    def box(self, lo, hi):
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        self.hexahedron([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                         [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]])

    def sections(self, rings):
        """Blocks joining consecutive z-sections; each ring is (cx, cy, z,
        half width in x, half height in y)."""
        def quad(cx, cy, z, hx, hy):
            return [[cx - hx, cy - hy, z], [cx + hx, cy - hy, z],
                    [cx + hx, cy + hy, z], [cx - hx, cy + hy, z]]
        for r0, r1 in zip(rings, rings[1:]):
            self.hexahedron(quad(*r0) + quad(*r1))

    def bar(self, p0, p1, half_x, half_t):
        """A flat strip from p0 to p1 in the y-z plane: `half_x` wide in x,
        `half_t` thick across the strip."""
        d = unit(sub(p1, p0))
        n = [0.0, -d[2], d[1]]  # in-plane normal of the strip
        corners = []
        for p in (p0, p1):
            for sx, st in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                corners.append([p[0] + sx * half_x, p[1] + st * half_t * n[1],
                                p[2] + st * half_t * n[2]])
        self.hexahedron(corners)


def retractor():
    """A flat blade bent through 90 degrees into a hook that ends in a short
    lip (its end, the tip, at the origin, pointing -y), and a thicker handle
    with grip ridges."""
    m = Mesh()
    radius, lip, half_w, half_t = 8.0, 10.0, 6.0, 0.75
    blade_y = lip + radius
    # The lip, then an arc up to the blade; each segment runs half a
    # thickness past its ends so the bends stay closed.
    steps = 6
    path = [[0.0, 0.0, 0.0]] + [
        [0.0, lip + radius * math.cos(a), radius - radius * math.sin(a)]
        for a in (math.pi / 2 * (1 - i / steps) for i in range(steps + 1))]
    for i, (p0, p1) in enumerate(zip(path, path[1:])):
        ext = [half_t * x for x in unit(sub(p1, p0))]
        start = p0 if i == 0 else sub(p0, ext)  # the tip itself stays at the origin
        m.bar(start, [p1[k] + ext[k] for k in range(3)], half_w, half_t)
    # The straight blade, then a taper into the handle.
    m.box([-half_w, blade_y - half_t, radius - half_t], [half_w, blade_y + half_t, 45.0])
    m.sections([(0.0, blade_y, 45.0, half_w, half_t), (0.0, blade_y, 52.0, 5.0, 3.0)])
    m.box([-5.0, blade_y - 3.0, 52.0], [5.0, blade_y + 3.0, 130.0])
    for z in (70.0, 85.0, 100.0, 115.0):
        m.box([-5.5, blade_y - 3.5, z], [5.5, blade_y + 3.5, z + 4.0])
    return m


def forceps():
    """Tweezers: two thin arms, joined in a block at the back (z = 112..120
    mm), that spring apart and taper to tips meeting at the origin."""
    m = Mesh()
    # (x of the arm's centre, z, half thickness in x, half width in y)
    path = [(0.45, 0.0, 0.4, 0.6), (1.0, 12.0, 0.5, 1.2), (3.2, 40.0, 0.6, 2.5),
            (4.2, 80.0, 0.6, 3.0), (3.6, 104.0, 0.6, 3.0), (3.0, 113.0, 0.6, 3.0)]

    def outer_x(z):  # the arm's outer face at z
        for (x0, z0, h0, _), (x1, z1, h1, _) in zip(path, path[1:]):
            if z0 <= z <= z1:
                t = (z - z0) / (z1 - z0)
                return x0 + h0 + t * (x1 + h1 - x0 - h0)
        raise ValueError(z)

    for side in (-1.0, 1.0):
        m.sections([(side * x, 0.0, z, hx, hy) for x, z, hx, hy in path])
        # Grip serrations on the outside of each arm, sunk a little into it.
        for z in range(55, 95, 6):
            x0 = min(outer_x(z), outer_x(z + 2.0)) - 0.2
            x1 = max(outer_x(z), outer_x(z + 2.0)) + 0.4
            xs = sorted((side * x0, side * x1))
            m.box([xs[0], -2.6, z], [xs[1], 2.6, z + 2.0])
    m.box([-3.6, -3.0, 112.0], [3.6, 3.0, 120.0])
    return m


def pack(mesh):
    """The mesh as one glTF buffer: positions, normals (float VEC3), indices
    (unsigned short). Returns (bytes, accessors, bufferViews)."""
    f32 = lambda v: struct.unpack("<f", struct.pack("<f", v))[0]  # bounds must match the stored floats
    pos = [[f32(x) for x in p] for p in mesh.positions]
    n = len(pos)
    assert n < 65536
    blob = b"".join(struct.pack("<3f", *p) for p in pos)
    blob += b"".join(struct.pack("<3f", *v) for v in mesh.normals)
    idx = struct.pack("<%dH" % len(mesh.indices), *mesh.indices)
    idx += b"\0" * (-len(idx) % 4)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n, "target": 34962},
             {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n, "target": 34962},
             {"buffer": 0, "byteOffset": 24 * n, "byteLength": 2 * len(mesh.indices),
              "target": 34963}]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
         "min": [min(p[i] for p in pos) for i in range(3)],
         "max": [max(p[i] for p in pos) for i in range(3)]},
        {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": len(mesh.indices), "type": "SCALAR"},
    ]
    return blob + idx, accessors, views


def document(name, mesh, color, buffer):
    data, accessors, views = pack(mesh)
    buffer = dict(buffer(data), byteLength=len(data))
    doc = {
        "asset": {"version": "2.0", "generator": "cutaway scripts/make_tool_meshes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": name, "mesh": 0}],
        "meshes": [{"name": name, "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": name + " steel", "pbrMetallicRoughness": {
            "baseColorFactor": color, "metallicFactor": 1.0, "roughnessFactor": 0.35}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer],
    }
    return doc, data


def write_glb(path, name, mesh, color):
    doc, data = document(name, mesh, color, lambda d: {})
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    total = 12 + 8 + len(text) + 8 + len(data)
    path.write_bytes(struct.pack("<4sII", b"glTF", 2, total) +
                     struct.pack("<I4s", len(text), b"JSON") + text +
                     struct.pack("<I4s", len(data), b"BIN\0") + data)


def write_gltf(path, name, mesh, color):
    uri = lambda d: {"uri": "data:application/octet-stream;base64," +
                     base64.b64encode(d).decode("ascii")}
    doc, _ = document(name, mesh, color, uri)
    path.write_text(json.dumps(doc, indent=1) + "\n")


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenes" / "meshes"
    out.mkdir(parents=True, exist_ok=True)
    write_glb(out / "retractor.glb", "retractor", retractor(), [0.75, 0.77, 0.8, 1.0])
    write_gltf(out / "forceps.gltf", "forceps", forceps(), [0.8, 0.8, 0.82, 1.0])
    for f in ("retractor.glb", "forceps.gltf"):
        print(f"{out / f}: {(out / f).stat().st_size} bytes")


if __name__ == "__main__":
    main()
