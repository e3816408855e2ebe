//! Generic create, read, update and delete over any [`Resource`] table.

use super::{ListFilter, Page, Record, Resource, SqlValue, DEFAULT_PAGE_LIMIT, MAX_PAGE_LIMIT};
use crate::service::error::{ApiError, Validator};
use crate::service::etag;
use crate::service::extract::from_value;
use crate::service::store::Row;
use crate::service::store::{numbered, Conn, Pool};
use serde_json::Value;

// Table and column names in generated SQL come from the `Resource` constants and the
// filters' fixed conditions, never from a client; every client value is bound.

/// Binds every value of a `&[SqlValue]` to a sqlx query builder, in order.
macro_rules! bind_values {
    ($query:expr, $values:expr) => {{
        let mut query = $query;
        for v in $values {
            query = match v {
                SqlValue::Int(i) => query.bind(*i),
                SqlValue::Real(f) => query.bind(*f),
                SqlValue::Text(s) => query.bind(s.as_str()),
                SqlValue::Null => query.bind(Option::<i64>::None),
            };
        }
        query
    }};
}

/// Lists the rows matching `filter`, one page.
pub async fn list<R: Record, F: ListFilter>(pool: &Pool, filter: &F) -> Result<Page<R>, ApiError> {
    let page = filter.page();
    let limit = page.limit.unwrap_or(DEFAULT_PAGE_LIMIT);
    let offset = page.offset.unwrap_or(0);
    let mut v = Validator::new();
    v.check((1..=MAX_PAGE_LIMIT).contains(&limit), "limit", format!("must be between 1 and {MAX_PAGE_LIMIT}"));
    v.check(offset >= 0, "offset", "must be >= 0");
    filter.validate(&mut v);
    if v.has_errors() {
        return Err(to_bad_query(v));
    }
    let conditions = filter.conditions();
    let where_sql = if conditions.is_empty() {
        String::new()
    } else {
        let parts: Vec<&str> = conditions.iter().map(|(sql, _)| sql.as_str()).collect();
        format!(" WHERE {}", parts.join(" AND "))
    };
    let values: Vec<SqlValue> = conditions.into_iter().flat_map(|(_, v)| v).collect();
    let table = R::Data::TABLE;

    let count_sql = format!("SELECT COUNT(*) FROM {table}{where_sql}");
    let total = bind_values!(sqlx::query_scalar::<_, i64>(numbered(&count_sql)), &values).fetch_one(pool).await?;

    let sql = format!("SELECT * FROM {table}{where_sql} ORDER BY id LIMIT ? OFFSET ?");
    let mut all = values.clone();
    all.push(SqlValue::Int(limit));
    all.push(SqlValue::Int(offset));
    let items = bind_values!(sqlx::query_as::<_, R>(numbered(&sql)), &all).fetch_all(pool).await?;
    Ok(Page { items, total, limit, offset })
}

fn to_bad_query(v: Validator) -> ApiError {
    match v.finish() {
        Err(ApiError::Validation(errors)) => ApiError::Status {
            status: axum::http::StatusCode::BAD_REQUEST,
            detail: errors
                .iter()
                .map(|e| format!("query parameter {}: {}", e.field, e.reason))
                .collect::<Vec<_>>()
                .join("; "),
        },
        other => other.err().unwrap_or_else(|| ApiError::BadRequest("invalid query".into())),
    }
}

/// Reads one row, or 404.
pub async fn get<R: Record>(pool: &Pool, id: i64) -> Result<R, ApiError> {
    fetch::<R>(&mut *pool.acquire().await?, id).await
}

async fn fetch<R: Record>(conn: &mut Conn, id: i64) -> Result<R, ApiError> {
    let sql = format!("SELECT * FROM {} WHERE id = ?", R::Data::TABLE);
    sqlx::query_as::<_, R>(numbered(&sql))
        .bind(id)
        .fetch_optional(conn)
        .await?
        .ok_or_else(|| ApiError::not_found(format!("no {} with id {id}", R::Data::SINGULAR)))
}

/// Validates `data` and the rows it references.
async fn check<D: Resource>(conn: &mut Conn, data: &D) -> Result<(), ApiError> {
    let mut v = Validator::new();
    data.validate(&mut v);
    for r in data.references() {
        let exists: Option<i64> = sqlx::query_scalar(numbered(&format!("SELECT id FROM {} WHERE id = ?", r.table)))
            .bind(r.id)
            .fetch_optional(&mut *conn)
            .await?;
        if exists.is_none() {
            v.fail(r.field, format!("no row with id {} in {}", r.id, r.table));
        }
    }
    v.finish()
}

// Write transactions are exclusive from their start (`store::begin_exclusive`): SQLite's
// write lock (a deferred transaction that reads first cannot upgrade its lock once another
// connection has written, and would fail at once with SQLITE_BUSY instead of waiting), and
// on PostgreSQL an advisory lock, so that no two replicas interleave a read-modify-write.

/// Inserts a validated row and returns it.
pub async fn create<R: Record>(pool: &Pool, data: R::Data) -> Result<R, ApiError> {
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    check(&mut tx, &data).await?;
    let columns = R::Data::COLUMNS;
    let placeholders = vec!["?"; columns.len()].join(", ");
    let sql = format!("INSERT INTO {} ({}) VALUES ({placeholders}) RETURNING id", R::Data::TABLE, columns.join(", "));
    let values = data.values();
    let row: Row = bind_values!(sqlx::query(numbered(&sql)), &values).fetch_one(&mut *tx).await?;
    let id: i64 = sqlx::Row::try_get(&row, "id")?;
    R::Data::after_write(&mut tx, id, None, &data).await?;
    let record = fetch::<R>(&mut tx, id).await?;
    tx.commit().await?;
    Ok(record)
}

/// Replaces a row's data; marks it edited so later migrations leave it alone. With
/// `if_match`, refuses (412) unless the row still has that entity tag; refused data is
/// told first (422), as it would be refused whatever the tag.
pub async fn replace<R: Record>(pool: &Pool, id: i64, data: R::Data, if_match: Option<&str>) -> Result<R, ApiError> {
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    let current = fetch::<R>(&mut tx, id).await?;
    check(&mut tx, &data).await?;
    etag::check(if_match, &current)?;
    let record = write::<R>(&mut tx, id, current.data(), data, Edit::Data).await?;
    tx.commit().await?;
    Ok(record)
}

/// Whether a write changes the row's data, or only its flags ([`Resource::FLAGS`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Edit {
    Data,
    FlagsOnly,
}

/// Writes a row's checked data inside the caller's write transaction and reads it back; a
/// write of its data marks it edited, so later migrations leave it alone.
async fn write<R: Record>(
    conn: &mut Conn,
    id: i64,
    before: &R::Data,
    data: R::Data,
    edit: Edit,
) -> Result<R, ApiError> {
    let sets: Vec<String> = R::Data::COLUMNS.iter().map(|c| format!("{c} = ?")).collect();
    let edited = if edit == Edit::Data { "edited = 1, " } else { "" };
    let sql = format!(
        "UPDATE {} SET {}, {edited}updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?",
        R::Data::TABLE,
        sets.join(", ")
    );
    let mut values = data.values();
    values.push(SqlValue::Int(id));
    bind_values!(sqlx::query(numbered(&sql)), &values).execute(&mut *conn).await?;
    R::Data::after_write(conn, id, Some(before), &data).await?;
    fetch::<R>(conn, id).await
}

/// Applies a JSON merge patch (RFC 7396) to a row's data. A patch that does not name
/// `source` marks the row as the shop's (`source = user`). The row is read, merged and
/// written in one write transaction, so two patches of different fields both land.
/// With `if_match`, refuses (412) unless the row still has that entity tag.
pub async fn patch<R: Record>(pool: &Pool, id: i64, patch: Value, if_match: Option<&str>) -> Result<R, ApiError> {
    if !patch.is_object() {
        return Err(ApiError::field("body", "a merge patch must be a JSON object"));
    }
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    let current = fetch::<R>(&mut tx, id).await?;
    let mut merged = serde_json::to_value(current.data()).map_err(|e| ApiError::Internal(e.to_string()))?;
    let named = |key: &str| patch.get(key).is_some();
    let edit = match patch.as_object() {
        Some(fields) if !fields.is_empty() && fields.keys().all(|k| R::Data::FLAGS.contains(&k.as_str())) => {
            Edit::FlagsOnly
        }
        _ => Edit::Data,
    };
    if !named("source") && edit == Edit::Data {
        merged["source"] = Value::from("user");
    }
    for flag in R::Data::FLAGS.iter().filter(|f| !named(f)) {
        if let Some(fields) = merged.as_object_mut() {
            fields.remove(*flag);
        }
    }
    let removed: Vec<String> =
        patch.as_object().into_iter().flatten().filter(|(_, v)| v.is_null()).map(|(k, _)| k.clone()).collect();
    merge(&mut merged, patch);
    let data: R::Data = from_value(merged).map_err(|e| required_not_removable(e, &removed))?;
    check(&mut tx, &data).await?;
    etag::check(if_match, &current)?;
    let record = write::<R>(&mut tx, id, current.data(), data, edit).await?;
    tx.commit().await?;
    Ok(record)
}

/// A patch that sets a required field to `null` (which removes it) is told so.
fn required_not_removable(error: ApiError, removed: &[String]) -> ApiError {
    match error {
        ApiError::Validation(errors) => ApiError::Validation(
            errors
                .into_iter()
                .map(|mut e| {
                    if removed.contains(&e.field) {
                        e.reason = "is required: a merge patch cannot remove it with null".to_string();
                    }
                    e
                })
                .collect(),
        ),
        other => other,
    }
}

/// RFC 7396 JSON merge patch.
fn merge(target: &mut Value, patch: Value) {
    match patch {
        Value::Object(entries) => {
            if !target.is_object() {
                *target = Value::Object(Default::default());
            }
            if let Value::Object(map) = target {
                for (key, value) in entries {
                    if value.is_null() {
                        map.remove(&key);
                    } else {
                        merge(map.entry(key).or_insert(Value::Null), value);
                    }
                }
            }
        }
        other => *target = other,
    }
}

/// Deletes a row, refusing with 409 while other rows still reference it. With
/// `if_match`, refuses (412) unless the row still has that entity tag.
pub async fn delete<R: Record>(pool: &Pool, id: i64, if_match: Option<&str>) -> Result<(), ApiError> {
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    let current = fetch::<R>(&mut tx, id).await?;
    etag::check(if_match, &current)?;
    let mut users = Vec::new();
    for (table, column, what) in R::Data::REFERENCED_BY {
        let n: i64 = sqlx::query_scalar(numbered(&format!("SELECT COUNT(*) FROM {table} WHERE {column} = ?")))
            .bind(id)
            .fetch_one(&mut *tx)
            .await?;
        if n > 0 {
            users.push(format!("{n} {what}"));
        }
    }
    if !users.is_empty() {
        return Err(ApiError::Conflict(format!(
            "{} {id} is still referenced by {}: delete or move those first",
            R::Data::SINGULAR,
            users.join(", ")
        )));
    }
    sqlx::query(numbered(&format!("DELETE FROM {} WHERE id = ?", R::Data::TABLE))).bind(id).execute(&mut *tx).await?;
    R::Data::after_delete(&mut tx, id, current.data()).await?;
    tx.commit().await?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::merge;
    use serde_json::json;

    #[test]
    fn a_merge_patch_replaces_named_fields_removes_nulls_and_keeps_the_rest() {
        let mut doc = json!({"a": 1, "b": {"c": 2, "d": 3}, "e": 4});
        merge(&mut doc, json!({"a": 9, "b": {"c": null}, "e": null}));
        assert_eq!(doc, json!({"a": 9, "b": {"d": 3}}));
    }
}
