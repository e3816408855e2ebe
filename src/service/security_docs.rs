//! What the OpenAPI document says of keys, roles and rate limits: the bearer scheme, the
//! role each operation needs (as its security scope and in its description), and its
//! 401, 403 and 429 answers. Written from the same rule the middleware applies
//! ([`auth::required_role`]), so the two cannot disagree.

use crate::service::auth::{self, operations};
use crate::service::keys::model::Role;
use utoipa::openapi::path::Operation;
use utoipa::openapi::schema::{ObjectBuilder, Type};
use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityRequirement, SecurityScheme};
use utoipa::openapi::{ContentBuilder, HeaderBuilder, OpenApi, PathItem, Ref, ResponseBuilder};

/// The name of the security scheme in the document.
pub const SCHEME: &str = "apiKey";

/// Adds the security scheme and, to every `/v1` operation, its role and its 401, 403 and
/// 429 answers.
pub fn describe(doc: &mut OpenApi) {
    let scheme = HttpBuilder::new()
        .scheme(HttpAuthScheme::Bearer)
        .description(Some(
            "An API key (`dieplan keys create`, `POST /v1/keys` or `DIEPLAN_ADMIN_KEY`), sent as `Authorization: Bearer <key>`. Needed once any key exists; the scope is the least role the operation needs: reader < planner < admin.",
        ))
        .build();
    doc.components.get_or_insert_with(Default::default).add_security_scheme(SCHEME, SecurityScheme::Http(scheme));
    for (path, item) in doc.paths.paths.iter_mut() {
        let roles: Vec<_> = operations(item)
            .into_iter()
            .map(|(method, op)| {
                let tag = op.tags.as_ref().and_then(|t| t.first()).map(String::as_str);
                (method.clone(), auth::required_role(&method, path, tag))
            })
            .collect();
        for (method, role) in roles {
            if let (Some(role), Some(op)) = (role, operation_mut(item, &method)) {
                secure(op, role);
            }
        }
    }
}

fn operation_mut<'a>(item: &'a mut PathItem, method: &axum::http::Method) -> Option<&'a mut Operation> {
    use axum::http::Method;
    match *method {
        Method::GET => item.get.as_mut(),
        Method::POST => item.post.as_mut(),
        Method::PUT => item.put.as_mut(),
        Method::PATCH => item.patch.as_mut(),
        Method::DELETE => item.delete.as_mut(),
        Method::HEAD => item.head.as_mut(),
        _ => None,
    }
}

fn secure(op: &mut Operation, role: Role) {
    op.security = Some(vec![SecurityRequirement::new(SCHEME, [role.as_str()])]);
    let note = format!("Needs a key of role `{}` or above, once any key exists.", role.as_str());
    op.description = Some(match op.description.take() {
        Some(text) if !text.is_empty() => format!("{text}\n\n{note}"),
        _ => note,
    });
    let responses = &mut op.responses.responses;
    let mut unauthorized = problem("No key, or an unknown or revoked one", None);
    unauthorized.headers.insert(
        "WWW-Authenticate".into(),
        HeaderBuilder::new()
            .schema(ObjectBuilder::new().schema_type(Type::String))
            .description(Some("`Bearer`: send a key as `Authorization: Bearer <key>`"))
            .build(),
    );
    responses.insert("401".into(), unauthorized.into());
    if role > Role::Reader {
        responses.insert("403".into(), problem("The key's role may not do this", None).into());
    }
    let retry = HeaderBuilder::new()
        .schema(ObjectBuilder::new().schema_type(Type::Integer).minimum(Some(1)))
        .description(Some("Seconds until the key may make a request again"))
        .build();
    responses
        .insert("429".into(), problem("The key made more requests than its rate limit allows", Some(retry)).into());
}

/// A problem-document response, with `Retry-After` when given.
pub fn problem(description: &str, retry_after: Option<utoipa::openapi::Header>) -> utoipa::openapi::Response {
    let content = ContentBuilder::new().schema(Some(Ref::from_schema_name("Problem"))).build();
    let mut builder = ResponseBuilder::new().description(description).content("application/problem+json", content);
    if let Some(header) = retry_after {
        builder = builder.header("Retry-After", header);
    }
    builder.build()
}
