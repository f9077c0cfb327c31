#!/usr/bin/python3
"""Single-thread CPU ns per simulated step (Arnold steps + transit points) of
the Arnold planner's technique variants on the maps of issue 20.

Each cell (map x variant) is its own sweep of RUNS runs (seeds 0..RUNS-1, ic
jittered 1e-6, ds_index 3, c 0.5, f 2, dc 0.9, max_pr 50) with --threads 1;
its time is the sweep process's user + system CPU time, setup, engine and
HDF5 included. The binaries take turns cell by cell, so that they share the
machine's state. Prints one table per binary, each cell also as a ratio to
original-open on the same size and SR.
  usage: tests/benchmarks/variant_steps.py RUNS BIN...
"""
import os
import sys
import tempfile

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_cpu import cpu  # noqa: E402  (the same CPU measure as the shard timings)

MAPS = [("200m SR1 open", 200, 1, "no_obstacles"), ("200m SR1 five", 200, 1, "five_squares"),
        ("50m SR1 open", 50, 1, "no_obstacles"), ("50m SR1 five", 50, 1, "five_squares"),
        ("50m SR4 open", 50, 4, "no_obstacles"), ("50m SR4 five", 50, 4, "five_squares")]
VARIANTS = [("original", ""), ("MZ", "map_zoning = 1\nc = 0.5\n"),
            ("IS+MZ+SC", "index_switching = 1\nmap_zoning = 1\nc = 0.5\nf = 2\n")]


def spec(runs, size, sr, env, fixed):
    return (f'[sweep]\nname = "variant_steps"\n[fixed]\ndc = 0.9\nmax_pr = 50\nic_jitter = 1e-6\nds_index = 3\n'
            f'size = {size}\nsr = {sr}\nenv = "{env}"\n{fixed}[axes]\nseed = {{ start = 0, stop = {runs - 1}, step = 1 }}\n')


def main():
    if len(sys.argv) < 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit("usage: variant_steps.py RUNS BIN...")
    runs, bins = int(sys.argv[1]), sys.argv[2:]
    ns = {}
    with tempfile.TemporaryDirectory(prefix="chaosweep-variants.") as work:
        for label, size, sr, env in MAPS:
            for variant, fixed in VARIANTS:
                path = os.path.join(work, "spec.toml")
                with open(path, "w") as f:
                    f.write(spec(runs, size, sr, env, fixed))
                for b, binary in enumerate(bins):
                    out = os.path.join(work, f"{b}.h5")
                    t = cpu([binary, "sweep", path, "-o", out, "--threads", "1", "-q", "--progress", "never",
                                  "--force"])
                    r = h5py.File(out, "r")["runs"][...]
                    ns[b, label, variant] = 1e9 * t / float(r["steps"].sum() + r["transit_points"].sum())
    for b, binary in enumerate(bins):
        print(f"== {binary} ({runs} runs per cell)")
        print(f"{'map':15}" + "".join(f"{v:>18}" for v, _ in VARIANTS) + "   (ns/step, x original-open)")
        for label, *_ in MAPS:
            ref = ns[b, label.replace("five", "open"), "original"]
            print(f"{label:15}" + "".join(f"{ns[b, label, v]:9.1f} ({ns[b, label, v] / ref:4.2f}x)" for v, _ in VARIANTS))
    if len(bins) > 1:
        print(f"== per cell, {bins[-1]} / {bins[0]}")
        for label, *_ in MAPS:
            print(f"{label:15}" + "".join(f"{ns[len(bins) - 1, label, v] / ns[0, label, v]:18.2f}" for v, _ in VARIANTS))


if __name__ == "__main__":
    main()
