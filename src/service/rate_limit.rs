//! Per-key rate limits: a token bucket (GCRA, the `governor` crate) per key, refilled at
//! the key's requests a minute, as deep as a minute's requests.

use governor::clock::{Clock, DefaultClock};
use governor::{DefaultDirectRateLimiter, Quota, RateLimiter};
use std::collections::HashMap;
use std::num::NonZeroU32;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The buckets of the keys that have made requests since the start.
#[derive(Default)]
pub struct RateLimits {
    buckets: Mutex<HashMap<i64, Arc<DefaultDirectRateLimiter>>>,
}

impl RateLimits {
    /// Takes one request from key `id`'s bucket of `per_minute` requests a minute (0:
    /// unlimited); `Err` with how long to wait when the bucket is empty.
    pub fn check(&self, id: i64, per_minute: i64) -> Result<(), Duration> {
        let Some(rate) = u32::try_from(per_minute).ok().and_then(NonZeroU32::new) else {
            return Ok(());
        };
        let bucket = {
            let mut buckets = self.buckets.lock().unwrap_or_else(|p| p.into_inner());
            buckets.entry(id).or_insert_with(|| Arc::new(RateLimiter::direct(Quota::per_minute(rate)))).clone()
        };
        bucket.check().map_err(|not_until| not_until.wait_time_from(DefaultClock::default().now()))
    }
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
        for _ in 0..3 {
            assert!(limits.check(7, 3).is_ok());
        }
        let wait = limits.check(7, 3).expect_err("the fourth request is refused");
        assert!(wait > Duration::from_secs(15) && wait <= Duration::from_secs(20), "{wait:?}");
        assert!(limits.check(8, 3).is_ok(), "another key has its own bucket");
    }

    #[test]
    fn a_limit_of_zero_is_no_limit() {
        let limits = RateLimits::default();
        assert!((0..1000).all(|_| limits.check(1, 0).is_ok()));
    }

    #[test]
    fn retry_after_rounds_up_to_whole_seconds() {
        assert_eq!(retry_after_s(Duration::from_millis(1)), 1);
        assert_eq!(retry_after_s(Duration::from_millis(19_001)), 20);
        assert_eq!(retry_after_s(Duration::from_secs(20)), 20);
        assert_eq!(retry_after_s(Duration::ZERO), 1);
    }
}
