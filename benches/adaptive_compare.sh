#!/usr/bin/env bash
# dieplan's trochoid plans against FreeCAD's Adaptive clearing (libarea's Adaptive2d), both
# judged by dieplan's simulator (see benches/adaptive_compare.rs and BENCHMARKS.md).
#
#   bash benches/adaptive_compare.sh [OUT_DIR [POCKET]]
#
# Installs Debian's `freecad` with apt-get when Python cannot import its `area` module (as
# root, or with sudo), writes the Adaptive programs of every pocket of
# benches/adaptive/pockets.json at the step-overs in ADAPTIVE_STEPOVERS (percent of the tool
# diameter; FreeCAD's default is 20), then runs the judging bench. OUT_DIR (default
# target/adaptive) receives every program, dieplan's too.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
out="${1:-$root/target/adaptive}"
pocket="${2:-}"
stepovers="${ADAPTIVE_STEPOVERS:-20 12 8 6 4 3}"

has_area() {
    python3 - <<'EOF' 2>/dev/null
import os, sys
for lib in ("/usr/lib/freecad-python3/lib", "/usr/lib/freecad/lib"):
    if os.path.isdir(lib):
        sys.path.insert(0, lib)
import area
area.Adaptive2d()
EOF
}

if ! has_area; then
    echo "FreeCAD's libarea (Python module area) is missing: installing Debian's freecad" >&2
    as_root=()
    if [ "$(id -u)" != 0 ]; then
        command -v sudo >/dev/null || { echo "need root or sudo to install freecad" >&2; exit 1; }
        as_root=(sudo)
    fi
    "${as_root[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends freecad >/dev/null
    has_area || { echo "freecad installed, but python3 cannot import area" >&2; exit 1; }
fi

mkdir -p "$out"
# shellcheck disable=SC2086
python3 "$here/adaptive/adaptive_gcode.py" "$here/adaptive/pockets.json" "$out" $stepovers | grep -v '^\*\*\|^Tool Diameter\|^Accuracy\|^All cleared'
cd "$root"
cargo bench --bench adaptive_compare -- "$out" ${pocket:+"$pocket"}
