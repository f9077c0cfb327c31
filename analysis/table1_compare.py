#!/usr/bin/env python3
"""Markdown table: each Table 1 row of seed 000, the paper's CT, our CT for the
same parameters, and the median (and quartiles) of our CT over the
ic-jittered samples of experiments/table1_spread.toml.

    python3 analysis/table1_compare.py out/table1/paper_params.h5 out/table1/spread.h5

Reads the result files with the repository's Python package (python/chaosweep:
Debian's python3-h5py and python3-pandas).
"""
import csv
import math
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from chaosweep import read_runs  # noqa: E402

ENV_OBSTACLES = {"no_obstacles": 0, "one_square": 1, "four_squares": 4, "five_squares": 5}
VARIANT_SHORT = {
    "original": "original", "logistic": "Logistic map", "index_switching": "IS",
    "map_zoning": "MZ", "scaling": "SC", "index_switching+map_zoning": "IS+MZ",
    "index_switching+scaling": "IS+SC", "map_zoning+scaling": "MZ+SC",
    "index_switching+map_zoning+scaling": "IS+MZ+SC",
}


def main(paper_params, spread):
    root = Path(__file__).resolve().parent.parent
    paper = {r["row"]: r for r in csv.DictReader(
        line for line in open(root / "experiments/table1_paper.csv") if not line.startswith("#"))}
    same = {r["label"]: r for r in read_runs(paper_params).to_dict("records")}
    samples = defaultdict(list)
    for r in read_runs(spread).to_dict("records"):
        samples[r["label"]].append(r)

    print("| row | technique | map | SR | obst. | c | DSindex | f | paper CT | our CT | "
          "our median CT [q1, q3] | ok | median / paper | paper PR | our median PR |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    ratios, widths, below = [], [], []
    for row in sorted(same, key=int):
        r = same[row]
        s = samples.get(row, [])
        ok = [x["coverage_time"] for x in s if x["status"] == "ok"]
        med = float(np.median(ok)) if ok else math.nan
        q1, q3 = (np.percentile(ok, [25, 75]) if ok else (math.nan, math.nan))
        pct = float(paper[row]["paper_ct"])
        ratios.append(med / pct)
        widths.append((q3 - q1) / med)
        # The paper's CT as a percentile of our samples (a sample that missed
        # the target counts as slower than any).
        below.append(100.0 * sum(1 for t in ok if t <= pct) / len(s) if s else math.nan)
        mz = int(r["map_zoning"]) == 1
        logistic = r["planner"] == "logistic"
        print(f"| {row} | {VARIANT_SHORT.get(r['variant'], r['variant'])} "
              f"| {r['size_x']:.0f} m | {r['sr']:.0f} | {ENV_OBSTACLES.get(r['env'], r['env'])} "
              f"| {r['c'] if mz else 'N/A'} | {'N/A' if logistic else int(r['ds_index'])} | {r['f']:g} "
              f"| {pct:.3g} | {r['coverage_time']:.3g} | {med:.3g} [{q1:.3g}, {q3:.3g}] "
              f"| {len(ok)}/{len(s)} | {med / pct:.2f} | {paper[row]['paper_pr']} "
              f"| {med / r['t_opt']:.1f} |")
    print()
    print(f"Median over rows of (our median CT / paper CT): {np.median(ratios):.2f}; "
          f"range {min(ratios):.2f} to {max(ratios):.2f}.")
    spread = [w for w in widths if w > 0]  # the Logistic row has no Arnold state: its samples coincide
    print(f"Our q1-q3 range as a share of our median, over the rows whose samples differ: {min(spread):.0%} to "
          f"{max(spread):.0%} (median {np.median(spread):.0%}).")
    print(f"The paper's CT as a percentile of our samples: median over rows {np.median(below):.0f}%; "
          f"below our 10th percentile in {sum(1 for b in below if b < 10)} of {len(below)} rows.")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
