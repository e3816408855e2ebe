#!/usr/bin/env bash
# Drives the web page in a real browser: starts the dieplan binary on a free port with a
# temporary database, runs page.test.mjs (playwright-core with Debian's chromium) against
# it, and stops the service. Screenshots land in target/browser-screenshots/.
#
#   DIEPLAN_BIN=target/release/dieplan bash tests/browser/run.sh
#
# Installs what is missing: chromium with apt-get (as root, or with sudo), and the npm
# packages of tests/browser (npm ci) when node_modules is missing or older than the lock.
# Without DIEPLAN_BIN it builds the release binary first. `cargo test --release` runs it
# through tests/api/browser.rs with the binary cargo just built.
set -euo pipefail
exec 2>&1 # one stream, in order, for tests/api/browser.rs
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
HERE="$ROOT/tests/browser"
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}

fail() { echo "browser test: $*" >&2; exit 1; }

for tool in node npm curl python3; do
  command -v "$tool" >/dev/null || fail "$tool is required (install Node.js 20 or newer, curl and python3)"
done
node -e 'process.exit(Number(process.versions.node.split(".")[0]) >= 20 ? 0 : 1)' \
  || fail "Node.js 20 or newer is required, found $(node --version)"

if [ ! -x "$CHROMIUM" ]; then
  echo "browser test: $CHROMIUM is missing; installing Debian's chromium"
  if [ "$(id -u)" = 0 ]; then
    SUDO=""
  elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
    SUDO="sudo -n"
  else
    fail "chromium is not installed and this user cannot install it: run 'apt-get install -y chromium' as root"
  fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y chromium >/dev/null \
    || { DEBIAN_FRONTEND=noninteractive $SUDO apt-get update >/dev/null && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y chromium >/dev/null; } \
    || fail "apt-get could not install chromium"
  [ -x "$CHROMIUM" ] || fail "chromium was installed but $CHROMIUM does not exist"
fi

STAMP="$HERE/node_modules/.package-lock.json"
if [ ! -d "$HERE/node_modules/playwright-core" ] || [ ! -f "$STAMP" ] || [ "$HERE/package-lock.json" -nt "$STAMP" ]; then
  echo "browser test: installing npm packages (npm ci)"
  (cd "$HERE" && npm ci --no-audit --no-fund --loglevel=error) || fail "npm ci failed in tests/browser"
fi

# shellcheck source=tests/serve.sh
source "$ROOT/tests/serve.sh"
BASE=$DIEPLAN

export SCREENSHOT_DIR=${SCREENSHOT_DIR:-$ROOT/target/browser-screenshots}
if ! CHROMIUM="$CHROMIUM" node "$HERE/page.test.mjs" "$BASE"; then
  echo "--- server log"; tail -n 40 "$TMP/server.log"
  exit 1
fi
