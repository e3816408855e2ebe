//! Why a value was refused, in the words of the API rather than of Rust: serde and the
//! parsers it calls describe what they wanted as `usize`, `f64`, `struct ToolData` or
//! `a sequence`; a client sees "a whole number from 0 to 4294967295", "a number",
//! "an object", "an array". Every rejection of a JSON body, a query or a path parameter
//! passes through [`reason`] before it is sent.

use crate::service::error::{excerpt, shown};

/// The reason a deserialisation `message` gives, rewritten without Rust type names, long
/// input or JSON positions: `invalid type: string "x", expected f64` becomes
/// `must be a number, got "x"`.
pub fn reason(message: &str) -> String {
    let message = message.trim();
    if let Some(rest) = message.strip_prefix("invalid type: ").or_else(|| message.strip_prefix("invalid value: ")) {
        if let Some((got, wanted)) = rest.rsplit_once(", expected ") {
            return format!("must be {}, got {}", expectation(wanted), unexpected(got));
        }
    }
    if let Some(rest) = message.strip_prefix("invalid length ") {
        if let Some((len, wanted)) = rest.split_once(", expected ") {
            return format!("must be {}, got {len} items", expectation(wanted));
        }
    }
    if let Some(rest) = message.strip_prefix("unknown variant ") {
        return match rest.split_once(", expected ") {
            Some((got, names)) => format!("must be {names}, got {}", quoted_excerpt(got)),
            None => format!("is not an accepted value: {}", quoted_excerpt(rest.split(',').next().unwrap_or(rest))),
        };
    }
    if let Some(rest) = message.strip_prefix("unknown field ") {
        return match rest.split_once(", expected ") {
            Some((got, names)) => format!("{} is not a field here (the fields are {names})", quoted_excerpt(got)),
            None => format!("{} is not a field here", quoted_excerpt(rest.split(',').next().unwrap_or(rest))),
        };
    }
    if let Some(name) = message.strip_prefix("duplicate field ") {
        return format!("{} is given twice", quoted_excerpt(name));
    }
    if message.starts_with("data did not match any variant of untagged enum") {
        return "matches none of the forms the schema allows".to_string();
    }
    if let Some(wanted) = parse_failure(message) {
        return format!("must be {wanted}");
    }
    scrub(message)
}

/// What a path or query parameter of Rust type `type_name` must be, and the value given.
pub fn parameter_reason(type_name: &str, value: &str) -> String {
    format!("must be {}, got {}", expectation(type_name), quoted_excerpt(&format!("`{value}`")))
}

/// The messages of Rust's number and boolean parsers (query parameters are parsed from
/// text), as what the value must be.
fn parse_failure(message: &str) -> Option<&'static str> {
    match message {
        "invalid digit found in string"
        | "cannot parse integer from empty string"
        | "number too large to fit in target type"
        | "number too small to fit in target type" => Some("a whole number in the documented range"),
        "invalid float literal" | "cannot parse float from empty string" => Some("a number"),
        "provided string was not `true` or `false`" => Some("true or false"),
        _ => None,
    }
}

/// What serde expected, in the API's words.
fn expectation(wanted: &str) -> String {
    let wanted = wanted.trim();
    let words = match wanted {
        "u8" => Some(format!("a whole number from 0 to {}", u8::MAX)),
        "u16" => Some(format!("a whole number from 0 to {}", u16::MAX)),
        "u32" => Some(format!("a whole number from 0 to {}", u32::MAX)),
        "u64" | "usize" | "u128" => Some(format!("a whole number from 0 to {}", u64::MAX)),
        "i8" => Some(format!("a whole number from {} to {}", i8::MIN, i8::MAX)),
        "i16" => Some(format!("a whole number from {} to {}", i16::MIN, i16::MAX)),
        "i32" => Some(format!("a whole number from {} to {}", i32::MIN, i32::MAX)),
        "i64" | "isize" | "i128" => Some(format!("a whole number from {} to {}", i64::MIN, i64::MAX)),
        "f32" | "f64" => Some("a number".to_string()),
        "a boolean" | "bool" => Some("true or false".to_string()),
        "a string" | "a borrowed string" | "String" | "str" => Some("a string".to_string()),
        "a character" | "a char" | "char" => Some("a single character".to_string()),
        "a sequence" => Some("an array".to_string()),
        "a map" => Some("an object".to_string()),
        "option" => Some("a value or null".to_string()),
        "unit" => Some("null".to_string()),
        "variant identifier" | "field identifier" => Some("one of the names the schema lists".to_string()),
        _ => None,
    };
    if let Some(words) = words {
        return words;
    }
    for prefix in ["struct ", "internally tagged enum ", "adjacently tagged enum ", "map "] {
        if wanted.starts_with(prefix) {
            return "an object".to_string();
        }
    }
    if wanted.starts_with("enum ") {
        return "one of the names the schema lists".to_string();
    }
    if let Some(n) = wanted.strip_prefix("a tuple of size ").or_else(|| wanted.strip_prefix("an array of length ")) {
        return format!("an array of {n} items");
    }
    if wanted.starts_with("tuple struct ") {
        return "an array".to_string();
    }
    scrub(wanted)
}

/// The value serde refused (`integer `5``, `floating point `1e308``, `string "abc"`), as
/// the client wrote it, short.
fn unexpected(got: &str) -> String {
    let got = got.trim();
    for prefix in ["integer ", "boolean ", "character ", "string "] {
        if let Some(value) = got.strip_prefix(prefix) {
            return quoted_excerpt(value);
        }
    }
    if let Some(value) = got.strip_prefix("floating point ") {
        let number = value.trim_matches('`');
        return match number.parse::<f64>() {
            Ok(x) => shown(x),
            Err(_) => quoted_excerpt(value),
        };
    }
    match got {
        "sequence" => "an array".to_string(),
        "map" => "an object".to_string(),
        "unit value" | "Option value" | "null" => "null".to_string(),
        "unit variant" | "newtype variant" | "tuple variant" | "struct variant" | "enum" => "a name".to_string(),
        other => scrub(other),
    }
}

/// A quoted value (between backticks or double quotes) cut to its first characters.
fn quoted_excerpt(value: &str) -> String {
    let value = value.trim();
    for quote in ['`', '"'] {
        if let Some(inner) = value.strip_prefix(quote).and_then(|v| v.strip_suffix(quote)) {
            return format!("{quote}{}{quote}", excerpt(inner));
        }
    }
    excerpt(value)
}

/// Any other message, with Rust's primitive type names said in words.
fn scrub(message: &str) -> String {
    const NAMES: [(&str, &str); 14] = [
        ("usize", "whole number"),
        ("isize", "whole number"),
        ("u8", "whole number"),
        ("u16", "whole number"),
        ("u32", "whole number"),
        ("u64", "whole number"),
        ("i8", "whole number"),
        ("i16", "whole number"),
        ("i32", "whole number"),
        ("i64", "whole number"),
        ("f32", "number"),
        ("f64", "number"),
        ("a sequence", "an array"),
        ("a map", "an object"),
    ];
    let mut text = excerpt_long(message);
    for (name, words) in NAMES {
        text = replace_word(&text, name, words);
    }
    text
}

/// Messages stay readable: at most this many characters.
const MAX_REASON_CHARS: usize = 300;

fn excerpt_long(message: &str) -> String {
    match message.char_indices().nth(MAX_REASON_CHARS) {
        Some((cut, _)) => format!("{}…", &message[..cut]),
        None => message.to_string(),
    }
}

/// `text` with every whole-word `name` replaced by `words`.
fn replace_word(text: &str, name: &str, words: &str) -> String {
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(name) {
        let before = rest[..at].chars().next_back();
        let after = rest[at + name.len()..].chars().next();
        out.push_str(&rest[..at]);
        if before.is_some_and(is_word) || after.is_some_and(is_word) {
            out.push_str(name);
        } else {
            out.push_str(words);
        }
        rest = &rest[at + name.len()..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrong_type_is_said_in_the_api_s_words_with_the_value_given() {
        assert_eq!(reason(r#"invalid type: string "ten", expected f64"#), r#"must be a number, got "ten""#);
        assert_eq!(
            reason("invalid value: integer `-1`, expected usize"),
            "must be a whole number from 0 to 18446744073709551615, got `-1`"
        );
        assert_eq!(reason("invalid type: sequence, expected struct ToolData"), "must be an object, got an array");
        assert_eq!(reason("invalid type: map, expected a sequence"), "must be an array, got an object");
        assert_eq!(reason("invalid type: null, expected a string"), "must be a string, got null");
        assert_eq!(reason("invalid length 3, expected a tuple of size 2"), "must be an array of 2 items, got 3 items");
    }

    #[test]
    fn a_huge_number_is_shown_short() {
        let digits = format!("1{}.0", "0".repeat(308));
        let said = reason(&format!("invalid type: floating point `{digits}`, expected u32"));
        assert_eq!(said, "must be a whole number from 0 to 4294967295, got 1e308");
    }

    #[test]
    fn no_reason_names_a_rust_type() {
        for message in [
            "invalid type: boolean `true`, expected i64",
            "invalid type: string \"x\", expected internally tagged enum Shape",
            "invalid type: integer `3`, expected enum Operation",
            "data did not match any variant of untagged enum JobInput",
            "invalid digit found in string",
            "expected u32 or a list of f64",
        ] {
            let said = reason(message);
            for name in ["i64", "u32", "f64", "usize", "enum ", "struct", "Shape", "JobInput", "Operation"] {
                assert!(!said.contains(name), "{message} -> {said}");
            }
        }
    }

    #[test]
    fn unknown_names_list_the_accepted_ones() {
        assert_eq!(
            reason("unknown variant `squar`, expected one of `square`, `ball`"),
            "must be one of `square`, `ball`, got `squar`"
        );
        assert_eq!(
            reason("unknown field `colour`, expected `color` or `width`"),
            "`colour` is not a field here (the fields are `color` or `width`)"
        );
    }

    #[test]
    fn a_path_parameter_of_the_wrong_type_is_said_in_words() {
        assert_eq!(
            parameter_reason("i64", "abc"),
            "must be a whole number from -9223372036854775808 to 9223372036854775807, got `abc`"
        );
    }
}
