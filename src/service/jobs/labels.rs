//! A job's name and tags: given on submit (beside `kind` and `input` in `POST /v1/jobs`, or
//! beside the request's own fields on the named endpoints), kept in the job's row, shown in
//! the job and in lists, and searched by `GET /v1/jobs?name=…&tag=…`.

use crate::service::error::{excerpt, FieldError};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Longest name, characters.
pub const MAX_NAME_CHARS: usize = 200;
/// Most tags of a job.
pub const MAX_TAGS: usize = 20;
/// Longest tag, characters.
pub const MAX_TAG_CHARS: usize = 64;
/// The characters a tag may have besides ASCII letters and digits.
pub const TAG_PUNCTUATION: &str = "-_.:/";

/// A job's name and tags as submitted.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
pub struct JobLabels {
    /// What to call the job (1 to 200 characters, no control characters): shown in the
    /// job and in lists, and found by `GET /v1/jobs?name=` (a case-insensitive substring).
    #[schema(
        min_length = 1,
        max_length = 200,
        pattern = r"^[^\u0000-\u001F\u007F]*$",
        example = "Die 4711, cavity A, roughing"
    )]
    pub name: Option<String>,
    /// Up to 20 distinct tags, each 1 to 64 ASCII letters, digits and `-_.:/`, kept in
    /// the order given; `GET /v1/jobs?tag=` finds the jobs that have every tag it names.
    #[serde(default)]
    #[schema(max_items = 20, value_type = Vec<Tag>, example = json!(["die:4711", "roughing"]))]
    pub tags: Vec<String>,
}

/// One tag: 1 to 64 ASCII letters, digits and `-_.:/`.
#[derive(ToSchema)]
#[schema(pattern = r"^[A-Za-z0-9_.:/-]{1,64}$")]
#[allow(dead_code)]
pub struct Tag(String);

/// Why `tag` is not a tag, if it is not.
pub fn tag_fault(tag: &str) -> Option<String> {
    let chars = tag.chars().count();
    if chars == 0 {
        return Some("must not be empty".to_string());
    }
    if chars > MAX_TAG_CHARS {
        return Some(format!("must be at most {MAX_TAG_CHARS} characters, got {chars}"));
    }
    let bad = tag.chars().find(|c| !(c.is_ascii_alphanumeric() || TAG_PUNCTUATION.contains(*c)));
    bad.map(|c| format!("may have only ASCII letters, digits and {TAG_PUNCTUATION}, got {c:?} in \"{}\"", excerpt(tag)))
}

impl JobLabels {
    /// Every fault of the name and tags, with field paths starting with `prefix`.
    pub fn faults(&self, prefix: &str) -> Vec<FieldError> {
        let mut faults = Vec::new();
        let mut fail = |field: String, reason: String| faults.push(FieldError { field, reason });
        if let Some(name) = &self.name {
            let chars = name.chars().count();
            if chars == 0 {
                fail(format!("{prefix}name"), "must not be empty (leave it out for no name)".to_string());
            } else if chars > MAX_NAME_CHARS {
                fail(format!("{prefix}name"), format!("must be at most {MAX_NAME_CHARS} characters, got {chars}"));
            }
            if name.chars().any(|c| c <= '\u{1f}' || c == '\u{7f}') {
                fail(format!("{prefix}name"), "must not have control characters (line breaks, tabs)".to_string());
            }
        }
        if self.tags.len() > MAX_TAGS {
            fail(format!("{prefix}tags"), format!("must have at most {MAX_TAGS} tags, got {}", self.tags.len()));
        }
        for (i, tag) in self.tags.iter().enumerate() {
            if let Some(reason) = tag_fault(tag) {
                fail(format!("{prefix}tags[{i}]"), reason);
            } else if self.tags[..i].contains(tag) {
                fail(format!("{prefix}tags[{i}]"), format!("repeats the tag \"{tag}\""));
            }
        }
        faults
    }

    /// The name as searched: folded to lower case.
    pub fn name_key(&self) -> Option<String> {
        self.name.as_deref().map(fold)
    }
}

/// `text` folded to lower case for the case-insensitive name search.
pub fn fold(text: &str) -> String {
    text.to_lowercase()
}

/// A `LIKE` pattern that matches names containing `needle` (folded), with `%`, `_` and the
/// escape character itself escaped by `\`.
pub fn contains_pattern(needle: &str) -> String {
    let mut pattern = String::with_capacity(needle.len() + 2);
    pattern.push('%');
    for c in fold(needle).chars() {
        if matches!(c, '%' | '_' | '\\') {
            pattern.push('\\');
        }
        pattern.push(c);
    }
    pattern.push('%');
    pattern
}

/// Takes the labels out of a submission's JSON object (the named endpoints' body), leaving
/// the kind's input; the faults of labels that do not even read (a name that is not text,
/// tags that are not a list of texts) are returned named.
pub fn take(body: &mut serde_json::Value) -> (JobLabels, Vec<FieldError>) {
    let Some(object) = body.as_object_mut() else {
        return (JobLabels::default(), Vec::new());
    };
    let mut faults = Vec::new();
    let name = match object.shift_remove("name") {
        None | Some(serde_json::Value::Null) => None,
        Some(serde_json::Value::String(name)) => Some(name),
        Some(other) => {
            faults.push(FieldError { field: "name".into(), reason: format!("must be text, got {other}") });
            None
        }
    };
    let tags = match object.shift_remove("tags") {
        None => Vec::new(),
        Some(serde_json::Value::Array(items)) => items
            .into_iter()
            .enumerate()
            .filter_map(|(i, item)| match item {
                serde_json::Value::String(tag) => Some(tag),
                other => {
                    faults
                        .push(FieldError { field: format!("tags[{i}]"), reason: format!("must be text, got {other}") });
                    None
                }
            })
            .collect(),
        Some(other) => {
            faults.push(FieldError { field: "tags".into(), reason: format!("must be a list of tags, got {other}") });
            Vec::new()
        }
    };
    (JobLabels { name, tags }, faults)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn fields(faults: &[FieldError]) -> Vec<&str> {
        faults.iter().map(|f| f.field.as_str()).collect()
    }

    #[test]
    fn a_name_and_tags_within_the_rules_have_no_fault() {
        let labels = JobLabels {
            name: Some("Die 4711 — cavité A".into()),
            tags: vec!["die:4711".into(), "a/b_c.d-e".into()],
        };
        assert!(labels.faults("").is_empty());
        assert_eq!(labels.name_key().as_deref(), Some("die 4711 — cavité a"));
    }

    #[test]
    fn every_fault_of_the_name_and_the_tags_is_named_at_once() {
        let mut tags: Vec<String> = (0..21).map(|i| format!("t{i}")).collect();
        tags[1] = "has space".into();
        tags[2] = "x".repeat(65);
        tags[3] = String::new();
        tags[4] = "t0".into();
        let labels = JobLabels { name: Some("n".repeat(201)), tags };
        let faults = labels.faults("input.");
        assert_eq!(
            fields(&faults),
            ["input.name", "input.tags", "input.tags[1]", "input.tags[2]", "input.tags[3]", "input.tags[4]"]
        );
        assert!(faults[2].reason.contains("' '"), "{}", faults[2].reason);
        let broken = JobLabels { name: Some("two\nlines".into()), tags: vec![] };
        assert_eq!(fields(&broken.faults("")), ["name"]);
    }

    #[test]
    fn labels_are_taken_out_of_a_body_and_faults_of_their_type_are_named() {
        let mut body = json!({"program": {"gcode": "G0 X0"}, "name": "a", "tags": ["x", 3]});
        assert_eq!(fields(&take(&mut json!({"tags": null})).1), ["tags"], "no tags is [], not null");
        let (labels, faults) = take(&mut body);
        assert_eq!(body, json!({"program": {"gcode": "G0 X0"}}));
        assert_eq!(labels, JobLabels { name: Some("a".into()), tags: vec!["x".into()] });
        assert_eq!(fields(&faults), ["tags[1]"]);
    }

    #[test]
    fn the_name_pattern_escapes_like_wildcards_and_folds_case() {
        assert_eq!(contains_pattern("A_b%\\"), "%a\\_b\\%\\\\%");
    }
}
