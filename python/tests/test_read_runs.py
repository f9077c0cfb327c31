"""chaosweep.read_runs on files the binary writes: a finished sweep, a
partial file (a sweep stopped by SIGINT), a merge of shards; text as str,
status categorical, provenance typed, filters applied per chunk.
Run by ctest (Python.ReadRunsGivesTheRowsAsADataFrame) with CHAOSWEEP_BIN set."""
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

import chaosweep  # noqa: E402
from chaosweep import STATUSES, StoreError, read_provenance, read_runs  # noqa: E402

BIN = os.environ.get("CHAOSWEEP_BIN", str(ROOT / "build/release/chaosweep"))
LABEL = "→" + "x" * 120  # non-ASCII (one toml++ reads safely), longer than any old fixed width

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


def sweep(tmp_path, text, *args, name="s"):
    spec, out = tmp_path / f"{name}.toml", tmp_path / f"{name}.h5"
    spec.write_text(text)
    subprocess.run([BIN, "sweep", str(spec), "-o", str(out), "-q", "--progress", "never", *args], check=True)
    return spec, out


def test_a_finished_sweep_reads_with_str_text_categorical_status_and_typed_provenance(tmp_path):
    spec, out = sweep(tmp_path, SPEC)
    df = read_runs(out)
    assert df["run_id"].tolist() == list(range(6))
    assert df["A"].tolist() == [0.4] * 3 + [0.5] * 3
    assert df["A"].dtype == np.float64 and df["steps"].dtype == np.int64
    assert all(type(v) is str for v in df["label"]) and set(df["label"]) == {LABEL}
    assert set(df["env"]) == {"empty"}
    assert isinstance(df["status"].dtype, pd.CategoricalDtype)
    assert list(df["status"].cat.categories) == list(STATUSES)
    assert (df["status"] == "ok").dtype == bool  # a column of booleans, not a scalar False
    ok = df["status"] == "ok"
    assert df.loc[ok, "coverage_time"].notna().all() and df.loc[~ok, "coverage_time"].isna().all()
    a = df.attrs
    assert a["runs_total"] == 6 and type(a["runs_total"]) is int
    assert a["git_dirty"] in (True, False) and type(a["git_dirty"]) is bool
    assert a["layout_version"] == 2 and a["shard"] == "0/1" and a["partial"] is False
    assert Path(a["spec_path"]).is_absolute() and Path(a["spec_path"]) == spec.resolve()
    assert "A = [0.4, 0.5]" in a["spec"]
    assert read_provenance(out) == a


def test_where_and_columns_filter_and_select(tmp_path):
    _, out = sweep(tmp_path, SPEC)
    full = read_runs(out)
    some = read_runs(out, where="ds_index >= 2 and A == 0.5", columns=["run_id", "status"])
    assert list(some.columns) == ["run_id", "status"]
    assert some["run_id"].tolist() == full.loc[(full.ds_index >= 2) & (full.A == 0.5), "run_id"].tolist()
    by_callable = read_runs(out, where=lambda c: c["run_id"] % 2 == 0)
    assert by_callable["run_id"].tolist() == [0, 2, 4]
    assert len(read_runs(out, where="run_id > 100")) == 0
    with pytest.raises(StoreError, match="no column 'nope'"):
        read_runs(out, columns=["nope"])


def test_many_chunks_read_as_one_frame(tmp_path, monkeypatch):
    _, out = sweep(tmp_path, SPEC)
    monkeypatch.setattr(chaosweep.runs, "CHUNK_ROWS", 4)
    df = read_runs(out, where="status == 'ok' or status != 'ok'")
    assert df["run_id"].tolist() == list(range(6))
    assert isinstance(df["status"].dtype, pd.CategoricalDtype)


def test_a_partial_file_of_an_interrupted_sweep_reads_its_finished_rows(tmp_path):
    spec = tmp_path / "long.toml"
    spec.write_text("[fixed]\nsize = 30\nsr = 1\nmax_time = 20000\n[axes]\nA = { start = 0.3, stop = 0.7, num = 40 }\n"
                    "B = { start = 0.1, stop = 0.8, num = 40 }\n")
    out = tmp_path / "long.h5"
    p = subprocess.Popen([BIN, "sweep", str(spec), "-o", str(out), "-q", "--progress", "never", "--threads", "1",
                          "--batch", "16", "--flush-seconds", "0.5"])
    partial = Path(str(out) + ".partial")
    deadline = time.time() + 60
    while time.time() < deadline:
        if partial.exists() and read_provenance(partial) and len(read_runs(partial, columns=["run_id"])) > 0:
            break
        time.sleep(0.2)
    p.send_signal(signal.SIGINT)
    p.wait(timeout=60)
    assert not out.exists()
    df = read_runs(partial)
    assert len(df) > 0 and df["run_id"].tolist() == list(range(len(df)))
    assert df.attrs["partial"] is True and df.attrs["runs_total"] == 1600
    with pytest.raises(StoreError, match=re.escape(f"{partial}")):
        read_runs(out)  # no finished file yet; the message points at the partial one


def test_a_merge_of_shards_equals_the_single_machine_file(tmp_path):
    spec, whole = sweep(tmp_path, SPEC)
    shards = []
    for k in range(2):
        shard = tmp_path / f"shard{k}.h5"
        subprocess.run([BIN, "sweep", str(spec), "-o", str(shard), "-q", "--progress", "never", "--shard", f"{k}/2"],
                       check=True)
        shards.append(str(shard))
    merged = tmp_path / "merged.h5"
    subprocess.run([BIN, "merge", "-o", str(merged), *shards], check=True, capture_output=True)
    a, b = read_runs(whole), read_runs(merged)
    drop = ["wall_time"]
    pd.testing.assert_frame_equal(a.drop(columns=drop), b.drop(columns=drop))


def test_what_is_not_a_result_file_is_named(tmp_path):
    with pytest.raises(StoreError, match="no such file"):
        read_runs(tmp_path / "missing.h5")
    with pytest.raises(StoreError, match="not a regular file"):
        read_runs(tmp_path)
    import h5py
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = [1, 2, 3]
    with pytest.raises(StoreError, match="not a chaosweep result file"):
        read_runs(other)
    journal = Path(str(other) + ".journal")
    journal.write_bytes(b"x")
    with pytest.raises(StoreError, match="cut short"):
        read_runs(other)


def test_the_status_vocabulary_is_the_engines():
    source = (ROOT / "kernels/core/param_table.cpp").read_text()
    body = source[source.index("const char* to_string(Status v)"):]
    body = body[:body.index("\n}\n")]
    assert tuple(re.findall(r'return "(\w+)";', body)) == STATUSES


def test_export_writes_csv_and_json_lines_that_read_back_as_the_runs(tmp_path):
    _, out = sweep(tmp_path, SPEC)
    runs = read_runs(out)
    for name in ("runs.csv", "runs.jsonl"):
        target = tmp_path / name
        subprocess.run([BIN, "export", str(out), "-o", str(target)], check=True)
        # Parsed exactly (pandas' default float parsers may be off by an ulp).
        back = pd.read_csv(target, keep_default_na=False, na_values=[""], float_precision="round_trip") \
            if name.endswith(".csv") else pd.read_json(target, lines=True, dtype=False, precise_float=True)
        assert list(back.columns) == list(runs.columns)
        for col in runs.columns:
            a, b = runs[col], back[col]
            if a.dtype == np.float64:
                assert np.array_equal(a.to_numpy(), b.to_numpy(dtype=np.float64), equal_nan=True), col
            else:
                # In CSV an empty text field and a missing value are one thing.
                assert a.astype(str).tolist() == b.fillna("").astype(str).tolist(), col
    again = subprocess.run([BIN, "export", str(out), "-o", str(tmp_path / "runs.csv")], capture_output=True, text=True)
    assert again.returncode == 2 and "--force" in again.stderr
    bad = subprocess.run([BIN, "export", str(out), "-o", str(tmp_path / "runs.txt")], capture_output=True, text=True)
    assert bad.returncode == 2 and ".csv or .jsonl" in bad.stderr
    assert not (tmp_path / "runs.txt").exists()
