//! The `api_keys` table.

use super::model::{ApiKey, CreatedKey, KeyOrigin, NewKey, Role};
use super::secret;
use crate::service::error::{ApiError, Validator};
use crate::service::store::Pool;

/// Longest key name, characters.
const MAX_NAME_CHARS: usize = 100;
/// Highest per-key rate limit a client may set, requests a minute.
pub const MAX_RATE_LIMIT_PER_MINUTE: i64 = 1_000_000;
/// The name of the key `DIEPLAN_ADMIN_KEY` sets up.
const ENVIRONMENT_KEY_NAME: &str = "DIEPLAN_ADMIN_KEY";

/// A row of `api_keys`.
#[derive(Debug, Clone, sqlx::FromRow)]
pub struct KeyRow {
    pub id: i64,
    pub name: String,
    pub role: String,
    pub prefix: String,
    pub origin: String,
    pub rate_limit_per_minute: Option<i64>,
    pub created_at: String,
    pub last_used_at: Option<String>,
    pub revoked_at: Option<String>,
}

/// The columns of [`KeyRow`], for `concat!` into static SQL.
macro_rules! columns {
    () => {
        "id, name, role, prefix, origin, rate_limit_per_minute, created_at, last_used_at, revoked_at"
    };
}

impl KeyRow {
    pub fn role(&self) -> Result<Role, ApiError> {
        Role::parse(&self.role)
            .ok_or_else(|| ApiError::Internal(format!("key {} has unknown role {}", self.id, self.role)))
    }

    pub fn to_key(&self) -> Result<ApiKey, ApiError> {
        Ok(ApiKey {
            id: self.id,
            name: self.name.clone(),
            role: self.role()?,
            prefix: self.prefix.clone(),
            origin: KeyOrigin::parse(&self.origin)
                .ok_or_else(|| ApiError::Internal(format!("key {} has unknown origin {}", self.id, self.origin)))?,
            rate_limit_per_minute: self.rate_limit_per_minute,
            created_at: self.created_at.clone(),
            last_used_at: self.last_used_at.clone(),
            revoked_at: self.revoked_at.clone(),
        })
    }
}

/// Checks a key to make; every fault at once.
pub fn validate(new: &NewKey) -> Result<(), ApiError> {
    let mut v = Validator::new();
    v.not_blank("name", &new.name);
    v.check(new.name.chars().count() <= MAX_NAME_CHARS, "name", format!("must be at most {MAX_NAME_CHARS} characters"));
    if let Some(limit) = new.rate_limit_per_minute {
        v.check(
            (0..=MAX_RATE_LIMIT_PER_MINUTE).contains(&limit),
            "rate_limit_per_minute",
            format!("must be between 0 (unlimited) and {MAX_RATE_LIMIT_PER_MINUTE}, got {limit}"),
        );
    }
    v.finish()
}

/// Makes a key with a new secret and returns it with the secret (shown this once).
pub async fn create(pool: &Pool, new: &NewKey, origin: KeyOrigin) -> Result<CreatedKey, ApiError> {
    validate(new)?;
    let secret = secret::generate().map_err(|e| ApiError::Internal(format!("no random bytes for a key: {e}")))?;
    let id = insert(pool, new, origin, &secret).await?;
    Ok(CreatedKey { key: get(pool, id).await?.to_key()?, secret })
}

async fn insert(pool: &Pool, new: &NewKey, origin: KeyOrigin, secret: &str) -> Result<i64, ApiError> {
    Ok(sqlx::query_scalar(
        "INSERT INTO api_keys (name, role, prefix, secret_sha256, origin, rate_limit_per_minute) VALUES ($1, $2, $3, $4, $5, $6) RETURNING id",
    )
    .bind(new.name.trim())
    .bind(new.role.as_str())
    .bind(secret::shown_prefix(secret))
    .bind(secret::digest(secret))
    .bind(origin.as_str())
    .bind(new.rate_limit_per_minute)
    .fetch_one(pool)
    .await?)
}

/// Reads one key (revoked or not), or 404.
pub async fn get(pool: &Pool, id: i64) -> Result<KeyRow, ApiError> {
    sqlx::query_as::<_, KeyRow>(concat!("SELECT ", columns!(), " FROM api_keys WHERE id = $1"))
        .bind(id)
        .fetch_optional(pool)
        .await?
        .ok_or_else(|| ApiError::not_found(format!("no key with id {id}")))
}

/// Every key, oldest first, revoked ones too (they still name the jobs they made).
pub async fn list(pool: &Pool) -> Result<Vec<KeyRow>, ApiError> {
    Ok(sqlx::query_as::<_, KeyRow>(concat!("SELECT ", columns!(), " FROM api_keys ORDER BY id"))
        .fetch_all(pool)
        .await?)
}

/// The active key whose secret this is, if any.
pub async fn find_active(pool: &Pool, secret: &str) -> Result<Option<KeyRow>, sqlx::Error> {
    sqlx::query_as::<_, KeyRow>(concat!(
        "SELECT ",
        columns!(),
        " FROM api_keys WHERE secret_sha256 = $1 AND revoked_at IS NULL"
    ))
    .bind(secret::digest(secret))
    .fetch_optional(pool)
    .await
}

/// `true` once any key is active: from then on every `/v1` route needs one.
pub async fn any_active(pool: &Pool) -> Result<bool, sqlx::Error> {
    let active: crate::service::store::Flag =
        sqlx::query_scalar("SELECT EXISTS (SELECT 1 FROM api_keys WHERE revoked_at IS NULL)").fetch_one(pool).await?;
    Ok(active.0)
}

/// Notes that a key was used now.
pub async fn touch(pool: &Pool, id: i64) -> Result<(), sqlx::Error> {
    sqlx::query("UPDATE api_keys SET last_used_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = $1")
        .bind(id)
        .execute(pool)
        .await?;
    Ok(())
}

/// Revokes a key: it is refused from now on. The key of `DIEPLAN_ADMIN_KEY` is refused
/// here (409): it would come back at the next start; change the variable instead.
pub async fn revoke(pool: &Pool, id: i64) -> Result<KeyRow, ApiError> {
    let row = get(pool, id).await?;
    if row.origin == KeyOrigin::Environment.as_str() {
        return Err(ApiError::Conflict(format!(
            "key {id} is set up by DIEPLAN_ADMIN_KEY: change or remove the variable and restart to revoke it"
        )));
    }
    sqlx::query(
        "UPDATE api_keys SET revoked_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = $1 AND revoked_at IS NULL",
    )
    .bind(id)
    .execute(pool)
    .await?;
    get(pool, id).await
}

/// Sets up the admin key of `DIEPLAN_ADMIN_KEY` (at start): the key of this secret is
/// active, and a key of an earlier value of the variable is revoked. With no variable,
/// its earlier key is revoked too. Refuses a secret shorter than
/// [`secret::MIN_ENVIRONMENT_SECRET_CHARS`].
pub async fn install_environment_key(pool: &Pool, secret: Option<&str>) -> Result<(), EnvironmentKeyError> {
    let digest = secret.map(secret::digest);
    if let Some(secret) = secret {
        if secret.chars().count() < secret::MIN_ENVIRONMENT_SECRET_CHARS {
            return Err(EnvironmentKeyError::TooShort);
        }
    }
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    sqlx::query(
        "UPDATE api_keys SET revoked_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
         WHERE origin = 'environment' AND revoked_at IS NULL AND secret_sha256 IS DISTINCT FROM $1",
    )
    .bind(digest.as_deref())
    .execute(&mut *tx)
    .await?;
    if let (Some(secret), Some(digest)) = (secret, digest.as_deref()) {
        let existing: Option<(String, Option<String>)> =
            sqlx::query_as("SELECT origin, revoked_at FROM api_keys WHERE secret_sha256 = $1")
                .bind(digest)
                .fetch_optional(&mut *tx)
                .await?;
        match existing {
            None => {
                sqlx::query(
                    "INSERT INTO api_keys (name, role, prefix, secret_sha256, origin) VALUES ($1, 'admin', $2, $3, 'environment')",
                )
                .bind(ENVIRONMENT_KEY_NAME)
                .bind(secret::shown_prefix(secret))
                .bind(digest)
                .execute(&mut *tx)
                .await?;
            }
            Some((origin, _)) if origin != KeyOrigin::Environment.as_str() => {
                return Err(EnvironmentKeyError::InUse);
            }
            Some((_, revoked)) => {
                if revoked.is_some() {
                    sqlx::query("UPDATE api_keys SET revoked_at = NULL WHERE secret_sha256 = $1")
                        .bind(digest)
                        .execute(&mut *tx)
                        .await?;
                }
            }
        }
    }
    tx.commit().await?;
    Ok(())
}

/// Why `DIEPLAN_ADMIN_KEY` was refused.
#[derive(Debug, thiserror::Error)]
pub enum EnvironmentKeyError {
    #[error(
        "DIEPLAN_ADMIN_KEY must be at least {} characters (e.g. `openssl rand -hex 32`)",
        secret::MIN_ENVIRONMENT_SECRET_CHARS
    )]
    TooShort,
    #[error("DIEPLAN_ADMIN_KEY is the secret of a key made otherwise: choose a new secret")]
    InUse,
    #[error("database: {0}")]
    Database(#[from] sqlx::Error),
}
