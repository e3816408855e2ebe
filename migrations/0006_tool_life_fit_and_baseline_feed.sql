-- no-transaction
-- Tool life recalibrated (MODEL.md §9 as corrected), the baseline's inferred feed (MODEL.md §5),
-- the source `inferred`, and the baseline's NC program kept with its plan job.
--
-- 1. `inferred` joins the sources a row may carry (a value inferred from other figures of the
--    papers where a printed value contradicts them). SQLite cannot change a CHECK constraint in
--    place, so every table with a `source` column is rebuilt with the same columns, rows and
--    indexes (https://sqlite.org/lang_altertable.html, "Making Other Kinds Of Table Schema
--    Changes"): with foreign keys off, outside sqlx's transaction, in one transaction of its own.
-- 2. Tool life: gamma(alpha) and k are fitted to MODEL.md §9's table (seed 003, read in
--    tool-centre path terms: straight 320 m; concave R/r = 2 at F4320 15 m and at constant force
--    55 m; wave paths (A)/(B) constant force over F4320 x 5 / x 2) by
--    src/core/costing/calibration.rs: gamma 1 up to the standard engagement (25.84 deg at
--    Rd = 0.05 D), 2.2 at 40 deg, then seed 002 §2.4's steep shape (x2, x4, x8, x12 of the value
--    at 40 deg at 50, 60, 90, 180 deg); k = 2.5. The 10 mm square end mill's row, whose life
--    seed 003 measured, becomes `fitted`; the other flat tools take the same gamma and k (their
--    life and the carry-over stay assumed); the balls take the same table moved to the
--    engagement of their standard cut (78.46 deg), as 0004 moved the assumed one.
-- 3. The baseline's feed: seed 004 Table 3 prints fz 0.05 for the R5 ball's conventional
--    roughing, but Table 4's 153.9 m in 42'47" is 3597 mm/min, fz 0.375 at 4800 min^-1 with
--    2 flutes; the R5 row takes the inferred fz (`inferred`), the other balls' rows, scaled from
--    it, follow.
-- 4. job_programs: NC programs a job writes beside its main one (a plan's baseline), apart from
--    the jobs table like job_scenes.
-- Only unedited seeded rows are updated (WHERE seed_key = ... AND edited = 0).
PRAGMA foreign_keys = OFF;
BEGIN;

-- 1. The source 'inferred': every table with a source column, rebuilt.
CREATE TABLE materials_rebuilt (
    id            INTEGER PRIMARY KEY,
    name          TEXT    NOT NULL UNIQUE,
    designation   TEXT    NOT NULL DEFAULT '',
    hardness_hrc  REAL,
    description   TEXT    NOT NULL DEFAULT '',
    source        TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference     TEXT    NOT NULL DEFAULT '',
    seed_key      TEXT    UNIQUE,
    edited        INTEGER NOT NULL DEFAULT 0,
    created_at    TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at    TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
INSERT INTO materials_rebuilt (id, name, designation, hardness_hrc, description, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, name, designation, hardness_hrc, description, source, reference, seed_key, edited, created_at, updated_at FROM materials;
DROP TABLE materials;
ALTER TABLE materials_rebuilt RENAME TO materials;

CREATE TABLE tools_rebuilt (
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
    source            TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference         TEXT    NOT NULL DEFAULT '',
    seed_key          TEXT    UNIQUE,
    edited            INTEGER NOT NULL DEFAULT 0,
    created_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
INSERT INTO tools_rebuilt (id, name, tool_type, diameter_mm, flutes, corner_radius_mm, flute_length_mm, coating, substrate, price, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, name, tool_type, diameter_mm, flutes, corner_radius_mm, flute_length_mm, coating, substrate, price, source, reference, seed_key, edited, created_at, updated_at FROM tools;
DROP TABLE tools;
ALTER TABLE tools_rebuilt RENAME TO tools;
CREATE INDEX tools_by_type_diameter ON tools (tool_type, diameter_mm);

CREATE TABLE standard_conditions_rebuilt (
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
    source            TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference         TEXT    NOT NULL DEFAULT '',
    seed_key          TEXT    UNIQUE,
    edited            INTEGER NOT NULL DEFAULT 0,
    created_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at        TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    UNIQUE (tool_id, material_id, operation)
);
INSERT INTO standard_conditions_rebuilt (id, tool_id, material_id, operation, spindle_rpm, fz_mm, fz_min_mm, fz_max_mm, rd_mm, ad_mm, ad_last_layer_mm, notes, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, tool_id, material_id, operation, spindle_rpm, fz_mm, fz_min_mm, fz_max_mm, rd_mm, ad_mm, ad_last_layer_mm, notes, source, reference, seed_key, edited, created_at, updated_at FROM standard_conditions;
DROP TABLE standard_conditions;
ALTER TABLE standard_conditions_rebuilt RENAME TO standard_conditions;

CREATE TABLE force_models_rebuilt (
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
    source       TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference    TEXT    NOT NULL DEFAULT '',
    seed_key     TEXT    UNIQUE,
    edited       INTEGER NOT NULL DEFAULT 0,
    created_at   TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at   TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
INSERT INTO force_models_rebuilt (id, tool_id, material_id, t0_um, dt_um, l0_mm, dl_mm, b0, b1, b2, b11, b22, b12, r_squared, ad_ref_mm, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, tool_id, material_id, t0_um, dt_um, l0_mm, dl_mm, b0, b1, b2, b11, b22, b12, r_squared, ad_ref_mm, source, reference, seed_key, edited, created_at, updated_at FROM force_models;
DROP TABLE force_models;
ALTER TABLE force_models_rebuilt RENAME TO force_models;
CREATE INDEX force_models_by_tool ON force_models (tool_id, material_id);

CREATE TABLE tool_life_rebuilt (
    id                    INTEGER PRIMARY KEY,
    tool_id               INTEGER NOT NULL REFERENCES tools (id) ON DELETE RESTRICT,
    material_id           INTEGER NOT NULL REFERENCES materials (id) ON DELETE RESTRICT,
    life_m                REAL    NOT NULL CHECK (life_m > 0),
    gamma_table           TEXT    NOT NULL,
    force_exponent        REAL    NOT NULL CHECK (force_exponent >= 0),
    source                TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference             TEXT    NOT NULL DEFAULT '',
    seed_key              TEXT    UNIQUE,
    edited                INTEGER NOT NULL DEFAULT 0,
    created_at            TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at            TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    UNIQUE (tool_id, material_id)
);
INSERT INTO tool_life_rebuilt (id, tool_id, material_id, life_m, gamma_table, force_exponent, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, tool_id, material_id, life_m, gamma_table, force_exponent, source, reference, seed_key, edited, created_at, updated_at FROM tool_life;
DROP TABLE tool_life;
ALTER TABLE tool_life_rebuilt RENAME TO tool_life;

CREATE TABLE machines_rebuilt (
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
    source             TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference          TEXT    NOT NULL DEFAULT '',
    seed_key           TEXT    UNIQUE,
    edited             INTEGER NOT NULL DEFAULT 0,
    created_at         TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at         TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    coolant            TEXT    NOT NULL DEFAULT 'off' CHECK (coolant IN ('off', 'mist', 'flood'))
);
INSERT INTO machines_rebuilt (id, name, rapid_mm_min, max_feed_mm_min, max_spindle_rpm, accel_x_mm_s2, accel_y_mm_s2, accel_z_mm_s2, jerk_x_mm_s3, jerk_y_mm_s3, jerk_z_mm_s3, tool_change_s, source, reference, seed_key, edited, created_at, updated_at, coolant)
  SELECT id, name, rapid_mm_min, max_feed_mm_min, max_spindle_rpm, accel_x_mm_s2, accel_y_mm_s2, accel_z_mm_s2, jerk_x_mm_s3, jerk_y_mm_s3, jerk_z_mm_s3, tool_change_s, source, reference, seed_key, edited, created_at, updated_at, coolant FROM machines;
DROP TABLE machines;
ALTER TABLE machines_rebuilt RENAME TO machines;

CREATE TABLE cost_rates_rebuilt (
    id                      INTEGER PRIMARY KEY,
    name                    TEXT    NOT NULL UNIQUE,
    currency                TEXT    NOT NULL,
    machine_rate_per_hour   REAL    NOT NULL CHECK (machine_rate_per_hour >= 0),
    default_tool_price      REAL    NOT NULL CHECK (default_tool_price >= 0),
    source                  TEXT    NOT NULL CHECK (source IN ('paper', 'extrapolated', 'assumed', 'inferred', 'fitted', 'user')),
    reference               TEXT    NOT NULL DEFAULT '',
    seed_key                TEXT    UNIQUE,
    edited                  INTEGER NOT NULL DEFAULT 0,
    created_at              TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at              TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
INSERT INTO cost_rates_rebuilt (id, name, currency, machine_rate_per_hour, default_tool_price, source, reference, seed_key, edited, created_at, updated_at)
  SELECT id, name, currency, machine_rate_per_hour, default_tool_price, source, reference, seed_key, edited, created_at, updated_at FROM cost_rates;
DROP TABLE cost_rates;
ALTER TABLE cost_rates_rebuilt RENAME TO cost_rates;

-- 2. Tool life: gamma and k fitted to MODEL.md §9's table.
UPDATE tool_life
SET gamma_table = '[[0, 1], [25.842, 1], [40, 2.03], [50, 4.06], [60, 8.12], [90, 16.24], [180, 24.36]]',
    force_exponent = 2.61,
    source = 'fitted',
    reference = 'life 320 m of machined length at the standard straight conditions: seed 003; gamma(alpha) and k = 2.61 fitted to MODEL.md §9''s calibration table (seed 003 in tool-centre path terms: straight 320 m, concave R/r = 2 at F4320 15 m and at constant force 55 m, wave paths (A)/(B) life x 5 / x 2 at constant force; src/core/costing/calibration.rs): gamma 1 up to the standard engagement 25.84 deg, 2.03 at 40 deg, then seed 002 §2.4''s steep shape',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE seed_key = 'tool_life:square-10:skd61' AND edited = 0;

UPDATE tool_life
SET gamma_table = '[[0, 1], [25.842, 1], [40, 2.03], [50, 4.06], [60, 8.12], [90, 16.24], [180, 24.36]]',
    force_exponent = 2.61,
    reference = 'life 320 m assumed as the 10 mm tool of seed 003 until measured; gamma(alpha) and k = 2.61 as fitted on the 10 mm square end mill to MODEL.md §9''s calibration table (src/core/costing/calibration.rs), carried over: gamma 1 up to the standard engagement 25.84 deg (Rd = 0.05 D), 2.03 at 40 deg, then seed 002 §2.4''s steep shape (assumed for this tool)',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE seed_key IN ('tool_life:square-6:skd61', 'tool_life:square-8:skd61', 'tool_life:square-12:skd61',
                   'tool_life:square-13:skd61', 'tool_life:square-16:skd61',
                   'tool_life:radius-6:skd61', 'tool_life:radius-8:skd61', 'tool_life:radius-10:skd61',
                   'tool_life:radius-12:skd61', 'tool_life:radius-13:skd61', 'tool_life:radius-16:skd61')
  AND edited = 0;

UPDATE tool_life
SET gamma_table = '[[0, 1], [78.464, 1], [92.621, 2.03], [102.621, 4.06], [112.621, 8.12], [142.621, 16.24], [180, 19.612]]',
    force_exponent = 2.61,
    reference = 'life 320 m of machined length at the ball''s standard side cut (standard_side_cutting), assumed as the 10 mm straight end mill of seed 003 until measured (seed 004 Fig. 12: the R5 ball showed V_b 0.1 mm and a small chipping after the 153.9 m of case study I); gamma: the flat end mills'' fitted table (MODEL.md §9, src/core/costing/calibration.rs) moved from their standard engagement 25.84 deg to the ball''s in the 2.5-D model, 78.46 deg (Rd = 0.4 D), and cut at 180 deg, as 0004 moved the assumed one; k = 2.61 as fitted; assumed for this tool',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE seed_key IN ('tool_life:ball-6:skd61', 'tool_life:ball-8:skd61', 'tool_life:ball-10:skd61',
                   'tool_life:ball-12:skd61', 'tool_life:ball-13:skd61', 'tool_life:ball-16:skd61')
  AND edited = 0;

-- 3. The baseline's feed (MODEL.md §5).
UPDATE standard_conditions
SET fz_mm = 0.375, fz_min_mm = 0.01875, source = 'inferred',
    reference = 'S 4800, Rd 3.5, Ad 0.6: seed 004 Table 3; fz 0.375 inferred from seed 004 Table 4 (153.9 m cut in 42''47" = 3597 mm/min = fz 0.375 at 4800 min^-1 with 2 flutes), since Table 3''s fz 0.05 (480 mm/min) would take 320 min for that length: an OCR or print error (MODEL.md §5); fz_min = 0.05 fz assumed',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE seed_key = 'conditions:ball-10:skd61:conventional_ball_roughing' AND edited = 0;

WITH v (d, fz_mm) AS (VALUES (6, 0.225), (8, 0.3), (12, 0.45), (13, 0.4875), (16, 0.6))
UPDATE standard_conditions
SET fz_mm = v.fz_mm, fz_min_mm = 0.05 * v.fz_mm,
    reference = 'scaled from the R5 ball row (seed 004 Table 3, its fz 0.375 inferred from Table 4, MODEL.md §5) at equal cutting speed: S x 10/D, fz, Rd, Ad x D/10; fz_min = 0.05 fz',
    updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
FROM v
WHERE standard_conditions.seed_key = 'conditions:ball-' || v.d || ':skd61:conventional_ball_roughing'
  AND standard_conditions.edited = 0;

-- 4. Programs a job writes beside its main one.
CREATE TABLE job_programs (
    job_id   TEXT NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    part     TEXT NOT NULL,
    program  TEXT NOT NULL,
    PRIMARY KEY (job_id, part)
);

COMMIT;
PRAGMA foreign_keys = ON;
