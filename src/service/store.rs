//! The store: where the database is, opening and migrating it, and health. Two backends
//! serve the same store code through sqlx's `Any` driver: SQLite (a file, the embedded
//! default) and PostgreSQL (`postgres://…`, for several replicas on one database).
//!
//! The SQL of the store is written once for both: placeholders are `$1, $2, …` (SQLite
//! reads them too), booleans are stored as integers 0/1, upserts are `ON CONFLICT … DO
//! UPDATE`, and the few SQLite functions the SQL uses (`strftime` for the ISO timestamps,
//! `round(real, digits)`) exist in PostgreSQL as small functions of its migrations
//! (`migrations_pg/`). What differs stays in this module, [`super::jobs::store`] (the
//! claim) and [`super::retention`] (the vacuum).

use sqlx::any::{AnyPoolOptions, AnyTypeInfo, AnyTypeInfoKind};
use sqlx::sqlite::{SqliteAutoVacuum, SqliteConnectOptions, SqliteJournalMode, SqliteSynchronous};
use sqlx::{Any, ConnectOptions, Connection, Executor};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::time::Duration;

/// The pool every handler and worker uses, whichever the backend.
pub type Pool = sqlx::AnyPool;
/// One connection of a [`Pool`] (inside a transaction, too).
pub type Conn = sqlx::AnyConnection;
/// A row of either backend.
pub type Row = sqlx::any::AnyRow;
/// A transaction of either backend.
pub type Transaction = sqlx::Transaction<'static, Any>;

/// The embedded SQLite migrations of `migrations/`.
pub static MIGRATOR: sqlx::migrate::Migrator = sqlx::migrate!("./migrations");
/// The embedded PostgreSQL migrations of `migrations_pg/`: the same schema and the same
/// seed, in PostgreSQL's dialect.
pub static MIGRATOR_PG: sqlx::migrate::Migrator = sqlx::migrate!("./migrations_pg");

/// How long a writer waits for SQLite's lock before giving up.
const BUSY_TIMEOUT: Duration = Duration::from_secs(10);
/// Connections in a SQLite pool.
const SQLITE_MAX_CONNECTIONS: u32 = 8;
/// Connections in a PostgreSQL pool, per replica: PostgreSQL's default `max_connections`
/// (100) leaves room for five replicas and the tools of an operator.
const POSTGRES_MAX_CONNECTIONS: u32 = 16;
/// How long a request waits for a free connection before it fails.
const ACQUIRE_TIMEOUT: Duration = Duration::from_secs(30);
/// The advisory lock key that serializes read-modify-write transactions on PostgreSQL,
/// as SQLite's `BEGIN IMMEDIATE` does (ASCII "dieplan" as a number).
const WRITE_LOCK_KEY: i64 = 0x0064_6965_706c_616e;

/// Which database engine a pool talks to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    Sqlite,
    Postgres,
}

impl Backend {
    /// The backend of an open pool.
    pub fn of(pool: &Pool) -> Backend {
        if pool.connect_options().database_url.scheme().starts_with("postgres") {
            Backend::Postgres
        } else {
            Backend::Sqlite
        }
    }
}

/// Where the database is: `--database` / `DIEPLAN_DATABASE`, a SQLite file path or a
/// `postgres://` (or `postgresql://`) URL.
#[derive(Clone, PartialEq, Eq)]
pub enum Location {
    Sqlite(PathBuf),
    Postgres(String),
}

impl Location {
    /// Reads `--database`: a URL of scheme `postgres` or `postgresql` is PostgreSQL,
    /// anything else a SQLite file (a `sqlite://` prefix is allowed).
    pub fn parse(text: &str) -> Result<Location, String> {
        let text = text.trim();
        if text.is_empty() {
            return Err("the database must be a SQLite file path or a postgres:// URL".to_string());
        }
        if text.starts_with("postgres://") || text.starts_with("postgresql://") {
            url::Url::parse(text).map_err(|e| format!("not a valid PostgreSQL URL: {e}"))?;
            return Ok(Location::Postgres(text.to_string()));
        }
        let path = text.strip_prefix("sqlite://").or_else(|| text.strip_prefix("sqlite:")).unwrap_or(text);
        Ok(Location::Sqlite(PathBuf::from(path)))
    }

    pub fn backend(&self) -> Backend {
        match self {
            Location::Sqlite(_) => Backend::Sqlite,
            Location::Postgres(_) => Backend::Postgres,
        }
    }
}

impl From<PathBuf> for Location {
    fn from(path: PathBuf) -> Location {
        Location::Sqlite(path)
    }
}

impl FromStr for Location {
    type Err = String;
    fn from_str(text: &str) -> Result<Location, String> {
        Location::parse(text)
    }
}

/// Shows a SQLite path as it is and a PostgreSQL URL without its password.
impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Sqlite(path) => write!(f, "{}", path.display()),
            Location::Postgres(url) => match url::Url::parse(url) {
                Ok(mut url) => {
                    if url.password().is_some() {
                        let _ = url.set_password(Some("…"));
                    }
                    write!(f, "{url}")
                }
                Err(_) => f.write_str("postgres://…"),
            },
        }
    }
}

impl std::fmt::Debug for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Location({self})")
    }
}

/// Opens (creating if needed) the database and applies pending migrations.
pub async fn open(location: &Location) -> Result<Pool, sqlx::Error> {
    sqlx::any::install_default_drivers();
    match location {
        Location::Sqlite(path) => open_sqlite(path).await,
        Location::Postgres(url) => open_postgres(url).await,
    }
}

async fn open_sqlite(path: &Path) -> Result<Pool, sqlx::Error> {
    if let Some(parent) = path.parent() {
        if !parent.as_os_str().is_empty() {
            std::fs::create_dir_all(parent).map_err(sqlx::Error::Io)?;
        }
    }
    let url = format!("sqlite://{}", path.display());
    // What is a property of the file (created, WAL, incremental vacuum) is set up once
    // with SQLite's own options; what each connection needs, by `after_connect`.
    let mut setup = SqliteConnectOptions::from_str(&url)?
        .create_if_missing(true)
        .journal_mode(SqliteJournalMode::Wal)
        .auto_vacuum(SqliteAutoVacuum::Incremental)
        .busy_timeout(BUSY_TIMEOUT)
        .connect()
        .await?;
    ensure_incremental_vacuum(&mut setup).await?;
    setup.close().await?;
    let pool = AnyPoolOptions::new()
        .max_connections(SQLITE_MAX_CONNECTIONS)
        .after_connect(|conn, _| {
            Box::pin(async move {
                let pragmas = format!(
                    "PRAGMA foreign_keys = ON; PRAGMA synchronous = {}; PRAGMA busy_timeout = {}",
                    sqlite_synchronous_name(SqliteSynchronous::Normal),
                    BUSY_TIMEOUT.as_millis()
                );
                conn.execute(sqlx::AssertSqlSafe(pragmas)).await?;
                Ok(())
            })
        })
        .connect(&url)
        .await?;
    MIGRATOR.run(&pool).await?;
    Ok(pool)
}

fn sqlite_synchronous_name(mode: SqliteSynchronous) -> &'static str {
    match mode {
        SqliteSynchronous::Off => "OFF",
        SqliteSynchronous::Normal => "NORMAL",
        SqliteSynchronous::Full => "FULL",
        SqliteSynchronous::Extra => "EXTRA",
    }
}

async fn open_postgres(url: &str) -> Result<Pool, sqlx::Error> {
    let pool = AnyPoolOptions::new()
        .max_connections(POSTGRES_MAX_CONNECTIONS)
        .acquire_timeout(ACQUIRE_TIMEOUT)
        .connect(url)
        .await?;
    // sqlx takes an advisory lock while it migrates: replicas starting together apply
    // each migration once.
    MIGRATOR_PG.run(&pool).await?;
    Ok(pool)
}

/// SQLite's `auto_vacuum = INCREMENTAL`, so that the file can shrink after jobs are
/// purged ([`crate::service::retention`]). A new file gets it when created; a file made
/// before it is rewritten once (`VACUUM`), which takes a while on a large database.
async fn ensure_incremental_vacuum(conn: &mut sqlx::SqliteConnection) -> Result<(), sqlx::Error> {
    /// `PRAGMA auto_vacuum`'s value for INCREMENTAL.
    const INCREMENTAL: i64 = 2;
    let mode: i64 = sqlx::query_scalar("PRAGMA auto_vacuum").fetch_one(&mut *conn).await?;
    if mode != INCREMENTAL {
        tracing::info!("converting the database to incremental vacuum (once; rewrites the file)");
        sqlx::query("PRAGMA auto_vacuum = INCREMENTAL").execute(&mut *conn).await?;
        sqlx::query("VACUUM").execute(&mut *conn).await?;
    }
    Ok(())
}

/// The migrations of the pool's backend.
pub fn migrator(pool: &Pool) -> &'static sqlx::migrate::Migrator {
    match Backend::of(pool) {
        Backend::Sqlite => &MIGRATOR,
        Backend::Postgres => &MIGRATOR_PG,
    }
}

/// `true` when the database answers and every embedded migration has been applied.
pub async fn ready(pool: &Pool) -> Result<(), String> {
    let applied: Vec<i64> = sqlx::query_scalar("SELECT version FROM _sqlx_migrations WHERE success = TRUE")
        .fetch_all(pool)
        .await
        .map_err(|e| format!("database unreachable: {e}"))?;
    let missing: Vec<i64> = migrator(pool).iter().map(|m| m.version).filter(|v| !applied.contains(v)).collect();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(format!("migrations not applied: {missing:?}"))
    }
}

/// Begins a transaction that writes: SQLite takes its write lock at once (`BEGIN
/// IMMEDIATE`, so that two writers never deadlock upgrading a read lock); PostgreSQL's
/// row locks need nothing more.
pub async fn begin(pool: &Pool) -> Result<Transaction, sqlx::Error> {
    match Backend::of(pool) {
        Backend::Sqlite => pool.begin_with("BEGIN IMMEDIATE").await,
        Backend::Postgres => pool.begin().await,
    }
}

/// Begins a read-modify-write transaction that no other such transaction interleaves
/// with: SQLite's `BEGIN IMMEDIATE`, and on PostgreSQL a transaction-scoped advisory lock
/// taken first, so that a PATCH that reads a row, merges and writes it never loses a
/// concurrent one, on any replica.
pub async fn begin_exclusive(pool: &Pool) -> Result<Transaction, sqlx::Error> {
    let mut tx = begin(pool).await?;
    if Backend::of(pool) == Backend::Postgres {
        sqlx::query("SELECT 1 FROM (SELECT pg_advisory_xact_lock($1)) AS locked")
            .bind(WRITE_LOCK_KEY)
            .execute(&mut *tx)
            .await?;
    }
    Ok(tx)
}

/// Numbers the `?` placeholders of SQL assembled from parts (`$1, $2, …`, which both
/// backends read); static SQL is written numbered.
pub fn numbered(sql: &str) -> sqlx::AssertSqlSafe<String> {
    let mut out = String::with_capacity(sql.len() + 8);
    let (mut n, mut quoted) = (0, false);
    for c in sql.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                out.push(c);
            }
            '?' if !quoted => {
                n += 1;
                out.push_str(&format!("${n}"));
            }
            _ => out.push(c),
        }
    }
    sqlx::AssertSqlSafe(out)
}

/// A 0/1 flag column or a boolean expression, read as `bool` from either backend (SQLite
/// answers `EXISTS` and flags as integers, PostgreSQL `EXISTS` as a boolean). Use it with
/// `#[sqlx(try_from = "Flag")]` on a `bool` field, or as a scalar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flag(pub bool);

impl From<Flag> for bool {
    fn from(flag: Flag) -> bool {
        flag.0
    }
}

impl From<Flag> for Option<bool> {
    fn from(flag: Flag) -> Option<bool> {
        Some(flag.0)
    }
}

impl sqlx::Type<Any> for Flag {
    fn type_info() -> AnyTypeInfo {
        <i64 as sqlx::Type<Any>>::type_info()
    }

    fn compatible(ty: &AnyTypeInfo) -> bool {
        ty.kind().is_integer() || ty.kind() == AnyTypeInfoKind::Bool
    }
}

impl<'r> sqlx::Decode<'r, Any> for Flag {
    fn decode(value: sqlx::any::AnyValueRef<'r>) -> Result<Flag, sqlx::error::BoxDynError> {
        match <i64 as sqlx::Decode<Any>>::decode(value.clone()) {
            Ok(n) => Ok(Flag(n != 0)),
            Err(_) => Ok(Flag(<bool as sqlx::Decode<Any>>::decode(value)?)),
        }
    }
}

/// A blob of text (JSON, an NC program) as the store keeps it: written as bytes (`BLOB`
/// in SQLite, `bytea` in PostgreSQL), read back from bytes or from the text of rows
/// written before.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Text(pub String);

impl From<Text> for String {
    fn from(text: Text) -> String {
        text.0
    }
}

impl sqlx::Type<Any> for Text {
    fn type_info() -> AnyTypeInfo {
        <Vec<u8> as sqlx::Type<Any>>::type_info()
    }

    fn compatible(ty: &AnyTypeInfo) -> bool {
        matches!(ty.kind(), AnyTypeInfoKind::Blob | AnyTypeInfoKind::Text)
    }
}

impl<'r> sqlx::Decode<'r, Any> for Text {
    fn decode(value: sqlx::any::AnyValueRef<'r>) -> Result<Text, sqlx::error::BoxDynError> {
        match <String as sqlx::Decode<Any>>::decode(value.clone()) {
            Ok(text) => Ok(Text(text)),
            Err(_) => Ok(Text(String::from_utf8(<Vec<u8> as sqlx::Decode<Any>>::decode(value)?)?)),
        }
    }
}

/// A JSON column read into `T` (both backends keep JSON columns as text). Use it with
/// `#[sqlx(try_from = "JsonText<T>")]` and a `From<JsonText<T>>` for the field's type.
#[derive(Debug, Clone, PartialEq)]
pub struct JsonText<T>(pub T);

impl<T> sqlx::Type<Any> for JsonText<T> {
    fn type_info() -> AnyTypeInfo {
        <String as sqlx::Type<Any>>::type_info()
    }

    fn compatible(ty: &AnyTypeInfo) -> bool {
        matches!(ty.kind(), AnyTypeInfoKind::Blob | AnyTypeInfoKind::Text)
    }
}

impl<'r, T: serde::de::DeserializeOwned> sqlx::Decode<'r, Any> for JsonText<T> {
    fn decode(value: sqlx::any::AnyValueRef<'r>) -> Result<JsonText<T>, sqlx::error::BoxDynError> {
        let Text(text) = <Text as sqlx::Decode<Any>>::decode(value)?;
        Ok(JsonText(serde_json::from_str(&text)?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_postgres_url_is_postgres_and_anything_else_a_sqlite_file() {
        assert_eq!(Location::parse("postgres://u:p@db/dieplan").unwrap().backend(), Backend::Postgres);
        assert_eq!(Location::parse("postgresql://db/dieplan").unwrap().backend(), Backend::Postgres);
        assert_eq!(Location::parse("data/dieplan.sqlite").unwrap(), Location::Sqlite("data/dieplan.sqlite".into()));
        assert_eq!(Location::parse("sqlite://x.db").unwrap(), Location::Sqlite("x.db".into()));
        assert!(Location::parse("  ").is_err());
        assert!(Location::parse("postgres://[bad").is_err());
    }

    #[test]
    fn a_postgres_url_is_shown_without_its_password() {
        let shown = Location::parse("postgres://dieplan:hunter2@db:5432/dieplan").unwrap().to_string();
        assert!(!shown.contains("hunter2"), "{shown}");
        assert!(shown.contains("db:5432/dieplan"), "{shown}");
    }

    #[test]
    fn assembled_placeholders_are_numbered_outside_quotes() {
        assert_eq!(numbered("a = ? AND b = '?' AND c = ?").0, "a = $1 AND b = '?' AND c = $2");
    }
}
