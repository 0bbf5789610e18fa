#!/usr/bin/env python3
"""Validates every example scene in scenes/ (and the benchmark's, in
bench/scenes/) against scenes/scene.schema.json.

Also checks the schema itself, and that it rejects what cutaway rejects for
structural reasons (an unknown key, a wrong type, an out-of-range number), so
a schema that accepts everything cannot pass. Exit 0 when all is well.
"""
import json
import pathlib
import sys

import jsonschema

root = pathlib.Path(sys.argv[1])
schema = json.loads((root / "scenes" / "scene.schema.json").read_text())
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)

failures = 0
scenes = sorted((root / "scenes").glob("*.json"))
scenes = [s for s in scenes if s.name != "scene.schema.json"]
scenes += sorted((root / "bench" / "scenes").glob("*.json"))
for path in scenes:
    errors = list(validator.iter_errors(json.loads(path.read_text())))
    for e in errors:
        print(f"FAIL {path.relative_to(root)}: /{'/'.join(map(str, e.absolute_path))}: {e.message}")
    failures += bool(errors)
    if not errors:
        print(f"ok   {path.relative_to(root)}")

minimal = {"version": 1, "volume": {"phantom": "head"}}
must_fail = {
    "unknown key": {**minimal, "camera": {"fovv": 30}},
    "wrong type": {**minimal, "render": {"slice_spacing": "fine"}},
    "out of range": {**minimal, "render": {"size": [0, 512]}},
    "file and phantom": {"version": 1, "volume": {"phantom": "head", "file": "x.nrrd"}},
    "missing version": {"volume": {"phantom": "head"}},
}
for name, doc in must_fail.items():
    if validator.is_valid(doc):
        print(f"FAIL the schema accepts a scene with {name}")
        failures += 1
if not validator.is_valid(minimal):
    print("FAIL the schema rejects the minimal scene")
    failures += 1

print(f"{len(scenes) - failures} passed, {failures} failed")
sys.exit(1 if failures or not scenes else 0)
