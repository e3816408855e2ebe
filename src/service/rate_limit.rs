//! Per-key rate limits: a token bucket (GCRA) per key, refilled at the key's requests a
//! minute, as deep as a minute's requests. On SQLite (one process) the buckets live in
//! memory (the `governor` crate); on PostgreSQL, where several replicas serve the same
//! keys, each key's bucket is a row of `rate_limit_buckets` that every replica updates
//! atomically, so that N replicas allow a key its limit, not N times it.

use crate::service::store::{Backend, Flag, Pool};
use governor::clock::{Clock, DefaultClock};
use governor::{DefaultDirectRateLimiter, Quota, RateLimiter};
use std::collections::HashMap;
use std::num::NonZeroU32;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The span a bucket holds: a minute's requests may come at once.
const BUCKET_SPAN: Duration = Duration::from_secs(60);

/// One request taken from a shared bucket (GCRA, as `governor` does it in memory): the
/// request passes when the bucket's theoretical arrival time, pushed on by one request's
/// interval, is no more than [`BUCKET_SPAN`] ahead of now; it then stores the pushed time.
/// A new key's bucket starts full. Times are the database's (`now()`, microseconds), so
/// that the replicas' clocks do not matter. Answers whether it passed and, when it did
/// not, how long until it would (microseconds).
///   $1 key id, $2 the interval of one request (µs), $3 the span (µs)
const TAKE_SHARED: &str = "
    INSERT INTO rate_limit_buckets (key_id, tat_us, allowed)
    VALUES ($1, (extract(epoch FROM now()) * 1000000)::bigint + $2, TRUE)
    ON CONFLICT (key_id) DO UPDATE SET
        allowed = greatest(rate_limit_buckets.tat_us + $2, EXCLUDED.tat_us) - $3 <= EXCLUDED.tat_us - $2,
        tat_us = CASE
            WHEN greatest(rate_limit_buckets.tat_us + $2, EXCLUDED.tat_us) - $3 <= EXCLUDED.tat_us - $2
            THEN greatest(rate_limit_buckets.tat_us + $2, EXCLUDED.tat_us)
            ELSE rate_limit_buckets.tat_us
        END
    RETURNING allowed, tat_us + $2 - $3 - (extract(epoch FROM now()) * 1000000)::bigint AS wait_us";

/// The buckets of the keys: in memory for the keys that made requests since the start
/// (SQLite), or in the database (PostgreSQL).
#[derive(Default)]
pub struct RateLimits {
    /// Each key's rate and bucket, in memory.
    buckets: Mutex<HashMap<i64, (NonZeroU32, Arc<DefaultDirectRateLimiter>)>>,
}

impl RateLimits {
    /// Takes one request from key `id`'s bucket of `per_minute` requests a minute (0:
    /// unlimited), kept where the backend of `pool` wants it; `Some` wait when the bucket
    /// is empty.
    pub async fn check(&self, pool: &Pool, id: i64, per_minute: i64) -> Result<Option<Duration>, sqlx::Error> {
        let Some(rate) = limited(per_minute) else {
            return Ok(None);
        };
        match Backend::of(pool) {
            Backend::Sqlite => Ok(self.check_in_memory(id, rate).err()),
            Backend::Postgres => check_shared(pool, id, rate).await,
        }
    }

    /// Takes one request from the bucket this process keeps for key `id`; `Err` with how
    /// long to wait when the bucket is empty. A key whose limit changed gets a new, full
    /// bucket.
    fn check_in_memory(&self, id: i64, rate: NonZeroU32) -> Result<(), Duration> {
        let bucket = {
            let mut buckets = self.buckets.lock().unwrap_or_else(|p| p.into_inner());
            let entry = buckets.entry(id).or_insert_with(|| (rate, Arc::new(bucket(rate))));
            if entry.0 != rate {
                *entry = (rate, Arc::new(bucket(rate)));
            }
            entry.1.clone()
        };
        bucket.check().map_err(|not_until| not_until.wait_time_from(DefaultClock::default().now()))
    }
}

/// A full in-memory bucket of `rate` requests a minute ([`BUCKET_SPAN`] deep).
fn bucket(rate: NonZeroU32) -> DefaultDirectRateLimiter {
    RateLimiter::direct(Quota::per_minute(rate))
}

/// The rate of a limit of `per_minute` requests a minute; none when it is unlimited (0).
fn limited(per_minute: i64) -> Option<NonZeroU32> {
    u32::try_from(per_minute).ok().and_then(NonZeroU32::new)
}

/// Microseconds of a duration, as the database stores them.
fn micros(duration: Duration) -> i64 {
    i64::try_from(duration.as_micros()).unwrap_or(i64::MAX)
}

/// Takes one request from key `id`'s row of `rate_limit_buckets` ([`TAKE_SHARED`]).
async fn check_shared(pool: &Pool, id: i64, rate: NonZeroU32) -> Result<Option<Duration>, sqlx::Error> {
    let (Flag(allowed), wait_us): (Flag, i64) = sqlx::query_as(TAKE_SHARED)
        .bind(id)
        .bind(micros(BUCKET_SPAN / rate.get()))
        .bind(micros(BUCKET_SPAN))
        .fetch_one(pool)
        .await?;
    Ok((!allowed).then(|| Duration::from_micros(u64::try_from(wait_us).unwrap_or(0))))
}

/// Whole seconds to put in `Retry-After` for a wait: rounded up, at least 1.
pub fn retry_after_s(wait: Duration) -> u64 {
    (wait.as_secs() + u64::from(wait.subsec_nanos() > 0)).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_gets_a_minutes_requests_at_once_then_waits() {
        let limits = RateLimits::default();
        let three = NonZeroU32::new(3).unwrap();
        for _ in 0..3 {
            assert!(limits.check_in_memory(7, three).is_ok());
        }
        let wait = limits.check_in_memory(7, three).expect_err("the fourth request is refused");
        assert!(wait > Duration::from_secs(15) && wait <= Duration::from_secs(20), "{wait:?}");
        assert!(limits.check_in_memory(8, three).is_ok(), "another key has its own bucket");
    }

    #[test]
    fn a_limit_of_zero_is_no_limit() {
        assert_eq!(limited(0), None);
        assert_eq!(limited(-1), None);
        assert_eq!(limited(3), NonZeroU32::new(3));
    }

    #[test]
    fn a_key_whose_limit_changed_gets_a_full_bucket_of_the_new_limit() {
        let limits = RateLimits::default();
        let (one, two) = (NonZeroU32::new(1).unwrap(), NonZeroU32::new(2).unwrap());
        assert!(limits.check_in_memory(7, one).is_ok());
        assert!(limits.check_in_memory(7, one).is_err());
        assert!(limits.check_in_memory(7, two).is_ok() && limits.check_in_memory(7, two).is_ok());
        assert!(limits.check_in_memory(7, two).is_err());
    }

    #[test]
    fn retry_after_rounds_up_to_whole_seconds() {
        assert_eq!(retry_after_s(Duration::from_millis(1)), 1);
        assert_eq!(retry_after_s(Duration::from_millis(19_001)), 20);
        assert_eq!(retry_after_s(Duration::from_secs(20)), 20);
        assert_eq!(retry_after_s(Duration::ZERO), 1);
    }
}
