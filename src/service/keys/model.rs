//! Keys and roles as the API shows them.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// What a key may do. Each role can do everything the one before it can, except that a
/// planner sees only its own jobs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, ToSchema, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Reads everything: the database, every job, drawings, programs (`GET`).
    Reader,
    /// Reads the database, creates jobs, and reads and cancels its own jobs.
    Planner,
    /// Everything: database writes, every key's jobs, and the keys themselves.
    Admin,
}

impl Role {
    pub fn as_str(self) -> &'static str {
        match self {
            Role::Reader => "reader",
            Role::Planner => "planner",
            Role::Admin => "admin",
        }
    }

    pub fn parse(text: &str) -> Option<Role> {
        [Role::Reader, Role::Planner, Role::Admin].into_iter().find(|r| r.as_str() == text)
    }

    /// `true` when this role may do what `needed` allows.
    pub fn covers(self, needed: Role) -> bool {
        self >= needed
    }
}

/// How a key was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum KeyOrigin {
    /// `POST /v1/keys`.
    Api,
    /// `dieplan keys create`.
    Cli,
    /// `DIEPLAN_ADMIN_KEY` at start; replaced when the variable changes.
    Environment,
}

impl KeyOrigin {
    pub fn as_str(self) -> &'static str {
        match self {
            KeyOrigin::Api => "api",
            KeyOrigin::Cli => "cli",
            KeyOrigin::Environment => "environment",
        }
    }

    pub fn parse(text: &str) -> Option<KeyOrigin> {
        [KeyOrigin::Api, KeyOrigin::Cli, KeyOrigin::Environment].into_iter().find(|o| o.as_str() == text)
    }
}

/// A key to make.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"role": "planner", "name": "CAM station 2"}))]
pub struct NewKey {
    pub role: Role,
    /// Who or what uses it (1 to 100 characters), e.g. the CAM station or the MES.
    #[schema(min_length = 1, max_length = 100, pattern = r"\S")]
    pub name: String,
    /// Requests a minute this key may make (0: unlimited); the service's
    /// `--rate-limit-per-minute` when left out.
    #[serde(default)]
    #[schema(minimum = 0, maximum = 1_000_000)]
    pub rate_limit_per_minute: Option<i64>,
}

/// A key as lists show it: never its secret.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[schema(example = json!({"id": 2, "name": "CAM station 2", "role": "planner", "prefix": "dpk_q3Zr8TfA…", "origin": "api", "rate_limit_per_minute": null, "created_at": "2026-11-26T21:04:11.482Z", "last_used_at": null, "revoked_at": null}))]
pub struct ApiKey {
    pub id: i64,
    pub name: String,
    pub role: Role,
    /// The start of the secret, to recognise the key.
    pub prefix: String,
    pub origin: KeyOrigin,
    /// Requests a minute (0: unlimited); null: the service's default.
    pub rate_limit_per_minute: Option<i64>,
    pub created_at: String,
    /// Last request made with it, to the minute.
    pub last_used_at: Option<String>,
    /// When it was deleted; a revoked key is refused.
    pub revoked_at: Option<String>,
}

/// A key just made, with its secret: the only time the secret is shown.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[schema(example = json!({"id": 2, "name": "CAM station 2", "role": "planner", "prefix": "dpk_q3Zr8TfA…", "origin": "api", "rate_limit_per_minute": null, "created_at": "2026-11-26T21:04:11.482Z", "last_used_at": null, "revoked_at": null, "key": "dpk_q3Zr8TfAYk1Rj0cJ1uH9wV3nQm6pXe2LdBs7Gt4KfWo"}))]
pub struct CreatedKey {
    #[serde(flatten)]
    pub key: ApiKey,
    /// The secret, sent as `Authorization: Bearer <key>`. It is not stored and cannot be
    /// shown again: keep it now.
    #[serde(rename = "key")]
    pub secret: String,
}
