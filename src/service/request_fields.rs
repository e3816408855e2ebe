//! The request's names of the core's fields, in one table: a core error names the field
//! of the core's input it refuses (`z_bottom_mm` of an insertion spec); the problem sent
//! to the client names the request's field that set it (`z_bottom`).

/// `(core's name, request's name)`, matched against the last segment of a field path
/// (`layers[2].z_bottom_mm` is `layers[2].z_bottom`). Only the core's errors pass through
/// it: the service's own checks name the request's fields (`program.safe_z_mm` is the
/// program options' own name).
const REQUEST_NAMES: [(&str, &str); 3] = [("z_top_mm", "z_top"), ("z_bottom_mm", "z_bottom"), ("safe_z_mm", "safe_z")];

/// The request's name of the core's field `path`.
pub fn request_field(path: &str) -> String {
    let (parent, last) = match path.rsplit_once('.') {
        Some((parent, last)) => (Some(parent), last),
        None => (None, path),
    };
    match REQUEST_NAMES.iter().find(|(core, _)| *core == last) {
        Some((_, request)) => parent.map_or_else(|| request.to_string(), |p| format!("{p}.{request}")),
        None => path.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::request_field;

    #[test]
    fn a_core_field_is_named_as_the_request_names_it_at_any_depth() {
        assert_eq!(request_field("z_bottom_mm"), "z_bottom");
        assert_eq!(request_field("safe_z_mm"), "safe_z");
        assert_eq!(request_field("layers[2].z_top_mm"), "layers[2].z_top");
        assert_eq!(request_field("alpha_limit_deg"), "alpha_limit_deg");
        assert_eq!(request_field("contour.outer[3]"), "contour.outer[3]");
    }
}
