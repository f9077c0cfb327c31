#!/usr/bin/python3
"""CPU time (user + system of the sweep process, --threads 2) of shards of a
sweep spec, the binaries taking turns shard by shard, and `compare` of each
shard's files (the last binary's compare) so that a speed-up is shown on
identical results.
  usage: tests/benchmarks/sweep_cpu.py SPEC K/N[,K/N...] BIN...
"""
import os
import resource
import subprocess
import sys
import tempfile


def cpu(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def main():
    if len(sys.argv) < 4:
        sys.exit("usage: sweep_cpu.py SPEC K/N[,K/N...] BIN...")
    spec, shards, bins = sys.argv[1], sys.argv[2].split(","), sys.argv[3:]
    total = {b: 0.0 for b in bins}
    with tempfile.TemporaryDirectory(prefix="chaosweep-cpu.") as work:
        for shard in shards:
            files = []
            for i, b in enumerate(bins):
                out = os.path.join(work, f"{i}.h5")
                t = cpu([b, "sweep", spec, "-o", out, "--shard", shard, "--threads", "2", "-q", "--force",
                         "--progress", "never"])
                total[b] += t
                files.append(out)
                print(f"shard {shard}: {b}: {t:.1f} CPU-s", flush=True)
            for f in files[1:]:
                line = subprocess.run([bins[-1], "compare", files[0], f], capture_output=True, text=True).stdout
                print(f"  compare: {line.splitlines()[0] if line else '(no output)'}", flush=True)
    for b in bins:
        print(f"total {b}: {total[b]:.1f} CPU-s")
    print(f"ratio last / first: {total[bins[-1]] / total[bins[0]]:.3f}")


if __name__ == "__main__":
    main()
