//! The lab's routes: the page and its assets (embedded in the binary), and the JSON API
//! (documented in `docs/lab.md`). Every computation runs on a worker thread, at most
//! [`Settings::jobs`] at once, in fair turns between clients (see [`super::fair`]), within
//! [`Settings::time_limit`]; a request whose client went away stops its computation. Requests
//! whose `Host` is not an address of the lab are refused (a web page elsewhere cannot make a
//! browser read the lab's answers by renaming an address, "DNS rebinding").

use super::api;
use super::fair::{Client, Fair, PER_CLIENT};
use super::headers::SECURITY_HEADERS;
use super::limit::{AbandonOnDrop, Budget};
use super::query::ApiError;
use super::serve::Peer;
use axum::body::Body;
use axum::extract::{FromRequestParts, RawQuery, Request, State};
use axum::http::request::Parts;
use axum::http::HeaderMap;
use axum::http::{header, HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use serde::Serialize;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The page.
const INDEX_HTML: &str = include_str!("../assets/index.html");
/// Its script: the entry module, which imports the modules of [`MODULES`].
pub(crate) const LAB_JS: &str = include_str!("../assets/lab.js");
/// The page's ES modules, served at `/lab/<name>` (loaded as they are: no build step).
pub(crate) const MODULES: [(&str, &str); 10] = [
    ("api.js", include_str!("../assets/lab/api.js")),
    ("export.js", include_str!("../assets/lab/export.js")),
    ("form.js", include_str!("../assets/lab/form.js")),
    ("orbit.js", include_str!("../assets/lab/orbit.js")),
    ("panels.js", include_str!("../assets/lab/panels.js")),
    ("record.js", include_str!("../assets/lab/record.js")),
    ("scope.js", include_str!("../assets/lab/scope.js")),
    ("state.js", include_str!("../assets/lab/state.js")),
    ("sweepmap.js", include_str!("../assets/lab/sweepmap.js")),
    ("util.js", include_str!("../assets/lab/util.js")),
];
/// Its style sheet.
const LAB_CSS: &str = include_str!("../assets/lab.css");

/// How the server limits its work.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Time limit of one request, waiting included.
    pub time_limit: Duration,
    /// Computations at once; more requests wait for a turn within their time limit.
    pub jobs: usize,
    /// One line per request on standard error.
    pub verbose: bool,
    /// Host names and addresses a request's `Host` header may name (without port, lower
    /// case); `localhost` and the loopback addresses are always allowed.
    pub hosts: Vec<String>,
    /// The test hook of the browser tests (see [`Hold`]); `stickslip lab` never sets it.
    pub hold: Option<Hold>,
}

/// A test hook, for tests that must drop a request certainly still in flight (a browser test
/// presses Sweep twice and expects the first request aborted, whatever the machine's load):
/// a request to `path` whose query contains `query` waits, before it is computed, until the
/// next request to `path` arrives (or its client goes away). Only the browser tests' server
/// (the `lab_hold` example) sets it: `stickslip lab` has no flag or variable that does.
#[derive(Debug, Clone)]
pub struct Hold {
    /// The path of the requests held (`/api/sweep`).
    pub path: String,
    /// What the query of a held request contains (`to=2&steps=40`).
    pub query: String,
    /// Woken by each request to `path`.
    arrived: Arc<tokio::sync::Notify>,
}

impl Hold {
    /// Hold the requests to `path` whose query contains `query`.
    pub fn new(path: impl Into<String>, query: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            query: query.into(),
            arrived: Arc::new(tokio::sync::Notify::new()),
        }
    }
}

/// The [`Hold`] hook: a matching request waits for the next request to its path.
async fn hold(hold: Hold, request: Request, next: Next) -> Response {
    if request.uri().path() == hold.path {
        // The requests held before this one go on (no permit is kept for later ones).
        hold.arrived.notify_waiters();
        let held = request
            .uri()
            .query()
            .is_some_and(|q| q.contains(&hold.query));
        if held {
            hold.arrived.notified().await;
        }
    }
    next.run(request).await
}

/// The server's shared state.
#[derive(Clone)]
pub struct Lab {
    settings: Arc<Settings>,
    fair: Arc<Fair>,
    active: Arc<AtomicUsize>,
}

/// Header by which the page names itself (random, one per open page).
pub const CLIENT_HEADER: &str = "x-lab-client";

/// The client a request comes from ([`Client`]): the page's own id (the `x-lab-client`
/// header) at the request's address, or else its connection (`:port`) at that address.
impl<S: Send + Sync> FromRequestParts<S> for Client {
    type Rejection = std::convert::Infallible;

    async fn from_request_parts(parts: &mut Parts, _: &S) -> Result<Self, Self::Rejection> {
        let peer = parts.extensions.get::<Peer>().map(|p| p.0);
        let id = parts
            .headers
            .get(CLIENT_HEADER)
            .and_then(|v| v.to_str().ok())
            .filter(|v| {
                (1..=64).contains(&v.len())
                    && v.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-')
            });
        Ok(match (peer, id) {
            (Some(peer), Some(id)) => Client::new(peer.ip().to_string(), id),
            (Some(peer), None) => Client::new(peer.ip().to_string(), format!(":{}", peer.port())),
            (None, Some(id)) => Client::new("local", id),
            (None, None) => Client::new("local", "local"),
        })
    }
}

impl Lab {
    /// A lab with these settings.
    pub fn new(settings: Settings) -> Self {
        Self {
            fair: Fair::new(settings.jobs),
            settings: Arc::new(settings),
            active: Arc::new(AtomicUsize::new(0)),
        }
    }

    /// Computations running now (a stopped computation leaves this count).
    #[cfg(test)]
    pub fn active(&self) -> usize {
        self.active.load(Ordering::SeqCst)
    }

    /// The turns' queues (what the tests look into).
    #[cfg(test)]
    pub fn fair(&self) -> &Arc<Fair> {
        &self.fair
    }

    /// Run `work` of `client` on a worker thread, in its turn, within a new budget, and
    /// answer with its JSON.
    async fn compute<T, F>(&self, client: Client, work: F) -> Response
    where
        T: Serialize + Send + 'static,
        F: FnOnce(&Arc<Budget>) -> Result<T, ApiError> + Send + 'static,
    {
        let Some(slot) = self.fair.slot(&client) else {
            return ApiError::status(
                StatusCode::TOO_MANY_REQUESTS,
                format!(
                    "too many computations at once from this page: at most {PER_CLIENT} wait or \
                     run for one client; let one finish (or drop it) and try again"
                ),
            )
            .into_response();
        };
        let budget = Budget::new(self.settings.time_limit);
        // Dropped with this future when the client goes away: the computation then stops.
        let _abandon = AbandonOnDrop(budget.clone());
        let deadline = tokio::time::Instant::from_std(budget.deadline());
        let turn = match tokio::time::timeout_at(deadline, self.fair.turn(&client)).await {
            Ok(turn) => turn,
            Err(_) => {
                return ApiError::status(
                    StatusCode::SERVICE_UNAVAILABLE,
                    format!(
                        "the lab is busy: no worker was free within its time limit of {} s; \
                             try again",
                        budget.limit().as_secs_f64()
                    ),
                )
                .into_response()
            }
        };
        let active = self.active.clone();
        active.fetch_add(1, Ordering::SeqCst);
        let task_budget = budget.clone();
        let fair = self.fair.clone();
        let runtime = tokio::runtime::Handle::current();
        let task = tokio::task::spawn_blocking(move || {
            let _slot = slot;
            let _count = Decrement(active);
            task_budget.take_turns(fair, client, turn, runtime);
            let answer = work(&task_budget);
            task_budget.end_turns();
            answer.and_then(|answer| {
                serde_json::to_vec(&answer)
                    .map_err(|e| ApiError::status(StatusCode::INTERNAL_SERVER_ERROR, e.to_string()))
            })
        });
        match task.await {
            Ok(Ok(body)) => json(StatusCode::OK, body),
            Ok(Err(err)) => err.into_response(),
            Err(_) => ApiError::status(
                StatusCode::INTERNAL_SERVER_ERROR,
                "internal error: the computation failed (please report the query)",
            )
            .into_response(),
        }
    }
}

/// Decrements a counter when dropped.
struct Decrement(Arc<AtomicUsize>);

impl Drop for Decrement {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// A JSON answer, never cached.
fn json(status: StatusCode, body: Vec<u8>) -> Response {
    (
        status,
        [
            (header::CONTENT_TYPE, "application/json"),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body,
    )
        .into_response()
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut body = serde_json::json!({ "error": self.message });
        if let Some(field) = self.field {
            body["field"] = serde_json::Value::String(field);
        }
        json(self.status, body.to_string().into_bytes())
    }
}

/// The router of a lab.
pub fn router(lab: Lab) -> Router {
    let verbose = lab.settings.verbose;
    let hosts = lab.settings.clone();
    let router = Router::new()
        .route("/", get(index))
        .route("/index.html", get(index))
        .route("/lab.js", get(script))
        .route("/lab/{module}", get(module))
        .route("/lab.css", get(style))
        .route("/api/steady", get(steady))
        .route("/api/simulate", get(simulate))
        .route("/api/sweep", get(sweep))
        .route("/api/map", get(map))
        .route("/api/curve", get(curve))
        .route("/api/orbit", get(orbit))
        .route("/api/theory", get(theory))
        .route("/api/presets", get(presets))
        .route("/api/keys", get(keys))
        .route("/api/record", post(record))
        .route("/api/fit", post(fit))
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .with_state(lab);
    let router = match hosts.hold.clone() {
        Some(held) => router.layer(axum::middleware::from_fn(move |request, next| {
            hold(held.clone(), request, next)
        })),
        None => router,
    };
    let router = router
        .layer(axum::middleware::from_fn(move |request, next| {
            check_host(hosts.clone(), request, next)
        }))
        .layer(axum::middleware::map_response(security_headers));
    if verbose {
        router.layer(axum::middleware::from_fn(log))
    } else {
        router
    }
}

async fn security_headers(mut response: Response) -> Response {
    let h = response.headers_mut();
    for (name, value) in SECURITY_HEADERS {
        h.insert(name, HeaderValue::from_static(value));
    }
    response
}

/// The host part of a `Host` header, lower case, without port or brackets.
fn host_name(value: &str) -> String {
    let value = value.trim().to_ascii_lowercase();
    let host = if let Some(rest) = value.strip_prefix('[') {
        rest.split(']').next().unwrap_or_default().to_string()
    } else {
        value.split(':').next().unwrap_or_default().to_string()
    };
    host.trim_end_matches('.').to_string()
}

/// Answer only requests whose `Host` names the lab: `localhost`, a loopback address, an
/// address the lab listens on, or a name given with `--allow-host`. A request without `Host`
/// (not from a browser) passes.
async fn check_host(settings: Arc<Settings>, request: Request, next: Next) -> Response {
    let Some(value) = request.headers().get(header::HOST) else {
        return next.run(request).await;
    };
    let host = host_name(value.to_str().unwrap_or_default());
    let loopback = host == "localhost"
        || host
            .parse::<std::net::IpAddr>()
            .is_ok_and(|ip| ip.is_loopback());
    if loopback || settings.hosts.contains(&host) {
        return next.run(request).await;
    }
    ApiError::status(
        StatusCode::FORBIDDEN,
        format!(
            "this lab does not answer to the host '{}': open it by one of its addresses ({}), \
             or start it with --allow-host {} to allow this name",
            clip(&host, 60),
            std::iter::once("localhost")
                .chain(settings.hosts.iter().map(String::as_str))
                .collect::<Vec<_>>()
                .join(", "),
            clip(&host, 60),
        ),
    )
    .into_response()
}

/// At most `n` characters of `text`, without control characters.
fn clip(text: &str, n: usize) -> String {
    let mut out: String = text
        .chars()
        .take(n)
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    if text.chars().count() > n {
        out.push('…');
    }
    out
}

/// Prints the line of a request that ended without an answer (its client went away).
struct Aborted {
    line: Option<String>,
    started: Instant,
    peer: Option<std::net::SocketAddr>,
}

impl Drop for Aborted {
    fn drop(&mut self) {
        if let Some(line) = self.line.take() {
            let who = self.peer.map_or(String::new(), |p| format!(" ({p})"));
            eprintln!(
                "lab: {line} aborted after {:.1} ms: the client{who} went away",
                self.started.elapsed().as_secs_f64() * 1e3
            );
        }
    }
}

/// One line per request: method, path (at most 80 characters), status, milliseconds; or
/// `aborted` for a request whose client went away first, with the client's address and port
/// (logged before the line of the connection's end).
async fn log(request: Request, next: Next) -> Response {
    let started = Instant::now();
    let line = format!("{} {}", request.method(), clip(request.uri().path(), 80));
    let mut aborted = Aborted {
        line: Some(line),
        started,
        peer: request.extensions().get::<Peer>().map(|p| p.0),
    };
    let response = next.run(request).await;
    let line = aborted.line.take().unwrap_or_default();
    eprintln!(
        "lab: {line} {} {:.1} ms",
        response.status().as_u16(),
        started.elapsed().as_secs_f64() * 1e3
    );
    response
}

fn asset(content_type: &'static str, body: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        Body::from(body),
    )
        .into_response()
}

async fn index() -> Response {
    asset("text/html; charset=utf-8", INDEX_HTML)
}

async fn script() -> Response {
    asset("text/javascript; charset=utf-8", LAB_JS)
}

/// A module of the page, or the 404 of any other path.
async fn module(request: Request) -> Response {
    let name = request.uri().path().trim_start_matches("/lab/");
    match MODULES.iter().find(|(n, _)| *n == name) {
        Some((_, body)) => asset("text/javascript; charset=utf-8", body),
        None => not_found(request).await,
    }
}

async fn style() -> Response {
    asset("text/css; charset=utf-8", LAB_CSS)
}

async fn not_found(request: Request) -> Response {
    ApiError::status(
        StatusCode::NOT_FOUND,
        format!(
            "no such page: {} (the lab serves / and /api/steady, /api/simulate, /api/sweep, \
             /api/map, /api/curve, /api/orbit, /api/theory, /api/presets, /api/keys; POST /api/record, /api/fit)",
            clip(request.uri().path(), 80)
        ),
    )
    .into_response()
}

async fn method_not_allowed(request: Request) -> Response {
    ApiError::status(
        StatusCode::METHOD_NOT_ALLOWED,
        format!(
            "{} is not served here: the lab answers GET (and HEAD), and POST at /api/record \
             and /api/fit only",
            request.method()
        ),
    )
    .into_response()
}

async fn steady(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::SteadyRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn simulate(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::SimulateRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn sweep(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::SweepRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn map(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::MapRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn curve(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::CurveRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn orbit(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::OrbitRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn theory(State(lab): State<Lab>, client: Client, RawQuery(raw): RawQuery) -> Response {
    match api::TheoryRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(client, move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn record(
    State(lab): State<Lab>,
    client: Client,
    RawQuery(raw): RawQuery,
    headers: HeaderMap,
    body: Body,
) -> Response {
    match api::RecordRequest::parse(raw.as_deref()) {
        Ok(request) => match api::upload::read_upload(&headers, body).await {
            Ok(upload) => {
                let request = request.with_upload(upload);
                lab.compute(client, move |b| request.run(b)).await
            }
            Err(err) => err.into_response(),
        },
        Err(err) => err.into_response(),
    }
}

async fn fit(
    State(lab): State<Lab>,
    client: Client,
    RawQuery(raw): RawQuery,
    headers: HeaderMap,
    body: Body,
) -> Response {
    // The keys first: a bad key costs no upload.
    match api::FitRequest::parse(raw.as_deref()) {
        Ok(request) => match api::upload::read_upload(&headers, body).await {
            Ok(upload) => {
                let request = request.with_upload(upload);
                lab.compute(client, move |b| request.run(b)).await
            }
            Err(err) => err.into_response(),
        },
        Err(err) => err.into_response(),
    }
}

/// The answer of an endpoint that takes no keys.
fn fixed(path: &str, raw: Option<String>, answer: fn() -> serde_json::Value) -> Response {
    if let Some(raw) = raw.filter(|r| !r.is_empty()) {
        return ApiError::bad(format!(
            "{path} takes no keys (got '{}')",
            raw.chars().take(40).collect::<String>()
        ))
        .into_response();
    }
    json(StatusCode::OK, answer().to_string().into_bytes())
}

async fn presets(RawQuery(raw): RawQuery) -> Response {
    fixed("/api/presets", raw, api::presets)
}

async fn keys(RawQuery(raw): RawQuery) -> Response {
    fixed("/api/keys", raw, api::keys)
}
