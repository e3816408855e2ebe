"""Checks that finished jobs of every kind validate against the OpenAPI document.

Schemathesis validates every answer it gets, but the jobs it submits are random and
rarely finish; this submits one real job of each kind (the built-in examples of
GET /v1/examples, and a conditions request), waits for each, and validates the finished
job against `Job` (the oneOf by kind) and against its kind's own schema, so a result that
drifts from its documented type fails the test.

    python finished_jobs.py submit FILE   # submits the jobs, writes their ids to FILE
    python finished_jobs.py check FILE    # waits for them and validates them

Reads DIEPLAN (base URL) and DIEPLAN_KEY (a key) from the environment.
"""

import json
import os
import sys
import time
import urllib.request

import jsonschema_rs

BASE = os.environ["DIEPLAN"].rstrip("/")
KEY = os.environ["DIEPLAN_KEY"]
WAIT_S = 600
CONDITIONS = {"tool_type": "square", "diameter_mm": 10, "operation": "standard_side_cutting"}


def call(method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(BASE + path, data=data, method=method)
    request.add_header("Authorization", f"Bearer {KEY}")
    if data is not None:
        request.add_header("Content-Type", "application/json")
    with urllib.request.urlopen(request, timeout=60) as response:
        return json.load(response)


def submit(path):
    examples = call("GET", "/v1/examples")["items"]
    jobs = [{"kind": "conditions", "input": CONDITIONS, "title": "conditions"}]
    jobs += [{"kind": e["kind"], "input": e["input"], "title": e["id"]} for e in examples]
    ids = []
    for job in jobs:
        made = call("POST", "/v1/jobs", {"kind": job["kind"], "input": job["input"]})
        ids.append({"id": made["id"], "kind": job["kind"], "title": job["title"]})
    kinds = {job["kind"] for job in ids}
    missing = {"conditions", "analysis", "feeds", "costing", "trochoids", "plan"} - kinds
    if missing:
        sys.exit(f"finished_jobs: no example of kind {sorted(missing)}")
    with open(path, "w") as out:
        json.dump(ids, out)


def check(path):
    document = call("GET", "/openapi.json")
    components = document["components"]

    def validator(name):
        return jsonschema_rs.Draft202012Validator(
            {"$ref": f"#/components/schemas/{name}", "components": components}, validate_formats=True
        )

    any_job = validator("Job")
    faults = []
    for job in json.load(open(path)):
        deadline = time.monotonic() + WAIT_S
        while True:
            answer = call("GET", f"/v1/jobs/{job['id']}")
            if answer["status"] in ("succeeded", "failed", "cancelled") or time.monotonic() > deadline:
                break
            time.sleep(0.5)
        name = job["title"]
        if answer["status"] != "succeeded":
            faults.append(f"{name}: {answer['status']} ({json.dumps(answer.get('error'))[:300]})")
            continue
        kind_schema = job["kind"].capitalize() + "Job"
        for label, v in (("Job", any_job), (kind_schema, validator(kind_schema))):
            errors = [f"{'/'.join(map(str, e.instance_path))}: {e.message[:200]}" for e in v.iter_errors(answer)]
            if errors:
                faults.append(f"{name} does not validate against {label}: " + "; ".join(errors[:5]))
        print(f"finished_jobs: {name} ({job['kind']}) validates against Job and {kind_schema}")
    if faults:
        sys.exit("finished_jobs:\n  " + "\n  ".join(faults))


if __name__ == "__main__":
    {"submit": submit, "check": check}[sys.argv[1]](sys.argv[2])
