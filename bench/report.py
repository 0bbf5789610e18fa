#!/usr/bin/env python3
"""Writes the latest benchmark tables into docs/performance.md.

Usage: report.py RESULTS_JSON MARKDOWN

RESULTS_JSON is the list of records `make bench` writes (cutaway's frames,
bakes and turntable, and VTK's frames). The tables replace whatever lies
between the markers <!-- results:begin --> and <!-- results:end --> in
MARKDOWN; the rest of the page (the paper's Table 1, the notes) is left as
it is. Standard library only.
"""
import json
import statistics
import sys

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"


def dims(d):
    return "x".join(str(v) for v in d)


def ms(v):
    return "-" if v is None else f"{v:.0f}"


def frame_rows(records):
    vtk = {(r["dataset"], r["slice_spacing"]): r for r in records if r.get("renderer") == "vtk"}
    out = ["| dataset | dims | alignment | operator | method | d | median ms | min ms | max ms |"
           " fps | VTK median ms (same work) |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        if r.get("renderer") != "cutaway" or r.get("kind") == "turntable":
            continue
        v = vtk.get((r["dataset"], r["slice_spacing"])) if r["alignment"] == "none" else None
        out.append(f"| {r['dataset']} | {dims(r['dims'])} | {r['alignment']} | {r['operator']} |"
                   f" {r.get('method', 'slicing')} | {r['slice_spacing']:.1f} | {r['ms_median']:.0f} | {r['ms_min']:.0f} |"
                   f" {r['ms_max']:.0f} | {r['fps']:.2f} | {ms(v['ms_median']) if v else ''} |")
    return out


def bake_rows(records):
    out = ["| dataset | read | upload | gradients | distance field | its ranges | segment mask |"
           " segment region | operator map | value spans | new transfer | peak RSS MiB, one render (largest row) |"
           " peak RSS MiB, whole run | of it Vulkan MiB | goal MiB (4 x scan + 300) |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    seen = set()
    for r in records:
        if r.get("renderer") != "cutaway" or "bake_ms" not in r or r["dataset"] in seen:
            continue
        seen.add(r["dataset"])
        b = r["bake_ms"]
        out.append(f"| {r['dataset']} | {ms(b.get('read_ms'))} | {ms(b.get('upload_ms'))} |"
                   f" {ms(b.get('gradients_ms'))} | {ms(b.get('distance_field_ms'))} |"
                   f" {ms(b.get('field_ranges_ms'))} |"
                   f" {ms(b.get('segment_mask_ms'))} | {ms(b.get('segment_region_ms'))} |"
                   f" {ms(b.get('operator_map_ms'))} |"
                   f" {ms(b.get('value_spans_ms'))} | {ms(b.get('classify_ms'))} |"
                   f" {ms(r.get('render_peak_rss_mib_largest'))} |"
                   f" {ms(r['peak_rss_mib'])} | {ms(r.get('device_peak_mib'))} |"
                   f" {r['memory_goal_mib']:.0f} |")
    return out


def paired_rows(records):
    """VTK against cutaway's ray caster timed just before and after each of its runs."""
    rows = [r for r in records if r.get("renderer") == "vtk" and r.get("cutaway_paired_ms")]
    if not rows:
        return []
    out = ["VTK against cutaway's ray caster, the two alternating (cutaway, VTK, cutaway, ...);"
           " each VTK run's ratio is to the mean of the cutaway runs on either side of it:",
           "", "| dataset | d | VTK ms (median of its runs) | cutaway ms, in order |"
           " ratio per VTK run (> 1: cutaway faster) | median ratio |", "|---|---|---|---|---|---|"]
    for r in rows:
        cut = r["cutaway_paired_ms"]
        # Records of one round carry no "paired_ratios".
        ratios = r.get("paired_ratios") or [r["ms_median"] / ((cut[0] + cut[1]) / 2)]
        out.append(f"| {r['dataset']} | {r['slice_spacing']:.1f} | {r['ms_median']:.0f} |"
                   f" {' / '.join(f'{c:.0f}' for c in cut)} |"
                   f" {', '.join(f'{q:.2f}' for q in ratios)} |"
                   f" {statistics.median(ratios):.2f} |")
    return out + [""]


def turntable_lines(records):
    out = []
    for t in records:
        if t.get("kind") != "turntable":
            continue
        single = next((r["fps"] for r in records if r.get("renderer") == "cutaway"
                       and r.get("kind") != "turntable" and r["dataset"] == t["dataset"]
                       and r["alignment"] == "surface" and r["slice_spacing"] == 1.0
                       and r.get("method", "slicing") == t.get("method", "slicing")), None)
        steady = (f" The first frame's files were written after {t['first_frame_s']:.1f} s "
                  f"(loading the scan, uploads, bakes); from there **{t['steady_fps']:.2f} fps "
                  f"sustained**." if "steady_fps" in t else "")
        if "single_fps_before" in t:
            views = (f"Its {t['single_views']} views rendered one by one without files"
                     if "single_views" in t else "Single frames of the same scene")
            steady += (f" {views}, timed just before and just after the turntable:"
                       f" {t['single_fps_before']:.2f} and {t['single_fps_after']:.2f} fps.")
        if "interleaved" in t:
            w = t["interleaved"]
            steady += (f" Its {w['views']} views each rendered alone and again while the"
                       f" previous frame's files were written, in turns (free of the machine's"
                       f" drift): {w['ms_alone']:.0f} against {w['ms_with_files']:.0f} ms,"
                       f" **{w['ms_alone'] / w['ms_with_files']:.3f}** of the single-frame rate"
                       f" sustained.")
        out.append(f"Turntable: {t['dataset']}, surface-aligned operator, "
                   f"{t.get('method', 'slicing')}, d = 1.0, "
                   f"{t['frames']} frames written as {t['writes']}: {t['total_s']:.1f} s in all, "
                   f"{t['sustained_fps']:.2f} fps with the first frame's loading and bakes, "
                   f"against {single:.2f} fps for the table's single frames (the median view)."
                   + steady if single else "")
        if t.get("write_costs"):
            out += ["", f"Writing one {t['width']}x{t['height']} frame of it (half floats, "
                    "`/output/compression`; each the median of 5 writes):", "",
                    "| file | ms | KiB |", "|---|---|---|"]
            out += [f"| {w['file']} | {w['ms_median']:.1f} | {w['bytes'] / 1024:.0f} |"
                    for w in t["write_costs"]]
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        records = json.load(f)
    device = next((r.get("device") for r in records if r.get("device")), "unknown device")
    vtk = next((r.get("vtk_version") for r in records if r.get("renderer") == "vtk"), None)
    lines = [BEGIN, "",
             f"Measured by `make bench` on {device}; times in ms per 512x512 frame "
             "(median of the timed frames after a warm-up, the view turning between frames); "
             "bake times in ms, each the median of 3 runs.", ""]
    lines += frame_rows(records) + [""] + paired_rows(records) + bake_rows(records) + [""]
    lines += turntable_lines(records)
    if vtk:
        lines += ["", f"VTK {vtk}: `vtkFixedPointVolumeRayCastMapper` on the same volume "
                  "(normalized as cutaway uploads it), view, image size, sample distance, "
                  "transfer function and shading, in the same run."]
    lines += ["", END]
    with open(sys.argv[2]) as f:
        page = f.read()
    if BEGIN not in page or END not in page:
        sys.exit(f"report.py: {sys.argv[2]} has no {BEGIN} ... {END} section")
    head, rest = page.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    with open(sys.argv[2], "w") as f:
        f.write(head + "\n".join(lines) + tail)
    print(f"report.py: wrote the results section of {sys.argv[2]}")


if __name__ == "__main__":
    main()
