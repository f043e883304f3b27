//! The live view: an HTTP server that serves the view page and streams the robot's state over
//! a WebSocket while the program runs.
//!
//! [`router`] is an axum `Router` with the routes `/` (the page) and `/ws` (the stream), so a
//! larger server can mount it under a prefix (`Router::new().nest("/view", router(session))`;
//! the page is then at `/view` and finds its stream at `/view/ws`). [`LiveServer`] runs it on its own
//! tokio runtime and thread, never in the motion cycle.
//!
//! # Stream
//!
//! A viewer gets one `snapshot` message (the page data recorded so far, as embedded in a
//! replay page), then the messages of [`super::encode`]`::live_*`: `row` (robot state, 50 per
//! second of robot time), `instr`, `log`, `egm`, `egmState`, `path`, and `end` when the run is
//! over (then the server closes the connection). A viewer that falls more than
//! [`super::LIVE_BUFFER`] messages behind loses the oldest and gets a `lagged` message with
//! their number. Messages the snapshot already contained may follow it once; their times
//! (rows) and indexes (instructions, log entries) tell the page to skip them.

use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use axum::Router;
use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::http::{StatusCode, header};
use axum::response::{Html, IntoResponse, Response};
use axum::routing::get;
use tokio::sync::{broadcast, oneshot};

use super::{ViewSession, encode};

/// How long a stopping server waits for its viewers to receive the `end` message.
const CLOSE_GRACE: Duration = Duration::from_secs(2);

#[derive(Clone)]
struct AppState {
    session: ViewSession,
    viewers: Arc<Viewers>,
}

/// Viewers connected now and since the start.
#[derive(Debug, Default)]
struct Viewers {
    now: AtomicUsize,
    total: AtomicUsize,
}

/// The live view's routes (`/` and `/ws`) for `session`.
pub fn router(session: ViewSession) -> Router {
    router_counted(session, Arc::new(Viewers::default()))
}

fn router_counted(session: ViewSession, viewers: Arc<Viewers>) -> Router {
    Router::new()
        .route("/", get(page))
        .route("/ws", get(ws))
        // Browsers ask for it; the page has none.
        .route("/favicon.ico", get(|| async { StatusCode::NO_CONTENT }))
        .with_state(AppState { session, viewers })
}

async fn page(State(s): State<AppState>) -> Response {
    (
        [(header::CACHE_CONTROL, "no-store")],
        Html(s.session.page(true)),
    )
        .into_response()
}

async fn ws(upgrade: WebSocketUpgrade, State(s): State<AppState>) -> Response {
    upgrade.on_upgrade(move |socket| stream(socket, s))
}

/// Decrements the viewer count when a stream ends, however it ends.
struct Viewer(Arc<Viewers>);

impl Drop for Viewer {
    fn drop(&mut self) {
        self.0.now.fetch_sub(1, Ordering::SeqCst);
    }
}

async fn stream(mut socket: WebSocket, s: AppState) {
    s.viewers.now.fetch_add(1, Ordering::SeqCst);
    s.viewers.total.fetch_add(1, Ordering::SeqCst);
    let _viewer = Viewer(Arc::clone(&s.viewers));
    // Subscribe before taking the snapshot: nothing falls between the two.
    let mut rx = s.session.subscribe();
    let rec = s.session.snapshot();
    let scene = s.session.scene();
    let snapshot = serde_json::json!({
        "type": "snapshot",
        "data": encode::page_data(&scene, &rec, true),
    });
    if socket
        .send(Message::Text(snapshot.to_string().into()))
        .await
        .is_err()
    {
        return;
    }
    let Some(rx) = rx.as_mut() else {
        // The run is already over: the snapshot is everything.
        let end = encode::live_end(rec.now).to_string();
        let _ = socket.send(Message::Text(end.into())).await;
        let _ = socket.send(Message::Close(None)).await;
        return;
    };
    loop {
        tokio::select! {
            msg = rx.recv() => match msg {
                Ok(text) => {
                    if socket.send(Message::Text((&*text).into())).await.is_err() {
                        return;
                    }
                }
                Err(broadcast::error::RecvError::Lagged(n)) => {
                    let lagged = serde_json::json!({"type": "lagged", "n": n}).to_string();
                    if socket.send(Message::Text(lagged.into())).await.is_err() {
                        return;
                    }
                }
                Err(broadcast::error::RecvError::Closed) => {
                    let _ = socket.send(Message::Close(None)).await;
                    return;
                }
            },
            incoming = socket.recv() => match incoming {
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => return,
                Some(Ok(_)) => {}
            },
        }
    }
}

/// A running live-view server (see the module docs).
pub struct LiveServer {
    addr: SocketAddr,
    session: ViewSession,
    viewers: Arc<Viewers>,
    shutdown: Option<oneshot::Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl std::fmt::Debug for LiveServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LiveServer")
            .field("addr", &self.addr)
            .finish_non_exhaustive()
    }
}

impl LiveServer {
    /// Bind `addr` (port 0: any free port) and serve `session`'s page and stream on a thread
    /// of its own. The stream starts now.
    pub fn start(addr: SocketAddr, session: ViewSession) -> Result<LiveServer, String> {
        let listener = std::net::TcpListener::bind(addr)
            .map_err(|e| format!("--view-live: cannot listen on {addr}: {e}"))?;
        listener
            .set_nonblocking(true)
            .map_err(|e| format!("--view-live: {e}"))?;
        let local = listener
            .local_addr()
            .map_err(|e| format!("--view-live: {e}"))?;
        session.enable_live();
        let viewers = Arc::new(Viewers::default());
        let app = router_counted(session.clone(), Arc::clone(&viewers));
        let (tx, rx) = oneshot::channel::<()>();
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(|e| format!("--view-live: cannot start the server's runtime: {e}"))?;
        let count = Arc::clone(&viewers);
        let thread = std::thread::Builder::new()
            .name("rapidvc-view".into())
            .spawn(move || {
                runtime.block_on(async move {
                    let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                        return;
                    };
                    let server = axum::serve(listener, app);
                    tokio::select! {
                        _ = server => {}
                        _ = rx => {
                            // Let the viewers receive the end of the stream.
                            let deadline = tokio::time::Instant::now() + CLOSE_GRACE;
                            while count.now.load(Ordering::SeqCst) > 0
                                && tokio::time::Instant::now() < deadline
                            {
                                tokio::time::sleep(Duration::from_millis(10)).await;
                            }
                        }
                    }
                });
                runtime.shutdown_timeout(Duration::from_millis(100));
            })
            .map_err(|e| format!("--view-live: cannot start the server thread: {e}"))?;
        Ok(LiveServer {
            addr: local,
            session,
            viewers,
            shutdown: Some(tx),
            thread: Some(thread),
        })
    }

    /// The address the server listens on.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Viewers connected to the stream now.
    pub fn viewers(&self) -> usize {
        self.viewers.now.load(Ordering::SeqCst)
    }

    /// Viewers that connected to the stream since the start.
    pub fn viewers_total(&self) -> usize {
        self.viewers.total.load(Ordering::SeqCst)
    }

    /// End the stream (viewers get `end`) and stop the server.
    pub fn stop(mut self) {
        self.shutdown_now();
    }

    fn shutdown_now(&mut self) {
        self.session.close_live();
        if let Some(tx) = self.shutdown.take() {
            let _ = tx.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for LiveServer {
    fn drop(&mut self) {
        self.shutdown_now();
    }
}
