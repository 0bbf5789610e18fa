"""Compare two builds of cutaway's benchmark in alternating runs.

This machine's speed drifts by 20-40 % over minutes, more than most changes
worth measuring, so a change is judged by pairs: each pair runs build A and
build B back to back on the same rows (their order alternating from pair to
pair), and the table gives, per row, the median of A's and of B's frame
medians and the median and range of B / A over the pairs. A ratio whose range
straddles 1 is within the noise; so can be one that does not: the same build
against itself gave 0.86-1.27 over 8 pairs, medians 0.95-0.98
(docs/design/profiling.md#noise-first). The drift only ever adds time,
so two more columns compare each build's least disturbed runs: B's fastest
frame median over A's, and B's fastest frame (the row's cheapest view) over
A's. Where the drift comes in bursts they are steadier than the median ratio
(docs/design/profiling.md#noise-first),
but not immune: a build that only swapped a `pow` for a product once came
out 10 % slower by them, where it could only be faster.

Usage: python3 bench/ab_compare.py BENCH_A BENCH_B [--pairs N] [--table FILE]
       [--datasets LIST] [--alignments LIST] [--methods LIST] [--spacings LIST]
       [--frames N] [--size N]

BENCH_A and BENCH_B are cutaway_bench executables (copy build/bench/cutaway_bench
aside before rebuilding), or scripts that run one with another environment.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def run(binary, args, json_path):
    """One run of `binary`: its rows' (median, fastest) frame times, by (dataset, alignment,
    method, d)."""
    command = [binary, "--alignments", args.alignments, "--methods", args.methods,
               "--spacings", args.spacings, "--frames", str(args.frames), "--size", str(args.size),
               "--turntable", "0", "--bake-repeats", "0", "--json", json_path]
    if args.datasets:
        command += ["--datasets", args.datasets]
    if args.table:
        command += ["--table", args.table]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"ab_compare: {binary} failed (exit {done.returncode}):\n{done.stdout[-2000:]}")
    with open(json_path) as f:
        records = json.load(f)
    return {(r["dataset"], r["alignment"], r["method"], r["slice_spacing"]):
            (r["ms_median"], r["ms_min"]) for r in records if "ms_median" in r}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bench_a")
    parser.add_argument("bench_b")
    parser.add_argument("--pairs", type=int, default=6)
    parser.add_argument("--table", help="the benchmark's table (default: its own)")
    parser.add_argument("--datasets", default="ct_head,chest_ct",
                        help="comma-separated; empty: every dataset of the table")
    parser.add_argument("--alignments", default="none,surface")
    parser.add_argument("--methods", default="raycast")
    parser.add_argument("--spacings", default="1.0")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    args = parser.parse_args()
    if args.pairs < 1:
        parser.error("--pairs must be at least 1")
    for binary in (args.bench_a, args.bench_b):
        if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
            parser.error(f"{binary}: not an executable file")

    times = {}  # row -> list of ((A median, A fastest), (B median, B fastest)) ms
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "records.json")
        for pair in range(args.pairs):
            order = ["A", "B"] if pair % 2 == 0 else ["B", "A"]
            medians = {tag: run(args.bench_a if tag == "A" else args.bench_b, args, path)
                       for tag in order}
            for row, a_ms in medians["A"].items():
                if row in medians["B"]:
                    times.setdefault(row, []).append((a_ms, medians["B"][row]))
            print(f"pair {pair + 1}/{args.pairs} done", file=sys.stderr)

    print("| dataset | alignment | method | d | A ms | B ms | B / A median | B / A range | "
          "fastest median B / A | fastest frame B / A | pairs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (dataset, alignment, method, d), pairs in sorted(times.items()):
        ratios = sorted(b[0] / a[0] for a, b in pairs)
        a_ms = statistics.median(a[0] for a, _ in pairs)
        b_ms = statistics.median(b[0] for _, b in pairs)
        fastest = min(b[0] for _, b in pairs) / min(a[0] for a, _ in pairs)
        frame = min(b[1] for _, b in pairs) / min(a[1] for a, _ in pairs)
        print(f"| {dataset} | {alignment} | {method} | {d} | {a_ms:.1f} | {b_ms:.1f} | "
              f"{statistics.median(ratios):.3f} | {ratios[0]:.3f}-{ratios[-1]:.3f} | "
              f"{fastest:.3f} | {frame:.3f} | {len(ratios)} |")


if __name__ == "__main__":
    main()
