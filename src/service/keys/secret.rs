//! Key secrets: 32 bytes from the operating system's generator, shown once as text, kept
//! only as their SHA-256.

use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine;
use sha2::{Digest, Sha256};

/// Random bytes in a secret: 256 bits, beyond any guessing.
const SECRET_BYTES: usize = 32;
/// What every secret dieplan makes starts with, so a leaked one is easy to recognise.
pub const SECRET_PREFIX: &str = "dpk_";
/// Characters of a secret kept in clear (with [`SECRET_PREFIX`]) to recognise a key in lists.
const SHOWN_CHARS: usize = 8;
/// Shortest secret accepted from `DIEPLAN_ADMIN_KEY`: 32 characters of `openssl rand -hex
/// 16` carry 128 bits.
pub const MIN_ENVIRONMENT_SECRET_CHARS: usize = 32;

/// A new secret: [`SECRET_PREFIX`] and 32 random bytes in URL-safe base64 (47 characters).
pub fn generate() -> Result<String, getrandom::Error> {
    let mut bytes = [0u8; SECRET_BYTES];
    getrandom::fill(&mut bytes)?;
    Ok(format!("{SECRET_PREFIX}{}", URL_SAFE_NO_PAD.encode(bytes)))
}

/// The SHA-256 of a secret, in hex: what the table keeps and looks keys up by. A fast hash
/// is enough: the secrets are random, not passwords, so there is nothing to brute-force.
pub fn digest(secret: &str) -> String {
    hex::encode(Sha256::digest(secret.as_bytes()))
}

/// The start of a secret that lists show (`dpk_Ab3x…`): enough to tell keys apart,
/// far too little to use.
pub fn shown_prefix(secret: &str) -> String {
    let start: String = secret.chars().take(SECRET_PREFIX.len() + SHOWN_CHARS).collect();
    format!("{start}…")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_secrets_differ_and_carry_the_prefix_and_256_bits() {
        let a = generate().unwrap();
        let b = generate().unwrap();
        assert_ne!(a, b);
        assert!(a.starts_with(SECRET_PREFIX));
        assert_eq!(a.len(), SECRET_PREFIX.len() + 43);
    }

    #[test]
    fn the_digest_is_the_sha256_of_the_secret_in_hex() {
        assert_eq!(digest("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }

    #[test]
    fn a_listed_key_shows_only_the_start_of_its_secret() {
        assert_eq!(shown_prefix("dpk_ABCDEFGHIJKLMNOP"), "dpk_ABCDEFGH…");
    }
}
