"""Compare two builds of cutaway's benchmark frame by frame, taking turns.

ab_compare.py runs whole benchmarks one after the other; this machine's
speed drifts by 20-40 % over minutes, so it needs many pairs to see a 5 %
change. Here both builds run the same row at once and take turns
(cutaway_bench --baton, bench/baton.hpp): one renders while the other waits,
and they swap between frames every `--slice` seconds, so the drift reaches
both within seconds. Their frames are paired by view (frame i of both shows
the same turntable angle). The table gives, per row, the median of B / A
over the views and its quartiles, and each build's median frame.

Usage: python3 bench/ab_interleave.py BENCH_A BENCH_B [--rounds N]
       [--dataset ct_head] [--alignments none,surface] [--method raycast]
       [--spacing 1.0] [--frames 40] [--slice 1.0] [--size 512] [--table FILE]

BENCH_A and BENCH_B are cutaway_bench executables (copy build/bench/cutaway_bench
aside before rebuilding), or scripts that `exec` one with another environment.
Rounds alternate which build holds the first turn.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def start(binary, args, alignment, json_path, baton, baton_id, log):
    command = [binary, "--datasets", args.dataset, "--alignments", alignment, "--methods",
               args.method, "--spacings", str(args.spacing), "--frames", str(args.frames),
               "--size", str(args.size), "--turntable", "0", "--bake-repeats", "0",
               "--json", json_path, "--baton", baton, "--baton-id", str(baton_id),
               "--baton-slice", str(args.slice)]
    if args.table:
        command += ["--table", args.table]
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)


def frames(json_path):
    """The row's frame times, by view."""
    with open(json_path) as f:
        records = [r for r in json.load(f) if "frame_ms" in r]
    if len(records) != 1:
        sys.exit(f"ab_interleave: expected one row in {json_path}, found {len(records)}")
    return records[0]["frame_ms"]


def quartiles(values):
    values = sorted(values)
    if len(values) < 4:
        return values[0], values[-1]
    q = statistics.quantiles(values, n=4)
    return q[0], q[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bench_a")
    parser.add_argument("bench_b")
    parser.add_argument("--rounds", type=int, default=1, help="runs of each row, alternating which build takes the first turn")
    parser.add_argument("--dataset", default="ct_head")
    parser.add_argument("--alignments", default="none,surface")
    parser.add_argument("--method", default="raycast")
    parser.add_argument("--spacing", type=float, default=1.0)
    parser.add_argument("--frames", type=int, default=40)
    parser.add_argument("--slice", type=float, default=1.0, help="seconds per turn")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--table", help="the benchmark's table (default: its own)")
    args = parser.parse_args()
    for binary in (args.bench_a, args.bench_b):
        if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
            parser.error(f"{binary}: not an executable file")

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for alignment in args.alignments.split(","):
            a_all, b_all, ratios = [], [], []
            for rnd in range(args.rounds):
                order = [args.bench_a, args.bench_b] if rnd % 2 == 0 else [args.bench_b,
                                                                             args.bench_a]
                paths = [os.path.join(tmp, f"{tag}.json") for tag in ("first", "second")]
                baton = os.path.join(tmp, f"baton_{alignment}_{rnd}")
                with open(baton, "w") as f:
                    f.write("0\n")
                with open(os.path.join(tmp, "log"), "w") as log:
                    procs = [start(b, args, alignment, p, baton, i, log)
                             for i, (b, p) in enumerate(zip(order, paths))]
                    # A process that fails leaves no marker: leave it in its
                    # place, so the other does not wait for its turn forever.
                    while any(p.poll() is None for p in procs):
                        for i, p in enumerate(procs):
                            if p.poll() is not None and not os.path.exists(f"{baton}.done{i}"):
                                with open(f"{baton}.done{i}", "w") as f:
                                    f.write("exited\n")
                        time.sleep(0.05)
                for p, b in zip(procs, order):
                    if p.returncode != 0:
                        with open(os.path.join(tmp, "log")) as log:
                            sys.exit(f"ab_interleave: {b} failed (exit {p.returncode}):\n"
                                     f"{log.read()[-2000:]}")
                first, second = (frames(p) for p in paths)
                a, b = (first, second) if order[0] == args.bench_a else (second, first)
                for x, y in zip(a, b):
                    a_all.append(x)
                    b_all.append(y)
                    ratios.append(y / x)
                print(f"{alignment}: round {rnd + 1}/{args.rounds}, {len(ratios)} views paired",
                      file=sys.stderr, flush=True)
            lo, hi = quartiles(ratios)
            rows.append(f"| {args.dataset} | {alignment} | {args.method} | {args.spacing:.1f} |"
                        f" {statistics.median(a_all):.1f} | {statistics.median(b_all):.1f} |"
                        f" {statistics.median(ratios):.3f} | {lo:.3f}-{hi:.3f} | {len(ratios)} |")
    print("| dataset | alignment | method | d | A ms | B ms | B / A median | quartiles | views |")
    print("|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
