"""tools/benchlib.py: reading Google Benchmark JSON for tools/bench and tools/bench-ratios.

Benchmarks are named BM_<Family>/<size...>/<variant>: those that differ only in the variant
form a group, and the one labelled "anchor" is the group's reference, measured in the same run.
"""
import json
import re
import statistics
import subprocess
import sys

MS_PER = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load(args):
    if args[0].endswith(".json"):
        with open(args[0]) as f:
            return json.load(f)
    out = subprocess.run([args[0], "--benchmark_format=json", *args[1:]],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    return json.loads(out)


def collect(benchmarks):
    """run name -> {"ms", "cv", "fps", "bytes", "anchor"}: the median aggregate, else the median of runs."""
    runs, failed = {}, False
    for b in benchmarks:
        # A fixed iteration count shows in the name ("/iterations:120"): not part of the case.
        name = re.sub(r"/iterations:\d+", "", b["run_name"].removesuffix("/real_time"))
        if b.get("error_occurred"):
            print(f"{name}: ERROR {b.get('error_message', '')}", file=sys.stderr)
            failed = True
            continue
        r = runs.setdefault(name, {"runs": [], "median": None, "anchor": False, "cv": None})
        if b.get("aggregate_name") == "cv":
            r["cv"] = b["real_time"]
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        r["anchor"] |= b.get("label") == "anchor"
        if b.get("run_type") != "aggregate" or b.get("aggregate_name") == "median":
            r["raw"] = b  # every field, counters included (the median's when repeated)
        row = (b["real_time"] * MS_PER[b["time_unit"]], b.get("frames/s"), b.get("bytes"))
        if b.get("run_type") == "aggregate":
            r["median"] = row
        else:
            r["runs"].append(row)
    for r in runs.values():
        rows = [r["median"]] if r["median"] else r["runs"]
        med = lambda i: statistics.median(x[i] for x in rows) if rows[0][i] is not None else None
        r["ms"], r["fps"], r["bytes"] = med(0), med(1), med(2)
    return runs, failed


def groups_of(runs):
    """group name -> [(variant, run)], in the binary's order."""
    groups = {}
    for name, r in runs.items():
        group, _, variant = name.rpartition("/")
        groups.setdefault(group, []).append((variant, r))
    return groups
