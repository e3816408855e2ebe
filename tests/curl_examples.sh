#!/usr/bin/env bash
# Starts the dieplan binary on a free port with a temporary database and runs every
# ```sh block of README.md's "API examples" section against it, in order, in one shell
# (so later examples can use variables set by earlier ones). Then checks a few answers
# and that SIGTERM stops the service cleanly.
#
#   DIEPLAN_BIN=target/release/dieplan bash tests/curl_examples.sh
#
# Without DIEPLAN_BIN it builds the release binary first. `cargo test --release` runs it
# through tests/api/curl_examples.rs with the binary cargo just built.
set -euo pipefail
cd "$(dirname "$0")/.."

for tool in curl jq python3; do
  command -v "$tool" >/dev/null || { echo "curl_examples: $tool is required" >&2; exit 1; }
done

# shellcheck source=tests/serve.sh
source tests/serve.sh

# Collect the examples: ```sh blocks between the two markers of README.md.
awk -v out="$TMP/examples.sh" -f tests/readme_examples.awk README.md
COUNT=$(grep -c '^echo "--- example' "$TMP/examples.sh" || true)
[ "$COUNT" -ge 12 ] || { echo "expected at least 12 README examples, found $COUNT"; exit 1; }

echo "running $COUNT README examples against $DIEPLAN"
if ! bash -euo pipefail "$TMP/examples.sh" >"$TMP/examples.out" 2>&1; then
  cat "$TMP/examples.out"
  echo "a README example failed (see the last '--- example' above)"
  echo "--- server log"; tail -n 30 "$TMP/server.log"
  exit 1
fi

# The last examples made keys, so the service now needs one: make an admin key with the
# command line, as an operator would.
KEY=$("$BIN" keys create --role admin --name curl-checks --database "$TMP/dieplan.sqlite" 2>/dev/null)
[ -n "$KEY" ] || { echo "dieplan keys create printed no key"; exit 1; }
code=$(curl -sS -o /dev/null -w '%{http_code}' "$DIEPLAN/v1/tools?limit=1")
[ "$code" = 401 ] || { echo "expected 401 without a key once keys exist, got $code"; exit 1; }
echo "ok: without a key the service answers 401 once keys exist"

# Answers the README promises.
check() { # description, jq filter, URL path, method, body
  local got
  got=$(curl -sS -X "$4" "$DIEPLAN$3" -H "authorization: Bearer $KEY" -H 'content-type: application/json' -H 'Prefer: wait=60' ${5:+-d "$5"})
  echo "$got" | jq -e "$2" >/dev/null || { echo "check failed: $1: $got"; exit 1; }
  echo "ok: $1"
}
check "10 mm standard conditions give F 5760 and beta0 = 269.1 N" \
  '((.result.conditions.feed_mm_min - 5760) | fabs) < 1e-6 and ((.result.force.fxy_n - 269.1) | fabs) < 1e-3' \
  /v1/conditions POST '{"tool_type": "square", "diameter_mm": 10}'
check "18 seeded tools" '.total == 18' "/v1/tools?limit=1" GET ""
check "a bad request is a problem document naming the field" \
  '.status == 422 and .errors[0].field == "diameter_mm"' /v1/conditions POST '{"tool_type": "square", "diameter_mm": 11}'
check "a concave arc of R/r 2 is cut at about 1160 mm/min for a constant force" \
  '[.result.blocks.feed_mm_min[] | select(. != null)] | any(. > 1136 and . < 1184)' /v1/feeds POST \
  '{"program": {"gcode": "G21 G90\nS9600 M3\nG0 X0 Y0 Z5\nG1 Z-10 F1000\nG1 X5 F5760\nG3 X5 Y0 I-5 J0\nM30\n"}, "tool_type": "square", "diameter_mm": 10, "stock": {"box": {"x_min": -30, "y_min": -30, "z_min": -10, "x_max": 30, "y_max": 30, "z_max": 0}, "open": [{"circle": {"cx": 0, "cy": 0, "r": 9.5}}]}}'
check "trochoids make the box with a 12 mm slot safe: nothing above 40 degrees, no gouge, nothing left" \
  '.result.verification.passed and .result.verification.outside_zcut.max_alpha_deg <= 40 and ([.result.treatments[] | select(.kind == "trochoid")] | length) > 0' \
  /v1/trochoids POST '{"contour": {"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]}, "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}'

# SIGTERM: graceful stop with exit code 0.
kill -TERM "$PID"
for _ in $(seq 1 100); do kill -0 "$PID" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$PID" 2>/dev/null; then echo "the service did not stop on SIGTERM"; exit 1; fi
CODE=0; wait "$PID" || CODE=$?
[ "$CODE" -eq 0 ] || { echo "exit code $CODE after SIGTERM"; exit 1; }
grep -q "stopped" "$TMP/server.log" || { echo "no graceful stop in the log"; cat "$TMP/server.log"; exit 1; }
echo "ok: SIGTERM stops the service gracefully"
echo "curl_examples: all $COUNT examples and checks passed"
