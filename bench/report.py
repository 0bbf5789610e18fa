#!/usr/bin/env python3
"""Writes benchmark tables into a generated section of docs/performance.md.

Usage: report.py RESULTS_JSON MARKDOWN [--section NAME]

RESULTS_JSON is the list of records `make bench` writes (cutaway's frames,
bakes and turntable, and VTK's frames). The tables replace whatever lies
between the markers <!-- NAME:begin --> and <!-- NAME:end --> in MARKDOWN
(NAME: `results` unless given); the rest of the page is left as it is.
`make bench` writes the `results` section from bench/results.json; the GPU
section is written the same way from a GPU machine's records:

    report.py docs/performance/results_nvidia_h200.json docs/performance.md --section results-gpu

Standard library only.
"""
import argparse
import json
import statistics


def markers(section):
    return f"<!-- {section}:begin -->", f"<!-- {section}:end -->"


def dims(d):
    return "x".join(str(v) for v in d)


def ms(v):
    return "-" if v is None else f"{v:.0f}"


# Columns of the frame table, in this order; others follow in the order met.
METHODS = ["raycast", "slicing"]
ALIGNMENTS = ["none", "axis", "surface", "segment"]
METHOD_NAMES = {"raycast": "ray cast", "slicing": "slicing"}


def ordered(known, values):
    return [v for v in known if v in values] + [v for v in dict.fromkeys(values) if v not in known]


def frame_ms(v):
    """A frame time: one decimal below 100 ms (a GPU's frames), whole above."""
    return "-" if v is None else (f"{v:.1f}" if v < 100 else f"{v:.0f}")


def frame_rows(records):
    """One row per dataset and slice spacing, a column per method and alignment: median ms."""
    frames = [r for r in records if r.get("renderer") == "cutaway" and r.get("kind") != "turntable"
              and "ms_median" in r]
    if not frames:
        return []
    methods = ordered(METHODS, [r.get("method", "slicing") for r in frames])
    alignments = ordered(ALIGNMENTS, [r["alignment"] for r in frames])
    cells, rows, operators = {}, {}, {}
    for r in frames:
        row = (r["dataset"], r["slice_spacing"])
        rows.setdefault(row, r)
        if r["operator"] != "none":
            operators.setdefault(r["dataset"], r["operator"])
        cells[row + (r.get("method", "slicing"), r["alignment"])] = r["ms_median"]
    columns = [(m, a) for m in methods for a in alignments]
    head = " | ".join(f"{METHOD_NAMES.get(m, m)}: {a}" if a == alignments[0] else a
                      for m, a in columns)
    out = [f"| dataset | dims | operator | d | {head} |", "|---" * (4 + len(columns)) + "|"]
    for (dataset, d), first in rows.items():
        values = " | ".join(frame_ms(cells.get((dataset, d, m, a))) for m, a in columns)
        out.append(f"| {dataset} | {dims(first['dims'])} | {operators.get(dataset, 'none')} |"
                   f" {d:.1f} | {values} |")
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


def section_lines(records):
    device = next((r.get("device") for r in records if r.get("device")), "unknown device")
    vtk = next((r.get("vtk_version") for r in records if r.get("renderer") == "vtk"), None)
    lines = [f"Measured by `make bench` on {device}. Frames: median ms per 512x512 frame"
             " (after a warm-up, the view turning between frames); fps = 1000 / ms.", ""]
    lines += frame_rows(records) + [""] + paired_rows(records)
    lines += ["Bakes (ms, each the median of 3 runs) and peak memory (MiB):", ""]
    lines += bake_rows(records) + [""] + turntable_lines(records)
    if vtk:
        lines += ["", f"VTK {vtk}: `vtkFixedPointVolumeRayCastMapper` on the same volume "
                  "(normalized as cutaway uploads it), view, image size, sample distance, "
                  "transfer function and shading, in the same run."]
    return lines


def main():
    parser = argparse.ArgumentParser(usage="report.py RESULTS_JSON MARKDOWN [--section NAME]")
    parser.add_argument("results")
    parser.add_argument("markdown")
    parser.add_argument("--section", default="results",
                        help="write between <!-- SECTION:begin --> and <!-- SECTION:end -->")
    args = parser.parse_args()
    try:
        with open(args.results) as f:
            records = json.load(f)
        with open(args.markdown) as f:
            page = f.read()
    except (OSError, ValueError) as e:
        parser.exit(2, f"report.py: {e}\n")
    begin, end = markers(args.section)
    if page.count(begin) != 1 or page.count(end) != 1 or page.index(begin) > page.index(end):
        parser.exit(2, f"report.py: {args.markdown} has no single {begin} ... {end} section\n")
    head, rest = page.split(begin, 1)
    tail = rest.split(end, 1)[1]
    lines = [begin, ""] + section_lines(records) + ["", end]
    with open(args.markdown, "w") as f:
        f.write(head + "\n".join(lines) + tail)
    print(f"report.py: wrote the {args.section} section of {args.markdown}")


if __name__ == "__main__":
    main()
