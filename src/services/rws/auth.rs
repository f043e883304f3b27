//! Login to Robot Web Services: HTTP digest authentication (RFC 7616 / 2617, MD5, `qop=auth`)
//! and the sessions it opens.
//!
//! * **Challenge.** A request without a valid session cookie and without valid credentials
//!   gets `401` with `WWW-Authenticate: Digest realm="validusers@robapi.abb", qop="auth",
//!   nonce="…", algorithm=MD5, opaque="…"`. Nonces are stateless: the issue time and an MD5 tag
//!   keyed with a random per-server secret, so a flood of unauthenticated requests costs no
//!   memory. A nonce older than the nonce lifetime is answered with `stale=true` (clients
//!   retry at once without asking the user).
//! * **Verification.** The client's `Authorization` header is parsed and its digest recomputed
//!   by the `digest_auth` crate; user name, realm, `qop=auth`, the nonce's tag and age, and the
//!   `uri` (the request's path) are checked here, the digests compared in constant time.
//! * **Sessions.** A verified request opens a session and sets two cookies as a controller
//!   does: `-http-session-` and `ABBCX` (abb_robot_client sends `ABBCX` alone when it opens a
//!   subscription's WebSocket). Later requests with the `ABBCX` cookie need no credentials
//!   (abb_librws sends cookies only). Sessions are bounded in number: opening one more than
//!   the limit closes the least recently used (one with a connected subscription only when
//!   all have one); a session unused for the idle time ends. Wrong credentials are refused
//!   even together with a valid cookie.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use digest_auth::{AuthContext, AuthorizationHeader, HttpMethod};
use md5::{Digest, Md5};

/// The realm RobotWare's RWS 1.0 announces.
pub const REALM: &str = "validusers@robapi.abb";

/// The session cookie abb_robot_client reads by name.
pub const ABBCX: &str = "ABBCX";
/// The HTTP session cookie.
pub const HTTP_SESSION: &str = "-http-session-";

/// `n` random bytes from the operating system as lowercase hex.
pub fn random_hex(n: usize) -> String {
    let mut bytes = vec![0u8; n];
    // The OS generator failing is not something a server can carry on without; fall back to
    // the clock so the process stays up (the value is then guessable, which the error says).
    if getrandom::fill(&mut bytes).is_err() {
        let t = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0);
        for (i, b) in bytes.iter_mut().enumerate() {
            *b = (t >> ((i % 16) * 8)) as u8 ^ (i as u8);
        }
    }
    hex(&bytes)
}

fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 2);
    for b in bytes {
        s.push_str(&format!("{b:02x}"));
    }
    s
}

/// Compare two strings in time that depends only on their lengths.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

/// What the credentials of one request are worth.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Credentials {
    /// No `Authorization: Digest` header.
    Missing,
    /// Valid: user and password match, nonce fresh.
    Valid,
    /// Right password, but the nonce has expired: challenge again with `stale=true`.
    Stale,
    /// Wrong user, password, realm or a forged nonce.
    Invalid(String),
}

/// The digest side: the account, the nonce key and lifetime.
#[derive(Debug)]
pub struct Digester {
    user: String,
    password: String,
    secret: String,
    opaque: String,
    lifetime: Duration,
    start: Instant,
}

impl Digester {
    /// For the account `user`/`password`, nonces valid for `lifetime`.
    pub fn new(user: &str, password: &str, lifetime: Duration) -> Digester {
        Digester {
            user: user.to_string(),
            password: password.to_string(),
            secret: random_hex(32),
            opaque: random_hex(16),
            lifetime,
            start: Instant::now(),
        }
    }

    fn tag(&self, issued: u64) -> String {
        let mut h = Md5::new();
        h.update(self.secret.as_bytes());
        h.update(issued.to_be_bytes());
        hex(&h.finalize())
    }

    fn now_s(&self) -> u64 {
        self.start.elapsed().as_secs()
    }

    /// A fresh nonce: issue time (seconds since the server started) and its tag.
    pub fn nonce(&self) -> String {
        let issued = self.now_s();
        format!("{issued:016x}{}", self.tag(issued))
    }

    /// The `WWW-Authenticate` value of a challenge.
    pub fn challenge(&self, stale: bool) -> String {
        format!(
            "Digest realm=\"{REALM}\", qop=\"auth\", nonce=\"{}\", opaque=\"{}\", algorithm=MD5, stale={}",
            self.nonce(),
            self.opaque,
            if stale { "true" } else { "false" }
        )
    }

    /// Check an `Authorization` header of a request with `method` on `path` (the path without
    /// the query) and `path_and_query`.
    pub fn check(
        &self,
        header: Option<&str>,
        method: &str,
        path: &str,
        path_and_query: &str,
    ) -> Credentials {
        let Some(value) = header else {
            return Credentials::Missing;
        };
        if !value.trim_start().starts_with("Digest") {
            return Credentials::Missing;
        }
        let Ok(mut auth) = AuthorizationHeader::parse(value) else {
            return Credentials::Invalid("the Authorization header is not a valid digest".into());
        };
        if auth.username != self.user {
            return Credentials::Invalid(format!("unknown user `{}`", auth.username));
        }
        if auth.realm != REALM {
            return Credentials::Invalid(format!("wrong realm `{}`", auth.realm));
        }
        if auth.cnonce.is_none() || auth.qop.is_none() {
            return Credentials::Invalid("qop=auth with a cnonce is required".into());
        }
        // The uri must name this request (RFC 7616 3.4.6); clients differ on the query.
        let uri_path = auth.uri.split('?').next().unwrap_or("");
        if auth.uri != path_and_query && uri_path != path {
            return Credentials::Invalid(format!("the digest is for `{}`, not `{path}`", auth.uri));
        }
        let stale = match self.nonce_age(&auth.nonce) {
            Some(age) => age > self.lifetime.as_secs(),
            None => return Credentials::Invalid("the nonce was not issued by this server".into()),
        };
        let sent = std::mem::take(&mut auth.response);
        let ctx = AuthContext::new_with_method(
            self.user.as_str(),
            self.password.as_str(),
            auth.uri.clone(),
            None::<&[u8]>,
            HttpMethod(method.to_string().into()),
        );
        auth.digest(&ctx);
        if !same(
            &sent.to_ascii_lowercase(),
            &auth.response.to_ascii_lowercase(),
        ) {
            return Credentials::Invalid("wrong password".into());
        }
        if stale {
            Credentials::Stale
        } else {
            Credentials::Valid
        }
    }

    /// Seconds since `nonce` was issued, if it is one of ours.
    fn nonce_age(&self, nonce: &str) -> Option<u64> {
        let (time, tag) = (nonce.get(..16)?, nonce.get(16..)?);
        let issued = u64::from_str_radix(time, 16).ok()?;
        same(tag, &self.tag(issued)).then(|| self.now_s().saturating_sub(issued))
    }
}

/// One login.
#[derive(Clone, Debug)]
pub struct Session {
    /// The `-http-session-` cookie's value.
    pub http: String,
    /// When it was last used.
    pub last_used: Instant,
    /// WebSockets of its subscriptions open now.
    pub sockets: usize,
    /// Remote mastering (`users/rmmp`) granted: the privilege (`modify`, `exec`).
    pub rmmp: Option<String>,
    /// What `POST /users` registered: user name, application, location, locale.
    pub registered: Option<[String; 4]>,
}

/// Every session, by `ABBCX` value, bounded in number.
#[derive(Debug)]
pub struct Sessions {
    map: HashMap<String, Session>,
    max: usize,
    idle: Duration,
    /// Sessions opened since the start, and closed to make room.
    pub opened: u64,
    /// Sessions closed because the limit was reached.
    pub evicted: u64,
}

impl Sessions {
    /// At most `max` sessions (at least one), each ending after `idle` unused.
    pub fn new(max: usize, idle: Duration) -> Sessions {
        Sessions {
            map: HashMap::new(),
            max: max.max(1),
            idle,
            opened: 0,
            evicted: 0,
        }
    }

    /// How many are open.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// True when none is open.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// The session of cookie values `abbcx` (and `http`, when the client sent it), marked used.
    pub fn touch(&mut self, abbcx: &str, http: Option<&str>) -> Option<&mut Session> {
        let idle = self.idle;
        let s = self.map.get_mut(abbcx)?;
        if s.sockets == 0 && s.last_used.elapsed() > idle {
            return None;
        }
        if http.is_some_and(|h| !same(h, &s.http)) {
            return None;
        }
        s.last_used = Instant::now();
        Some(s)
    }

    /// The session `abbcx`, unchanged.
    pub fn get_mut(&mut self, abbcx: &str) -> Option<&mut Session> {
        self.map.get_mut(abbcx)
    }

    /// Open a session; returns its `ABBCX` and `-http-session-` values, and the session
    /// closed to make room, if any.
    pub fn open(&mut self) -> (String, String, Option<String>) {
        let mut evicted = None;
        if self.map.len() >= self.max {
            let victim = self
                .map
                .iter()
                .min_by_key(|(_, s)| (s.sockets > 0, s.last_used))
                .map(|(k, _)| k.clone());
            if let Some(k) = victim {
                self.map.remove(&k);
                self.evicted += 1;
                evicted = Some(k);
            }
        }
        let abbcx = random_hex(16);
        let http = random_hex(16);
        self.map.insert(
            abbcx.clone(),
            Session {
                http: http.clone(),
                last_used: Instant::now(),
                sockets: 0,
                rmmp: None,
                registered: None,
            },
        );
        self.opened += 1;
        (abbcx, http, evicted)
    }

    /// Close a session (logout).
    pub fn close(&mut self, abbcx: &str) -> bool {
        self.map.remove(abbcx).is_some()
    }

    /// Close every session idle too long (none with a connected subscription); returns them.
    pub fn sweep(&mut self) -> Vec<String> {
        let idle = self.idle;
        let gone: Vec<String> = self
            .map
            .iter()
            .filter(|(_, s)| s.sockets == 0 && s.last_used.elapsed() > idle)
            .map(|(k, _)| k.clone())
            .collect();
        for k in &gone {
            self.map.remove(k);
        }
        gone
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A client response computed by the crate's client side for `challenge`.
    fn respond(challenge: &str, user: &str, pw: &str, method: &str, uri: &str) -> String {
        let mut prompt = digest_auth::parse(challenge).unwrap();
        let ctx = AuthContext::new_with_method(
            user,
            pw,
            uri,
            None::<&[u8]>,
            HttpMethod(method.to_string().into()),
        );
        prompt.respond(&ctx).unwrap().to_header_string()
    }

    #[test]
    fn right_credentials_pass_and_wrong_ones_fail() {
        let d = Digester::new("Default User", "robotics", Duration::from_secs(60));
        let ch = d.challenge(false);
        let ok = respond(&ch, "Default User", "robotics", "GET", "/rw/system?json=1");
        assert_eq!(
            d.check(Some(&ok), "GET", "/rw/system", "/rw/system?json=1"),
            Credentials::Valid
        );
        let bad = respond(&ch, "Default User", "wrong", "GET", "/rw/system");
        assert!(matches!(
            d.check(Some(&bad), "GET", "/rw/system", "/rw/system"),
            Credentials::Invalid(m) if m.contains("password")
        ));
        let other = respond(&ch, "Admin", "robotics", "GET", "/rw/system");
        assert!(matches!(
            d.check(Some(&other), "GET", "/rw/system", "/rw/system"),
            Credentials::Invalid(_)
        ));
        // The digest covers the method and the uri.
        assert!(matches!(
            d.check(Some(&ok), "POST", "/rw/system", "/rw/system?json=1"),
            Credentials::Invalid(_)
        ));
        assert!(matches!(
            d.check(Some(&ok), "GET", "/rw/panel", "/rw/panel"),
            Credentials::Invalid(_)
        ));
        assert_eq!(d.check(None, "GET", "/", "/"), Credentials::Missing);
        assert_eq!(
            d.check(Some("Basic abc"), "GET", "/", "/"),
            Credentials::Missing
        );
    }

    #[test]
    fn forged_and_expired_nonces_are_told_apart() {
        let d = Digester::new("u", "p", Duration::from_secs(0));
        let ch = d.challenge(false);
        let forged = ch.replace(&d.nonce()[16..], &"0".repeat(32));
        let r = respond(&forged, "u", "p", "GET", "/x");
        assert!(matches!(
            d.check(Some(&r), "GET", "/x", "/x"),
            Credentials::Invalid(m) if m.contains("nonce")
        ));
        // Lifetime 0: a nonce from one second ago is stale, but the password is right.
        let old = format!("{:016x}{}", 0u64, d.tag(0));
        let ch_old = ch.replace(&d.nonce(), &old);
        let r = respond(&ch_old, "u", "p", "GET", "/x");
        std::thread::sleep(Duration::from_millis(1100));
        assert_eq!(d.check(Some(&r), "GET", "/x", "/x"), Credentials::Stale);
    }

    #[test]
    fn sessions_are_bounded_and_the_least_recently_used_goes_first() {
        let mut s = Sessions::new(3, Duration::from_secs(60));
        let (a, ah, _) = s.open();
        let (b, _, _) = s.open();
        let (c, _, _) = s.open();
        std::thread::sleep(Duration::from_millis(2));
        assert!(s.touch(&a, Some(&ah)).is_some());
        assert!(s.touch(&a, Some("forged")).is_none());
        s.get_mut(&b).unwrap().sockets = 1;
        let (_, _, gone) = s.open();
        assert_eq!(
            gone.as_deref(),
            Some(c.as_str()),
            "c: oldest without a socket"
        );
        assert_eq!(s.len(), 3);
        assert_eq!(s.evicted, 1);
        for _ in 0..1000 {
            s.open();
        }
        assert_eq!(s.len(), 3);
    }

    #[test]
    fn idle_sessions_end() {
        let mut s = Sessions::new(10, Duration::from_millis(0));
        let (a, _, _) = s.open();
        std::thread::sleep(Duration::from_millis(2));
        assert!(s.touch(&a, None).is_none());
        assert_eq!(s.sweep(), vec![a]);
        assert!(s.is_empty());
    }
}
