//! API keys with roles: the secret (made, hashed), the `api_keys` table, the `/v1/keys`
//! routes and the `dieplan keys` command. The middleware that checks them is
//! [`crate::service::auth`].

pub mod cli;
pub mod model;
pub mod routes;
pub mod secret;
pub mod store;
