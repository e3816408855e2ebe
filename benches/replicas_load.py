#!/usr/bin/env python3
"""Several replicas on one PostgreSQL (BENCHMARKS.md, "Several replicas on PostgreSQL"):
the throughput of small jobs with 1 and 2 replicas of the binary on one machine, and the
same load on one SQLite instance for reference.

Starts a throwaway PostgreSQL (tests/postgres/start.sh: Debian's postgresql, installed when
missing), then for each set-up (SQLite; PostgreSQL with 1 replica; PostgreSQL with 2
replicas, each on a database of its own) starts the replicas on free loopback ports (each
with its default workers, one per core), and runs `--clients` clients for `--seconds` s,
each submitting `conditions` jobs one after another with `Prefer: wait=60` on its own
keep-alive connection, spread round robin over the replicas (as a proxy would). Reports
finished jobs per second, latency percentiles and failures.

Only the standard library; the clients are threads (the client side is itself limited by
the interpreter: the figures are lower bounds of the service's).

    cargo build --release
    python3 benches/replicas_load.py --bin target/release/dieplan

Run it on an idle machine for figures to compare; not part of the test suite.
"""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from jobs_load import free_port, percentile, throughput, wait_ready  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
JOB = json.dumps({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}}).encode()


def start_postgres():
    directory = tempfile.mkdtemp(prefix="dieplan-bench-pg-")
    port = free_port()
    out = subprocess.run(
        ["bash", os.path.join(ROOT, "tests/postgres/start.sh"), directory, str(port), str(os.getpid())],
        check=True, capture_output=True, text=True,
    )
    return out.stdout.strip().splitlines()[-1], port


def create_database(server_port, name):
    createdb = sorted(glob.glob("/usr/lib/postgresql/*/bin/createdb"))[-1]
    subprocess.run([createdb, "-h", "127.0.0.1", "-p", str(server_port), "-U", "dieplan", name], check=True)


def start_replicas(binary, database, count):
    procs, ports = [], []
    for _ in range(count):
        port = free_port()
        procs.append(subprocess.Popen(
            [binary, "serve", "--addr", f"127.0.0.1:{port}", "--database", database],
            env={**os.environ, "DIEPLAN_LOG": "warn"}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        ))
        ports.append(port)
        wait_ready(port)  # one after the other: the first migrates and seeds
    return procs, ports


def report(name, latencies, failures, elapsed):
    print(f"{name:<28} {len(latencies) / elapsed:7.1f} jobs/s  p50 {percentile(latencies, 50):.3f} s  "
          f"p95 {percentile(latencies, 95):.3f} s  p99 {percentile(latencies, 99):.3f} s  failed {failures}",
          flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/dieplan")
    ap.add_argument("--clients", type=int, default=64)
    ap.add_argument("--seconds", type=float, default=20)
    args = ap.parse_args()
    binary = os.path.abspath(args.bin)
    server, server_port = start_postgres()
    print(f"{args.clients} clients, {args.seconds:.0f} s each, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")

    with tempfile.TemporaryDirectory() as d:
        procs, ports = start_replicas(binary, os.path.join(d, "bench.sqlite"), 1)
        try:
            report("SQLite, 1 instance", *throughput(ports, args.clients, args.seconds, "/v1/jobs", JOB))
        finally:
            for p in procs:
                p.terminate()
                p.wait()

    for count in (1, 2):
        name = f"bench_{count}_{os.getpid()}"
        create_database(server_port, name)
        procs, ports = start_replicas(binary, f"{server}/{name}", count)
        try:
            report(f"PostgreSQL, {count} replica{'s' if count > 1 else ''}", *throughput(ports, args.clients, args.seconds, "/v1/jobs", JOB))
        finally:
            for p in procs:
                p.terminate()
                p.wait()


if __name__ == "__main__":
    main()
