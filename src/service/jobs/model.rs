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

    pub fn parse(text: &str) -> Option<JobKind> {
        [JobKind::Conditions, JobKind::Analysis, JobKind::Feeds, JobKind::Costing, JobKind::Trochoids, JobKind::Plan]
            .into_iter()
            .find(|k| k.as_str() == text)
    }
}

/// Links of a job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct JobLinks {
    /// This job.
    #[serde(rename = "self")]
    pub this: String,
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

/// A job with its input and, once finished, its result or error.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Job {
    pub id: String,
    pub kind: JobKind,
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
    /// The input as submitted.
    pub input: serde_json::Value,
    /// The result, when succeeded; its shape depends on `kind`.
    pub result: Option<serde_json::Value>,
    /// Why it failed.
    pub error: Option<Problem>,
    pub links: JobLinks,
}

/// A job without its input and result, as lists show it.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct JobSummary {
    pub id: String,
    pub kind: JobKind,
    pub status: JobStatus,
    pub progress: f64,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
    /// The id of the API key that created it; null when made without keys.
    pub key_id: Option<i64>,
    pub links: JobLinks,
}

impl From<Job> for JobSummary {
    fn from(job: Job) -> Self {
        JobSummary {
            id: job.id,
            kind: job.kind,
            status: job.status,
            progress: job.progress,
            created_at: job.created_at,
            started_at: job.started_at,
            finished_at: job.finished_at,
            key_id: job.key_id,
            links: job.links,
        }
    }
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
}

impl ProgramPart {
    pub fn as_str(self) -> &'static str {
        match self {
            ProgramPart::Main => "main",
            ProgramPart::Baseline => "baseline",
        }
    }
}
