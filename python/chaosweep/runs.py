"""The result store (docs/store.md) as a pandas DataFrame."""

import fcntl
import os
import time
from pathlib import Path

import h5py
import numpy as np
import pandas as pd

# Every status a run ends with, in the engine's order (kernels/core/param_table.cpp,
# to_string(Status)); python/tests checks the two lists agree.
STATUSES = ("ok", "timeout", "diverged", "stuck", "invalid", "error")

# Rows per read: memory is bounded by a chunk (and what `where` keeps), not by the file.
CHUNK_ROWS = 1 << 16


class StoreError(RuntimeError):
    """A file that is not a chaosweep result file, or cannot be read now."""


def _text(value):
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return _text(value[()])
    return value


def _python(value):
    """An attribute as the Python value it stands for."""
    value = _text(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    return value


class _SharedLock:
    """flock(LOCK_SH) on the file, as chaosweep's readers take it: a write
    session (which holds LOCK_EX) is never seen half done."""

    def __init__(self, path, timeout):
        self.path, self.timeout, self.fd = path, timeout, None

    def __enter__(self):
        self.fd = os.open(self.path, os.O_RDONLY)
        deadline = time.monotonic() + self.timeout
        while True:
            try:
                fcntl.flock(self.fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
                return self
            except BlockingIOError:
                if time.monotonic() > deadline:
                    os.close(self.fd)
                    raise StoreError(f"{self.path}: another process has the file open for writing "
                                     f"for more than {self.timeout:g} s; try again") from None
                time.sleep(0.05)

    def __exit__(self, *exc):
        os.close(self.fd)


def _check_readable(path):
    if not path.exists():
        partial = path.with_name(path.name + ".partial")
        hint = f" (an unfinished sweep's rows are in {partial})" if partial.exists() else ""
        raise StoreError(f"{path}: no such file{hint}")
    if not path.is_file():
        raise StoreError(f"{path}: not a regular file")


def _check_no_pending_journal(path):
    """Under the shared lock a journal exists only if a write was cut short."""
    journal = path.with_name(path.name + ".journal")
    if journal.exists() and journal.stat().st_size > 0:
        # Only chaosweep reads through a pending journal (docs/store.md, "Recovery").
        raise StoreError(f"{path}: a write to it was cut short ({journal.name} is pending); "
                         f"`chaosweep sweep --resume` rolls it back (chaosweep's own readers, e.g. "
                         f"`chaosweep table`, read it as of its last complete write)")


def _frame(rows, names, string_fields):
    columns = {}
    for name in names:
        col = rows[name]
        if name in string_fields:
            columns[name] = np.array([v.decode("utf-8") if isinstance(v, bytes) else v for v in col.tolist()],
                                     dtype=object)
        else:
            columns[name] = col
    return pd.DataFrame(columns, columns=names)


class _Opened:
    """The file checked, under the shared lock, with no pending journal, open in h5py."""

    def __init__(self, path, lock_timeout):
        self.path = Path(path)
        _check_readable(self.path)
        self.lock = _SharedLock(self.path, timeout=lock_timeout)

    def __enter__(self):
        self.lock.__enter__()
        try:
            _check_no_pending_journal(self.path)
            self.file = h5py.File(self.path, "r")
        except BaseException:
            self.lock.__exit__()
            raise
        return self.file

    def __exit__(self, *exc):
        self.file.close()
        self.lock.__exit__()


def read_provenance(path, lock_timeout=10.0):
    """The file's root attributes (spec, spec_hash, shard, runs_total, git_dirty, ...)
    as Python values: text as str, counts as int, flags as bool."""
    with _Opened(path, lock_timeout) as f:
        return _provenance(f, Path(path))


def _provenance(f, path):
    attrs = {k: _python(v) for k, v in f.attrs.items()}
    attrs["path"] = str(path.resolve())
    attrs["partial"] = path.name.endswith(".partial")
    return attrs


def read_runs(path, where=None, columns=None, lock_timeout=10.0):
    """The rows of a result file as a DataFrame, in run_id order.

    where: a pandas query string (``"status == 'ok' and sr == 4"``) or a
    callable taking a chunk's DataFrame and returning a boolean mask; applied
    chunk by chunk, so a filtered read of a large file stays small.
    columns: the columns to keep (default: all).
    The provenance is in ``df.attrs`` (see read_provenance)."""
    with _Opened(path, lock_timeout) as f:
        return _read_rows(f, Path(path), where, columns)


def _read_rows(f, path, where, columns):
    if "runs" not in f or not isinstance(f["runs"], h5py.Dataset) or f["runs"].dtype.names is None:
        raise StoreError(f"{path}: no /runs table of rows: not a chaosweep result file")
    ds = f["runs"]
    names = list(ds.dtype.names)
    if columns is not None:
        unknown = [c for c in columns if c not in names]
        if unknown:
            raise StoreError(f"{path}: no column {', '.join(map(repr, unknown))} "
                             f"(the file has {', '.join(names)})")
        names = list(columns)
    text_fields = {n for n in ds.dtype.names if h5py.check_string_dtype(ds.dtype[n]) is not None}
    parts = []
    # where may name columns that are not kept: filter first, then select.
    for start in range(0, max(ds.shape[0], 1), CHUNK_ROWS):
        chunk = _frame(ds[start:start + CHUNK_ROWS], ds.dtype.names, text_fields)
        if where is not None and len(chunk):
            mask = chunk.eval(where) if isinstance(where, str) else where(chunk)
            chunk = chunk[np.asarray(mask, dtype=bool)]
        parts.append(chunk[names])
    frame = pd.concat(parts, ignore_index=True)
    if "status" in frame:
        frame["status"] = pd.Categorical(frame["status"], categories=STATUSES)
    frame.attrs = _provenance(f, path)
    return frame
