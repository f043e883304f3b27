//! Robot Web Services 1.0 (RobotWare 6) over plain HTTP, as on an IRC5: the REST resources
//! and WebSocket subscriptions that abb_robot_client, abb_librws and the ROS drivers use,
//! answered from a running controller through its [`ServiceHandle`].
//!
//! * [`router`] builds the axum `Router` (every resource behind digest login and the session
//!   cookie); a caller may nest more routes into it afterwards, for example the live view
//!   under `/view` (`router(h, o).nest("/view", live::router(session))`), which then stays
//!   outside the login.
//! * [`RwsServer::start`] runs a router on its own thread and tokio runtime, bounded in
//!   connections; [`bind`] picks the address (127.0.0.1:80 as on a controller's default,
//!   127.0.0.1:8080 when port 80 is not allowed).
//!
//! The resource families live in one file each below `rws/`: `execution.rs` (execution,
//! tasks, modules), `panel.rs`, `iosystem.rs`, `symbols.rs` (RAPID data, properties, search),
//! `fileservice.rs` (and `ctrl/$RAMDISK`), `elog.rs`, `motion.rs` (mechanical units,
//! joint and robot targets), `system.rs` (`rw/system`, `ctrl`, `rw/cfg`), `users.rs`
//! (`users`, `users/rmmp`, `rw/dipc`, `logout`) and `subscription.rs`; `auth.rs` holds login
//! and sessions, `repr.rs` the XHTML and JSON representations. `docs/rws.md` lists every
//! resource with the client that uses it, the limits and the choices made where ABB
//! documents nothing.

pub mod auth;
mod elog;
mod execution;
mod fileservice;
mod iosystem;
mod motion;
mod panel;
pub mod repr;
mod subscription;
mod symbols;
mod system;
mod users;

use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::{Arc, Mutex, MutexGuard};
use std::task::{Context, Poll};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use axum::Router;
use axum::body::{Body, Bytes};
use axum::extract::{Request, State as AxState};
use axum::http::{HeaderMap, HeaderValue, Method, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::sync::{OwnedSemaphorePermit, Semaphore, oneshot};

use crate::controller::service::{Reply, Request as CtrlRequest, ServiceHandle};
use auth::{Credentials, Digester, Sessions};
use repr::{Format, RwsError, State};

/// What a remote mastering request (`users/rmmp`) gets: a headless controller has no
/// FlexPendant user to ask.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RmmpPolicy {
    /// Granted at once (the default: as if the pendant user said yes).
    #[default]
    Grant,
    /// Refused at once (as if the pendant user said no).
    Deny,
}

/// Settings of the RWS server. [`RwsOptions::default`] gives the values documented in
/// `docs/rws.md`.
#[derive(Clone, Debug)]
pub struct RwsOptions {
    /// The account's user name (`Default User`).
    pub user: String,
    /// The account's password (`robotics`).
    pub password: String,
    /// Most sessions open at once; one more closes the least recently used.
    pub max_sessions: usize,
    /// A session unused this long ends.
    pub session_idle: Duration,
    /// A digest nonce is fresh this long (then `stale=true`).
    pub nonce_lifetime: Duration,
    /// Most subscriptions at once (all sessions).
    pub max_subscriptions: usize,
    /// Most resources in one subscription.
    pub max_subscription_resources: usize,
    /// A subscription without a connected WebSocket this long is removed.
    pub subscription_unclaimed: Duration,
    /// A WebSocket frame the client does not take within this time closes the socket.
    pub send_timeout: Duration,
    /// Largest request body (forms) in bytes.
    pub max_body: usize,
    /// Largest file upload (`PUT fileservice/…`) in bytes.
    pub max_upload: usize,
    /// Most TCP connections served at once; more wait in the listen queue.
    pub max_connections: usize,
    /// How long a request waits for the controller's answer (then 503).
    pub controller_timeout: Duration,
    /// Remote mastering requests.
    pub rmmp: RmmpPolicy,
}

impl Default for RwsOptions {
    fn default() -> RwsOptions {
        RwsOptions {
            user: "Default User".into(),
            password: "robotics".into(),
            max_sessions: 70,
            session_idle: Duration::from_secs(15 * 60),
            nonce_lifetime: Duration::from_secs(300),
            max_subscriptions: 64,
            max_subscription_resources: 100,
            subscription_unclaimed: Duration::from_secs(60),
            send_timeout: Duration::from_secs(5),
            max_body: 64 * 1024,
            max_upload: 16 * 1024 * 1024,
            max_connections: 256,
            controller_timeout: Duration::from_secs(10),
            rmmp: RmmpPolicy::Grant,
        }
    }
}

/// Sessions and subscriptions, behind one lock that is never held across an await.
#[derive(Debug)]
struct Registry {
    sessions: Sessions,
    subs: subscription::Subscriptions,
    last_sweep: Instant,
}

/// What every request handler shares.
#[derive(Debug)]
struct Shared {
    handle: ServiceHandle,
    opts: RwsOptions,
    digester: Digester,
    registry: Mutex<Registry>,
    uploads: Arc<Semaphore>,
}

impl Shared {
    fn registry(&self) -> MutexGuard<'_, Registry> {
        // A handler that panicked while holding the lock left consistent maps behind (each
        // change is one insert or remove): keep serving.
        self.registry
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Ask the controller, bounded by the controller time-out.
    async fn ask<T>(&self, make: impl FnOnce(Reply<T>) -> CtrlRequest) -> Result<T, RwsError> {
        match tokio::time::timeout(self.opts.controller_timeout, self.handle.ask(make)).await {
            Ok(r) => r.map_err(RwsError::from),
            Err(_) => Err(RwsError::new(
                StatusCode::SERVICE_UNAVAILABLE,
                repr::codes::UNAVAILABLE,
                format!(
                    "the controller did not answer within {} s",
                    self.opts.controller_timeout.as_secs_f64()
                ),
            )),
        }
    }

    /// Close sessions idle too long and subscriptions nobody claimed, at most once a second.
    fn sweep(&self) {
        let mut reg = self.registry();
        if reg.last_sweep.elapsed() < Duration::from_secs(1) {
            return;
        }
        reg.last_sweep = Instant::now();
        let gone = reg.sessions.sweep();
        let unclaimed = self.opts.subscription_unclaimed;
        for s in gone {
            reg.subs.close_session(&s);
        }
        reg.subs.sweep(unclaimed);
    }
}

/// One parsed request, as the resource handlers see it.
#[derive(Debug)]
struct Rq {
    method: Method,
    /// Percent-decoded path segments, empty ones dropped.
    segs: Vec<String>,
    /// The path as sent (for messages).
    path: String,
    query: Vec<(String, String)>,
    form: Vec<(String, String)>,
    body: Bytes,
    format: Format,
    /// `http://host:port` as the client addressed us.
    origin: String,
    /// The session's `ABBCX` value.
    session: String,
}

impl Rq {
    fn query(&self, key: &str) -> Option<&str> {
        self.query
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    fn action(&self) -> Option<&str> {
        self.query("action")
    }

    fn form(&self, key: &str) -> Option<&str> {
        self.form
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// A form field the request must have.
    fn need(&self, key: &str) -> Result<&str, RwsError> {
        self.form(key)
            .ok_or_else(|| RwsError::bad(format!("the form field `{key}` is missing")))
    }

    fn method_error(&self) -> RwsError {
        RwsError::method(self.method.as_str(), &self.path)
    }

    fn unknown_action(&self) -> RwsError {
        match self.action() {
            Some(a) => RwsError::bad(format!("unknown action `{a}` on {}", self.path)),
            None => self.method_error(),
        }
    }
}

/// What a handler answers.
#[derive(Debug)]
enum Answer {
    /// 200 with a state.
    Ok(State),
    /// 204.
    NoContent,
    /// A finished response (files, WebSocket, …).
    Raw(Response),
}

type Outcome = Result<Answer, RwsError>;

/// The RWS routes for `handle`, every one behind login. More routes may be nested into the
/// result afterwards (they are then outside the login).
pub fn router(handle: ServiceHandle, options: RwsOptions) -> Router {
    let digester = Digester::new(&options.user, &options.password, options.nonce_lifetime);
    let shared = Arc::new(Shared {
        handle,
        registry: Mutex::new(Registry {
            sessions: Sessions::new(options.max_sessions, options.session_idle),
            subs: subscription::Subscriptions::new(options.max_subscriptions),
            last_sweep: Instant::now(),
        }),
        digester,
        uploads: Arc::new(Semaphore::new(4)),
        opts: options,
    });
    Router::new()
        .route("/poll/{id}", get(subscription::poll))
        .fallback(dispatch)
        .layer(middleware::from_fn_with_state(shared.clone(), login))
        .with_state(shared)
}

/// `http://host:port` from the Host header (checked), or `http://localhost`.
fn origin(headers: &HeaderMap) -> String {
    let host = headers
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .filter(|h| {
            !h.is_empty()
                && h.len() <= 255
                && h.bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b"-.:[]_".contains(&b))
        })
        .unwrap_or("localhost");
    format!("http://{host}")
}

fn wants_json(query: Option<&str>) -> Format {
    let json = query.is_some_and(|q| {
        form_urlencoded::parse(q.as_bytes()).any(|(k, v)| k == "json" && v == "1")
    });
    if json { Format::Json } else { Format::Xhtml }
}

fn cookie<'h>(headers: &'h HeaderMap, name: &str) -> Option<&'h str> {
    headers
        .get_all(header::COOKIE)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(';'))
        .filter_map(|kv| kv.trim().split_once('='))
        .find(|(k, _)| *k == name)
        .map(|(_, v)| v.trim_matches('"'))
}

/// The session a request belongs to (its `ABBCX` value), found by the login middleware.
#[derive(Clone, Debug)]
struct SessionId(String);

/// The login middleware: a valid session cookie or valid digest credentials, else 401.
async fn login(AxState(shared): AxState<Arc<Shared>>, mut req: Request, next: Next) -> Response {
    shared.sweep();
    let format = wants_json(req.uri().query());
    let origin = origin(req.headers());
    let path = req.uri().path().to_string();
    let pq = req
        .uri()
        .path_and_query()
        .map(|p| p.as_str().to_string())
        .unwrap_or_else(|| path.clone());
    let creds = shared.digester.check(
        req.headers()
            .get(header::AUTHORIZATION)
            .and_then(|v| v.to_str().ok()),
        req.method().as_str(),
        &path,
        &pq,
    );
    let abbcx = cookie(req.headers(), auth::ABBCX).map(str::to_string);
    let http = cookie(req.headers(), auth::HTTP_SESSION).map(str::to_string);
    let known = abbcx.filter(|a| {
        shared
            .registry()
            .sessions
            .touch(a, http.as_deref())
            .is_some()
    });
    let challenge = |stale: bool, msg: &str| {
        let mut r = RwsError::new(
            StatusCode::UNAUTHORIZED,
            repr::codes::UNAUTHORIZED,
            msg.to_string(),
        )
        .render(format, &origin);
        if let Ok(v) = HeaderValue::from_str(&shared.digester.challenge(stale)) {
            r.headers_mut().insert(header::WWW_AUTHENTICATE, v);
        }
        r
    };
    let (session, new_cookies) = match (creds, known) {
        (Credentials::Invalid(why), _) => return challenge(false, &format!("login failed: {why}")),
        (_, Some(s)) => (s, None),
        (Credentials::Valid, None) => {
            let (abbcx, http, evicted) = shared.registry().sessions.open();
            if let Some(e) = evicted {
                shared.registry().subs.close_session(&e);
            }
            (abbcx.clone(), Some((abbcx, http)))
        }
        (Credentials::Stale, None) => return challenge(true, "the nonce has expired"),
        (Credentials::Missing, None) => return challenge(false, "login required"),
    };
    req.extensions_mut().insert(SessionId(session));
    let mut resp = next.run(req).await;
    if let Some((abbcx, http)) = new_cookies {
        for c in [
            format!("{}={http}; path=/; HttpOnly", auth::HTTP_SESSION),
            format!("{}={abbcx}; path=/", auth::ABBCX),
        ] {
            if let Ok(v) = HeaderValue::from_str(&c) {
                resp.headers_mut().append(header::SET_COOKIE, v);
            }
        }
    }
    resp
}

/// Every resource except the WebSocket: parse, then route by path.
async fn dispatch(AxState(shared): AxState<Arc<Shared>>, req: Request) -> Response {
    let (parts, body) = req.into_parts();
    let format = wants_json(parts.uri.query());
    let origin = origin(&parts.headers);
    let session = parts
        .extensions
        .get::<SessionId>()
        .map(|s| s.0.clone())
        .unwrap_or_default();
    let path = parts.uri.path().to_string();
    let segs: Vec<String> = path
        .split('/')
        .filter(|s| !s.is_empty())
        .map(|s| {
            percent_encoding::percent_decode_str(s)
                .decode_utf8_lossy()
                .into_owned()
        })
        .collect();
    let is_upload = parts.method == Method::PUT && segs.first().is_some_and(|s| s == "fileservice");
    let limit = if is_upload {
        shared.opts.max_upload
    } else {
        shared.opts.max_body
    };
    // Uploads wait for one of a few slots, so concurrent uploads bound the memory.
    let _slot = if is_upload {
        shared.uploads.clone().acquire_owned().await.ok()
    } else {
        None
    };
    let body = match read_body(body, limit).await {
        Ok(b) => b,
        Err(e) => return e.render(format, &origin),
    };
    let query: Vec<(String, String)> = parts
        .uri
        .query()
        .map(|q| form_urlencoded::parse(q.as_bytes()).into_owned().collect())
        .unwrap_or_default();
    let form = if is_upload {
        Vec::new()
    } else {
        form_urlencoded::parse(&body).into_owned().collect()
    };
    let rq = Rq {
        method: parts.method,
        segs,
        path,
        query,
        form,
        body,
        format,
        origin: origin.clone(),
        session,
    };
    match route(&shared, &rq).await {
        Ok(Answer::Ok(s)) => s.render(format, &origin),
        Ok(Answer::NoContent) => StatusCode::NO_CONTENT.into_response(),
        Ok(Answer::Raw(r)) => r,
        Err(e) => e.render(format, &origin),
    }
}

async fn read_body(body: Body, limit: usize) -> Result<Bytes, RwsError> {
    axum::body::to_bytes(body, limit).await.map_err(|e| {
        // axum wraps http-body-util's `LengthLimitError` ("length limit exceeded").
        let mut too_large = false;
        let mut source: Option<&dyn std::error::Error> = Some(&e);
        while let Some(err) = source {
            too_large |= err.to_string().contains("length limit exceeded");
            source = err.source();
        }
        if too_large {
            RwsError::new(
                StatusCode::PAYLOAD_TOO_LARGE,
                repr::codes::TOO_LARGE,
                format!("the request body is larger than {limit} bytes"),
            )
        } else {
            RwsError::bad(format!("the request body could not be read: {e}"))
        }
    })
}

async fn route(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    let s: Vec<&str> = rq.segs.iter().map(String::as_str).collect();
    match s.as_slice() {
        ["rw", "rapid", "execution"] => execution::execution(shared, rq).await,
        ["rw", "rapid", "tasks", rest @ ..] => execution::tasks(shared, rq, rest).await,
        ["rw", "rapid", "modules"] => execution::modules(shared, rq).await,
        ["rw", "rapid", "symbol", "data", "RAPID", rest @ ..] => {
            symbols::data(shared, rq, rest).await
        }
        ["rw", "rapid", "symbol", "properties", "RAPID", rest @ ..] => {
            symbols::properties(shared, rq, rest).await
        }
        ["rw", "rapid", "symbols"] => symbols::search(shared, rq).await,
        ["rw", "panel", what] => panel::panel(shared, rq, what).await,
        ["rw", "iosystem", "signals", rest @ ..] => iosystem::signals(shared, rq, rest).await,
        ["rw", "elog", rest @ ..] => elog::elog(shared, rq, rest).await,
        ["rw", "motionsystem", "mechunits", rest @ ..] => motion::mechunits(shared, rq, rest).await,
        ["rw", "system"] => system::system(shared, rq).await,
        ["rw", "cfg", domain, type_name, "instances"] => {
            system::cfg(shared, rq, domain, type_name).await
        }
        ["ctrl"] => system::ctrl(shared, rq).await,
        ["ctrl", var] => fileservice::env_var(shared, rq, var).await,
        ["fileservice", rest @ ..] => fileservice::fileservice(shared, rq, rest).await,
        ["rw", "dipc", rest @ ..] => users::dipc(shared, rq, rest).await,
        ["users", rest @ ..] => users::users(shared, rq, rest).await,
        ["logout"] => users::logout(shared, rq),
        ["subscription", rest @ ..] => subscription::subscription(shared, rq, rest).await,
        _ => Err(RwsError::not_found(format!(
            "no resource {} (rapidvc serves the resources listed in docs/rws.md)",
            rq.path
        ))),
    }
}

/// Where to listen: `addr` when given; otherwise 127.0.0.1:80 as on a controller, and
/// 127.0.0.1:8080 when port 80 is not allowed (no privilege) or taken.
pub fn bind(addr: Option<SocketAddr>) -> std::io::Result<std::net::TcpListener> {
    match addr {
        Some(a) => std::net::TcpListener::bind(a),
        None => std::net::TcpListener::bind(("127.0.0.1", 80))
            .or_else(|_| std::net::TcpListener::bind(("127.0.0.1", FALLBACK_PORT))),
    }
}

/// The port [`bind`] falls back to when port 80 cannot be had.
pub const FALLBACK_PORT: u16 = 8080;

/// A listener that serves at most a fixed number of connections at once.
struct Limited {
    inner: tokio::net::TcpListener,
    slots: Arc<Semaphore>,
}

/// A connection holding one of the listener's slots until it closes.
struct Conn {
    io: tokio::net::TcpStream,
    _slot: OwnedSemaphorePermit,
}

impl AsyncRead for Conn {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.io).poll_read(cx, buf)
    }
}

impl AsyncWrite for Conn {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        Pin::new(&mut self.io).poll_write(cx, buf)
    }
    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.io).poll_flush(cx)
    }
    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.io).poll_shutdown(cx)
    }
}

impl axum::serve::Listener for Limited {
    type Io = Conn;
    type Addr = SocketAddr;

    async fn accept(&mut self) -> (Conn, SocketAddr) {
        loop {
            let slot = match self.slots.clone().acquire_owned().await {
                Ok(s) => s,
                // The semaphore is never closed; should it be, wait as for a full one.
                Err(_) => {
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            };
            match self.inner.accept().await {
                Ok((io, addr)) => {
                    let _ = io.set_nodelay(true);
                    return (Conn { io, _slot: slot }, addr);
                }
                // Out of file descriptors and the like: back off, keep serving.
                Err(_) => tokio::time::sleep(Duration::from_millis(50)).await,
            }
        }
    }

    fn local_addr(&self) -> std::io::Result<SocketAddr> {
        self.inner.local_addr()
    }
}

/// Serve `router` on `listener` with at most `max_connections` connections at once, until
/// `shutdown` resolves.
pub async fn serve(
    listener: tokio::net::TcpListener,
    router: Router,
    max_connections: usize,
    shutdown: impl std::future::Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    let limited = Limited {
        inner: listener,
        slots: Arc::new(Semaphore::new(max_connections.max(1))),
    };
    axum::serve(limited, router)
        .with_graceful_shutdown(shutdown)
        .await
}

/// An RWS server on its own thread and tokio runtime.
#[derive(Debug)]
pub struct RwsServer {
    addr: SocketAddr,
    stop: Option<oneshot::Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl RwsServer {
    /// Serve `router` (from [`router`], possibly with more routes nested) on `listener`.
    pub fn start(
        listener: std::net::TcpListener,
        router: Router,
        max_connections: usize,
    ) -> std::io::Result<RwsServer> {
        listener.set_nonblocking(true)?;
        let addr = listener.local_addr()?;
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .thread_name("rapidvc-rws")
            .enable_all()
            .build()?;
        let (stop, stopped) = oneshot::channel::<()>();
        let (ready_tx, ready_rx) = std::sync::mpsc::channel();
        let thread = std::thread::Builder::new()
            .name("rapidvc-rws".into())
            .spawn(move || {
                rt.block_on(async move {
                    let listener = match tokio::net::TcpListener::from_std(listener) {
                        Ok(l) => l,
                        Err(e) => {
                            let _ = ready_tx.send(Err(e));
                            return;
                        }
                    };
                    let _ = ready_tx.send(Ok(()));
                    let _ = serve(listener, router, max_connections, async {
                        let _ = stopped.await;
                    })
                    .await;
                });
                // Open WebSockets and slow connections do not keep the server from stopping.
                rt.shutdown_timeout(Duration::from_secs(1));
            })?;
        match ready_rx.recv() {
            Ok(Ok(())) => Ok(RwsServer {
                addr,
                stop: Some(stop),
                thread: Some(thread),
            }),
            Ok(Err(e)) => Err(e),
            Err(_) => Err(std::io::Error::other(
                "the RWS server thread ended at start",
            )),
        }
    }

    /// Where it listens.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// The base URL clients use (`http://127.0.0.1:80`).
    pub fn url(&self) -> String {
        format!("http://{}", self.addr)
    }

    /// Stop serving and wait for the thread.
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for RwsServer {
    fn drop(&mut self) {
        self.shutdown();
    }
}

/// Numbers as RobotWare writes them: integers without a fraction, others as Rust's shortest
/// round-trip text.
fn num(v: f64) -> String {
    if v.is_finite() && v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

/// Case-insensitive lookup in a list of names.
fn find_ci<'a, T>(items: &'a [T], name: &str, key: impl Fn(&T) -> &str) -> Option<&'a T> {
    items.iter().find(|t| key(t).eq_ignore_ascii_case(name))
}
