-- PostgreSQL's version of migrations/0011_job_lanes.sql: the same schema and seed in PostgreSQL's
-- dialect (src/service/store.rs says how the two sets agree). Append-only, like migrations/.
-- A fair queue (issue 30): short jobs run in their own lane, ahead of long ones, so a
-- conditions job is never starved behind plans.
--   interactive  conditions, and analysis, feeds and costing of a small input
--   batch        everything else (plans, trochoids, large programs)
ALTER TABLE jobs ADD COLUMN lane TEXT NOT NULL DEFAULT 'batch' CHECK (lane IN ('interactive', 'batch'));
UPDATE jobs SET lane = 'interactive' WHERE kind = 'conditions';
CREATE INDEX jobs_by_lane ON jobs (status, lane, created_at);
