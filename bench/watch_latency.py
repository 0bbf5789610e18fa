"""Time `cutaway watch` from an edit of the scene on disk to its new preview.

Starts `cutaway watch` on a scene (default scenes/retractor_ct_head.json,
which reads ../shared/data/ct_head.nii.gz) at 512x512 and, once the first
preview is written, edits a copy of the scene in turns: the transfer
function, the camera and the operator's parameters, each written whole under
another name and renamed over the scene, as editors do. The time of an edit
runs from the rename until the watch reports the new preview (its poll, the
wait for the file to hold still, the render and the PNG). Prints each edit's
time and the median per kind of edit; the first preview (which loads the
scan and bakes everything) separately.

Usage: python3 bench/watch_latency.py [--scene FILE] [--edits N] [--size WxH]
       [--cutaway BINARY]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def edits(scene, n):
    """n edited copies of the scene, cycling through three kinds of edit."""
    for i in range(n):
        d = json.loads(json.dumps(scene))
        kind = ("transfer", "camera", "operator")[i % 3]
        if kind == "transfer":
            for p in d["transfer"]["points"]:
                p["alpha"] = min(1.0, p["alpha"] * (0.9 if i % 2 else 1.1))
        elif kind == "camera":
            orbit = d.setdefault("camera", {}).setdefault("orbit", {})
            orbit["azimuth"] = orbit.get("azimuth", 0) + 10 * (i + 1)
        elif d.get("operators"):
            params = d["operators"][0].setdefault("params", {})
            params["opening"] = 20 + (i % 4) * 5
        yield kind, d


def wait_for(log, count, deadline=120):
    start = time.monotonic()
    while time.monotonic() - start < deadline:
        with open(log) as f:
            if f.read().count("updated in") >= count:
                return True
        time.sleep(0.005)
    return False


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes", "retractor_ct_head.json"))
    p.add_argument("--edits", type=int, default=12)
    p.add_argument("--size", default="512x512")
    p.add_argument("--cutaway", default=os.path.join(ROOT, "build", "cutaway"))
    args = p.parse_args()
    scene = json.load(open(args.scene))
    volume = scene.get("volume", {}).get("file")
    folder = tempfile.mkdtemp(prefix="cutaway_watch_")
    if volume:
        path = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(args.scene)), volume))
        if not os.path.exists(path):
            print(f"skipped: {path} not found (the shared scans are absent)")
            return 0
        scene["volume"]["file"] = path
    target = os.path.join(folder, "scene.json")
    json.dump(scene, open(target, "w"), indent=2)
    log = os.path.join(folder, "log.txt")
    watch = subprocess.Popen([args.cutaway, "watch", target, "--size", args.size, "-o",
                              os.path.join(folder, "preview.png"), "--poll", "0.05"],
                             stderr=open(log, "w"))
    try:
        start = time.monotonic()
        if not wait_for(log, 1):
            print("no first preview:\n" + open(log).read(), file=sys.stderr)
            return 1
        print(f"first preview: {time.monotonic() - start:.2f} s (loads and bakes)")
        times = {}
        for i, (kind, d) in enumerate(edits(scene, args.edits)):
            json.dump(d, open(target + ".tmp", "w"), indent=2)
            edited = time.monotonic()
            os.replace(target + ".tmp", target)
            if not wait_for(log, i + 2):
                print("no preview after an edit:\n" + open(log).read(), file=sys.stderr)
                return 1
            times.setdefault(kind, []).append(time.monotonic() - edited)
            time.sleep(0.3)
        every = [t for ts in times.values() for t in ts]
        for kind, ts in times.items():
            print(f"{kind:9s} median {statistics.median(ts):.2f} s over {len(ts)} edits")
        print(f"all       median {statistics.median(every):.2f} s, "
              f"range {min(every):.2f}-{max(every):.2f} s")
    finally:
        watch.terminate()
        watch.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
