//! The two representations of RWS 1.0 resources, built from one model.
//!
//! Every answer is a [`State`]: a list of [`Item`]s, each with ABB's `class` (`rap-task-li`),
//! a `title`, links and named fields. It renders as
//!
//! * **XHTML** (the default): `<div class="state">` with a `<ul>` of
//!   `<li class="…" title="…"><span class="field">value</span>…</li>`, as abb_librws reads it
//!   with an XML DOM parser (so the text is well-formed XML, every value escaped);
//! * **JSON** (`?json=1`, `Content-Type: application/json` exactly):
//!   `{"_links":{"base":{"href":…}},"_embedded":{"_state":[{"_type":"…","_title":"…",…}]}}`,
//!   as abb_robot_client reads it.
//!
//! Errors ([`RwsError`]) render as ABB's status body: `<div class="status"><span
//! class="code">…</span><span class="msg">…</span></div>`, or
//! `{"_embedded":{"status":{"code":…,"msg":"…"}}}`.

use std::fmt::Write as _;

use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::{Map, Value, json};

/// The content type of XHTML answers (RobotWare's own).
pub const XHTML: &str = "application/xhtml+xml;v=1.0";
/// The content type of JSON answers: exactly this, abb_robot_client compares it whole.
pub const JSON: &str = "application/json";

/// Which representation the client asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// XHTML (the default).
    Xhtml,
    /// JSON (`json=1`).
    Json,
}

/// A field value: text, or a list of small records (the event log's `argv`).
#[derive(Clone, Debug, PartialEq)]
pub enum FieldValue {
    /// Text (numbers too, as RobotWare writes them).
    Text(String),
    /// Nested items (configuration attributes, event arguments).
    Items(Vec<Item>),
}

/// One `<li>` / one element of `_state`.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// ABB's class (`_type`).
    pub class: String,
    /// The title attribute (`_title`).
    pub title: String,
    /// Links (`rel`, `href`).
    pub links: Vec<(String, String)>,
    /// Named fields in order.
    pub fields: Vec<(String, FieldValue)>,
}

impl Item {
    /// An item with a class and a title.
    pub fn new(class: &str, title: impl Into<String>) -> Item {
        Item {
            class: class.to_string(),
            title: title.into(),
            links: Vec::new(),
            fields: Vec::new(),
        }
    }

    /// Add a text field.
    pub fn field(mut self, name: &str, value: impl ToString) -> Item {
        self.fields
            .push((name.to_string(), FieldValue::Text(value.to_string())));
        self
    }

    /// Add a list of nested items.
    pub fn items(mut self, name: &str, items: Vec<Item>) -> Item {
        self.fields
            .push((name.to_string(), FieldValue::Items(items)));
        self
    }

    /// Add a link.
    pub fn link(mut self, rel: &str, href: impl Into<String>) -> Item {
        self.links.push((rel.to_string(), href.into()));
        self
    }
}

/// A whole answer.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// The XHTML `<title>` (`rapid`, `panel`, …).
    pub title: &'static str,
    /// The base the relative links are resolved against (`rw/rapid/`), below the server.
    pub base: String,
    /// The resource's own link, relative to `base`.
    pub self_href: String,
    /// The items.
    pub items: Vec<Item>,
}

impl State {
    /// A state of `items` under `base`.
    pub fn new(title: &'static str, base: &str, self_href: impl Into<String>) -> State {
        State {
            title,
            base: base.to_string(),
            self_href: self_href.into(),
            items: Vec::new(),
        }
    }

    /// Add an item.
    pub fn item(mut self, item: Item) -> State {
        self.items.push(item);
        self
    }

    /// Render for a client at `origin` (`http://host:port`).
    pub fn render(&self, format: Format, origin: &str) -> Response {
        let base = format!("{origin}/{}", self.base);
        match format {
            Format::Json => json_response(StatusCode::OK, self.json(&base)),
            Format::Xhtml => xhtml_response(StatusCode::OK, self.xhtml(&base)),
        }
    }

    fn json(&self, base: &str) -> Value {
        let state: Vec<Value> = self.items.iter().map(item_json).collect();
        json!({
            "_links": { "base": { "href": base } },
            "_embedded": { "_state": state },
        })
    }

    /// The XHTML document.
    pub fn xhtml(&self, base: &str) -> String {
        let mut out = page_head(self.title, base);
        out.push_str("<div class=\"state\">\n");
        let _ = writeln!(
            out,
            "<a href=\"{}\" rel=\"self\"></a>",
            esc(&self.self_href)
        );
        out.push_str("<ul>\n");
        for item in &self.items {
            item_xhtml(&mut out, item);
        }
        out.push_str("</ul>\n</div>\n</body>\n</html>\n");
        out
    }
}

fn page_head(title: &str, base: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<html xmlns=\"http://www.w3.org/1999/xhtml\">\n\
         <head>\n<title>{}</title>\n<base href=\"{}\"/>\n</head>\n<body>\n",
        esc(title),
        esc(base)
    )
}

fn item_json(item: &Item) -> Value {
    let mut m = Map::new();
    if !item.links.is_empty() {
        let mut links = Map::new();
        for (rel, href) in &item.links {
            links.insert(rel.clone(), json!({ "href": href }));
        }
        m.insert("_links".into(), Value::Object(links));
    }
    m.insert("_type".into(), Value::String(item.class.clone()));
    m.insert("_title".into(), Value::String(item.title.clone()));
    for (name, value) in &item.fields {
        let v = match value {
            FieldValue::Text(t) => Value::String(t.clone()),
            FieldValue::Items(items) => Value::Array(items.iter().map(item_json).collect()),
        };
        m.insert(name.clone(), v);
    }
    Value::Object(m)
}

/// One `<li>` on one line (subscription clients match a line with a regular expression).
pub fn item_xhtml(out: &mut String, item: &Item) {
    let _ = write!(
        out,
        "<li class=\"{}\" title=\"{}\">",
        esc(&item.class),
        esc(&item.title)
    );
    for (rel, href) in &item.links {
        let _ = write!(out, "<a href=\"{}\" rel=\"{}\"></a>", esc(href), esc(rel));
    }
    for (name, value) in &item.fields {
        match value {
            FieldValue::Text(t) => {
                let _ = write!(out, "<span class=\"{}\">{}</span>", esc(name), esc(t));
            }
            FieldValue::Items(items) => {
                let _ = write!(out, "<ul class=\"{}\">", esc(name));
                for i in items {
                    item_xhtml(out, i);
                }
                out.push_str("</ul>");
            }
        }
    }
    out.push_str("</li>\n");
}

/// Escape text for XML content and attributes.
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // XML 1.0 has no other control characters than tab, newline and return.
            c if (c as u32) < 0x20 && !matches!(c, '\t' | '\n' | '\r') => {
                let _ = write!(out, "&#xFFFD;");
            }
            c => out.push(c),
        }
    }
    out
}

fn json_response(status: StatusCode, body: Value) -> Response {
    (
        status,
        [(header::CONTENT_TYPE, HeaderValue::from_static(JSON))],
        body.to_string(),
    )
        .into_response()
}

fn xhtml_response(status: StatusCode, body: String) -> Response {
    (
        status,
        [(header::CONTENT_TYPE, HeaderValue::from_static(XHTML))],
        body,
    )
        .into_response()
}

/// An RWS error: the HTTP status, a controller return code and a message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RwsError {
    /// HTTP status.
    pub status: StatusCode,
    /// Controller return code (see [`codes`]).
    pub code: i64,
    /// What went wrong, for a person.
    pub msg: String,
}

/// The controller return codes rapidvc answers with. ABB publishes its table only as a
/// resource of a running controller; the one code a client checks (abb_robot_client:
/// "queue exists") is ABB's, the others are rapidvc's own, in the same format (negative
/// 32-bit numbers), listed in `docs/rws.md`.
pub mod codes {
    /// The external queue exists already (abb_robot_client checks this number).
    pub const DIPC_EXISTS: i64 = -1_073_445_879;
    /// No such resource (task, signal, symbol, file, …).
    pub const NOT_FOUND: i64 = -1_073_414_143;
    /// The request is malformed or a value does not fit.
    pub const BAD_VALUE: i64 = -1_073_414_142;
    /// Not allowed in the controller's state.
    pub const NOT_ALLOWED: i64 = -1_073_414_141;
    /// The controller does not answer (stopped or busy).
    pub const UNAVAILABLE: i64 = -1_073_414_140;
    /// Login required or failed.
    pub const UNAUTHORIZED: i64 = -1_073_414_139;
    /// The body is larger than allowed.
    pub const TOO_LARGE: i64 = -1_073_414_138;
    /// A limit (subscriptions, resources) is reached.
    pub const LIMIT: i64 = -1_073_414_137;
    /// The method is not served on this resource.
    pub const METHOD: i64 = -1_073_414_136;
    /// A feature of RWS that rapidvc does not serve.
    pub const UNSUPPORTED: i64 = -1_073_414_135;
}

impl RwsError {
    /// An error with status, code and message.
    pub fn new(status: StatusCode, code: i64, msg: impl Into<String>) -> RwsError {
        RwsError {
            status,
            code,
            msg: msg.into(),
        }
    }

    /// 400 with a message.
    pub fn bad(msg: impl Into<String>) -> RwsError {
        RwsError::new(StatusCode::BAD_REQUEST, codes::BAD_VALUE, msg)
    }

    /// 404 with a message.
    pub fn not_found(msg: impl Into<String>) -> RwsError {
        RwsError::new(StatusCode::NOT_FOUND, codes::NOT_FOUND, msg)
    }

    /// 400: a feature rapidvc does not serve, named.
    pub fn unsupported(what: impl std::fmt::Display) -> RwsError {
        RwsError::new(
            StatusCode::BAD_REQUEST,
            codes::UNSUPPORTED,
            format!("{what} is not supported by rapidvc"),
        )
    }

    /// 405 for `method` on `path`.
    pub fn method(method: &str, path: &str) -> RwsError {
        RwsError::new(
            StatusCode::METHOD_NOT_ALLOWED,
            codes::METHOD,
            format!("{method} is not served on {path}"),
        )
    }

    /// Render in `format`.
    pub fn render(&self, format: Format, origin: &str) -> Response {
        match format {
            Format::Json => json_response(
                self.status,
                json!({
                    "_links": { "base": { "href": format!("{origin}/") } },
                    "_embedded": { "status": { "code": self.code, "msg": self.msg } },
                }),
            ),
            Format::Xhtml => {
                let mut body = page_head("rw", &format!("{origin}/"));
                let _ = write!(
                    body,
                    "<div class=\"status\">\n<span class=\"code\">{}</span>\n\
                     <span class=\"msg\">{}</span>\n</div>\n</body>\n</html>\n",
                    self.code,
                    esc(&self.msg)
                );
                xhtml_response(self.status, body)
            }
        }
    }
}

impl From<crate::controller::service::ServiceError> for RwsError {
    fn from(e: crate::controller::service::ServiceError) -> RwsError {
        use crate::controller::service::ServiceError as E;
        let (status, code) = match &e {
            E::NotFound(_) => (StatusCode::NOT_FOUND, codes::NOT_FOUND),
            E::BadValue(_) => (StatusCode::BAD_REQUEST, codes::BAD_VALUE),
            E::NotAllowed(_) => (StatusCode::FORBIDDEN, codes::NOT_ALLOWED),
            E::Gone => (StatusCode::SERVICE_UNAVAILABLE, codes::UNAVAILABLE),
        };
        RwsError::new(status, code, e.to_string())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    fn sample() -> State {
        State::new("rapid", "rw/rapid/", "tasks").item(
            Item::new("rap-task-li", "T_ROB1")
                .link("self", "tasks/T_ROB1")
                .field("name", "T_ROB1")
                .field("motiontask", "TRUE")
                .field("note", "a<b & \"c\""),
        )
    }

    #[test]
    fn xhtml_has_abb_classes_and_escapes_values() {
        let x = sample().xhtml("http://h/rw/rapid/");
        assert!(x.starts_with("<?xml version=\"1.0\""));
        assert!(x.contains(
            "<li class=\"rap-task-li\" title=\"T_ROB1\"><a href=\"tasks/T_ROB1\" rel=\"self\"></a>\
             <span class=\"name\">T_ROB1</span><span class=\"motiontask\">TRUE</span>"
        ));
        assert!(x.contains("a&lt;b &amp; &quot;c&quot;"));
    }

    #[test]
    fn json_has_the_embedded_state_shape() {
        let j = sample().json("http://h/rw/rapid/");
        assert_eq!(j["_links"]["base"]["href"], "http://h/rw/rapid/");
        let s = &j["_embedded"]["_state"][0];
        assert_eq!(s["_type"], "rap-task-li");
        assert_eq!(s["_title"], "T_ROB1");
        assert_eq!(s["motiontask"], "TRUE");
        assert_eq!(s["_links"]["self"]["href"], "tasks/T_ROB1");
    }

    #[test]
    fn control_characters_never_break_the_xml() {
        assert_eq!(esc("a\u{1}b\tc"), "a&#xFFFD;b\tc");
    }
}
