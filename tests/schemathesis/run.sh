#!/usr/bin/env bash
# Runs Schemathesis with every check against a running dieplan: it reads the service's own
# /openapi.json, sends what the document allows (and what it forbids), and fails on any
# answer the document does not promise (an undocumented status or header, a body that does
# not validate, valid input refused, invalid input accepted, a 5xx, a missing 401 ...).
#
#   DIEPLAN=http://127.0.0.1:8080 DIEPLAN_KEY=dpk_... bash tests/schemathesis/run.sh
#
# Then it checks that a finished job of every kind validates against the document
# (finished_jobs.py). DIEPLAN_KEY must be an admin key, so every route can be reached. Schemathesis is
# installed into a virtual environment under target/ when missing (pip, from PyPI).
# SCHEMATHESIS_EXAMPLES (default 12) bounds the cases per operation and phase, and
# SCHEMATHESIS_SEED (default 1) fixes them: the run is the same every time; change the seed
# to explore further. The report is written to target/schemathesis/.
# `cargo test --release` runs it from tests/api/schemathesis.rs against the real app.
set -euo pipefail
cd "$(dirname "$0")/../.."

: "${DIEPLAN:?set DIEPLAN to the base URL of the service}"
: "${DIEPLAN_KEY:?DIEPLAN_KEY must be an admin key}"
VERSION="4.32.5"
VENV="${SCHEMATHESIS_VENV:-target/schemathesis-venv}"
ST="$VENV/bin/schemathesis"

if ! "$ST" --version 2>/dev/null | grep -q "$VERSION"; then
  command -v python3 >/dev/null || { echo "schemathesis: python3 is required to install Schemathesis" >&2; exit 1; }
  echo "schemathesis: installing schemathesis $VERSION into $VENV"
  if ! { python3 -m venv "$VENV" && "$VENV/bin/pip" install --quiet "schemathesis==$VERSION"; }; then
    echo "schemathesis: could not install schemathesis $VERSION with pip into $VENV (is PyPI reachable, and python3-venv installed?)" >&2
    exit 1
  fi
fi

REPORT=target/schemathesis
mkdir -p "$REPORT"
# Real jobs of every kind, queued first so they finish while Schemathesis runs.
"$VENV/bin/python" tests/schemathesis/finished_jobs.py submit "$REPORT/jobs.json"
"$ST" --config-file tests/schemathesis/schemathesis.toml run "$DIEPLAN/openapi.json" \
  --checks all \
  --header "Authorization: Bearer $DIEPLAN_KEY" \
  --max-examples "${SCHEMATHESIS_EXAMPLES:-12}" \
  --seed "${SCHEMATHESIS_SEED:-1}" \
  --generation-database none \
  --workers 2 \
  --request-timeout 30 \
  --no-color \
  --report junit --report-dir "$REPORT"
"$VENV/bin/python" tests/schemathesis/finished_jobs.py check "$REPORT/jobs.json"
