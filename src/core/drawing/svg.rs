//! A tiny SVG writer: elements appended to a `String` with `std::fmt::Write`, numbers in
//! a fixed number of decimals and text XML-escaped, so the output is deterministic and
//! well-formed.

use std::fmt::{self, Write};

/// Decimals of coordinates and lengths (px).
pub const DECIMALS: usize = 2;
/// The SVG namespace.
const SVG_NS: &str = "http://www.w3.org/2000/svg";
/// The font of all text.
pub const FONT_FAMILY: &str = "DejaVu Sans, Arial, Helvetica, sans-serif";

/// A number written with [`DECIMALS`] decimals (`-0.00` written `0.00`, non-finite as 0).
#[derive(Debug, Clone, Copy)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = if self.0.is_finite() { self.0 } else { 0.0 };
        let half_unit = 0.5 * 10f64.powi(-(DECIMALS as i32));
        let v = if v.abs() < half_unit { 0.0 } else { v };
        write!(f, "{v:.DECIMALS$}")
    }
}

/// `text` with `& < > " '` escaped, for text content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Control characters are not allowed in XML 1.0.
            c if (c as u32) < 0x20 && !matches!(c, '\t' | '\n' | '\r') => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Attributes of one element, written in the order they are added.
#[derive(Debug, Clone, Default)]
pub struct Attrs(String);

impl Attrs {
    pub fn new() -> Attrs {
        Attrs(String::new())
    }

    /// `class="…"`.
    pub fn class(self, class: &str) -> Attrs {
        self.str("class", class)
    }

    /// A text attribute (escaped).
    pub fn str(mut self, name: &str, value: &str) -> Attrs {
        let _ = write!(self.0, " {name}=\"{}\"", escape(value));
        self
    }

    /// A numeric attribute in fixed decimals.
    pub fn num(mut self, name: &str, value: f64) -> Attrs {
        let _ = write!(self.0, " {name}=\"{}\"", Num(value));
        self
    }

    /// An attribute whose value is displayed as is (colours, integers).
    pub fn show(mut self, name: &str, value: impl fmt::Display) -> Attrs {
        let _ = write!(self.0, " {name}=\"{}\"", escape(&value.to_string()));
        self
    }
}

impl fmt::Display for Attrs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Horizontal anchoring of text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn as_str(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// An SVG document being written.
#[derive(Debug)]
pub struct Svg {
    out: String,
    open_groups: usize,
}

impl Svg {
    /// Opens a document of `width` × `height` px (its `viewBox` the same), with a `<title>`.
    pub fn new(width: f64, height: f64, title: &str, class: &str) -> Svg {
        let mut out = String::with_capacity(16 * 1024);
        let _ = write!(
            out,
            "<svg xmlns=\"{SVG_NS}\" class=\"{}\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" \
             font-family=\"{FONT_FAMILY}\">\n<title>{}</title>\n",
            escape(class),
            escape(title),
            w = Num(width),
            h = Num(height),
        );
        Svg { out, open_groups: 0 }
    }

    /// A fragment: elements without the document's header, to be inserted into a
    /// document with [`Svg::insert`] (e.g. drawn before the document's size is known).
    pub fn fragment() -> Svg {
        Svg { out: String::with_capacity(16 * 1024), open_groups: 0 }
    }

    /// Inserts a fragment finished with [`Svg::finish_fragment`].
    pub fn insert(&mut self, fragment: &str) {
        self.out.push_str(fragment);
    }

    /// Closes the open groups of a fragment and returns its elements.
    pub fn finish_fragment(mut self) -> String {
        while self.open_groups > 0 {
            self.end_group();
        }
        self.out
    }

    /// Bytes written so far.
    pub fn len(&self) -> usize {
        self.out.len()
    }

    /// Whether nothing has been written (never: the header is written at once).
    pub fn is_empty(&self) -> bool {
        self.out.is_empty()
    }

    /// Opens a `<g>`.
    pub fn group(&mut self, attrs: Attrs) {
        let _ = writeln!(self.out, "<g{attrs}>");
        self.open_groups += 1;
    }

    /// Closes the last `<g>`.
    pub fn end_group(&mut self) {
        if self.open_groups > 0 {
            self.out.push_str("</g>\n");
            self.open_groups -= 1;
        }
    }

    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, attrs: Attrs) {
        let _ = writeln!(
            self.out,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{attrs}/>",
            Num(x),
            Num(y),
            Num(w.max(0.0)),
            Num(h.max(0.0))
        );
    }

    pub fn line(&mut self, from: (f64, f64), to: (f64, f64), attrs: Attrs) {
        let _ = writeln!(
            self.out,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"{attrs}/>",
            Num(from.0),
            Num(from.1),
            Num(to.0),
            Num(to.1)
        );
    }

    pub fn circle(&mut self, center: (f64, f64), r: f64, attrs: Attrs) {
        let _ =
            writeln!(self.out, "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{attrs}/>", Num(center.0), Num(center.1), Num(r));
    }

    /// An open polyline through `points`.
    pub fn polyline(&mut self, points: impl IntoIterator<Item = (f64, f64)>, attrs: Attrs) {
        self.poly("polyline", points, attrs);
    }

    /// A closed polygon through `points`.
    pub fn polygon(&mut self, points: impl IntoIterator<Item = (f64, f64)>, attrs: Attrs) {
        self.poly("polygon", points, attrs);
    }

    fn poly(&mut self, tag: &str, points: impl IntoIterator<Item = (f64, f64)>, attrs: Attrs) {
        let _ = write!(self.out, "<{tag} points=\"");
        for (i, (x, y)) in points.into_iter().enumerate() {
            let sep = if i == 0 { "" } else { " " };
            let _ = write!(self.out, "{sep}{},{}", Num(x), Num(y));
        }
        let _ = writeln!(self.out, "\"{attrs}/>");
    }

    /// A `<path>` whose `d` is built by [`PathData`].
    pub fn path(&mut self, d: &PathData, attrs: Attrs) {
        let _ = writeln!(self.out, "<path d=\"{}\"{attrs}/>", d.0);
    }

    /// Text at `at` (baseline), escaped.
    pub fn text(&mut self, at: (f64, f64), size: f64, anchor: Anchor, text: &str, attrs: Attrs) {
        let _ = writeln!(
            self.out,
            "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"{}\"{attrs}>{}</text>",
            Num(at.0),
            Num(at.1),
            Num(size),
            anchor.as_str(),
            escape(text)
        );
    }

    /// Closes the open groups and the document.
    pub fn finish(mut self) -> String {
        while self.open_groups > 0 {
            self.end_group();
        }
        self.out.push_str("</svg>\n");
        self.out
    }
}

/// The `d` attribute of a path: subpaths of straight segments.
#[derive(Debug, Clone, Default)]
pub struct PathData(String);

impl PathData {
    pub fn new() -> PathData {
        PathData(String::new())
    }

    /// Starts a subpath at `p`.
    pub fn move_to(&mut self, p: (f64, f64)) {
        let sep = if self.0.is_empty() { "" } else { " " };
        let _ = write!(self.0, "{sep}M{} {}", Num(p.0), Num(p.1));
    }

    /// A straight segment to `p`.
    pub fn line_to(&mut self, p: (f64, f64)) {
        let _ = write!(self.0, " L{} {}", Num(p.0), Num(p.1));
    }

    /// A zero-length segment: a dot with round caps (a lone point of a series).
    pub fn dot(&mut self) {
        self.0.push_str(" l0 0");
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// Approximate width of `text` at `size` px (for layout: 0.6 em per character).
pub fn text_width(text: &str, size: f64) -> f64 {
    const EM_PER_CHAR: f64 = 0.6;
    text.chars().count() as f64 * size * EM_PER_CHAR
}

/// Test helper: checks that `svg` is well-formed XML as this writer produces it (tags
/// balanced, attributes quoted, `<` and `&` only as markup or entities).
#[cfg(test)]
pub(crate) fn check_well_formed(svg: &str) -> Result<(), String> {
    let mut stack: Vec<String> = Vec::new();
    let mut rest = svg;
    let entity_ok = |s: &str| {
        let mut parts = s.split('&');
        parts.next();
        parts.all(|p| ["amp;", "lt;", "gt;", "quot;", "apos;"].iter().any(|e| p.starts_with(e)))
    };
    while let Some(open) = rest.find('<') {
        let text = &rest[..open];
        if text.contains('>') || !entity_ok(text) {
            return Err(format!("bad text {text:?}"));
        }
        let close = rest[open..].find('>').ok_or("unclosed tag")? + open;
        let tag = &rest[open + 1..close];
        rest = &rest[close + 1..];
        if tag.contains('<') || !tag.matches('"').count().is_multiple_of(2) || !entity_ok(tag) {
            return Err(format!("bad tag {tag:?}"));
        }
        if let Some(name) = tag.strip_prefix('/') {
            match stack.pop() {
                Some(open_name) if open_name == name => {}
                other => return Err(format!("</{name}> closes {other:?}")),
            }
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap_or("").to_string());
        }
        if stack.is_empty() && !rest.trim().is_empty() {
            return Err("content after the root".into());
        }
    }
    if stack.is_empty() {
        Ok(())
    } else {
        Err(format!("unclosed {stack:?}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_a_fixed_number_of_decimals() {
        assert_eq!(Num(1.0).to_string(), "1.00");
        assert_eq!(Num(2.345_678).to_string(), "2.35");
        assert_eq!(Num(-0.001).to_string(), "0.00");
        assert_eq!(Num(f64::NAN).to_string(), "0.00");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\" > 'd'"), "a&lt;b &amp; &quot;c&quot; &gt; &apos;d&apos;");
    }

    #[test]
    fn a_document_is_well_formed_and_deterministic() {
        let draw = || {
            let mut svg = Svg::new(100.0, 50.0, "a <title> & more", "test");
            svg.group(Attrs::new().class("g").str("data-name", "x&y"));
            svg.rect(0.0, 0.0, 10.0, 5.0, Attrs::new().show("fill", "#ffffff"));
            svg.polyline([(0.0, 0.0), (1.0, 2.0)], Attrs::new().class("p"));
            let mut d = PathData::new();
            d.move_to((1.0, 1.0));
            d.line_to((2.0, 3.0));
            svg.path(&d, Attrs::new());
            svg.text((5.0, 5.0), 12.0, Anchor::Middle, "α < 40° & ok", Attrs::new());
            svg.finish()
        };
        let out = draw();
        assert_eq!(out, draw());
        check_well_formed(&out).unwrap();
        assert!(out.contains("viewBox=\"0 0 100.00 50.00\""));
        assert!(out.contains("<title>a &lt;title&gt; &amp; more</title>"));
        assert!(out.contains("α &lt; 40° &amp; ok"));
    }

    #[test]
    fn the_checker_rejects_unbalanced_tags_and_raw_ampersands() {
        assert!(check_well_formed("<svg><g></svg>").is_err());
        assert!(check_well_formed("<svg><text>a & b</text></svg>").is_err());
        assert!(check_well_formed("<svg><text>a &amp; b</text></svg>").is_ok());
    }
}
