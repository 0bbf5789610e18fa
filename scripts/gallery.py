#!/usr/bin/env python3
"""Renders the gallery: every scene below at its own size (512 x 512), from
../shared/data where it needs a real scan, then writes half-size PNG previews
to docs/gallery/ and docs/gallery.md with each picture, its scene file, the
command and the render time. Run through `make gallery`.

Usage: scripts/gallery.py CUTAWAY_BINARY [NAME ...]   (names: render only those)
Standard library only: PNGs are read and written with zlib.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (scene name, title, what it shows, frames in the preview or None for frame 0)
GALLERY = [
    ("fig3_axis_ct_head", "Figure 3(a): axis-aligned peel",
     "A scalp flap on `ct_head` cut along its box: skin and bone lift together.", None),
    ("fig3_surface_ct_head", "Figure 3(b): surface-aligned peel",
     "The same peel, 6 mm below the skin's distance field: only the scalp lifts.", None),
    ("fig3_segment_ct_head", "Figure 3(c): segment-aligned peel",
     "The same peel keeping the bone segment (values 0.5 to 1) in place.", None),
    ("fig1c_peelers_ct_head", "Figure 1(c): several peelers at once",
     "Three surface-aligned flaps on one head, composited with the stencil.", None),
    ("fig7_retractor_shallow_ct_head", "Figure 7(a): retractor, surface-aligned, 4 mm",
     "A retractor that spreads only the scalp.", None),
    ("fig7_retractor_deep_ct_head", "Figure 7(b): retractor, surface-aligned, 12 mm",
     "The same retractor reaching through the skull.", None),
    ("fig7_retractor_segment_ct_head", "Figure 7(c): retractor, segment-aligned",
     "The same retractor keeping the bone in place.", None),
    ("fig8_dilator_lens_brain", "Figure 8: a dilator as a volumetric lens",
     "A spherical lens of magnification 2 on `brain_t1`, its box drawn as a glyph.", None),
    ("fig9_chest", "Figure 9: a retractor opening a torso, pliers pushing aside",
     "`chest_ct`: a retractor spreads the chest wall, its cut faces capped in red, over the "
     "heart; pliers push the aorta aside.", None),
    ("fig10_frog_tools", "Figure 10: retractor and pliers on the frog, with tool meshes",
     "The retractor keeps the organs (segment-aligned) while the rest spreads; pliers pull "
     "an eye; glTF retractor blades and forceps move with their operators.", None),
    ("fig12_orange_stages", "Figure 12: an orange peeled in stages",
     "Four frames of one scene: an animation track opens each surface-aligned flap in turn, "
     "lifting the rind and pith off the segments.", [0, 1, 2, 3]),
    ("turntable_peeled_head", "Turntable of a peeled head",
     "36 frames orbiting `ct_head` with a surface-aligned scalp flap (every ninth shown).",
     [0, 9, 18, 27]),
]


def read_png(path):
    data = open(path, "rb").read()
    i, idat, width, height, colour = 8, b"", 0, 0, 0
    while i < len(data):
        n = struct.unpack(">I", data[i:i + 4])[0]
        kind, chunk = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        i += 12 + n
        if kind == b"IHDR":
            width, height, _, colour = struct.unpack(">IIBB", chunk[:10])
        elif kind == b"IDAT":
            idat += chunk
    bpp = {2: 3, 6: 4}[colour]
    raw, rows, prev, o = zlib.decompress(idat), [], bytearray(width * bpp), 0
    for _ in range(height):
        f, line = raw[o], bytearray(raw[o + 1:o + 1 + width * bpp])
        o += 1 + width * bpp
        for x in range(len(line)):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], (prev[x - bpp] if x >= bpp else 0)
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[k * bpp:k * bpp + 3]) for k in range(width)])
        prev = line
    return rows


def half(rows):
    """Box-filtered half size: a preview small enough to commit."""
    out = []
    for y in range(0, len(rows) - 1, 2):
        r0, r1 = rows[y], rows[y + 1]
        out.append([tuple((r0[x][c] + r0[x + 1][c] + r1[x][c] + r1[x + 1][c] + 2) // 4
                          for c in range(3)) for x in range(0, len(r0) - 1, 2)])
    return out


def write_png(path, rows):
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    binary = os.path.abspath(sys.argv[1])
    only = set(sys.argv[2:])
    out_dir = os.path.join(ROOT, "docs", "gallery")
    os.makedirs(out_dir, exist_ok=True)
    results, started = {}, time.time()
    with tempfile.TemporaryDirectory(prefix="cutaway-gallery-") as tmp:
        for name, _, _, frames in GALLERY:
            if only and name not in only:
                continue
            scene = os.path.join(ROOT, "scenes", name + ".json")
            pattern = os.path.join(tmp, name + "_####.exr")
            t0 = time.time()
            run = subprocess.run([binary, "render", scene, "-o", pattern, "--png", "--quiet"],
                                 stderr=subprocess.PIPE, text=True)
            seconds = time.time() - t0
            if run.returncode != 0:
                print(f"gallery: {name}: skipped ({run.stderr.strip()})", flush=True)
                continue
            picked = frames or [0]
            strips = [half(read_png(os.path.join(tmp, f"{name}_{f:04d}.png"))) for f in picked]
            rows = [sum((s[y] for s in strips), []) for y in range(len(strips[0]))]
            write_png(os.path.join(out_dir, name + ".png"), rows)
            count = len([f for f in os.listdir(tmp) if f.startswith(name) and f.endswith(".exr")])
            results[name] = (seconds, count)
            print(f"gallery: {name}: {count} frame(s) in {seconds:.1f} s", flush=True)
    write_markdown(results)
    print(f"gallery: {len(results)} scene(s) in {time.time() - started:.0f} s; "
          f"previews in docs/gallery/, index in docs/gallery.md")


# A close-up that is not a scene of its own: a cut face before and after
# /operators/N/cut_face (its pictures are made by the command it shows).
CUT_FACE = r"""## A cut face, before and after `cut_face`

![Figure 3(a)'s flap, close up, cut faces in the data's colour](gallery/cut_face_before.png)
![The same, cut faces capped in red](gallery/cut_face_after.png)

Figure 3(a)'s flap close up: on the left the cut faces in the data's own colours, on the right
with `/operators/0/cut_face` (`{"color": [0.78, 0.2, 0.16], "mix": 0.85, "depth": 2}`), the flat
colour illustrators give a cross-section ([operators.md](operators.md#cut-faces)). 256 x 256:

```sh
build/cutaway render scenes/fig3_axis_ct_head.json --set /camera/fov=12 \
  --set '/camera/orbit/target=[0,10,95]' --set '/render/size=[256,256]' --png \
  --set '/operators/0/cut_face={"color":[0.78,0.2,0.16],"mix":0.85,"depth":2}'
```

## A cut face, whole slabs and sub-slabs

![Figure 3(b)'s flap and bared skull, close up, each slab taken whole](gallery/refine_before.png)
![The same with the default sub-slabs](gallery/refine_after.png)

Figure 3(b)'s flap and the skull it bares, close up: on the left each slab taken whole
(`"quality": "draft"`), the grain of one slab per voxel lit once on the cut bone and the
flap's underside; on the right the default, each slab that shows taken in 4 sub-slabs
(`/render/refine`, [quality.md](quality.md)). 256 x 256:

```sh
build/cutaway render scenes/fig3_surface_ct_head.json --set /camera/fov=12 \
  --set '/camera/orbit/target=[0,10,95]' --set '/render/size=[256,256]' --png \
  --set /render/quality=draft
```

## A cut's edge, each ray alone and over the pixel's footprint

![Figure 3(a)'s flap, close up, its cut decided by each pixel's ray alone](gallery/cut_edge_before.png)
![The same with the default coverage over each pixel's footprint](gallery/cut_edge_after.png)

Figure 3(a)'s flap close up: on the left `/render/cut_antialias` 0, where each pixel's ray alone
decides the cut and the flap's edges step from pixel to pixel; on the right the default, the cut
taken over each pixel's footprint ([quality.md](quality.md#antialiased-cuts)). 256 x 256:

```sh
build/cutaway render scenes/fig3_axis_ct_head.json --set /camera/fov=12 \
  --set '/camera/orbit/target=[0,10,95]' --set '/render/size=[256,256]' --png \
  --set /render/cut_antialias=0
```
"""


def write_markdown(results):
    path = os.path.join(ROOT, "docs", "gallery.md")
    old = {}
    if os.path.exists(path):  # keep the times of scenes not rendered this run
        for line in open(path):
            if line.startswith("<!-- time "):
                name, rest = line[len("<!-- time "):].split(" ", 1)
                old[name] = rest.split(" -->")[0]
    lines = ["# Gallery", "",
             "Every picture is a scene in `scenes/` rendered at 512 x 512 by `make gallery` "
             "(previews here at half size). Scenes that read a real scan take it from "
             "`../shared/data/`. Times are wall-clock on the development machine "
             "(2 cores, Mesa lavapipe, no GPU), including loading the scan and the bakes.", ""]
    for name, title, text, _ in GALLERY:
        if name in results:
            seconds, count = results[name]
            time_text = f"{seconds:.1f} s for {count} frame{'s' if count > 1 else ''}"
        else:
            time_text = old.get(name, "not rendered yet")
        lines += [f"## {title}", "", f"![{title}](gallery/{name}.png)", "", text, "",
                  f"- scene: [`scenes/{name}.json`](../scenes/{name}.json)",
                  f"- command: `build/cutaway render scenes/{name}.json --png`",
                  f"- render time: {time_text}", f"<!-- time {name} {time_text} -->", ""]
    lines += CUT_FACE.split("\n")
    open(path, "w").write("\n".join(lines))


if __name__ == "__main__":
    main()
