-- API keys with roles (issue 30). A key's secret is shown once, when it is made; only its
-- SHA-256 is kept. A deleted key is revoked, not removed, so the jobs it made still name it.
--   role     reader (GET), planner (reader + its own jobs), admin (everything)
--   origin   how it was made: api (POST /v1/keys), cli (dieplan keys create) or
--            environment (DIEPLAN_ADMIN_KEY, replaced when the variable changes)
--   prefix   the first characters of the secret, to recognise a key in lists
--   rate_limit_per_minute  requests a minute; NULL: the service's default; 0: unlimited
CREATE TABLE api_keys (
    id                     INTEGER PRIMARY KEY,
    name                   TEXT    NOT NULL,
    role                   TEXT    NOT NULL CHECK (role IN ('reader', 'planner', 'admin')),
    prefix                 TEXT    NOT NULL,
    secret_sha256          TEXT    NOT NULL UNIQUE,
    origin                 TEXT    NOT NULL CHECK (origin IN ('api', 'cli', 'environment')),
    rate_limit_per_minute  INTEGER CHECK (rate_limit_per_minute IS NULL OR rate_limit_per_minute >= 0),
    created_at             TEXT    NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    last_used_at           TEXT,
    revoked_at             TEXT
);
CREATE INDEX api_keys_active ON api_keys (revoked_at);

-- The key that created a job (NULL: made while the service ran without keys).
ALTER TABLE jobs ADD COLUMN key_id INTEGER REFERENCES api_keys (id);
CREATE INDEX jobs_by_key ON jobs (key_id, created_at);
