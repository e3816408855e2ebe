# Sourced by the test scripts that drive the release binary (tests/curl_examples.sh,
# tests/browser/run.sh): starts `dieplan serve` on a free port with a temporary database
# and waits until it is ready. Sets BIN, TMP (removed at exit), PID, and DIEPLAN (the base
# URL); the service is stopped at exit. Run from the repository's root.
#
# Without DIEPLAN_BIN it builds the release binary first.

BIN=${DIEPLAN_BIN:-}
if [ -z "$BIN" ]; then
  cargo build --release
  BIN=target/release/dieplan
fi

TMP=$(mktemp -d)
PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$BIN" serve --addr "127.0.0.1:$PORT" --database "$TMP/dieplan.sqlite" --workers 2 >"$TMP/server.log" 2>&1 &
PID=$!
cleanup() {
  kill "$PID" 2>/dev/null || true
  wait "$PID" 2>/dev/null || true
  rm -rf "$TMP"
}
trap cleanup EXIT

export DIEPLAN="http://127.0.0.1:$PORT"
for _ in $(seq 1 100); do
  curl -fsS "$DIEPLAN/healthz" >/dev/null 2>&1 && break
  sleep 0.1
done
curl -fsS "$DIEPLAN/readyz" >/dev/null || { echo "service did not become ready"; cat "$TMP/server.log"; exit 1; }
