//! Configuration from flags and environment variables, with defaults that work out of
//! the box.

use crate::service::store::Location;
use clap::{Args, ValueEnum};
use std::net::SocketAddr;

/// Log output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LogFormat {
    Text,
    Json,
}

/// Everything `dieplan serve` can be told.
#[derive(Debug, Clone, Args)]
pub struct Config {
    /// Address to listen on.
    #[arg(long, env = "DIEPLAN_ADDR", default_value = "127.0.0.1:8080")]
    pub addr: SocketAddr,
    /// The database: a SQLite file, or a `postgres://user:password@host/name` URL for
    /// several replicas on one PostgreSQL; created (SQLite) and migrated at start.
    #[arg(long, env = "DIEPLAN_DATABASE", default_value = "data/dieplan.sqlite", value_parser = Location::parse)]
    pub database: Location,
    /// Log format.
    #[arg(long, env = "DIEPLAN_LOG_FORMAT", value_enum, default_value_t = LogFormat::Text)]
    pub log_format: LogFormat,
    /// Log filter (tracing EnvFilter syntax), e.g. `info` or `dieplan=debug,tower_http=info`.
    #[arg(long, env = "DIEPLAN_LOG", default_value = "info")]
    pub log: String,
    /// Job workers; default: one per core. 0 runs an API-only instance that queues jobs
    /// for another instance on the same database.
    #[arg(long, env = "DIEPLAN_WORKERS")]
    pub workers: Option<usize>,
    /// Largest request body, bytes.
    #[arg(long, env = "DIEPLAN_BODY_LIMIT", default_value_t = 64 * 1024 * 1024)]
    pub body_limit: usize,
    /// Request timeout, seconds.
    #[arg(long, env = "DIEPLAN_REQUEST_TIMEOUT", default_value_t = 120)]
    pub request_timeout_s: u64,
    /// Longest `Prefer: wait=N` honoured, seconds (kept below the request timeout).
    #[arg(long, env = "DIEPLAN_MAX_WAIT", default_value_t = 60)]
    pub max_wait_s: u64,
    /// Origins allowed by CORS, comma-separated, or `*`; none by default.
    #[arg(long, env = "DIEPLAN_CORS_ORIGINS", value_delimiter = ',')]
    pub cors_origins: Vec<String>,
    /// Seconds running jobs get to stop at shutdown before the process exits.
    #[arg(long, env = "DIEPLAN_SHUTDOWN_GRACE", default_value_t = 10)]
    pub shutdown_grace_s: u64,
    /// Longest a job may run, seconds; a job still running then is stopped and fails.
    /// 0: no limit.
    #[arg(long, env = "DIEPLAN_JOB_TIME_LIMIT", default_value_t = DEFAULT_JOB_TIME_LIMIT_S)]
    pub job_time_limit_s: u64,
    /// An admin key set up at start (for Docker): a secret of at least 32 characters.
    /// Changing it revokes the key of its earlier value. Prefer the variable to the flag,
    /// which other users of the machine can read in the process list.
    #[arg(long, env = "DIEPLAN_ADMIN_KEY", hide_env_values = true, value_parser = parse_secret)]
    pub admin_key: Option<Secret>,
    /// Run without keys on an address other than loopback: anyone who reaches the port
    /// may do everything. Without it the service refuses to start so.
    #[arg(long, env = "DIEPLAN_INSECURE_NO_AUTH")]
    pub insecure_no_auth: bool,
    /// Host names (or `name:port`) the `Host` header must name, comma-separated; any when
    /// empty. The health probes are exempt.
    #[arg(long, env = "DIEPLAN_ALLOWED_HOSTS", value_delimiter = ',')]
    pub allowed_hosts: Vec<String>,
    /// Requests a minute each key may make, unless the key says otherwise; 0: unlimited.
    #[arg(long, env = "DIEPLAN_RATE_LIMIT", default_value_t = DEFAULT_RATE_LIMIT_PER_MINUTE)]
    pub rate_limit_per_minute: i64,
    /// Seconds a replica's lease on a running job lasts unless renewed: another replica
    /// on the same database takes the job this long after the replica died. The replica
    /// renews it every third of that.
    #[arg(long, env = "DIEPLAN_JOB_LEASE_SECONDS", default_value_t = DEFAULT_JOB_LEASE_SECONDS, value_parser = clap::value_parser!(u64).range(1..=86_400))]
    pub job_lease_seconds: u64,
    /// Finished jobs older than this many days are removed with their results; 0: kept.
    #[arg(long, env = "DIEPLAN_JOB_RETENTION_DAYS", default_value_t = DEFAULT_JOB_RETENTION_DAYS)]
    pub job_retention_days: u64,
    /// Memory each stock simulation of a job may take for its slices, MiB: a program's
    /// cutting levels beyond what it holds are merged, and the raster cell is coarsened
    /// where even 16 slices do not fit.
    #[arg(long, env = "DIEPLAN_STOCK_MEMORY_MB", default_value_t = DEFAULT_STOCK_MEMORY_MB, value_parser = clap::value_parser!(u64).range(1..=MAX_STOCK_MEMORY_MB))]
    pub stock_memory_mb: u64,
}

/// Default for [`Config::rate_limit_per_minute`]: 20 requests a second per key, far more
/// than the page's polling or a CAM plugin needs, and a brake on a runaway script.
pub const DEFAULT_RATE_LIMIT_PER_MINUTE: i64 = 1200;
/// Default for [`Config::job_lease_seconds`]: long enough that a database hiccup of a few
/// seconds never costs a running job, short enough that a dead replica's jobs resume
/// within half a minute.
pub const DEFAULT_JOB_LEASE_SECONDS: u64 = 30;
/// Default for [`Config::job_retention_days`].
pub const DEFAULT_JOB_RETENTION_DAYS: u64 = 30;
/// Default for [`Config::stock_memory_mb`]: the analysis's own default budget.
pub const DEFAULT_STOCK_MEMORY_MB: u64 = (crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES / BYTES_PER_MB) as u64;
/// Largest [`Config::stock_memory_mb`]: 1 TiB.
pub const MAX_STOCK_MEMORY_MB: u64 = 1024 * 1024;
/// Bytes in a MiB, the unit of [`Config::stock_memory_mb`].
const BYTES_PER_MB: usize = 1024 * 1024;

/// A secret that logs and `Debug` never show.
#[derive(Clone)]
pub struct Secret(pub String);

impl std::fmt::Debug for Secret {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Secret(…)")
    }
}

fn parse_secret(text: &str) -> Result<Secret, String> {
    Ok(Secret(text.trim().to_string()))
}

/// Default for [`Config::job_time_limit_s`]: an hour, far more than any job of the
/// benchmarks takes, and short enough that a runaway request frees its worker the same
/// shift.
pub const DEFAULT_JOB_TIME_LIMIT_S: u64 = 3600;

impl Config {
    /// A configuration with every default, for `database` (tests, embedding).
    pub fn with_database(database: impl Into<Location>) -> Config {
        Config {
            addr: SocketAddr::from(([127, 0, 0, 1], 0)),
            database: database.into(),
            log_format: LogFormat::Text,
            log: "info".to_string(),
            workers: None,
            body_limit: 64 * 1024 * 1024,
            request_timeout_s: 120,
            max_wait_s: 60,
            cors_origins: Vec::new(),
            shutdown_grace_s: 10,
            job_time_limit_s: DEFAULT_JOB_TIME_LIMIT_S,
            admin_key: None,
            insecure_no_auth: false,
            allowed_hosts: Vec::new(),
            rate_limit_per_minute: DEFAULT_RATE_LIMIT_PER_MINUTE,
            job_retention_days: DEFAULT_JOB_RETENTION_DAYS,
            job_lease_seconds: DEFAULT_JOB_LEASE_SECONDS,
            stock_memory_mb: DEFAULT_STOCK_MEMORY_MB,
        }
    }

    /// Memory each stock simulation of a job may take, bytes.
    pub fn stock_memory_bytes(&self) -> usize {
        usize::try_from(self.stock_memory_mb).map_or(usize::MAX, |mb| mb.saturating_mul(BYTES_PER_MB))
    }

    /// The longest a job may run, if limited.
    pub fn job_time_limit(&self) -> Option<std::time::Duration> {
        (self.job_time_limit_s > 0).then(|| std::time::Duration::from_secs(self.job_time_limit_s))
    }

    /// How long a replica's lease on a running job lasts.
    pub fn job_lease(&self) -> std::time::Duration {
        std::time::Duration::from_secs(self.job_lease_seconds.max(1))
    }

    /// The number of workers to start.
    pub fn worker_count(&self) -> usize {
        self.workers.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1))
    }

    /// The wait cap actually applied: never past the request timeout.
    pub fn effective_max_wait_s(&self) -> u64 {
        self.max_wait_s.min(self.request_timeout_s.saturating_sub(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    /// `dieplan serve`'s flags alone.
    #[derive(Parser)]
    struct Serve {
        #[command(flatten)]
        config: Config,
    }

    /// The stock memory budget `args` set, bytes.
    fn budget(args: &[&str]) -> Result<usize, clap::Error> {
        let argv = std::iter::once("serve").chain(args.iter().copied());
        Serve::try_parse_from(argv).map(|s| s.config.stock_memory_bytes())
    }

    #[test]
    fn the_stock_memory_budget_is_given_in_mib_defaults_to_a_gib_and_is_never_zero() {
        assert_eq!(budget(&[]).ok(), Some(1 << 30));
        assert_eq!(Config::with_database(std::path::PathBuf::from("x.sqlite")).stock_memory_bytes(), 1 << 30);
        assert_eq!(budget(&["--stock-memory-mb", "64"]).ok(), Some(64 << 20));
        assert!(budget(&["--stock-memory-mb", "0"]).is_err());
    }
}
