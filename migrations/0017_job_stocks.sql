-- The stock a finished job's simulation left (issue 32 item 3), kept so that another job
-- can start from it (`"stock": {"from_job": "<id>"}`): one row per job that simulated a
-- program on a stock (analysis, costing), removed with its job.
--   format     the version of the encoding of body (src/service/jobs/kept_stock.rs says
--              what each holds); a stock whose format this version does not read is
--              refused with a 422, never read wrongly
--   raw_bytes  the size of the encoded stock before compression, bytes
--   body       the encoded stock, compressed (zlib): the grid, every slice's z range and
--              the index of its raster, and each distinct raster's cells once
CREATE TABLE job_stocks (
    job_id     TEXT    NOT NULL PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
    format     INTEGER NOT NULL,
    raw_bytes  INTEGER NOT NULL,
    body       BLOB    NOT NULL
);
