"""Where a frame's time goes inside lavapipe's generated shader code.

lavapipe compiles shaders to machine code at run time, with no symbols, so a
profile of a render shows one anonymous block. This samples a running
cutaway_bench with `perf record` (a software clock: no hardware counters
needed), dumps the process's anonymous executable mappings with gdb while it
still runs, disassembles them with objdump and attributes the samples to the
instructions. lavapipe emits every sampled-texture read as a function of its
own (imageLoad and buffer reads are inline), so the table of functions says
what each kind of fetch costs; the same code compiled several times (lavapipe
keeps a copy per dispatch variant) is folded by size.

Usage: python3 bench/jit_profile.py [--bench build/bench/cutaway_bench]
           [--table FILE] [--dataset ct_head] [--alignment surface]
           [--method raycast] [--size 512] [--warmup 60] [--settle 3]
           [--seconds 6] [--listing FILE] [--hot N]

Needs perf (Debian linux-perf), gdb and objdump (binutils). The benchmark
runs `--frames 1000` of one row; sampling starts `--settle` seconds after
its generated code appears (at most `--warmup` seconds after the start: the
scan's loading and bakes come first) and the benchmark is then stopped.
"""
import argparse
import collections
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

# What a fetch function's code looks like, by its instructions (Mesa 22.3, x86-64).
SIGNATURES = [
    ("vpgatherdd", "32-bit texels gathered (RGBA8: the gradients)"),
    ("vcvtph2ps", "half-float texels (RGBA16F map or table, R16F/RG16F field)"),
    ("movzwl", "16-bit texels loaded one by one"),
    ("movzbl", "8-bit texels loaded one by one"),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", default="build/bench/cutaway_bench")
    parser.add_argument("--table", help="the benchmark's table (default: its own)")
    parser.add_argument("--dataset", default="ct_head")
    parser.add_argument("--alignment", default="surface")
    parser.add_argument("--method", default="raycast")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--warmup", type=float, default=60.0,
                        help="the most seconds to wait for the generated code")
    parser.add_argument("--settle", type=float, default=3.0,
                        help="seconds between the code's appearance and sampling")
    parser.add_argument("--seconds", type=float, default=6.0)
    parser.add_argument("--listing", help="write the annotated disassembly here")
    parser.add_argument("--hot", type=int, default=15,
                        help="the hottest 256-byte blocks of the largest function to list")
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="jit_profile_")
    try:
        profile(args, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def profile(args, work):
    """Runs the benchmark, samples it and prints the report."""
    for tool in ("perf", "gdb", "objdump"):
        if shutil.which(tool) is None:
            fail(f"{tool} not found (Debian: linux-perf, gdb, binutils; make bench installs them)")
    if not os.path.isfile(args.bench) or not os.access(args.bench, os.X_OK):
        fail(f"{args.bench}: not an executable file", 2)
    command = [args.bench, "--datasets", args.dataset, "--alignments", args.alignment,
               "--methods", args.method, "--spacings", "1.0", "--frames", "1000",
               "--size", str(args.size), "--turntable", "0", "--bake-repeats", "0",
               "--json", os.path.join(work, "r.json")]
    if args.table:
        command += ["--table", args.table]
    bench = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        pid = wait_for_code(bench, args.warmup)
        time.sleep(args.settle)
        data = os.path.join(work, "perf.data")
        subprocess.run(["perf", "record", "-q", "-e", "cpu-clock", "-F", "2000", "-p", str(pid),
                        "-o", data, "--", "sleep", str(args.seconds)],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        regions = dump_jit(pid, work)
    finally:
        for p in child_pids(bench.pid) + [bench.pid]:
            try:
                os.kill(p, signal.SIGKILL)
            except ProcessLookupError:
                pass
        bench.wait()
    ips = collections.Counter()
    script = subprocess.run(["perf", "script", "-i", data, "-F", "ip"], capture_output=True,
                            text=True, check=True).stdout
    for line in script.split():
        ips[int(line, 16)] += 1
    report(ips, regions, args)


def child_pids(pid):
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True,
                         text=True).stdout
    pids = [int(p) for p in out.split()]
    return pids + [c for p in pids for c in child_pids(p)]


def fail(message, code=1):
    print(f"jit_profile: {message}", file=sys.stderr)
    sys.exit(code)


def jit_mappings(pid):
    """(start, end) of the process's anonymous executable mappings."""
    out = []
    try:
        with open(f"/proc/{pid}/maps") as f:
            for line in f:
                parts = line.split()
                if len(parts) < 6 and "x" in parts[1]:
                    out.append(tuple(int(v, 16) for v in parts[0].split("-")))
    except OSError:
        pass
    return out


def wait_for_code(bench, most):
    """The renderer's pid, once generated code is there; exits after `most` seconds without."""
    deadline = time.monotonic() + most
    while time.monotonic() < deadline:
        if bench.poll() is not None:
            fail(f"the benchmark ended (exit {bench.returncode}) before a profile")
        pid = renderer_pid(bench.pid)
        if jit_mappings(pid):
            return pid
        time.sleep(0.2)
    fail(f"no generated code after {most} s (is the device lavapipe?)")


def renderer_pid(pid):
    """The benchmark renders each dataset in a child process: the busiest one."""
    candidates = [pid] + child_pids(pid)
    best, most = pid, -1.0
    for p in candidates:
        try:
            with open(f"/proc/{p}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            busy = float(fields[11]) + float(fields[12])  # utime + stime
        except (OSError, IndexError):
            continue
        if busy > most:
            best, most = p, busy
    return best


def dump_jit(pid, work):
    """(start, path) of each anonymous executable mapping, dumped while the process runs."""
    regions = []
    for start, end in jit_mappings(pid):
        path = os.path.join(work, f"jit_{start:x}.bin")
        subprocess.run(["gdb", "-p", str(pid), "-batch", "-ex",
                        f"dump binary memory {path} {start:#x} {end:#x}"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if os.path.exists(path):
            regions.append((start, path))
    if not regions:
        fail("no generated code found (is the device lavapipe?)")
    return regions


def functions(ips, regions):
    """Each generated function: (start, size, samples, instructions [(addr, samples, text)])."""
    out = []
    for start, path in regions:
        asm = subprocess.run(["objdump", "-D", "-b", "binary", "-m", "i386:x86-64",
                              f"--adjust-vma={start:#x}", path],
                             capture_output=True, text=True, check=True).stdout
        body = []
        for line in asm.splitlines():
            m = re.match(r"\s*([0-9a-f]+):\s+(?:[0-9a-f]{2} )+\s*(.*)", line)
            if not m:
                continue
            addr = int(m.group(1), 16)
            body.append((addr, ips.get(addr, 0), m.group(2)))
            if m.group(2).startswith("ret"):
                out.append((body[0][0], addr - body[0][0], sum(b[1] for b in body), body))
                body = []
    return out


def report(ips, regions, args):
    total = sum(ips.values())
    fns = functions(ips, regions)
    inside = sum(f[2] for f in fns)
    by_size = collections.defaultdict(lambda: [0, 0, None])
    for start, size, samples, body in fns:
        entry = by_size[size]
        entry[0] += samples
        entry[1] += 1
        entry[2] = entry[2] or body
    print(f"{total} samples, {100.0 * inside / max(total, 1):.1f} % in generated code "
          f"({args.dataset}, {args.alignment}, {args.method})\n")
    print("| function (bytes) | copies | share of all samples | what it reads |")
    print("|---|---|---|---|")
    rows = sorted(by_size.items(), key=lambda kv: -kv[1][0])
    largest = max(by_size, key=lambda s: by_size[s][0]) if by_size else None
    for size, (samples, copies, body) in rows:
        if samples * 200 < total:
            continue
        text = "\n".join(b[2] for b in body)
        what = "the shader's own code (loops, inline loads, lighting)" if size == largest else \
            next((label for key, label in SIGNATURES if key in text), "")
        print(f"| {size} | {copies} | {100.0 * samples / total:.1f} % | {what} |")
    if largest is None:
        return
    blocks = collections.Counter()
    for start, size, samples, body in fns:
        if size == largest:
            for addr, n, _ in body:
                blocks[(addr - start) // 256] += n
    print(f"\nHottest 256-byte blocks of the {largest}-byte function (offsets folded over copies):")
    for block, n in blocks.most_common(args.hot):
        print(f"  +{block * 256:#07x}  {100.0 * n / total:.1f} %")
    if args.listing:
        with open(args.listing, "w") as f:
            for start, size, samples, body in fns:
                f.write(f"# function at {start:#x}, {size} bytes, {samples} samples\n")
                for addr, n, text in body:
                    f.write(f"{n:6d} {addr - start:#07x} {text}\n")
        print(f"\nannotated listing: {args.listing}")


if __name__ == "__main__":
    main()
