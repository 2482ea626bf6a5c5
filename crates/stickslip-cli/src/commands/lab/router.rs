//! The lab's routes: the page and its assets (embedded in the binary), and the JSON API
//! (documented in `docs/lab.md`). Every computation runs on a worker thread, at most
//! [`Settings::jobs`] at once, within [`Settings::time_limit`]; a request whose client went
//! away stops its computation.

use super::api;
use super::limit::{AbandonOnDrop, Budget};
use super::query::ApiError;
use axum::body::Body;
use axum::extract::{RawQuery, Request, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use serde::Serialize;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::Semaphore;

/// The page.
const INDEX_HTML: &str = include_str!("../../../assets/lab/index.html");
/// Its script.
const LAB_JS: &str = include_str!("../../../assets/lab/lab.js");
/// Its style sheet.
const LAB_CSS: &str = include_str!("../../../assets/lab/lab.css");

/// How the server limits its work.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Time limit of one request, waiting included.
    pub time_limit: Duration,
    /// Computations at once; more requests wait for a turn within their time limit.
    pub jobs: usize,
    /// One line per request on standard error.
    pub verbose: bool,
}

/// The server's shared state.
#[derive(Clone)]
pub struct Lab {
    settings: Settings,
    permits: Arc<Semaphore>,
    active: Arc<AtomicUsize>,
}

impl Lab {
    /// A lab with these settings.
    pub fn new(settings: Settings) -> Self {
        Self {
            permits: Arc::new(Semaphore::new(settings.jobs.max(1))),
            settings,
            active: Arc::new(AtomicUsize::new(0)),
        }
    }

    /// Computations running now (a stopped computation leaves this count).
    #[cfg(test)]
    pub fn active(&self) -> usize {
        self.active.load(Ordering::SeqCst)
    }

    /// Run `work` on a worker thread within a new budget and answer with its JSON.
    async fn compute<T, F>(&self, work: F) -> Response
    where
        T: Serialize + Send + 'static,
        F: FnOnce(&Arc<Budget>) -> Result<T, ApiError> + Send + 'static,
    {
        let budget = Budget::new(self.settings.time_limit);
        // Dropped with this future when the client goes away: the computation then stops.
        let _abandon = AbandonOnDrop(budget.clone());
        let deadline = tokio::time::Instant::from_std(budget.deadline());
        let permit =
            match tokio::time::timeout_at(deadline, self.permits.clone().acquire_owned()).await {
                Ok(Ok(permit)) => permit,
                _ => {
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
        let task = tokio::task::spawn_blocking(move || {
            let _permit = permit;
            let _count = Decrement(active);
            work(&task_budget).and_then(|answer| {
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
    let router = Router::new()
        .route("/", get(index))
        .route("/index.html", get(index))
        .route("/lab.js", get(script))
        .route("/lab.css", get(style))
        .route("/api/steady", get(steady))
        .route("/api/simulate", get(simulate))
        .route("/api/sweep", get(sweep))
        .route("/api/map", get(map))
        .route("/api/theory", get(theory))
        .route("/api/presets", get(presets))
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .with_state(lab)
        .layer(axum::middleware::map_response(security_headers));
    if verbose {
        router.layer(axum::middleware::from_fn(log))
    } else {
        router
    }
}

/// Headers on every answer: no sniffing, no referrer, and a page that loads only its own
/// script and style (no CDN, no inline code).
async fn security_headers(mut response: Response) -> Response {
    let h = response.headers_mut();
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    h.insert(
        header::REFERRER_POLICY,
        HeaderValue::from_static("no-referrer"),
    );
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(
            "default-src 'self'; img-src 'self' data: blob:; connect-src 'self'; \
             object-src 'none'; base-uri 'none'; frame-ancestors 'none'",
        ),
    );
    response
}

/// One line per request: method, path, status, milliseconds.
async fn log(request: Request, next: Next) -> Response {
    let started = Instant::now();
    let method = request.method().clone();
    let path = request.uri().path().to_string();
    let response = next.run(request).await;
    eprintln!(
        "lab: {method} {path} {} {:.1} ms",
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

async fn style() -> Response {
    asset("text/css; charset=utf-8", LAB_CSS)
}

async fn not_found(request: Request) -> Response {
    ApiError::status(
        StatusCode::NOT_FOUND,
        format!(
            "no such page: {} (the lab serves / and /api/steady, /api/simulate, /api/sweep, \
             /api/map, /api/theory, /api/presets)",
            request.uri().path().chars().take(80).collect::<String>()
        ),
    )
    .into_response()
}

async fn method_not_allowed(request: Request) -> Response {
    ApiError::status(
        StatusCode::METHOD_NOT_ALLOWED,
        format!(
            "{} is not served here: the lab answers GET (and HEAD) only",
            request.method()
        ),
    )
    .into_response()
}

async fn steady(State(lab): State<Lab>, RawQuery(raw): RawQuery) -> Response {
    match api::SteadyRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn simulate(State(lab): State<Lab>, RawQuery(raw): RawQuery) -> Response {
    match api::SimulateRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn sweep(State(lab): State<Lab>, RawQuery(raw): RawQuery) -> Response {
    match api::SweepRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn map(State(lab): State<Lab>, RawQuery(raw): RawQuery) -> Response {
    match api::MapRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn theory(State(lab): State<Lab>, RawQuery(raw): RawQuery) -> Response {
    match api::TheoryRequest::parse(raw.as_deref()) {
        Ok(request) => lab.compute(move |b| request.run(b)).await,
        Err(err) => err.into_response(),
    }
}

async fn presets(RawQuery(raw): RawQuery) -> Response {
    if let Some(raw) = raw.filter(|r| !r.is_empty()) {
        return ApiError::bad(format!(
            "/api/presets takes no keys (got '{}')",
            raw.chars().take(40).collect::<String>()
        ))
        .into_response();
    }
    json(StatusCode::OK, api::presets().to_string().into_bytes())
}
