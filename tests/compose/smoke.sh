#!/usr/bin/env bash
# Runs docker/compose.yaml for real: builds the image, brings up each profile, runs every
# curl example of README.md against it (for `postgres` through nginx, with both replicas
# serving, a key's rate limit shared by them, and one replica killed), checks a few
# answers, and removes the containers and volumes again. Not part of `cargo test`: it
# needs Docker with compose, a few GB of disk and, the first time, a release build inside
# the image (22 minutes on the loaded 2-core development machine).
#
#   bash tests/compose/smoke.sh                 # both profiles
#   bash tests/compose/smoke.sh postgres        # one
#
# Needs docker with `docker compose` or `docker-compose`, curl, jq and python3. On a
# machine whose Docker reaches no registry, run tests/compose/offline_images.sh first.
# DIEPLAN_PORT picks the host port (a free one by default).
set -euo pipefail
cd "$(dirname "$0")/../.."

profiles=("$@")
[ ${#profiles[@]} -gt 0 ] || profiles=(sqlite postgres)
for tool in docker curl jq python3; do
  command -v "$tool" >/dev/null || { echo "smoke: $tool is required" >&2; exit 1; }
done
if docker compose version >/dev/null 2>&1; then
  compose_cmd=(docker compose)
elif command -v docker-compose >/dev/null; then
  compose_cmd=(docker-compose)
else
  echo "smoke: docker compose (or docker-compose) is required" >&2
  exit 1
fi

secret() { python3 -c "import secrets; print(secrets.token_hex($1))"; }
DIEPLAN_ADMIN_KEY=$(secret 32)
POSTGRES_PASSWORD=$(secret 16)
DIEPLAN_PORT=${DIEPLAN_PORT:-$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')}
# Every request logged (tower_http at debug), to see which replica served it.
DIEPLAN_LOG='info,tower_http=debug'
DIEPLAN="http://127.0.0.1:$DIEPLAN_PORT"
export DIEPLAN_ADMIN_KEY POSTGRES_PASSWORD DIEPLAN_PORT DIEPLAN_LOG DIEPLAN

PROJECT=dieplan-smoke
TMP=$(mktemp -d)
compose() { "${compose_cmd[@]}" -p "$PROJECT" -f docker/compose.yaml "$@"; }
down() { compose --profile sqlite --profile postgres down -v --remove-orphans >/dev/null 2>&1 || true; }
trap 'down; rm -rf "$TMP"' EXIT

# The examples are written for a service without keys; compose's service has its admin
# key, which every curl that names no key of its own sends.
cat >"$TMP/examples.sh" <<'SH'
curl() {
  local arg
  for arg in "$@"; do
    case "${arg,,}" in authorization:*) command curl "$@"; return ;; esac
  done
  command curl -H "Authorization: Bearer $DIEPLAN_ADMIN_KEY" "$@"
}
SH
awk -v out="$TMP/examples.sh" -f tests/readme_examples.awk README.md
COUNT=$(grep -c '^echo "--- example' "$TMP/examples.sh" || true)

fail() { # message, profile
  echo "smoke ($2): $1"
  compose --profile "$2" ps || true
  compose --profile "$2" logs --no-color --tail 40 || true
  exit 1
}

check() { # profile, description, jq filter, path, method, body
  local got
  got=$(command curl -sS -X "$5" "$DIEPLAN$4" -H "authorization: Bearer $DIEPLAN_ADMIN_KEY" \
    -H 'content-type: application/json' -H 'Prefer: wait=60' ${6:+-d "$6"})
  echo "$got" | jq -e "$3" >/dev/null || fail "check failed: $2: $got" "$1"
  echo "ok ($1): $2"
}

for profile in "${profiles[@]}"; do
  echo "=== profile $profile on $DIEPLAN"
  down
  started=$(date +%s)
  compose --profile "$profile" up -d --build >"$TMP/up-$profile.log" 2>&1 \
    || { cat "$TMP/up-$profile.log"; fail "compose up failed" "$profile"; }
  echo "up in $(( $(date +%s) - started )) s (with the image build, if any)"
  for _ in $(seq 1 180); do
    command curl -fsS "$DIEPLAN/readyz" >/dev/null 2>&1 && break
    sleep 1
  done
  command curl -fsS "$DIEPLAN/readyz" >/dev/null || fail "the service did not become ready" "$profile"

  if ! bash -euo pipefail "$TMP/examples.sh" >"$TMP/examples-$profile.out" 2>&1; then
    cat "$TMP/examples-$profile.out"
    fail "a README example failed (see the last '--- example' above)" "$profile"
  fi
  echo "ok ($profile): all $COUNT README examples"
  check "$profile" "10 mm standard conditions give F 5760 and beta0 = 269.1 N" \
    '((.result.conditions.feed_mm_min - 5760) | fabs) < 1e-6 and ((.result.force.fxy_n - 269.1) | fabs) < 1e-3' \
    /v1/conditions POST '{"tool_type": "square", "diameter_mm": 10}'
  check "$profile" "18 seeded tools" '.total == 18' "/v1/tools?limit=1" GET ""
  code=$(command curl -sS -o /dev/null -w '%{http_code}' "$DIEPLAN/v1/tools?limit=1")
  [ "$code" = 401 ] || fail "expected 401 without a key, got $code" "$profile"
  echo "ok ($profile): without a key the service answers 401"

  if [ "$profile" = postgres ]; then
    for replica in replica-1 replica-2; do
      served=$(compose logs --no-color "$replica" | grep -c 'finished processing request' || true)
      [ "$served" -gt 0 ] || fail "$replica served no request" "$profile"
      echo "ok ($profile): $replica served $served requests"
    done
    # A key's rate limit holds across the replicas: 4 requests a minute in all, not 4 each.
    limited=$(command curl -sS -X POST "$DIEPLAN/v1/keys" -H "authorization: Bearer $DIEPLAN_ADMIN_KEY" \
      -H 'content-type: application/json' -d '{"role": "reader", "name": "smoke", "rate_limit_per_minute": 4}' | jq -r .key)
    codes=$(for _ in 1 2 3 4 5 6; do
      command curl -sS -o /dev/null -w '%{http_code} ' "$DIEPLAN/v1/materials?limit=1" -H "authorization: Bearer $limited"
    done)
    [ "$codes" = "200 200 200 200 429 429 " ] || fail "a key of 4 requests a minute got: $codes" "$profile"
    echo "ok ($profile): a key of 4 requests a minute gets 4 through both replicas, then 429"
    # One replica gone: the other serves everything, through the same proxy.
    compose kill replica-1 >/dev/null 2>&1
    check "$profile" "with replica-1 killed, replica-2 answers through nginx" \
      '.status == "succeeded" and ((.result.conditions.feed_mm_min - 5760) | fabs) < 1e-6' \
      /v1/conditions POST '{"tool_type": "square", "diameter_mm": 10}'
  fi
  down
done
echo "smoke: ${profiles[*]} passed"
