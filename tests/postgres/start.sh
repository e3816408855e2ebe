#!/usr/bin/env bash
# Starts a throwaway PostgreSQL for the tests and benchmarks, and prints its URL
# (postgres://dieplan@127.0.0.1:PORT) on the last line of standard output.
#
#   tests/postgres/start.sh DIR PORT [WATCH_PID]
#
# DIR      an empty directory for the cluster (data, log), removed when the server stops
# PORT     the TCP port to listen on, on 127.0.0.1 only (no Unix socket)
# WATCH_PID  when given, the server is stopped (and DIR removed) once that process exits
#
# Debian's `postgresql` package is installed with apt-get when initdb is missing (as root,
# or with sudo). PostgreSQL refuses to run as root: as root, the cluster belongs to the
# `postgres` user the package creates and runs as it (runuser); otherwise as the caller.
# The only role is `dieplan`, trusted on 127.0.0.1: for tests, never for production.
set -euo pipefail
dir=${1:?usage: start.sh DIR PORT [WATCH_PID]}
port=${2:?usage: start.sh DIR PORT [WATCH_PID]}
watch=${3:-}

find_bin() {
    local b
    for b in /usr/lib/postgresql/*/bin; do
        [[ -x $b/initdb && -x $b/pg_ctl ]] && { echo "$b"; return 0; }
    done
    command -v initdb >/dev/null 2>&1 && command -v pg_ctl >/dev/null 2>&1 && { dirname "$(command -v initdb)"; return 0; }
    return 1
}

if ! bin=$(find_bin); then
    echo "PostgreSQL is missing: installing Debian's postgresql package" >&2
    sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get update -qq >&2 || true
    $sudo apt-get install -y -qq --no-install-recommends postgresql >&2
    bin=$(find_bin) || { echo "initdb and pg_ctl not found after installing postgresql" >&2; exit 1; }
fi

as_owner=()
if [[ $(id -u) -eq 0 ]]; then
    id postgres >/dev/null 2>&1 || useradd --system --home-dir /var/lib/postgresql --shell /bin/bash postgres
    chmod 0755 "$dir"
    as_owner=(runuser -u postgres --)
fi
mkdir -p "$dir/data"
[[ $(id -u) -eq 0 ]] && chown postgres "$dir/data" && touch "$dir/postgres.log" && chown postgres "$dir/postgres.log"

"${as_owner[@]}" "$bin/initdb" -D "$dir/data" -U dieplan --auth=trust --encoding=UTF8 --locale=C.UTF-8 >"$dir/initdb.log" 2>&1 \
    || { cat "$dir/initdb.log" >&2; exit 1; }
# fsync off: a test cluster thrown away after the run needs no durability, and saves the
# disk of a machine shared with builds.
"${as_owner[@]}" "$bin/pg_ctl" -D "$dir/data" -l "$dir/postgres.log" -w -t 60 \
    -o "-p $port -c listen_addresses=127.0.0.1 -c unix_socket_directories= -c fsync=off -c synchronous_commit=off -c full_page_writes=off -c max_connections=200" \
    start >/dev/null || { cat "$dir/postgres.log" >&2; exit 1; }

if [[ -n $watch ]]; then
    # Stops the server once the process that started it has exited (a test binary that
    # cannot run code at exit), then removes the cluster.
    setsid bash -c "while kill -0 $watch 2>/dev/null; do sleep 1; done
        ${as_owner[*]} '$bin/pg_ctl' -D '$dir/data' -m immediate stop
        rm -rf '$dir'" >/dev/null 2>&1 </dev/null &
fi
echo "postgres://dieplan@127.0.0.1:$port"
