//! A small HTTP/1.1 client for the RWS protocol tests: one connection per request (so raw,
//! malformed requests are possible too), digest login with the `digest_auth` crate's client
//! side, cookies kept between requests. Every read is bounded by a time-out.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

/// A response.
#[derive(Debug)]
pub struct Resp {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Resp {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.text()))
    }
}

/// Send `bytes` on a fresh connection and read the answer until the server closes.
pub fn raw(addr: SocketAddr, bytes: &[u8]) -> std::io::Result<Resp> {
    let mut s = TcpStream::connect(addr)?;
    s.set_read_timeout(Some(Duration::from_secs(10)))?;
    s.set_write_timeout(Some(Duration::from_secs(10)))?;
    s.write_all(bytes)?;
    let mut buf = Vec::new();
    let _ = s.read_to_end(&mut buf);
    parse(&buf).ok_or_else(|| {
        std::io::Error::other(format!(
            "no HTTP response: {:?}",
            String::from_utf8_lossy(&buf)
        ))
    })
}

fn parse(buf: &[u8]) -> Option<Resp> {
    let end = buf.windows(4).position(|w| w == b"\r\n\r\n")?;
    let head = String::from_utf8_lossy(&buf[..end]).into_owned();
    let mut lines = head.split("\r\n");
    let status: u16 = lines.next()?.split(' ').nth(1)?.parse().ok()?;
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect();
    let mut body = buf[end + 4..].to_vec();
    let chunked = headers
        .iter()
        .any(|(k, v)| k.eq_ignore_ascii_case("transfer-encoding") && v.contains("chunked"));
    if chunked {
        let mut out = Vec::new();
        let mut rest = &body[..];
        while let Some(p) = rest.windows(2).position(|w| w == b"\r\n") {
            let n = usize::from_str_radix(String::from_utf8_lossy(&rest[..p]).trim(), 16).ok()?;
            if n == 0 {
                break;
            }
            out.extend_from_slice(rest.get(p + 2..p + 2 + n)?);
            rest = rest.get(p + 4 + n..)?;
        }
        body = out;
    }
    Some(Resp {
        status,
        headers,
        body,
    })
}

/// A client with an account and the cookies the server gave it.
pub struct Client {
    pub addr: SocketAddr,
    pub user: String,
    pub password: String,
    pub cookies: Vec<(String, String)>,
    /// Send credentials (after a challenge); off: cookies only.
    pub digest: bool,
}

impl Client {
    pub fn new(addr: SocketAddr, user: &str, password: &str) -> Client {
        Client {
            addr,
            user: user.into(),
            password: password.into(),
            cookies: Vec::new(),
            digest: true,
        }
    }

    fn send(&self, method: &str, path: &str, body: &[u8], auth: Option<&str>) -> Resp {
        let mut req = format!(
            "{method} {path} HTTP/1.1\r\nHost: {}\r\nConnection: close\r\nContent-Length: {}\r\n",
            self.addr,
            body.len()
        );
        if !body.is_empty() {
            req.push_str("Content-Type: application/x-www-form-urlencoded\r\n");
        }
        if !self.cookies.is_empty() {
            let c: Vec<String> = self
                .cookies
                .iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect();
            req.push_str(&format!("Cookie: {}\r\n", c.join("; ")));
        }
        if let Some(a) = auth {
            req.push_str(&format!("Authorization: {a}\r\n"));
        }
        req.push_str("\r\n");
        let mut bytes = req.into_bytes();
        bytes.extend_from_slice(body);
        raw(self.addr, &bytes).unwrap()
    }

    fn keep_cookies(&mut self, r: &Resp) {
        for (k, v) in &r.headers {
            if !k.eq_ignore_ascii_case("set-cookie") {
                continue;
            }
            let Some((name, val)) = v.split(';').next().and_then(|kv| kv.split_once('=')) else {
                continue;
            };
            self.cookies.retain(|(n, _)| n != name);
            if !val.is_empty() {
                self.cookies.push((name.to_string(), val.to_string()));
            }
        }
    }

    /// A request; on a 401 with a challenge, answer it once with the credentials.
    pub fn request(&mut self, method: &str, path: &str, body: &[u8]) -> Resp {
        let r = self.send(method, path, body, None);
        self.keep_cookies(&r);
        if r.status != 401 || !self.digest {
            return r;
        }
        let Some(ch) = r.header("www-authenticate").map(str::to_string) else {
            return r;
        };
        let auth = self.authorization(method, path, &ch);
        let r = self.send(method, path, body, Some(&auth));
        self.keep_cookies(&r);
        r
    }

    /// A request that carries credentials from the start (a fresh challenge is fetched
    /// without cookies first), together with the cookies held.
    pub fn request_signed(&mut self, method: &str, path: &str, body: &[u8]) -> Resp {
        let cookies = std::mem::take(&mut self.cookies);
        let ch = self.send(method, path, body, None);
        self.cookies = cookies;
        let ch = ch.header("www-authenticate").unwrap().to_string();
        let auth = self.authorization(method, path, &ch);
        self.send(method, path, body, Some(&auth))
    }

    /// The `Authorization` header answering a digest challenge for this request.
    fn authorization(&self, method: &str, path: &str, challenge: &str) -> String {
        let mut prompt = digest_auth::parse(challenge).unwrap();
        let ctx = digest_auth::AuthContext::new_with_method(
            self.user.as_str(),
            self.password.as_str(),
            path,
            None::<&[u8]>,
            digest_auth::HttpMethod(method.to_string().into()),
        );
        prompt.respond(&ctx).unwrap().to_header_string()
    }

    pub fn get(&mut self, path: &str) -> Resp {
        self.request("GET", path, b"")
    }

    pub fn post(&mut self, path: &str, form: &str) -> Resp {
        self.request("POST", path, form.as_bytes())
    }

    pub fn cookie(&self, name: &str) -> Option<&str> {
        self.cookies
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}
