"""Time VTK's CPU ray caster on the same work as cutaway's benchmark, for comparison.

The C++ benchmark writes one spec per dataset, SPEC_DIR/vtk_<dataset>.json, next to
a raw uint16 volume, and its own records into RESULTS_JSON. This script renders each
spec with vtkFixedPointVolumeRayCastMapper, times rw.Render() per frame (the whole
frame as a user would see it), saves SPEC_DIR/vtk_<dataset>.png (slice spacing 1.0,
last frame) for comparing pictures by eye, replaces the "vtk" records in RESULTS_JSON
and prints a table of VTK against cutaway (alignment "none").

"Same work" means: the same volume (dims, spacing, origin), the same cameras
(a turntable, explicit clipping range), image size, sample distance along the ray in
mm, one ray per pixel, piecewise-linear transfer function with the same opacity unit
distance, trilinear interpolation and Phong shading with a camera headlight.

With --cutaway-bench BIN, each dataset's VTK runs are paired with cutaway's: BIN
times its ray caster on the same rows (no operator, the spec's spacings and frames)
just before and just after VTK, so that the ratio does not depend on how fast the
machine was minutes apart (the table's own rows ran long before). With --rounds R
(default 3) the two alternate: cutaway, VTK, cutaway, ..., VTK, cutaway, and each
VTK run is set against the mean of the cutaway runs on either side of it; a single
pair can be a third apart on this machine. The VTK records carry the median of
their rounds as "ms_median", cutaway's R + 1 medians as "cutaway_paired_ms", and
each round's ratio VTK / cutaway (> 1: cutaway faster) as "paired_ratios".

Usage: xvfb-run -a /usr/bin/python3 bench/vtk_bench.py SPEC_DIR RESULTS_JSON [--frames N]
       [--cutaway-bench BIN] [--rounds R]
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

METHOD = "vtkFixedPointVolumeRayCastMapper"


def build_scene(vtk, spec, spec_dir):
    """Return (render window, volume mapper) for one spec, not yet rendered."""
    nx, ny, nz = spec["dims"]
    raw = os.path.join(spec_dir, spec["raw"])
    if os.path.getsize(raw) != nx * ny * nz * 2:
        sys.exit(f"vtk_bench: {raw} holds {os.path.getsize(raw)} bytes, "
                 f"expected {nx * ny * nz * 2} for dims {spec['dims']} (uint16)")
    reader = vtk.vtkImageReader2()
    reader.SetFileName(raw)
    reader.SetDataScalarTypeToUnsignedShort()
    reader.SetDataByteOrderToLittleEndian()
    reader.SetFileDimensionality(3)
    reader.SetDataExtent(0, nx - 1, 0, ny - 1, 0, nz - 1)
    reader.SetDataSpacing(*spec["spacing"])
    reader.SetDataOrigin(*spec["origin"])
    reader.FileLowerLeftOn()  # rows are stored y-ascending; without this VTK flips y
    reader.Update()

    color, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
    for p in spec["transfer"]:
        color.AddRGBPoint(p["value"] * 65535.0, *p["color"])
        opacity.AddPoint(p["value"] * 65535.0, p["alpha"])
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(spec["opacity_unit_distance"])
    prop.SetInterpolationTypeToLinear()
    sh = spec["shading"]
    prop.SetShade(1 if sh["enabled"] else 0)
    prop.SetAmbient(sh["ambient"])
    prop.SetDiffuse(sh["diffuse"])
    prop.SetSpecular(sh["specular"])
    prop.SetSpecularPower(sh["power"])

    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.AutoAdjustSampleDistancesOff()
    if hasattr(mapper, "LockSampleDistanceToInputSpacingOff"):
        mapper.LockSampleDistanceToInputSpacingOff()
    mapper.SetImageSampleDistance(1.0)
    mapper.SetMinimumImageSampleDistance(1.0)
    mapper.SetMaximumImageSampleDistance(1.0)

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    ren = vtk.vtkRenderer()  # no lights added: VTK creates its default headlight
    ren.SetBackground(*spec["background"])
    ren.AddVolume(volume)
    ren.SetActiveCamera(vtk.vtkCamera())  # our own camera: no automatic ResetCamera
    rw = vtk.vtkRenderWindow()
    rw.SetOffScreenRendering(1)
    rw.SetSize(spec["width"], spec["height"])
    rw.AddRenderer(ren)
    return rw, ren, mapper


def set_camera(cam, c):
    cam.SetPosition(*c["position"])
    cam.SetFocalPoint(*c["focal_point"])
    cam.SetViewUp(*c["view_up"])
    cam.SetViewAngle(c["view_angle"])
    cam.SetParallelProjection(1 if c["parallel"] else 0)
    if c["parallel"]:
        cam.SetParallelScale(c["parallel_scale"])
    cam.SetClippingRange(*c["clipping_range"])


def save_png(vtk, rw, path):
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(rw)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def bench_spec(vtk, spec, spec_dir, frames, version):
    rw, ren, mapper = build_scene(vtk, spec, spec_dir)
    cam, cams = ren.GetActiveCamera(), spec["cameras"]
    frames = frames or spec.get("frames", len(cams))
    records = []
    for sd in spec["sample_distances"]:
        mapper.SetSampleDistance(sd["mm"])
        set_camera(cam, cams[0])
        for _ in range(spec.get("warmup", 1)):
            rw.Render()
        ms = []
        for i in range(frames):
            set_camera(cam, cams[i % len(cams)])
            t0 = time.perf_counter()
            rw.Render()
            ms.append((time.perf_counter() - t0) * 1000.0)
        if abs(sd["slice_spacing"] - 1.0) < 1e-6:
            save_png(vtk, rw, os.path.join(spec_dir, f"vtk_{spec['dataset']}.png"))
        med = statistics.median(ms)
        records.append({
            "renderer": "vtk", "method": METHOD, "dataset": spec["dataset"],
            "dims": list(spec["dims"]), "alignment": "none", "operator": "none",
            "width": spec["width"], "height": spec["height"],
            "slice_spacing": sd["slice_spacing"], "sample_distance_mm": sd["mm"],
            "frames": frames, "ms_median": round(med, 1), "ms_min": round(min(ms), 1),
            "ms_max": round(max(ms), 1), "fps": round(1000.0 / med, 2),
            "vtk_version": version})
        print(f"vtk_bench: {spec['dataset']} d={sd['slice_spacing']}: "
              f"{med:.1f} ms median over {frames} frames", file=sys.stderr)
    rw.Finalize()
    return records


def cutaway_raycast_ms(binary, spec, frames):
    """cutaway's ray caster on the spec's rows: {slice spacing: median ms}."""
    spacings = ",".join(f"{sd['slice_spacing']:g}" for sd in spec["sample_distances"])
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "paired.json")
        cmd = [binary, "--datasets", spec["dataset"], "--alignments", "none",
               "--methods", "raycast", "--spacings", spacings, "--turntable", "0",
               "--bake-repeats", "0", "--size", str(spec["width"]), "--json", out]
        cmd += ["--frames", str(frames or spec.get("frames", 5))]
        run = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if run.returncode != 0 or not os.path.exists(out):
            sys.exit(f"vtk_bench: {' '.join(cmd)} failed:\n{run.stderr}")
        with open(out) as f:
            return {round(float(r["slice_spacing"]), 6): float(r["ms_median"])
                    for r in json.load(f) if r.get("renderer") == "cutaway"}


def merge_rounds(vtk_rounds, cutaway_runs):
    """One record per slice spacing from R rounds of VTK records (`vtk_rounds`, a list
    of lists) and the R + 1 cutaway runs around them ({slice spacing: ms}; none
    without --cutaway-bench): the median and extremes over the rounds, and each
    round's ratio to the mean of the cutaway runs on either side of it."""
    merged = []
    for at, first in enumerate(vtk_rounds[0]):
        runs = [records[at] for records in vtk_rounds]
        medians = [r["ms_median"] for r in runs]
        med = statistics.median(medians)
        record = dict(first, ms_median=round(med, 1), fps=round(1000.0 / med, 2),
                      ms_min=min(r["ms_min"] for r in runs),
                      ms_max=max(r["ms_max"] for r in runs), rounds=len(runs))
        d = round(float(first["slice_spacing"]), 6)
        if len(cutaway_runs) == len(runs) + 1 and all(d in c for c in cutaway_runs):
            cut = [c[d] for c in cutaway_runs]
            record["cutaway_paired_ms"] = [round(c, 1) for c in cut]
            record["paired_ratios"] = [round(m / ((cut[i] + cut[i + 1]) / 2), 3)
                                       for i, m in enumerate(medians)]
        merged.append(record)
    return merged


def print_table(vtk_records, others, version):
    def cutaway_ms(r):
        """The faster of cutaway's methods (slicing, raycast) on the same row."""
        times = [float(o["ms_median"]) for o in others
                 if o.get("renderer") == "cutaway" and o.get("alignment") == "none"
                 and o.get("dataset") == r["dataset"]
                 and abs(float(o.get("slice_spacing", -1)) - r["slice_spacing"]) < 1e-6]
        return min(times) if times else None

    print(f"VTK {METHOD} {version}, same volume, view, image size, sample distance, "
          "transfer function; ratio > 1 means cutaway is faster\n")
    print("| dataset | dims | d | VTK ms median | VTK fps | cutaway ms median (none, faster"
          " method) | ratio | cutaway ray caster around the VTK runs | paired ratios (median) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in vtk_records:
        c = cutaway_ms(r)
        ratio = f"{r['ms_median'] / c:.2f}" if c else "-"
        paired = r.get("cutaway_paired_ms")
        pair_text = " / ".join(f"{v:.1f}" for v in paired) if paired else "-"
        ratios = r.get("paired_ratios")
        pair_ratio = (", ".join(f"{q:.2f}" for q in ratios) +
                      f" ({statistics.median(ratios):.2f})") if ratios else "-"
        print(f"| {r['dataset']} | {'x'.join(map(str, r['dims']))} | {r['slice_spacing']:g} "
              f"| {r['ms_median']:.1f} | {r['fps']:.2f} | {'-' if c is None else f'{c:.1f}'} "
              f"| {ratio} | {pair_text} | {pair_ratio} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("spec_dir")
    ap.add_argument("results_json")
    ap.add_argument("--frames", type=int, default=0, help="timed frames (default: the spec's)")
    ap.add_argument("--cutaway-bench", default="",
                    help="cutaway_bench binary: time its ray caster just before and after VTK")
    ap.add_argument("--rounds", type=int, default=3,
                    help="VTK runs per dataset, each between two of cutaway's (default 3)")
    args = ap.parse_args()
    if args.rounds < 1:
        ap.error(f"--rounds {args.rounds}: expected at least 1")
    try:
        import vtk
    except ImportError:
        print("vtk_bench: python3-vtk9 is not installed; skipping the VTK comparison",
              file=sys.stderr)
        return 0
    specs = sorted(glob.glob(os.path.join(args.spec_dir, "vtk_*.json")))
    if not specs:
        print(f"vtk_bench: no vtk_*.json specs in {args.spec_dir}; nothing to do")
        return 0
    display = os.environ.get("DISPLAY", "")
    num = display[1:].split(".")[0] if display.startswith(":") else None
    if not display or (num and not os.path.exists("/tmp/.X11-unix/X" + num)):
        # checked here because VTK abort()s the process when it cannot open the display
        sys.exit(f"vtk_bench: no X server at DISPLAY={display!r}; VTK needs one for its "
                 "render window: run xvfb-run -a /usr/bin/python3 bench/vtk_bench.py ...")
    version = vtk.vtkVersion.GetVTKVersion()
    mine = []
    for path in specs:
        with open(path) as f:
            spec = json.load(f)
        def cutaway():
            return [cutaway_raycast_ms(args.cutaway_bench, spec, args.frames)] \
                if args.cutaway_bench else []
        cutaway_runs, vtk_rounds = cutaway(), []
        for _ in range(args.rounds):
            vtk_rounds.append(bench_spec(vtk, spec, os.path.dirname(path), args.frames, version))
            cutaway_runs += cutaway()
        records = merge_rounds(vtk_rounds, cutaway_runs)
        for r in records:
            if "paired_ratios" in r:
                print(f"vtk_bench: {spec['dataset']} d={r['slice_spacing']:g}: cutaway's ray "
                      f"caster {r['cutaway_paired_ms']} ms around VTK's rounds, ratios "
                      f"{r['paired_ratios']}", file=sys.stderr)
        mine += records

    others = []
    if os.path.exists(args.results_json):
        with open(args.results_json) as f:
            others = [r for r in json.load(f) if r.get("renderer") != "vtk"]
    tmp = args.results_json + ".tmp"
    with open(tmp, "w") as f:
        json.dump(others + mine, f, indent=1)
        f.write("\n")
    os.replace(tmp, args.results_json)
    print_table(mine, others, version)
    return 0


if __name__ == "__main__":
    sys.exit(main())
