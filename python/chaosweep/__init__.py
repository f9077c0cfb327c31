"""Read chaosweep result files into pandas (Debian: python3-h5py, python3-pandas).

    from chaosweep import read_runs
    df = read_runs("out/demo/results.h5", where="status == 'ok'")
    df.attrs["spec_hash"], df.attrs["runs_total"]

Text columns come back as ``str``, ``status`` as a categorical over every
status the engine writes, the provenance in ``df.attrs`` as Python values.
Merged files, single-machine files and the ``OUT.partial`` of a running or
interrupted sweep are read alike (docs/store.md).
"""

from chaosweep.runs import STATUSES, StoreError, read_provenance, read_runs

__all__ = ["STATUSES", "StoreError", "read_provenance", "read_runs"]
