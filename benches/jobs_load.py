#!/usr/bin/env python3
"""Jobs under load (BENCHMARKS.md, "Jobs"): list latency with large jobs stored, and the
throughput of small jobs under many concurrent clients.

Starts a dieplan binary on a free loopback port with a temporary database, then

1. stores `--big-jobs` analysis jobs whose input is a G-code program of about `--big-mb` MB
   (comment lines and one cut: they run in moments, so what they leave is their input),
   and waits until they have finished;
2. `--rounds` times, sends `--list-clients` concurrent `GET /v1/jobs` (the default page,
   which holds every big job) together with one `GET /healthz`, and reports the latencies;
3. runs `--small-clients` clients for `--small-seconds` s, each submitting conditions jobs
   one after the other with `Prefer: wait=60` on its own keep-alive connection, and reports
   finished jobs per second and the latency percentiles;
4. reports the service's peak resident memory (VmHWM).

Only the standard library; the clients are threads (so the client side is itself limited
by the interpreter at high rates: the figure is a lower bound of the service's).

    cargo build --release
    python3 benches/jobs_load.py --bin target/release/dieplan

Run it on an idle machine for figures to compare; not part of the test suite.
"""

import argparse
import http.client
import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Client:
    """One keep-alive HTTP/1.1 connection."""

    def __init__(self, port):
        self.port = port
        self.conn = http.client.HTTPConnection("127.0.0.1", port, timeout=600)

    def request(self, method, path, body=None, headers=None):
        data = None if body is None else (body if isinstance(body, bytes) else json.dumps(body).encode())
        h = {"content-type": "application/json"} if data is not None else {}
        h.update(headers or {})
        for attempt in range(2):
            try:
                self.conn.request(method, path, body=data, headers=h)
                r = self.conn.getresponse()
                return r.status, r.read()
            except (http.client.HTTPException, ConnectionError):
                self.conn.close()
                self.conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=600)
                if attempt:
                    raise


def big_input(megabytes):
    line = "(" + "x" * 97 + ")\n"
    lines = int(megabytes * 1_000_000 / len(line))
    gcode = "G21 G90\n" + line * lines + "G0 X-6 Y10 Z5\nG1 Z-3 F500\nG1 X30 F2000\nM30\n"
    return json.dumps({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -5, "x_max": 20, "y_max": 20, "z_max": 0}},
    }).encode()


def percentile(values, p):
    values = sorted(values)
    if not values:
        return float("nan")
    k = min(len(values) - 1, max(0, round(p / 100 * (len(values) - 1))))
    return values[k]


def peak_rss_mb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return float("nan")


def wait_ready(port, deadline_s=60):
    end = time.time() + deadline_s
    while time.time() < end:
        try:
            if Client(port).request("GET", "/healthz")[0] == 200:
                return
        except OSError:
            pass
        time.sleep(0.2)
    sys.exit("the service did not start")


def store_big_jobs(port, count, megabytes):
    body = big_input(megabytes)
    print(f"storing {count} analysis jobs of {len(body) / 1e6:.1f} MB input each", flush=True)
    c = Client(port)
    for i in range(count):
        t = time.time()
        status, text = c.request("POST", "/v1/analysis", body)
        if status not in (201, 202):
            sys.exit(f"job {i} refused: {status} {text[:300]!r}")
        print(f"  job {i + 1} submitted in {time.time() - t:.1f} s", flush=True)
    # Wait until none is queued or running (a page of one row, so that even a list that
    # parses its rows reads little).
    while True:
        busy = 0
        for status in ("queued", "running"):
            _, text = c.request("GET", f"/v1/jobs?status={status}&limit=1")
            busy += json.loads(text)["total"]
        if busy == 0:
            break
        time.sleep(1)
    _, text = c.request("GET", "/v1/jobs?status=succeeded&limit=1")
    print(f"  {json.loads(text)['total']} succeeded", flush=True)


def list_latency(port, clients, rounds):
    lists, health = [], []
    for _ in range(rounds):
        barrier = threading.Barrier(clients + 1)
        def one(path, out):
            c = Client(port)
            barrier.wait()
            t = time.time()
            status, body = c.request("GET", path)
            out.append(time.time() - t)
            if status != 200:
                print(f"  {path}: {status} {body[:200]!r}", flush=True)
        threads = [threading.Thread(target=one, args=("/v1/jobs", lists)) for _ in range(clients)]
        threads.append(threading.Thread(target=one, args=("/healthz", health)))
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    return lists, health


CONDITIONS_JOB = json.dumps({"tool_type": "square", "diameter_mm": 10, "operation": "rough_side_cutting"}).encode()


def throughput(ports, clients, seconds, path="/v1/conditions", body=CONDITIONS_JOB):
    """`clients` threads, spread over `ports`, each POSTing `body` to `path` one after another
    with `Prefer: wait=60` for `seconds`: the latencies of the jobs that succeeded, the
    failures, and the time taken."""
    latencies, failures = [], []
    lock = threading.Lock()
    start_line = threading.Barrier(clients + 1)
    stop_at = [0.0]

    def client(port):
        c = Client(port)
        mine, bad = [], 0
        start_line.wait()
        while time.time() < stop_at[0]:
            t = time.time()
            try:
                status, text = c.request("POST", path, body, {"prefer": "wait=60"})
            except OSError:
                bad += 1
                continue
            if status == 201 and b'"succeeded"' in text:
                mine.append(time.time() - t)
            else:
                bad += 1
        with lock:
            latencies.extend(mine)
            failures.append(bad)

    threads = [threading.Thread(target=client, args=(ports[i % len(ports)],)) for i in range(clients)]
    for t in threads:
        t.start()
    stop_at[0] = time.time() + seconds
    t0 = time.time()
    start_line.wait()
    for t in threads:
        t.join()
    return latencies, sum(failures), time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/dieplan")
    ap.add_argument("--big-jobs", type=int, default=9)
    ap.add_argument("--big-mb", type=float, default=60)
    ap.add_argument("--list-clients", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--small-clients", type=int, default=200)
    ap.add_argument("--small-seconds", type=float, default=20)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()

    tmp = tempfile.mkdtemp(prefix="dieplan-bench-")
    port = free_port()
    log = open(os.path.join(tmp, "server.log"), "w")
    server = subprocess.Popen(
        [args.bin, "serve", "--addr", f"127.0.0.1:{port}", "--database", os.path.join(tmp, "dieplan.sqlite"),
         "--workers", str(args.workers)],
        stdout=log, stderr=subprocess.STDOUT, env={**os.environ, "RUST_LOG": "warn"})
    try:
        wait_ready(port)
        print(f"{args.bin} on port {port}; load average {os.getloadavg()[0]:.2f}", flush=True)
        if args.big_jobs:
            store_big_jobs(port, args.big_jobs, args.big_mb)
            lists, health = list_latency(port, args.list_clients, args.rounds)
            print(f"GET /v1/jobs, {args.list_clients} concurrent, {args.rounds} rounds: "
                  f"median {statistics.median(lists):.3f} s, max {max(lists):.3f} s", flush=True)
            print(f"GET /healthz meanwhile: median {statistics.median(health):.3f} s, max {max(health):.3f} s",
                  flush=True)
        lat, bad, elapsed = throughput([port], args.small_clients, args.small_seconds)
        print(f"conditions jobs, {args.small_clients} clients for {elapsed:.1f} s: {len(lat)} finished "
              f"({len(lat) / elapsed:.0f}/s), {bad} failed; latency p50 {percentile(lat, 50) * 1000:.0f} ms, "
              f"p95 {percentile(lat, 95) * 1000:.0f} ms, p99 {percentile(lat, 99) * 1000:.0f} ms", flush=True)
        print(f"service peak memory {peak_rss_mb(server.pid):.0f} MB; load average {os.getloadavg()[0]:.2f}",
              flush=True)
    finally:
        server.terminate()
        try:
            server.wait(timeout=60)
        except subprocess.TimeoutExpired:
            server.kill()
        log.close()


if __name__ == "__main__":
    main()
