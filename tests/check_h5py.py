#!/usr/bin/env python3
"""The result store is readable as-is by h5py (and so by pandas via
pd.DataFrame(f["runs"][:])): runs a small sweep, then checks columns, types,
values and provenance from Python: text whole (a 300-character label) and
declared UTF-8, numbers and booleans as such, layout_version 2 (docs/store.md).
Usage: check_h5py.py CHAOSWEEP_BIN"""
import math
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

LABEL = "a label of three hundred characters, " * 8
LABEL = LABEL[:300]

SPEC = f"""
[fixed]
label = "{LABEL}"
size = 12
sr = 2
max_time = 2000
[axes]
A = [0.4, 0.5]
ds_index = [1, 2, 3]
"""

with tempfile.TemporaryDirectory() as d:
    spec, out = Path(d, "s.toml"), Path(d, "r.h5")
    spec.write_text(SPEC)
    subprocess.run([sys.argv[1], "sweep", str(spec), "-o", str(out), "-q"], check=True)
    with h5py.File(out, "r") as f:
        runs = f["runs"][:]
        assert runs.shape == (6,), runs.shape
        names = runs.dtype.names
        for col in ("run_id", "param_hash", "env", "variant", "A", "B", "C", "f", "ds_index", "sr",
                    "size_x", "start_x", "status", "coverage_time", "final_coverage", "steps", "t_opt", "pr",
                    "wall_time"):
            assert col in names, col
        assert runs["run_id"].tolist() == list(range(6))
        assert runs["A"].dtype == np.float64 and runs["steps"].dtype == np.int64
        assert runs["A"].tolist() == [0.4] * 3 + [0.5] * 3
        assert runs["ds_index"].tolist() == [1, 2, 3] * 2
        # Text columns are UTF-8 (bytes in a compound, as h5py gives them), never cut.
        for col in ("env", "label", "variant", "status", "message", "planner"):
            assert h5py.check_string_dtype(f["runs"].dtype[col]).encoding == "utf-8", col
        assert [s.decode("utf-8") for s in runs["label"]] == [LABEL] * 6
        assert [s.decode() for s in runs["env"]] == ["empty"] * 6
        status = [s.decode() for s in runs["status"]]
        assert set(status) <= {"ok", "timeout", "stuck", "diverged", "invalid", "error"}, status
        for s, ct, pr, t_opt in zip(status, runs["coverage_time"], runs["pr"], runs["t_opt"]):
            assert (s == "ok") == (not math.isnan(ct))
            if s == "ok":
                assert abs(pr - ct / t_opt) < 1e-12
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
        for key in ("engine_version", "git_commit", "spec", "spec_hash", "host", "start_time", "end_time",
                    "shard", "simd_target", "runs_total"):
            assert key in attrs, key
        assert "A = [0.4, 0.5]" in attrs["spec"]
        # Numbers are numbers, booleans booleans (h5py's enum FALSE/TRUE), text str.
        assert attrs["shard"] == "0/1" and isinstance(attrs["shard"], str)
        assert isinstance(attrs["runs_total"], np.integer) and attrs["runs_total"] == 6
        assert isinstance(attrs["threads"], np.integer) and attrs["threads"] >= 1
        assert isinstance(attrs["git_dirty"], np.bool_), type(attrs["git_dirty"])
        assert attrs["layout_version"] == 2
    dump = shutil.which("h5dump")
    if dump:  # Debian's hdf5-tools, installed by ./quickstart
        header = subprocess.run([dump, "-H", str(out)], check=True, capture_output=True, text=True).stdout
        assert 'DATASET "runs"' in header and '"coverage_time"' in header
print("h5py reads the result store: ok")
