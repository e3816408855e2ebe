-- dieplan schema. Migrations are append-only: never edit a file once it has landed.
--
-- Every cutting-data row carries:
--   source    where its values come from: paper | extrapolated | assumed | fitted | user
--   reference the paper file and table, or how the value was derived
--   seed_key  a stable key for rows this project seeded (NULL for a shop's own rows)
--   edited    1 once a shop changed the row through the API.
-- A later migration that corrects seeded data must only touch
--   WHERE seed_key = '...' AND edited = 0
-- so that a shop's edits are never overwritten.

CREATE TABLE materials (
    id            INTEGER PRIMARY KEY,
    name          TEXT    NOT NULL UNIQUE,
    designation   TEXT    NOT NULL DEFAULT '',
    hardness_hrc  REAL,
    description   TEXT    NOT NULL DEFAULT '',
    source        TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference     TEXT    NOT NULL DEFAULT '',
    seed_key      TEXT    UNIQUE,
    edited        INTEGER NOT NULL DEFAULT 0,
    created_at    TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at    TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);

CREATE TABLE tools (
    id                INTEGER PRIMARY KEY,
    name              TEXT    NOT NULL UNIQUE,
    tool_type         TEXT    NOT NULL CHECK (tool_type IN ('square', 'radius', 'ball')),
    diameter_mm       REAL    NOT NULL CHECK (diameter_mm > 0),
    flutes            INTEGER NOT NULL CHECK (flutes > 0),
    corner_radius_mm  REAL    NOT NULL CHECK (corner_radius_mm >= 0),
    flute_length_mm   REAL,
    coating           TEXT    NOT NULL DEFAULT '',
    substrate         TEXT    NOT NULL DEFAULT '',
    price             REAL,
    source            TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference         TEXT    NOT NULL DEFAULT '',
    seed_key          TEXT    UNIQUE,
    edited            INTEGER NOT NULL DEFAULT 0,
    created_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX tools_by_type_diameter ON tools (tool_type, diameter_mm);

CREATE TABLE standard_conditions (
    id                INTEGER PRIMARY KEY,
    tool_id           INTEGER NOT NULL REFERENCES tools (id) ON DELETE RESTRICT,
    material_id       INTEGER NOT NULL REFERENCES materials (id) ON DELETE RESTRICT,
    operation         TEXT    NOT NULL,
    spindle_rpm       REAL    NOT NULL CHECK (spindle_rpm > 0),
    fz_mm             REAL    NOT NULL CHECK (fz_mm > 0),
    fz_min_mm         REAL    NOT NULL CHECK (fz_min_mm > 0),
    fz_max_mm         REAL,
    rd_mm             REAL    NOT NULL CHECK (rd_mm > 0),
    ad_mm             REAL    NOT NULL CHECK (ad_mm > 0),
    ad_last_layer_mm  REAL,
    notes             TEXT    NOT NULL DEFAULT '',
    source            TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference         TEXT    NOT NULL DEFAULT '',
    seed_key          TEXT    UNIQUE,
    edited            INTEGER NOT NULL DEFAULT 0,
    created_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    UNIQUE (tool_id, material_id, operation)
);

CREATE TABLE force_models (
    id           INTEGER PRIMARY KEY,
    tool_id      INTEGER NOT NULL REFERENCES tools (id) ON DELETE RESTRICT,
    material_id  INTEGER NOT NULL REFERENCES materials (id) ON DELETE RESTRICT,
    t0_um        REAL    NOT NULL CHECK (t0_um > 0),
    dt_um        REAL    NOT NULL CHECK (dt_um > 0),
    l0_mm        REAL    NOT NULL CHECK (l0_mm > 0),
    dl_mm        REAL    NOT NULL CHECK (dl_mm > 0),
    b0           REAL    NOT NULL,
    b1           REAL    NOT NULL,
    b2           REAL    NOT NULL,
    b11          REAL    NOT NULL,
    b22          REAL    NOT NULL,
    b12          REAL    NOT NULL,
    r_squared    REAL,
    ad_ref_mm    REAL    NOT NULL CHECK (ad_ref_mm > 0),
    source       TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference    TEXT    NOT NULL DEFAULT '',
    seed_key     TEXT    UNIQUE,
    edited       INTEGER NOT NULL DEFAULT 0,
    created_at   TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at   TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX force_models_by_tool ON force_models (tool_id, material_id);

CREATE TABLE tool_life (
    id                    INTEGER PRIMARY KEY,
    tool_id               INTEGER NOT NULL REFERENCES tools (id) ON DELETE RESTRICT,
    material_id           INTEGER NOT NULL REFERENCES materials (id) ON DELETE RESTRICT,
    life_m                REAL    NOT NULL CHECK (life_m > 0),
    gamma_table           TEXT    NOT NULL,
    force_exponent        REAL    NOT NULL CHECK (force_exponent >= 0),
    source                TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference             TEXT    NOT NULL DEFAULT '',
    seed_key              TEXT    UNIQUE,
    edited                INTEGER NOT NULL DEFAULT 0,
    created_at            TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at            TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    UNIQUE (tool_id, material_id)
);

CREATE TABLE machines (
    id                 INTEGER PRIMARY KEY,
    name               TEXT    NOT NULL UNIQUE,
    rapid_mm_min       REAL    NOT NULL CHECK (rapid_mm_min > 0),
    max_feed_mm_min    REAL    NOT NULL CHECK (max_feed_mm_min > 0),
    max_spindle_rpm    REAL    NOT NULL CHECK (max_spindle_rpm > 0),
    accel_x_mm_s2      REAL    NOT NULL CHECK (accel_x_mm_s2 > 0),
    accel_y_mm_s2      REAL    NOT NULL CHECK (accel_y_mm_s2 > 0),
    accel_z_mm_s2      REAL    NOT NULL CHECK (accel_z_mm_s2 > 0),
    jerk_x_mm_s3       REAL    NOT NULL CHECK (jerk_x_mm_s3 > 0),
    jerk_y_mm_s3       REAL    NOT NULL CHECK (jerk_y_mm_s3 > 0),
    jerk_z_mm_s3       REAL    NOT NULL CHECK (jerk_z_mm_s3 > 0),
    tool_change_s      REAL    NOT NULL CHECK (tool_change_s >= 0),
    source             TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference          TEXT    NOT NULL DEFAULT '',
    seed_key           TEXT    UNIQUE,
    edited             INTEGER NOT NULL DEFAULT 0,
    created_at         TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at         TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);

CREATE TABLE cost_rates (
    id                      INTEGER PRIMARY KEY,
    name                    TEXT    NOT NULL UNIQUE,
    currency                TEXT    NOT NULL,
    machine_rate_per_hour   REAL    NOT NULL CHECK (machine_rate_per_hour >= 0),
    default_tool_price      REAL    NOT NULL CHECK (default_tool_price >= 0),
    source                  TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'fitted', 'user')),
    reference               TEXT    NOT NULL DEFAULT '',
    seed_key                TEXT    UNIQUE,
    edited                  INTEGER NOT NULL DEFAULT 0,
    created_at              TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at              TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);

CREATE TABLE jobs (
    id                TEXT    PRIMARY KEY,
    kind              TEXT    NOT NULL,
    status            TEXT    NOT NULL CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
    progress          REAL    NOT NULL DEFAULT 0,
    input             TEXT    NOT NULL,
    prepared          TEXT    NOT NULL,
    result            TEXT,
    error             TEXT,
    program           TEXT,
    attempts          INTEGER NOT NULL DEFAULT 0,
    cancel_requested  INTEGER NOT NULL DEFAULT 0,
    created_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    started_at        TEXT,
    finished_at       TEXT,
    updated_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX jobs_by_status ON jobs (status, created_at);
CREATE INDEX jobs_by_created ON jobs (created_at);
