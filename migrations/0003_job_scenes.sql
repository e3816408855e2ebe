-- What a finished job leaves to be drawn (core::drawing::scene::Scene as JSON), apart from
-- the jobs table so that listing and polling jobs never read it.
CREATE TABLE job_scenes (
    job_id  TEXT PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
    scene   TEXT NOT NULL
);
