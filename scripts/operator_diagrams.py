#!/usr/bin/python3
"""Write the labelled operator diagrams of docs/operators.md as SVG
(docs/images/diagrams/), each a section through the operator's box in its
local frame, the tissue surface on top (local +z). The peeler's flap is drawn
from its own formulas (shaders/shared/operator_peeler.h): the layer beyond the
hinge wraps around a cylinder of radius R and continues straight.

  scripts/operator_diagrams.py [OUT_FOLDER]
"""
import math
import os
import sys

W, H = 760, 450
INK, SOFT, CUT, KEEP = "#222", "#888", "#c0392b", "#e8d9c4"
FONT = 'font-family="DejaVu Sans, sans-serif" font-size="13"'


def svg(body):
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
            f'viewBox="0 0 {W} {H}">\n<rect width="{W}" height="{H}" fill="white"/>\n'
            f'<defs><marker id="a" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" '
            f'markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
            f'fill="{INK}"/></marker></defs>\n{body}</svg>\n')


def text(x, y, s, anchor="start", colour=INK):
    return f'<text x="{x:.1f}" y="{y:.1f}" {FONT} fill="{colour}" text-anchor="{anchor}">{s}</text>\n'


def line(x1, y1, x2, y2, colour=INK, dash="", arrow="", width=1.5):
    d = f' stroke-dasharray="{dash}"' if dash else ""
    m = {"end": ' marker-end="url(#a)"', "both": ' marker-start="url(#a)" marker-end="url(#a)"'}
    return (f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" stroke="{colour}" '
            f'stroke-width="{width}"{d}{m.get(arrow, "")}/>\n')


def poly(points, fill, stroke=INK):
    p = " ".join(f"{x:.1f},{y:.1f}" for x, y in points)
    return f'<polygon points="{p}" fill="{fill}" stroke="{stroke}" stroke-width="1.2"/>\n'


class Frame:
    """Local (x, z) of the box [-X, X] x [-1, 1] to the picture."""
    def __init__(self, X, left=60, top=140, scale=100):
        self.X, self.left, self.top, self.s = X, left, top, scale

    def __call__(self, x, z):
        return self.left + (x + self.X) * self.s, self.top + (1 - z) * self.s


def peeler():
    X, h, t, R, theta = 2.0, -0.4, 0.35, 0.35, math.radians(150)
    f = Frame(X, top=200)
    body = poly([f(-X, 1), f(X, 1), f(X, -1), f(-X, -1)], KEEP)
    body += poly([f(h, 1), f(X, 1), f(X, 1 - t), f(h, 1 - t)], "white", CUT)  # the hole
    # The flap: skin (e = 0) and underside (e = t) of the layer x in (h, X].
    def moved(s, e):
        phi = s / R
        if phi <= theta:
            n = (math.sin(phi), -math.cos(phi))
            return h + (R + e) * n[0], 1 + R + (R + e) * n[1]
        n = (math.sin(theta), -math.cos(theta))
        tau = (math.cos(theta), math.sin(theta))
        rest = s - theta * R
        return (h + (R + e) * n[0] + rest * tau[0], 1 + R + (R + e) * n[1] + rest * tau[1])
    length = X - h
    steps = [length * i / 60 for i in range(61)]
    skin = [f(*moved(s, 0)) for s in steps]
    under = [f(*moved(s, t)) for s in reversed(steps)]
    body += poly(skin + under, "#f3c6a5", INK)
    hx, hy = f(h, 1)
    body += line(hx, hy - 20, hx, f(h, -1)[1], SOFT, "5,4")
    body += text(hx - 8, f(h, 0.3)[1], "hinge: mm from the box", "end")
    body += text(hx - 8, f(h, 0.3)[1] + 16, "centre along local x", "end")
    body += text(f(0.8, -0.3)[0], f(0.8, -0.3)[1], "the layer past the hinge (+x) lifts", "middle")
    body += text(f(0.8, -0.3)[0], f(0.8, -0.3)[1] + 18, "and folds back over it toward -x", "middle")
    x0, _ = f(X, 0)
    body += line(x0 + 12, f(X, 1)[1], x0 + 12, f(X, 1 - t)[1], INK, arrow="both")
    body += text(x0 + 18, f(X, 1 - t / 2)[1] + 4, "thickness")
    body += text(f(X, 1)[0] + 18, f(X, 1)[1] - 8, "surface side: local +z")
    cx, cy = f(h, 1 + R)
    body += f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{R * f.s:.1f}" fill="none" stroke="{SOFT}" stroke-dasharray="3,3"/>\n'
    body += line(cx, cy, cx + R * f.s, cy, SOFT)
    body += text(cx + R * f.s / 2, cy - 5, "radius", "middle", SOFT)
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 22,
                 "angle: how far the flap turns (0 flat, 180 folded flat back);  width: along local y (into the page)")
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 40,
                 "with surface alignment the lifted layer follows the surface: see alignment_surface.svg")
    return svg(body)


def retractor():
    X = 2.0
    f = Frame(X)
    body = poly([f(-X, 1), f(X, 1), f(X, -1), f(-X, -1)], KEEP)
    o, d = 0.6, 1.2  # half opening, depth
    body += poly([f(-o, 1), f(o, 1), f(0, 1 - d)], "white", CUT)
    body += line(*f(-o, 1.15), *f(o, 1.15), INK, arrow="both")
    body += text(f(0, 1.15)[0], f(0, 1.15)[1] - 8, "opening (full width at the surface)", "middle")
    body += line(*f(o + 0.25, 1), *f(o + 0.25, 1 - d), INK, arrow="both")
    body += text(f(o + 0.32, 1 - d / 2)[0], f(o + 0.32, 1 - d / 2)[1] + 4, "depth, from the surface down")
    for side in (-1, 1):
        a, b = f(side * 0.7, 0.55), f(side * 1.5, 0.55)
        body += line(*a, *b, INK, arrow="end")
    body += text(f(-1.9, 0.1)[0], f(-1.9, 0.1)[1], "tissue pushed aside along ±x")
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 22,
                 "length: how far the incision runs along local y (into the page); surface side: local +z")
    return svg(body)


def pliers():
    X = 2.0
    f = Frame(X)
    body = poly([f(-X, 1), f(X, 1), f(X, -1), f(-X, -1)], KEEP)
    c, r = f(-0.3, 0.1), 0.75 * f.s
    body += f'<circle cx="{c[0]:.1f}" cy="{c[1]:.1f}" r="{r:.1f}" fill="none" stroke="{SOFT}" stroke-dasharray="5,4"/>\n'
    body += f'<circle cx="{c[0]:.1f}" cy="{c[1]:.1f}" r="4" fill="{CUT}"/>\n'
    e = f(0.6, 0.55)
    body += line(*c, *e, CUT, arrow="end", width=2)
    body += text(c[0] + 8, c[1] + 20, "grasp (from the box centre)")
    body += text(e[0] + 8, e[1], "displacement: where the grasped point goes")
    body += text(c[0], c[1] + r + 16, "radius: the sphere of influence, 0 at its edge", "middle", SOFT)
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 22,
                 "the sphere must fit in the box; |displacement| stays below about half the radius")
    return svg(body)


def dilator():
    X = 2.0
    f = Frame(X)
    body = poly([f(-X, 1), f(X, 1), f(X, -1), f(-X, -1)], KEEP)
    c = f(0, 0)
    inner, outer = 0.35 * f.s, 0.7 * f.s
    body += f'<circle cx="{c[0]:.1f}" cy="{c[1]:.1f}" r="{outer:.1f}" fill="#f3c6a5" stroke="{INK}"/>\n'
    body += f'<circle cx="{c[0]:.1f}" cy="{c[1]:.1f}" r="{inner:.1f}" fill="none" stroke="{SOFT}" stroke-dasharray="4,3"/>\n'
    body += line(c[0], c[1], c[0] + inner, c[1], SOFT)
    body += text(c[0] + inner / 2, c[1] - 6, "radius", "middle", SOFT)
    body += line(c[0], c[1], c[0] - outer * 0.7, c[1] + outer * 0.7, INK, arrow="end")
    body += text(c[0] + outer + 10, c[1] + outer * 0.7, "shown radius x magnification")
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 22,
                 "what lies within radius is shown magnified; between the lens and the box's faces")
    body += text(f(-X, 1)[0], f(-X, -1)[1] + 40,
                 "the tissue is squeezed back to its place (shape: sphere, or cylinder about local z)")
    return svg(body)


def alignment_surface():
    X = 2.0
    f = Frame(X)
    body = ""
    surface = [(x / 20.0 - X, 0.75 + 0.12 * math.sin(3 * x / 20.0)) for x in range(0, int(40 * X) + 1)]
    body += poly([f(-X, -1), f(X, -1)] + [f(x, z) for x, z in reversed(surface)], KEEP)
    tau, delta = 0.6, 0.15
    band_hi = [f(x, z - tau + delta) for x, z in surface]
    band_lo = [f(x, z - tau - delta) for x, z in reversed(surface)]
    body += poly(band_hi + band_lo, "#d7e3f0", "none")
    body += "".join(line(*f(x1, z1 - tau), *f(x2, z2 - tau), INK, "6,4")
                    for (x1, z1), (x2, z2) in zip(surface, surface[1:]))
    body += "".join(line(*f(x1, z1), *f(x2, z2), INK, width=2) for (x1, z1), (x2, z2) in zip(surface, surface[1:]))
    xa = 1.4
    za = 0.75 + 0.12 * math.sin(3 * (xa + X))
    body += line(*f(xa, za), *f(xa, za - tau), INK, arrow="both")
    body += text(f(X, 0)[0] + 10, f(xa, za - tau / 2)[1], "depth (tau): mm below the surface")
    body += text(f(-1.9, -0.3)[0], f(-1.9, -0.3)[1],
                 "band (delta): normals blend to the surface's over depth ± band", colour="#3a5f8a")
    body += text(f(-1.9, 0.95)[0], f(-1.9, 0.95)[1] - 6, "surface: the object above threshold (Otsu's by default)")
    body += text(f(-1.9, 0.5)[0], f(-1.9, 0.5)[1], "above the depth: moves with the operator (the skin)")
    body += text(f(-1.9, -0.7)[0], f(-1.9, -0.7)[1], "below it: stays in place (the skull)")
    return svg(body)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "images", "diagrams")
    os.makedirs(out, exist_ok=True)
    for name, make in [("peeler", peeler), ("retractor", retractor), ("pliers", pliers),
                       ("dilator", dilator), ("alignment_surface", alignment_surface)]:
        with open(os.path.join(out, name + ".svg"), "w") as f:
            f.write(make())
    return 0


if __name__ == "__main__":
    sys.exit(main())
