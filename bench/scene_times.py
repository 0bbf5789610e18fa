"""Time whole `cutaway render` processes of scenes under two settings, in turns.

Each round renders every scene once with setting A and once with setting B,
back to back, their order alternating from round to round, so the machine's
drift (20-40 % over minutes on the 2-core machine:
docs/design/profiling.md#noise-first) falls on both alike. A whole process
counts what a user waits for: loading the scan, the bakes, every frame of
the scene (a sequence's too) and their EXRs. Prints per scene the median time of each and the median of the
B / A ratios over the rounds, with their range.

Usage: python3 bench/scene_times.py [--a "ARGS"] [--b "ARGS"] [--rounds N]
       [--scenes a,b,...] [--cutaway A_BINARY] [--cutaway-b B_BINARY]

ARGS are extra `cutaway render` arguments, such as "--set /render/refine=1".
By default A is the scenes as they are and B the same binary again; give
--cutaway-b to time another build. Scenes that read the shared scans are
skipped without them.
"""
import argparse
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GALLERY = ["demo", "fig3_axis_ct_head", "fig3_surface_ct_head", "fig3_segment_ct_head",
           "fig1c_peelers_ct_head", "fig7_retractor_shallow_ct_head",
           "fig7_retractor_deep_ct_head", "fig7_retractor_segment_ct_head",
           "fig8_dilator_lens_brain", "fig9_chest", "fig10_frog_tools", "fig12_orange_stages",
           "turntable_peeled_head"]


def render_seconds(binary, scene, extra, out_dir):
    """One whole `cutaway render` of the scene (every frame of a sequence), in seconds."""
    command = [binary, "render", os.path.join(ROOT, "scenes", scene + ".json"),
               "-o", os.path.join(out_dir, scene + "_####.exr"), "--quiet"] + extra
    start = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seconds = time.monotonic() - start
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: exit {result.returncode}\n{result.stderr}")
    return seconds


def shared_data_present():
    return os.path.isdir(os.path.join(ROOT, "..", "shared", "data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--a", default="", help="extra render arguments of setting A")
    parser.add_argument("--b", default="", help="extra render arguments of setting B")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--scenes", default=",".join(GALLERY))
    parser.add_argument("--cutaway", default=os.path.join(ROOT, "build", "cutaway"))
    parser.add_argument("--cutaway-b", default=None, help="the build setting B runs")
    args = parser.parse_args()
    binary_b = args.cutaway_b or args.cutaway
    scenes = [s for s in args.scenes.split(",") if s]
    if not shared_data_present():
        scenes = [s for s in scenes if s == "demo"]
        print("../shared/data is absent: only the demo is timed", file=sys.stderr)
    extra_a, extra_b = shlex.split(args.a), shlex.split(args.b)
    times = {s: ([], []) for s in scenes}
    with tempfile.TemporaryDirectory() as out_dir:
        for r in range(args.rounds):
            for scene in scenes:
                order = [(0, args.cutaway, extra_a), (1, binary_b, extra_b)]
                if r % 2 == 1:
                    order.reverse()
                for which, binary, extra in order:
                    times[scene][which].append(render_seconds(binary, scene, extra, out_dir))
    print("| scene | A s | B s | B / A median | range |")
    print("|---|---|---|---|---|")
    for scene in scenes:
        a, b = times[scene]
        ratios = [y / x for x, y in zip(a, b)]
        print(f"| {scene} | {statistics.median(a):.2f} | {statistics.median(b):.2f} | "
              f"{statistics.median(ratios):.2f} | {min(ratios):.2f}-{max(ratios):.2f} |")


if __name__ == "__main__":
    main()
