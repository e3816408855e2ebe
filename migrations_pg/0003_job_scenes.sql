-- PostgreSQL's version of migrations/0003_job_scenes.sql: the same schema and seed in PostgreSQL's
-- dialect (src/service/store.rs says how the two sets agree). Append-only, like migrations/.
-- What a finished job leaves to be drawn (core::drawing::scene::Scene as JSON), apart from
-- the jobs table so that listing and polling jobs never read it.
CREATE TABLE job_scenes (
    job_id  TEXT PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
    scene   BYTEA NOT NULL
);
