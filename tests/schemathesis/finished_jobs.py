"""Checks that finished jobs of every kind validate against the OpenAPI document.

Schemathesis validates every answer it gets, but the jobs it submits are random and
rarely finish; this submits one real job of each kind (the built-in examples of
GET /v1/examples, and a conditions request), waits for each, and validates the finished
job against `Job` (the oneOf by kind) and against its kind's own schema, so a result that
drifts from its documented type fails the test. It also validates every example of the
document (`example` and `examples` of a schema, a parameter or a media type) against the
schema it illustrates, so no example shows a value the service would not send or accept.

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


def example_faults(document):
    """Every example of the document that does not validate against its own schema."""
    components = document["components"]
    faults = []

    def validate(where, schema, example):
        v = jsonschema_rs.Draft202012Validator({**schema, "components": components}, validate_formats=True)
        errors = [f"{'/'.join(map(str, e.instance_path))}: {e.message[:160]}" for e in v.iter_errors(example)]
        if errors:
            faults.append(f"the example at {where} does not validate: " + "; ".join(errors[:3]))

    def schema_examples(where, schema):
        if not isinstance(schema, dict):
            return
        bare = {k: v for k, v in schema.items() if k not in ("example", "examples")}
        if "example" in schema:
            validate(where, bare, schema["example"])
        for i, example in enumerate(schema.get("examples") or []):
            validate(f"{where}/examples/{i}", bare, example)
        for key, value in schema.items():
            if key in ("properties", "patternProperties", "$defs"):
                for name, inner in value.items():
                    schema_examples(f"{where}/{key}/{name}", inner)
            elif key in ("items", "additionalProperties", "not", "contains"):
                schema_examples(f"{where}/{key}", value)
            elif key in ("oneOf", "anyOf", "allOf", "prefixItems"):
                for i, inner in enumerate(value):
                    schema_examples(f"{where}/{key}/{i}", inner)

    for name, schema in components["schemas"].items():
        schema_examples(f"#/components/schemas/{name}", schema)
    for route, item in document["paths"].items():
        for method, operation in item.items():
            if not isinstance(operation, dict):
                continue
            for parameter in operation.get("parameters", []):
                schema_examples(f"{method.upper()} {route} parameter {parameter['name']}", parameter.get("schema"))
            media = [("request", m) for m in (operation.get("requestBody") or {}).get("content", {}).values()]
            for status, response in operation.get("responses", {}).items():
                media += [(status, m) for m in response.get("content", {}).values()]
            for label, m in media:
                if "example" in m and "schema" in m:
                    validate(f"{method.upper()} {route} {label}", m["schema"], m["example"])
    return faults


def check(path):
    document = call("GET", "/openapi.json")
    components = document["components"]

    def validator(name):
        return jsonschema_rs.Draft202012Validator(
            {"$ref": f"#/components/schemas/{name}", "components": components}, validate_formats=True
        )

    any_job = validator("Job")
    faults = example_faults(document)
    print("finished_jobs: every example of the document validates against its schema" if not faults else "")
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
