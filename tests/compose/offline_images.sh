#!/usr/bin/env bash
# Builds local stand-ins for the four public images docker/ uses, for a machine whose
# Docker cannot reach a container registry but can reach Debian's mirror and crates.io
# (the development VM of issue 31 is one). Each stand-in is made from Debian bookworm's
# own packages and tagged with the public image's name, so that docker/Dockerfile and
# docker/compose.yaml run unchanged:
#
#   debian:bookworm-slim   debootstrap --variant=minbase bookworm, imported
#   rust:1.95-bookworm     that + gcc and libc6-dev, this machine's Rust 1.95 and its
#                          cargo cache (the crates of Cargo.lock), cargo offline
#   postgres:16-bookworm   that + Debian's postgresql (15), with an entry point that
#                          honours POSTGRES_USER, POSTGRES_PASSWORD and POSTGRES_DB on a
#                          fresh /var/lib/postgresql/data as the official image does
#   nginx:1.27-bookworm    that + Debian's nginx-light (1.22), in the foreground
#
# An image that already exists under its tag (pulled, or made by an earlier run) is kept.
# Needs root (debootstrap), docker, and the `debootstrap` package (installed when missing).
#
#   bash tests/compose/offline_images.sh
set -euo pipefail
DOCKER=${DOCKER:-docker}
MIRROR=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
RUST_VERSION=1.95.0

have() { "$DOCKER" image inspect "$1" >/dev/null 2>&1; }
build() { # tag, Dockerfile text on stdin
  local tag=$1 dir
  have "$tag" && { echo "kept $tag"; return; }
  dir=$(mktemp -d)
  cat >"$dir/Dockerfile"
  "$DOCKER" build -q -t "$tag" "$dir"
  rm -rf "$dir"
  echo "built $tag"
}

if ! have debian:bookworm-slim; then
  command -v debootstrap >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap
  root=$(mktemp -d)
  debootstrap --variant=minbase bookworm "$root" "$MIRROR" >/dev/null
  rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
  tar -C "$root" -c . | "$DOCKER" import -c 'CMD ["bash"]' \
    -c 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' - debian:bookworm-slim >/dev/null
  rm -rf "$root"
  echo "imported debian:bookworm-slim"
fi

# The toolchain and the crates come from this machine (the containers may not trust the
# proxy through which it reaches static.rust-lang.org and crates.io): its Rust, which must
# be 1.95, and its cargo cache, with cargo offline in the image.
if ! have rust:1.95-bookworm; then
  sysroot=$(rustc --print sysroot)
  rustc --version | grep -q "^rustc $RUST_VERSION " || { echo "this machine's rustc is not $RUST_VERSION" >&2; exit 1; }
  ctx=$(mktemp -d)
  mkdir -p "$ctx/rust" "$ctx/cargo/registry"
  cp -a "$sysroot/bin" "$sysroot/lib" "$ctx/rust/"
  cp -a "${CARGO_HOME:-$HOME/.cargo}/registry/cache" "${CARGO_HOME:-$HOME/.cargo}/registry/index" "$ctx/cargo/registry/"
  cat >"$ctx/Dockerfile" <<'DOCKERFILE'
FROM debian:bookworm-slim
RUN apt-get update && apt-get install -y --no-install-recommends ca-certificates gcc libc6-dev make pkg-config \
 && rm -rf /var/lib/apt/lists/*
COPY rust /usr/local/rust
COPY cargo /usr/local/cargo
ENV CARGO_HOME=/usr/local/cargo PATH=/usr/local/rust/bin:/usr/local/cargo/bin:$PATH CARGO_NET_OFFLINE=true
RUN chmod -R a+w /usr/local/cargo && cargo --version && rustc --version
DOCKERFILE
  "$DOCKER" build -q -t rust:1.95-bookworm "$ctx"
  rm -rf "$ctx"
  echo "built rust:1.95-bookworm"
fi

build nginx:1.27-bookworm <<'DOCKERFILE'
FROM debian:bookworm-slim
RUN apt-get update && apt-get install -y --no-install-recommends nginx-light && rm -rf /var/lib/apt/lists/*
STOPSIGNAL SIGQUIT
CMD ["nginx", "-g", "daemon off;"]
DOCKERFILE

build postgres:16-bookworm <<'DOCKERFILE'
FROM debian:bookworm-slim
RUN apt-get update && apt-get install -y --no-install-recommends postgresql && rm -rf /var/lib/apt/lists/* \
 && mkdir -p /var/lib/postgresql/data /var/run/postgresql && chown -R postgres /var/lib/postgresql /var/run/postgresql
RUN printf '%s\n' '#!/bin/bash' 'set -euo pipefail' \
  'bin=$(ls -d /usr/lib/postgresql/*/bin | tail -n 1)' \
  'export PGDATA=${PGDATA:-/var/lib/postgresql/data}' \
  'if [ "$(id -u)" = 0 ]; then chown -R postgres "$PGDATA" /var/run/postgresql; exec runuser -u postgres -- "$0" "$@"; fi' \
  'if [ ! -s "$PGDATA/PG_VERSION" ]; then' \
  '  pw=$(mktemp); printf "%s" "${POSTGRES_PASSWORD:?}" >"$pw"' \
  '  "$bin/initdb" -D "$PGDATA" -U "${POSTGRES_USER:-postgres}" --pwfile="$pw" --auth-local=trust --auth-host=scram-sha-256 >/dev/null' \
  '  rm -f "$pw"; echo "host all all all scram-sha-256" >>"$PGDATA/pg_hba.conf"' \
  '  "$bin/pg_ctl" -D "$PGDATA" -w -o "-c listen_addresses=" start >/dev/null' \
  '  db=${POSTGRES_DB:-${POSTGRES_USER:-postgres}}' \
  '  [ "$db" = postgres ] || "$bin/psql" -v ON_ERROR_STOP=1 -U "${POSTGRES_USER:-postgres}" -d postgres -c "CREATE DATABASE \"$db\"" >/dev/null' \
  '  "$bin/pg_ctl" -D "$PGDATA" -w stop >/dev/null' \
  'fi' \
  'exec "$bin/postgres" -D "$PGDATA" -c listen_addresses="*"' >/usr/local/bin/docker-entrypoint.sh \
 && chmod +x /usr/local/bin/docker-entrypoint.sh
ENV PATH=/usr/lib/postgresql/15/bin:$PATH
STOPSIGNAL SIGINT
EXPOSE 5432
ENTRYPOINT ["docker-entrypoint.sh"]
DOCKERFILE
