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
finished jobs per second, latency percentiles and failures. Then what the rate limits shared
by the replicas cost: reads of one material on 2 replicas with an unlimited key, then with a
limited one that is never refused (`--keys-only` runs this part alone).

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
import secrets
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from jobs_load import Client, free_port, percentile, throughput, wait_ready  # noqa: E402

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


def start_replicas(binary, database, count, env=None):
    procs, ports = [], []
    for _ in range(count):
        port = free_port()
        procs.append(subprocess.Popen(
            [binary, "serve", "--addr", f"127.0.0.1:{port}", "--database", database],
            env={**os.environ, "DIEPLAN_LOG": "warn", **(env or {})},
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        ))
        ports.append(port)
        wait_ready(port)  # one after the other: the first migrates and seeds
    return procs, ports


def report(name, latencies, failures, elapsed):
    print(f"{name:<28} {len(latencies) / elapsed:7.1f} jobs/s  p50 {percentile(latencies, 50):.3f} s  "
          f"p95 {percentile(latencies, 95):.3f} s  p99 {percentile(latencies, 99):.3f} s  failed {failures}",
          flush=True)


def make_key(port, admin, limit):
    """A reader key of `limit` requests a minute (0: unlimited), made with the admin key."""
    status, text = Client(port).request("POST", "/v1/keys", {"role": "reader", "name": f"bench {limit}",
                                                              "rate_limit_per_minute": limit},
                                        {"authorization": f"Bearer {admin}"})
    assert status == 201, text
    return json.loads(text)["key"]


def reads(ports, key, clients, seconds):
    """`clients` threads, spread over `ports`, each reading one material with `key` one
    request after another for `seconds`: the latencies of the answers, the failures and the
    time taken."""
    latencies, failures, lock = [], [0], threading.Lock()
    stop_at = time.time() + seconds

    def client(port):
        c, mine, bad = Client(port), [], 0
        while time.time() < stop_at:
            t = time.time()
            status, _ = c.request("GET", "/v1/materials/1", None, {"authorization": f"Bearer {key}"})
            if status == 200:
                mine.append(time.time() - t)
            else:
                bad += 1
        with lock:
            latencies.extend(mine)
            failures[0] += bad

    t0 = time.time()
    threads = [threading.Thread(target=client, args=(ports[i % len(ports)],)) for i in range(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return latencies, failures[0], time.time() - t0


def rate_limit_cost(binary, server, server_port, clients, seconds):
    """Reads with an unlimited key, then with a limited one that is never refused (10^6 a
    minute) on 2 replicas: the difference is what the shared bucket costs each request."""
    name = f"bench_keys_{os.getpid()}"
    create_database(server_port, name)
    admin = secrets.token_hex(32)
    procs, ports = start_replicas(binary, f"{server}/{name}", 2, {"DIEPLAN_ADMIN_KEY": admin})
    try:
        for label, limit in (("unlimited key", 0), ("limited key (shared bucket)", 10**6)):
            latencies, failures, elapsed = reads(ports, make_key(ports[0], admin, limit), clients, seconds)
            print(f"{'reads, 2 replicas, ' + label:<48} {len(latencies) / elapsed:7.1f} requests/s  "
                  f"p50 {percentile(latencies, 50) * 1000:.2f} ms  p99 {percentile(latencies, 99) * 1000:.2f} ms  "
                  f"failed {failures}", flush=True)
    finally:
        for p in procs:
            p.terminate()
            p.wait()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/dieplan")
    ap.add_argument("--clients", type=int, default=64)
    ap.add_argument("--seconds", type=float, default=20)
    ap.add_argument("--keys-only", action="store_true", help="only the cost of the shared rate limits")
    args = ap.parse_args()
    binary = os.path.abspath(args.bin)
    server, server_port = start_postgres()
    print(f"{args.clients} clients, {args.seconds:.0f} s each, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")
    if args.keys_only:
        rate_limit_cost(binary, server, server_port, args.clients, args.seconds)
        return

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
    rate_limit_cost(binary, server, server_port, args.clients, args.seconds)


if __name__ == "__main__":
    main()
