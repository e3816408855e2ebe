-- PostgreSQL's version of migrations/0016_job_labels.sql: the same schema in PostgreSQL's
-- dialect (src/service/store.rs says how the two sets agree). Append-only, like migrations/.
-- A job's name and tags (issue 33), given on submit, shown in the job and in lists, and
-- searched by `GET /v1/jobs?name=…&tag=…`.
--   name      what the user called the job (1 to 200 characters), or null
--   name_key  the name folded to lower case by the service (Unicode's rules, the same on
--             every backend), which the case-insensitive name search matches against
--   tags      the tags in the order given, as a JSON array of strings (what the job shows)
-- job_tags holds one row per tag of a job, for the tag filter; removed with its job.
ALTER TABLE jobs ADD COLUMN name TEXT;
ALTER TABLE jobs ADD COLUMN name_key TEXT;
ALTER TABLE jobs ADD COLUMN tags TEXT NOT NULL DEFAULT '[]';
CREATE TABLE job_tags (
    job_id  TEXT  NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    tag     TEXT  NOT NULL,
    PRIMARY KEY (job_id, tag)
);
CREATE INDEX job_tags_by_tag ON job_tags (tag, job_id);
