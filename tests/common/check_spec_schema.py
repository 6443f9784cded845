#!/usr/bin/python3
"""The JSON Schema of `fe2heart spec-schema` against real specs, with Debian's jsonschema.

usage: check_spec_schema.py schema|doc FE2HEART SOURCE_DIR

schema:
- both emitted documents are valid JSON Schema 2020-12;
- every config in configs/ (study-*.json included), every exemplar in tests/data/schema/
  and the CLI positive controls validate against the right schema (run, unit,
  circulation or study) and pass `fe2heart validate`;
- every tests/data/schema/reject_*.json is rejected by the schema AND by `fe2heart
  validate` (exit 2), so the schema bites where the reader does;
doc:
- `fe2heart spec-doc` has a line for every property the JSON Schema declares, and the
  lines of keys only some branches have (gmsh file, macro-law material, unit mesh_file,
  Guccione parameters) with integers shown as integers.
Prints what failed and exits 1 on any failure.
"""
import glob
import json
import os
import re
import subprocess
import sys

import jsonschema

mode, fe2heart, src = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def run(*args):
    return subprocess.run([fe2heart, *args], capture_output=True, text=True, timeout=120)


def load_schema(*flags):
    out = run("spec-schema", *flags)
    if out.returncode != 0:
        sys.exit(f"fe2heart spec-schema {' '.join(flags)} exited {out.returncode}: {out.stderr}")
    schema = json.loads(out.stdout)
    jsonschema.Draft202012Validator.check_schema(schema)  # raises if not valid 2020-12
    if schema.get("$schema") != "https://json-schema.org/draft/2020-12/schema":
        fail(f"spec-schema {flags}: $schema is {schema.get('$schema')}")
    return schema


schemas = {"run": load_schema(), "unit": load_schema("--unit"),
           "circulation": load_schema("--circulation"), "study": load_schema("--study")}
validators = {k: jsonschema.Draft202012Validator(s) for k, s in schemas.items()}


def kind_of(spec):
    if "base" in spec and ("variants" in spec or "one_at_a_time" in spec):
        return "study"  # fe2heart study (tools/study_spec.h); `validate` also checks its variants
    if "ventricles" in spec or ("circulation" in spec and "mesh" not in spec):
        return "circulation"  # fe2heart circulation (common/circulation/circulation_run_spec.h)
    return "unit" if "unit" in spec and "mesh" not in spec else "run"


def rel(path):
    return os.path.relpath(path, src)


def check_specs():
    good = sorted(glob.glob(os.path.join(src, "configs", "*.json")))
    good += sorted(p for p in glob.glob(os.path.join(src, "tests/data/schema/*.json"))
                   if not os.path.basename(p).startswith("reject_"))
    good += [os.path.join(src, p) for p in ("tests/data/bad/small_valid.json",
                                            "tests/data/bad/valid_tets.json",
                                            "tests/data/bad/periodic_unit.json",
                                            "tests/mpi/farm_scene.json")]
    bad = sorted(glob.glob(os.path.join(src, "tests/data/schema/reject_*.json")))
    if len(good) < 8 or len(bad) < 8:
        fail(f"expected >= 8 accepted and >= 8 rejected specs, found {len(good)} and {len(bad)}")

    for path in good:
        with open(path) as f:
            spec = json.load(f)
        errors = list(validators[kind_of(spec)].iter_errors(spec))
        if errors:
            fail(f"{rel(path)}: the {kind_of(spec)} schema rejects it: {errors[0].message} "
                 f"at /{'/'.join(map(str, errors[0].absolute_path))}")
        v = run("validate", path)
        if v.returncode != 0:
            fail(f"{rel(path)}: fe2heart validate exited {v.returncode}: "
                 f"{v.stdout.strip()} {v.stderr.strip()}")
        else:
            print(f"ok   {rel(path)} ({kind_of(spec)} spec): schema and reader accept it")

    for path in bad:
        with open(path) as f:
            spec = json.load(f)
        if validators[kind_of(spec)].is_valid(spec):
            fail(f"{rel(path)}: the {kind_of(spec)} schema accepts it ({spec['title']})")
        v = run("validate", path)
        if v.returncode != 2:
            fail(f"{rel(path)}: fe2heart validate exited {v.returncode}, expected 2 "
                 f"({v.stdout.strip()} {v.stderr.strip()})")
        else:
            said = (v.stdout.strip() + " " + v.stderr.strip()).strip().splitlines()[-1]
            print(f"ok   {rel(path)}: schema and reader reject it; the reader says: {said}")



def property_names(node, out):
    """Every property name declared anywhere in a JSON Schema document."""
    if isinstance(node, dict):
        for name, sub in node.get("properties", {}).items():
            out.add(name)
            property_names(sub, out)
        for k, sub in node.items():
            if k != "properties":
                property_names(sub, out)
    elif isinstance(node, list):
        for sub in node:
            property_names(sub, out)
    return out


def check_doc():
    doc = run("spec-doc")
    if doc.returncode != 0:
        fail(f"spec-doc exited {doc.returncode}")
    doc_keys = set(re.findall(r"^  \S*/([A-Za-z_0-9]+) ", doc.stdout, re.M))
    names = set()
    for schema in schemas.values():
        property_names(schema, names)
    missing = sorted(names - doc_keys)
    if missing:
        fail(f"spec-doc has no line for these schema properties: {missing}")
    else:
        print(f"ok   spec-doc has a line for each of the {len(names)} property names of the schemas")
    lines = {  # path: the rest of its line, spaces collapsed
        "/mesh/file": 'string (required), when kind = "gmsh": Gmsh 4.1 ASCII mesh file',
        "/mesh/divisions": 'array of 3 integers in [1, 1000] (required), when kind = "box": '
                           'cells per axis (6 tets per cell)',
        "/time/steps": "integer in [1, 10000000] (default 1): number of steps",
        "/models/<name>/material": 'object <material> (required), when kind = "macro_law": '
                                   'constitutive law',
        "<unit>/mesh_file": 'string (required), when cell = "mesh_file": Gmsh 4.1 hex mesh of the cell',
        "<unit>/resolution": 'array of 3 integers in [1, 1000] (default [8, 4, 4]), when cell = '
                             '"two_cells": hexahedra per axis',
        "<material>/kappa": 'number > 0 (default 100000), when model = "guccione": volumetric '
                            'penalty kappa (Pa), U = kappa/2 (J-1)^2',
        "/farm/stall_timeout": None,  # present (its text belongs to the farm's owner)
    }
    found = {}
    for line in doc.stdout.splitlines():
        m = re.match(r"^  (\S+) +(.*)$", line)
        if m:
            found.setdefault(m.group(1), re.sub(" +", " ", m.group(2)))
    for path, text in lines.items():
        if path not in found:
            fail(f"spec-doc has no line for {path}")
        elif text is not None and found[path] != text:
            fail(f"spec-doc line of {path}:\n  got      {found[path]}\n  expected {text}")
        else:
            print(f"ok   spec-doc: {path}")


{"schema": check_specs, "doc": check_doc}[mode]()

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("all spec-schema checks passed")
