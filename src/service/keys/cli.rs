//! `dieplan keys …`: make, list and revoke keys on the database directly, e.g. the first
//! admin key of a service bound to the network.

use super::model::{KeyOrigin, NewKey, Role};
use super::store;
use crate::service::store::Location;
use clap::{Args, Subcommand};

/// The `keys` subcommands.
#[derive(Debug, Subcommand)]
pub enum KeysCommand {
    /// Make a key and print its secret (shown this once) on standard output.
    Create(CreateArgs),
    /// List the keys (never their secrets).
    List(DatabaseArg),
    /// Revoke a key by id.
    Revoke(RevokeArgs),
}

/// The database the command works on.
#[derive(Debug, Args)]
pub struct DatabaseArg {
    /// The service's database: a SQLite file or a `postgres://` URL (created and migrated
    /// if missing).
    #[arg(long, env = "DIEPLAN_DATABASE", default_value = "data/dieplan.sqlite", value_parser = Location::parse)]
    pub database: Location,
}

#[derive(Debug, Args)]
pub struct CreateArgs {
    #[arg(long, value_enum)]
    pub role: Role,
    /// Who or what uses it, e.g. the CAM station.
    #[arg(long)]
    pub name: String,
    /// Requests a minute (0: unlimited); the service's default when left out.
    #[arg(long)]
    pub rate_limit_per_minute: Option<i64>,
    #[command(flatten)]
    pub database: DatabaseArg,
}

#[derive(Debug, Args)]
pub struct RevokeArgs {
    /// The key's id (see `dieplan keys list`).
    pub id: i64,
    #[command(flatten)]
    pub database: DatabaseArg,
}

/// Runs a `keys` subcommand; the text to print on standard output, or why it failed.
pub async fn run(command: KeysCommand) -> Result<String, String> {
    let database = match &command {
        KeysCommand::Create(a) => &a.database.database,
        KeysCommand::List(a) => &a.database,
        KeysCommand::Revoke(a) => &a.database.database,
    };
    let pool = crate::service::store::open(database).await.map_err(|e| format!("database {}: {e}", database))?;
    let problem = |e: crate::service::error::ApiError| e.problem().detail;
    let out = match command {
        KeysCommand::Create(args) => {
            let new = NewKey { role: args.role, name: args.name, rate_limit_per_minute: args.rate_limit_per_minute };
            let created = store::create(&pool, &new, KeyOrigin::Cli).await.map_err(problem)?;
            eprintln!(
                "made {} key {} ({}); its secret follows and is not shown again",
                created.key.role.as_str(),
                created.key.id,
                created.key.name
            );
            created.secret
        }
        KeysCommand::List(_) => {
            let rows = store::list(&pool).await.map_err(problem)?;
            let mut out =
                format!("{:>4}  {:<8} {:<16} {:<12} {:<25} name", "id", "role", "prefix", "origin", "revoked");
            for row in rows {
                out.push_str(&format!(
                    "\n{:>4}  {:<8} {:<16} {:<12} {:<25} {}",
                    row.id,
                    row.role,
                    row.prefix,
                    row.origin,
                    row.revoked_at.as_deref().unwrap_or("-"),
                    row.name
                ));
            }
            out
        }
        KeysCommand::Revoke(args) => {
            let row = store::revoke(&pool, args.id).await.map_err(problem)?;
            format!("revoked key {} ({})", row.id, row.name)
        }
    };
    pool.close().await;
    Ok(out)
}
