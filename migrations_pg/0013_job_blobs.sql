-- PostgreSQL's version of migrations/0013_job_blobs.sql; the blobs are bytea.
-- Jobs that scale with their count, not their size (issue 30, item 2). A job's input, its
-- prepared form and its result move out of the jobs row into job_blobs, and its main NC
-- program into job_programs (part 'main', beside a plan's 'baseline'); the row keeps what
-- lists and polls show, so listing or polling jobs never reads a blob.
--   job_blobs.part   input     the request as submitted (JSON, served by /v1/jobs/{id}/input)
--                    prepared  what the submission resolved from the database (JSON, for the worker)
--                    result    the result of a succeeded job (JSON, served inside the job as stored)
--   jobs.error_title the title of a failed job's problem
--   jobs.input_bytes, jobs.result_bytes  the sizes of the input and result, bytes
--   jobs.summary     a few headline figures of the result (JSON object, small)
CREATE TABLE job_blobs (
    job_id  TEXT  NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    part    TEXT  NOT NULL CHECK (part IN ('input', 'prepared', 'result')),
    body    BYTEA NOT NULL,
    PRIMARY KEY (job_id, part)
);

INSERT INTO job_blobs (job_id, part, body) SELECT id, 'input', convert_to(input, 'UTF8') FROM jobs;
INSERT INTO job_blobs (job_id, part, body) SELECT id, 'prepared', convert_to(prepared, 'UTF8') FROM jobs;
INSERT INTO job_blobs (job_id, part, body) SELECT id, 'result', convert_to(result, 'UTF8') FROM jobs WHERE result IS NOT NULL;
INSERT INTO job_programs (job_id, part, program) SELECT id, 'main', convert_to(program, 'UTF8') FROM jobs WHERE program IS NOT NULL
ON CONFLICT (job_id, part) DO UPDATE SET program = excluded.program;

ALTER TABLE jobs ADD COLUMN error_title TEXT;
ALTER TABLE jobs ADD COLUMN input_bytes BIGINT NOT NULL DEFAULT 0;
ALTER TABLE jobs ADD COLUMN result_bytes BIGINT;
ALTER TABLE jobs ADD COLUMN summary TEXT;
UPDATE jobs SET error_title = error::jsonb ->> 'title' WHERE error IS NOT NULL;
UPDATE jobs SET input_bytes = octet_length(input), result_bytes = octet_length(result);

ALTER TABLE jobs DROP COLUMN input;
ALTER TABLE jobs DROP COLUMN prepared;
ALTER TABLE jobs DROP COLUMN result;
ALTER TABLE jobs DROP COLUMN program;
