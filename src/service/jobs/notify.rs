//! Telling the other replicas on a PostgreSQL database what happened to jobs, at once,
//! with `LISTEN`/`NOTIFY`: a job was queued (idle workers everywhere look for it), a
//! running job's cancellation was asked for (the replica running it stops it), a job
//! finished (clients waiting for it on any replica are answered). Polling stays the
//! fallback: a lost notification delays, it never loses (workers look at the table every
//! few seconds, and the lease keeper reads cancellations every second).
//!
//! SQLite has one process: these are no-ops there.

use crate::service::store::{Backend, Pool};
use sqlx::postgres::PgListener;
use std::time::Duration;

/// The notification channels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event {
    /// A job was queued; the payload is its id.
    Queued,
    /// A client asked for a running job to stop; the payload is its id.
    CancelRequested,
    /// A job finished (succeeded, failed or was cancelled); the payload is its id.
    Finished,
}

impl Event {
    const ALL: [Event; 3] = [Event::Queued, Event::CancelRequested, Event::Finished];

    fn channel(self) -> &'static str {
        match self {
            Event::Queued => "dieplan_job_queued",
            Event::CancelRequested => "dieplan_job_cancel",
            Event::Finished => "dieplan_job_finished",
        }
    }

    fn of_channel(channel: &str) -> Option<Event> {
        Event::ALL.into_iter().find(|e| e.channel() == channel)
    }
}

/// How long the listener waits before connecting again after losing its connection.
const RECONNECT_DELAY: Duration = Duration::from_secs(1);

/// Tells the other replicas about `event` of job `id` (empty for [`Event::Queued`]) (PostgreSQL; nothing on SQLite).
/// A failure is logged: polling catches up.
pub async fn send(pool: &Pool, event: Event, id: &str) {
    if Backend::of(pool) != Backend::Postgres {
        return;
    }
    let sent = sqlx::query("SELECT 1 FROM (SELECT pg_notify($1, $2)) AS sent")
        .bind(event.channel())
        .bind(id)
        .execute(pool)
        .await;
    if let Err(e) = sent {
        tracing::warn!(error = %e, job = id, ?event, "could not notify the other replicas; they will poll");
    }
}

/// Listens to the events of every replica (PostgreSQL) and hands each to `on_event`, until
/// the task is aborted. `None` on SQLite.
pub fn listen(
    pool: &Pool,
    on_event: impl Fn(Event, &str) + Send + Sync + 'static,
) -> Option<tokio::task::JoinHandle<()>> {
    if Backend::of(pool) != Backend::Postgres {
        return None;
    }
    let url = pool.connect_options().database_url.to_string();
    Some(tokio::spawn(async move {
        loop {
            match listen_once(&url, &on_event).await {
                Ok(()) => return,
                Err(e) => {
                    tracing::warn!(error = %e, "lost the database's job notifications; listening again");
                    tokio::time::sleep(RECONNECT_DELAY).await;
                }
            }
        }
    }))
}

async fn listen_once(url: &str, on_event: &(impl Fn(Event, &str) + Send + Sync)) -> Result<(), sqlx::Error> {
    let mut listener = PgListener::connect(url).await?;
    listener.listen_all(Event::ALL.map(Event::channel)).await?;
    loop {
        let notification = listener.recv().await?;
        if let Some(event) = Event::of_channel(notification.channel()) {
            on_event(event, notification.payload());
        }
    }
}
