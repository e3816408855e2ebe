-- PostgreSQL only (SQLite has no 0015): the rate limits of the API keys, shared by every
-- replica (issue 31). One replica (SQLite is always one) keeps its keys' buckets in memory;
-- several replicas on one PostgreSQL must count a key's requests together, or N replicas
-- would allow N times its limit. So each key has one row here, updated atomically by every
-- request it makes (src/service/rate_limit.rs): the state of the same token bucket (GCRA:
-- a minute's requests at once, then one every 60 s / limit) that one replica keeps in memory.
--   tat_us   the bucket's theoretical arrival time (microseconds since 1970, by the
--            database's clock, so that the replicas' clocks do not matter): a request at
--            time t passes when tat_us + 60 s / limit - 60 s <= t
--   allowed  whether the key's last request passed (read back by the statement that counts it)
CREATE TABLE rate_limit_buckets (
    key_id   BIGINT  PRIMARY KEY REFERENCES api_keys (id) ON DELETE CASCADE,
    tat_us   BIGINT  NOT NULL,
    allowed  BOOLEAN NOT NULL
);
