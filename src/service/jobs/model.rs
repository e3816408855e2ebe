//! Jobs as the API shows them.

use crate::service::error::Problem;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Where a job is in its life.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum JobStatus {
    Queued,
    Running,
    Succeeded,
    Failed,
    Cancelled,
}

impl JobStatus {
    pub fn as_str(self) -> &'static str {
        match self {
            JobStatus::Queued => "queued",
            JobStatus::Running => "running",
            JobStatus::Succeeded => "succeeded",
            JobStatus::Failed => "failed",
            JobStatus::Cancelled => "cancelled",
        }
    }

    pub fn parse(text: &str) -> Option<JobStatus> {
        [JobStatus::Queued, JobStatus::Running, JobStatus::Succeeded, JobStatus::Failed, JobStatus::Cancelled]
            .into_iter()
            .find(|s| s.as_str() == text)
    }

    /// `true` once the job will not change any more.
    pub fn is_terminal(self) -> bool {
        matches!(self, JobStatus::Succeeded | JobStatus::Failed | JobStatus::Cancelled)
    }
}

/// What a job computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum JobKind {
    /// Recommended cutting conditions and the models' predictions for them
    /// (`POST /v1/conditions`).
    Conditions,
    /// Engagement, chip thickness, force and critical regions along a tool path
    /// (`POST /v1/analysis`).
    Analysis,
    /// Feeds optimised for a constant cutting-point feed or a constant force, written as
    /// an NC program (`POST /v1/feeds`).
    Feeds,
    /// Time, tool-life consumption and cost of an NC program (`POST /v1/costing`).
    Costing,
    /// Trochoid cycles and z-cut division inserted where a pocket's contour-parallel path
    /// overloads the tool (`POST /v1/trochoids`).
    Trochoids,
    /// The whole flow for a cavity: tool choice, layers, feeds, cost, tuning, baseline
    /// (`POST /v1/plans`).
    Plan,
}

impl JobKind {
    pub fn as_str(self) -> &'static str {
        match self {
            JobKind::Conditions => "conditions",
            JobKind::Analysis => "analysis",
            JobKind::Feeds => "feeds",
            JobKind::Costing => "costing",
            JobKind::Trochoids => "trochoids",
            JobKind::Plan => "plan",
        }
    }

    /// Every kind.
    pub const ALL: [JobKind; 6] =
        [JobKind::Conditions, JobKind::Analysis, JobKind::Feeds, JobKind::Costing, JobKind::Trochoids, JobKind::Plan];

    pub fn parse(text: &str) -> Option<JobKind> {
        JobKind::ALL.into_iter().find(|k| k.as_str() == text)
    }
}

/// A job's id as a path parameter or a field: a UUID, read in any case and with or
/// without hyphens, and kept in the hyphenated lower-case form jobs are stored under. A
/// malformed one is refused naming the field (`GET /v1/jobs/abc` is a 400 about `id`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, ToSchema)]
#[schema(value_type = String, format = "uuid", example = "0f8e9c3a-2b1d-4e5f-9a7b-6c5d4e3f2a10")]
pub struct JobId(String);

impl JobId {
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl std::ops::Deref for JobId {
    type Target = str;

    fn deref(&self) -> &str {
        &self.0
    }
}

impl std::fmt::Display for JobId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl<'de> Deserialize<'de> for JobId {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        uuid::Uuid::try_parse(&text).map(|id| JobId(id.hyphenated().to_string())).map_err(|_| {
            serde::de::Error::invalid_value(serde::de::Unexpected::Str(&text), &"a job id (a UUID, as in Location)")
        })
    }
}

/// Links of a job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct JobLinks {
    /// This job.
    #[serde(rename = "self")]
    pub this: String,
    /// Its input as submitted (`getJobInput`).
    pub input: String,
    /// The NC program, when the job produced one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub program: Option<String>,
    /// What can be drawn of the job (`getJobViews`), once it succeeded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub views: Option<String>,
    /// The plan view as SVG (`getJobDrawing`), once it succeeded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drawing: Option<String>,
}

/// A job and, once finished, its result or error (its input is at `links.input`).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Job {
    pub id: String,
    pub kind: JobKind,
    /// What the user called the job on submit, if anything.
    pub name: Option<String>,
    /// Its tags, in the order given on submit.
    pub tags: Vec<String>,
    pub status: JobStatus,
    /// Finished fraction, 0..1.
    pub progress: f64,
    /// How many times a worker has started it (a restart re-runs interrupted jobs).
    pub attempts: i64,
    /// A cancellation was asked for and the worker has not stopped yet.
    pub cancel_requested: bool,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
    pub updated_at: String,
    /// The id of the API key that created it; null when it was made while the service
    /// ran without keys.
    pub key_id: Option<i64>,
    /// Size of the input as submitted, bytes.
    pub input_bytes: i64,
    /// Size of the result, bytes, once succeeded.
    pub result_bytes: Option<i64>,
    /// Why it failed.
    pub error: Option<Problem>,
    pub links: JobLinks,
    /// The result, once succeeded (absent before); its shape depends on `kind`. Served as
    /// stored.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub result: Option<serde_json::Value>,
}

/// A job as lists show it: its row, without its input and result.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct JobSummary {
    pub id: String,
    pub kind: JobKind,
    /// What the user called the job on submit, if anything.
    pub name: Option<String>,
    /// Its tags, in the order given on submit.
    pub tags: Vec<String>,
    pub status: JobStatus,
    pub progress: f64,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
    /// The id of the API key that created it; null when made without keys.
    pub key_id: Option<i64>,
    /// The title of the problem of a failed job.
    pub error_title: Option<String>,
    /// Headline figures of a succeeded job's result: its numbers, short texts and flags at
    /// the top level and one level down (`totals.cost`), at most 32.
    pub summary: Option<serde_json::Value>,
    pub links: JobLinks,
}

/// Most figures in a job's [`JobSummary::summary`].
pub const MAX_HEADLINE_FIGURES: usize = 32;
/// Longest text kept in a summary, characters.
const MAX_HEADLINE_TEXT_CHARS: usize = 80;

/// The headline figures of a result: the numbers, short texts and flags of its top level
/// and of its objects one level down, keyed `name` and `object.name`, at most
/// [`MAX_HEADLINE_FIGURES`] (the top level first).
pub fn headline(result: &serde_json::Value) -> serde_json::Value {
    use serde_json::{Map, Value};
    let scalar = |v: &Value| match v {
        Value::Number(_) | Value::Bool(_) => true,
        Value::String(s) => s.chars().count() <= MAX_HEADLINE_TEXT_CHARS,
        _ => false,
    };
    let mut figures = Map::new();
    let Some(top) = result.as_object() else {
        return Value::Object(figures);
    };
    let first = top.iter().filter(|(_, v)| scalar(v)).map(|(k, v)| (k.clone(), v.clone()));
    let nested = top.iter().filter_map(|(k, v)| Some((k, v.as_object()?))).flat_map(|(k, inner)| {
        inner.iter().filter(|(_, v)| scalar(v)).map(move |(name, v)| (format!("{k}.{name}"), v.clone()))
    });
    figures.extend(first.chain(nested).take(MAX_HEADLINE_FIGURES));
    Value::Object(figures)
}

/// Which of a job's NC programs `GET /v1/jobs/{id}/program` serves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProgramPart {
    /// The program the job makes (feeds, trochoids, the plan's chosen tool).
    #[default]
    Main,
    /// A plan's conventional baseline: the R5 ball's thin contour-parallel levels.
    Baseline,
    /// The program a trochoids job changed: its base path (the program sent, or the
    /// generated contour-parallel path), whose lines the base path's overloads name.
    Base,
}

impl ProgramPart {
    pub fn as_str(self) -> &'static str {
        match self {
            ProgramPart::Main => "main",
            ProgramPart::Baseline => "baseline",
            ProgramPart::Base => "base",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_job_id_is_a_uuid_kept_hyphenated_in_lower_case_and_anything_else_is_refused() {
        let id: JobId = serde_json::from_value(json!("0F8E9C3A2B1D4E5F9A7B6C5D4E3F2A10")).unwrap();
        assert_eq!(id.as_str(), "0f8e9c3a-2b1d-4e5f-9a7b-6c5d4e3f2a10");
        let refused = serde_json::from_value::<JobId>(json!("abc")).unwrap_err().to_string();
        assert!(refused.contains("a job id"), "{refused}");
    }

    #[test]
    fn a_summary_keeps_the_short_figures_of_the_top_two_levels_and_no_lists() {
        let result = json!({"chosen_tool_id": 7, "name": "x".repeat(81), "totals": {"cost": 12.5, "ok": true,
            "layers": [1, 2]}, "candidates": [{"cost": 1}], "deep": {"a": {"b": 1}}});
        assert_eq!(headline(&result), json!({"chosen_tool_id": 7, "totals.cost": 12.5, "totals.ok": true}));
        let wide: serde_json::Map<String, serde_json::Value> = (0..50).map(|i| (format!("f{i}"), json!(i))).collect();
        assert_eq!(headline(&serde_json::Value::Object(wide)).as_object().map(|m| m.len()), Some(MAX_HEADLINE_FIGURES));
    }
}
