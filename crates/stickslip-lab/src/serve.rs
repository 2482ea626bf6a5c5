//! The lab's connections: accepted up to [`MAX_CONNECTIONS`] at once and
//! [`MAX_PER_ADDRESS`] from one address (more from that address are answered with a JSON 429
//! and closed, so that one computer's script cannot fill the server), each with a time limit
//! for its request headers (which is also how long an idle connection stays open, between
//! two requests), a limit on a stalled answer, and a JSON 414 or 431 (with the page's security
//! headers) for a request head too long to parse (a line over [`MAX_LINE`] bytes, more than
//! [`MAX_HEADERS`] header lines, a head over [`MAX_HEAD`] bytes). The answers themselves come
//! from the [`router`](super::router).

use super::headers::raw_answer;
use axum::Router;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use std::collections::HashMap;
use std::future::Future;
use std::io;
use std::net::{IpAddr, SocketAddr};
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::{Duration, Instant};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{watch, Semaphore};
use tokio::time::Sleep;

/// How the server treats connections.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Time for the request headers to arrive, from the connection's start or the end of the
    /// previous answer: a half-sent request, or a connection left idle, is closed after it.
    pub header_timeout: Duration,
    /// Time an answer may wait for the client to read it.
    pub write_timeout: Duration,
    /// Connections open at once; more wait in the system's queue until one closes.
    pub max_connections: usize,
    /// Connections open at once from one address; more from it are answered with a JSON 429
    /// and closed.
    pub per_address: usize,
}

/// Header (and idle) time limit.
pub const HEADER_TIMEOUT: Duration = Duration::from_secs(10);
/// Stalled answer time limit.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(30);
/// Connections at once: a classroom of 30 browsers with six connections each, twice over.
pub const MAX_CONNECTIONS: usize = 400;
/// Connections at once from one address: a browser opens at most six to one server, so this
/// is five browsers on one computer (or behind one address), and a twelfth of
/// [`MAX_CONNECTIONS`]: a script on one computer cannot fill the server.
pub const MAX_PER_ADDRESS: usize = 32;
/// Longest line of a request head: the query is capped at 4096 bytes, and a longer line is
/// answered here, with the JSON and the headers of every other answer.
pub const MAX_LINE: usize = 16 * 1024;
/// Most header lines of a request (a browser sends about fifteen); more are answered here
/// with a JSON 431, before the HTTP parser (whose own limit is 100) would answer a bare one.
pub const MAX_HEADERS: usize = 64;
/// Longest request head, all its lines together; a longer one is answered here with a JSON
/// 431, before the HTTP parser's own limit.
pub const MAX_HEAD: usize = 64 * 1024;

/// Refusals of connections over [`MAX_PER_ADDRESS`] being written at once; beyond, such a
/// connection is closed without an answer.
const MAX_REFUSING: usize = 64;

/// After a refusal, the rest of the request is read and dropped until the client has been
/// quiet this long (or [`MAX_DRAIN`] bytes have come): a socket closed with unread input is
/// reset, and a reset can reach the client before it has read the refusal.
const LINGER: Duration = Duration::from_millis(200);

/// The most bytes read and dropped after a refusal.
const MAX_DRAIN: usize = 1 << 20;

impl Default for Limits {
    fn default() -> Self {
        Self {
            header_timeout: HEADER_TIMEOUT,
            write_timeout: WRITE_TIMEOUT,
            max_connections: MAX_CONNECTIONS,
            per_address: MAX_PER_ADDRESS,
        }
    }
}

/// The connections open from each address.
#[derive(Debug, Default)]
struct PerAddress(Mutex<HashMap<IpAddr, usize>>);

/// One open connection of an address, counted until dropped.
struct Counted {
    counts: Arc<PerAddress>,
    address: IpAddr,
}

impl PerAddress {
    /// Count one more connection from `address`, or `None` when it has `cap` open already.
    fn admit(self: &Arc<Self>, address: IpAddr, cap: usize) -> Option<Counted> {
        let mut counts = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let open = counts.entry(address).or_insert(0);
        if *open >= cap {
            return None;
        }
        *open += 1;
        Some(Counted {
            counts: self.clone(),
            address,
        })
    }
}

impl Drop for Counted {
    fn drop(&mut self) {
        let mut counts = self.counts.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(open) = counts.get_mut(&self.address) {
            *open -= 1;
            if *open == 0 {
                counts.remove(&self.address);
            }
        }
    }
}

/// Answer a connection over its address's cap with a JSON 429 and close it: the answer is
/// written at once (a client may still be sending its request), the rest of what it sends is
/// read and dropped until it is quiet for [`LINGER`] (so that the close does not reset the
/// connection before the answer is read), all within a second.
async fn refuse_connection(mut stream: TcpStream, peer: SocketAddr, cap: usize) {
    let answer = raw_answer(
        "429 Too Many Requests",
        &format!(
            "too many connections from {}: the lab keeps at most {cap} open from one address              (a browser opens at most six); close other pages or scripts of this computer that              use the lab, and try again",
            peer.ip()
        ),
    );
    let _ = tokio::time::timeout(Duration::from_secs(1), async {
        stream.write_all(answer.as_bytes()).await?;
        let mut scratch = [0u8; 4096];
        let mut drained = 0;
        while let Ok(Ok(n)) = tokio::time::timeout(LINGER, stream.read(&mut scratch)).await {
            drained += n;
            if n == 0 || drained > MAX_DRAIN {
                break;
            }
        }
        stream.shutdown().await
    })
    .await;
}

/// The client's address, in each request's extensions.
#[derive(Debug, Clone, Copy)]
pub struct Peer(pub SocketAddr);

/// Serve `app` on `listener` until `shutdown` resolves; then stop accepting, let the requests
/// in flight finish (at most `grace`) and return.
///
/// # Errors
/// When the listener fails for good.
pub async fn serve(
    listener: TcpListener,
    app: Router,
    limits: Limits,
    verbose: bool,
    shutdown: impl Future<Output = ()>,
    grace: Duration,
) -> io::Result<()> {
    let slots = Arc::new(Semaphore::new(limits.max_connections.max(1)));
    let per_address = Arc::new(PerAddress::default());
    let refusing = Arc::new(Semaphore::new(MAX_REFUSING));
    let (stop, stopped) = watch::channel(false);
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let slot = tokio::select! {
            () = &mut shutdown => break,
            slot = slots.clone().acquire_owned() => slot.expect("the semaphore is never closed"),
        };
        let (stream, peer) = tokio::select! {
            () = &mut shutdown => break,
            accepted = listener.accept() => match accepted {
                Ok(accepted) => accepted,
                Err(e) => {
                    // Out of file descriptors and the like: wait a little, keep serving.
                    if verbose {
                        eprintln!("lab: cannot accept a connection: {e}");
                    }
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            },
        };
        let _ = stream.set_nodelay(true);
        let Some(counted) = per_address.admit(peer.ip(), limits.per_address.max(1)) else {
            drop(slot);
            if verbose {
                eprintln!(
                    "lab: connection from {peer} refused: {} open from its address already",
                    limits.per_address
                );
            }
            if let Ok(refusal) = refusing.clone().try_acquire_owned() {
                let cap = limits.per_address;
                tokio::spawn(async move {
                    let _refusal = refusal;
                    refuse_connection(stream, peer, cap).await;
                });
            }
            continue;
        };
        let app = app.clone().layer(axum::Extension(Peer(peer)));
        let mut stopped = stopped.clone();
        tokio::spawn(async move {
            let _slot = slot;
            let _counted = counted;
            let io = TokioIo::new(Guarded::new(stream, limits.write_timeout));
            let mut builder = hyper::server::conn::http1::Builder::new();
            builder
                .timer(TokioTimer::new())
                .header_read_timeout(limits.header_timeout)
                .keep_alive(true);
            let mut connection =
                Box::pin(builder.serve_connection(io, TowerToHyperService::new(app)));
            let started = Instant::now();
            let result = tokio::select! {
                result = connection.as_mut() => result,
                _ = async { let _ = stopped.wait_for(|&s| s).await; } => {
                    connection.as_mut().graceful_shutdown();
                    connection.as_mut().await
                }
            };
            // A request still in flight ends with its connection (and is logged as aborted)
            // before the connection's own line.
            drop(connection);
            if let (Err(e), true) = (result, verbose) {
                let why = if e.is_timeout() {
                    format!(
                        "no complete request within {} s",
                        limits.header_timeout.as_secs_f64()
                    )
                } else {
                    e.to_string()
                };
                eprintln!(
                    "lab: connection from {peer} closed after {:.1} s: {why}",
                    started.elapsed().as_secs_f64()
                );
            }
        });
    }
    let _ = stop.send(true);
    // Wait for the connections to finish, at most `grace`.
    let all = u32::try_from(limits.max_connections.max(1)).unwrap_or(u32::MAX);
    let _ = tokio::time::timeout(grace, slots.acquire_many(all)).await;
    Ok(())
}

/// A client's socket, watched: a request head too long to parse (a line over [`MAX_LINE`]
/// bytes, more than [`MAX_HEADERS`] header lines, over [`MAX_HEAD`] bytes in all) is answered
/// with a JSON 414 or 431 and the connection closed; an answer the client does not read within
/// the write time limit ends the connection.
struct Guarded {
    stream: TcpStream,
    write_timeout: Duration,
    stall: Option<Pin<Box<Sleep>>>,
    /// The lines of the request heads read so far.
    lines: Lines,
    /// Refused: reads drain the rest of the request and then end, writes are dropped.
    refused: bool,
    /// Bytes read and dropped since the refusal, and the quiet time running.
    drained: usize,
    quiet: Option<Pin<Box<Sleep>>>,
}

/// Why a request head is refused before it is parsed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TooLarge {
    /// The request line is longer than [`MAX_LINE`] (414).
    RequestLine,
    /// A header line is longer than [`MAX_LINE`] (431).
    HeaderLine,
    /// More than [`MAX_HEADERS`] header lines (431).
    Headers,
    /// The head is longer than [`MAX_HEAD`] (431).
    Head,
}

impl TooLarge {
    /// The status line and the error.
    fn answer(self) -> (&'static str, String) {
        let most = format!(
            "the lab takes queries of at most {} bytes",
            super::query::MAX_QUERY_BYTES
        );
        match self {
            TooLarge::RequestLine => (
                "414 URI Too Long",
                format!("the request line is longer than {MAX_LINE} bytes: {most}"),
            ),
            TooLarge::HeaderLine => (
                "431 Request Header Fields Too Large",
                format!("a header line is longer than {MAX_LINE} bytes: {most}"),
            ),
            TooLarge::Headers => (
                "431 Request Header Fields Too Large",
                format!(
                    "the request has more than {MAX_HEADERS} header lines: the lab reads at most                      {MAX_HEADERS} (a browser sends about fifteen)"
                ),
            ),
            TooLarge::Head => (
                "431 Request Header Fields Too Large",
                format!(
                    "the request's head is longer than {MAX_HEAD} bytes: the lab reads at most                      {MAX_HEAD}"
                ),
            ),
        }
    }
}

/// The lines of the request heads on a connection, followed byte by byte; a request's body
/// (its `Content-Length` bytes) is skipped, so that a long line of an uploaded record is not
/// taken for a long head line. After a body of unknown length (`Transfer-Encoding: chunked`)
/// the connection is no longer followed (hyper's own limits of the head then apply).
#[derive(Debug, Default)]
struct Lines {
    /// Bytes of the current line, and the current line's number within its head (0: the
    /// request line).
    line: usize,
    line_number: usize,
    /// Bytes of the current head so far.
    head: usize,
    /// The current line's first bytes (enough for the headers looked at).
    start: Vec<u8>,
    /// The current head's `Content-Length`, and whether its body is chunked.
    content_length: Option<u64>,
    chunked: bool,
    /// Bytes of a body still to skip.
    body_left: u64,
    /// A chunked body was seen: the rest of the connection is not followed.
    done: bool,
}

impl Lines {
    /// Follow `bytes`; whether the head they belong to is too large, and how.
    fn too_large(&mut self, bytes: &[u8]) -> Option<TooLarge> {
        for &b in bytes {
            if self.done {
                return None;
            }
            if self.body_left > 0 {
                self.body_left -= 1;
                continue;
            }
            self.head += 1;
            if b == b'\n' {
                if self.line <= 1 {
                    // An empty line ("\r\n" or "\n") ends a head (then its body follows) and the
                    // next line is a request line.
                    if self.line_number > 0 {
                        self.body_left = self.content_length.take().unwrap_or(0);
                        self.done = std::mem::take(&mut self.chunked);
                    }
                    self.line_number = 0;
                    self.head = 0;
                } else {
                    if self.line_number == 0 {
                        self.content_length = None;
                        self.chunked = false;
                    } else {
                        self.header();
                    }
                    self.line_number += 1;
                    // Lines after the request line: header lines.
                    if self.line_number - 1 > MAX_HEADERS {
                        return Some(TooLarge::Headers);
                    }
                }
                self.line = 0;
                self.start.clear();
            } else {
                self.line += 1;
                if self.start.len() < 64 {
                    self.start.push(b);
                }
                if self.line > MAX_LINE {
                    return Some(if self.line_number == 0 {
                        TooLarge::RequestLine
                    } else {
                        TooLarge::HeaderLine
                    });
                }
            }
            if self.head > MAX_HEAD {
                return Some(TooLarge::Head);
            }
        }
        None
    }

    /// Note the body's length or chunking from the header line just read.
    fn header(&mut self) {
        let line = String::from_utf8_lossy(&self.start).to_ascii_lowercase();
        let Some((name, value)) = line.split_once(':') else {
            return;
        };
        let value = value.trim();
        match name.trim() {
            "content-length" => self.content_length = value.parse().ok(),
            "transfer-encoding" => self.chunked = value.contains("chunked"),
            _ => {}
        }
    }
}

impl Guarded {
    fn new(stream: TcpStream, write_timeout: Duration) -> Self {
        Self {
            stream,
            write_timeout,
            stall: None,
            lines: Lines::default(),
            refused: false,
            drained: 0,
            quiet: None,
        }
    }

    /// After a refusal: read and drop what the client still sends; the end of the stream (for
    /// the parser, which then closes) once the client is quiet for [`LINGER`], has closed, or
    /// has sent [`MAX_DRAIN`] bytes more.
    fn drain(&mut self, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let mut scratch = [0u8; 8192];
        loop {
            let mut dropped = ReadBuf::new(&mut scratch);
            match Pin::new(&mut self.stream).poll_read(cx, &mut dropped) {
                Poll::Ready(Ok(())) if !dropped.filled().is_empty() => {
                    self.drained += dropped.filled().len();
                    self.quiet = None;
                    if self.drained > MAX_DRAIN {
                        return Poll::Ready(Ok(()));
                    }
                }
                Poll::Ready(_) => return Poll::Ready(Ok(())),
                Poll::Pending => {
                    let quiet = self
                        .quiet
                        .get_or_insert_with(|| Box::pin(tokio::time::sleep(LINGER)));
                    return match quiet.as_mut().poll(cx) {
                        Poll::Ready(()) => Poll::Ready(Ok(())),
                        Poll::Pending => Poll::Pending,
                    };
                }
            }
        }
    }

    /// Write the refusal straight to the socket (it is small: the socket's buffer takes it).
    fn refuse(&mut self, why: TooLarge) {
        self.refused = true;
        let (status, message) = why.answer();
        let _ = self
            .stream
            .try_write(raw_answer(status, &message).as_bytes());
    }
}

impl AsyncRead for Guarded {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let this = self.get_mut();
        if this.refused {
            return this.drain(cx);
        }
        let before = buf.filled().len();
        let result = Pin::new(&mut this.stream).poll_read(cx, buf);
        if let Poll::Ready(Ok(())) = result {
            let new = buf.filled()[before..].to_vec();
            if let Some(why) = this.lines.too_large(&new) {
                this.refuse(why);
                // Nothing of this read reaches the parser, which sees the end of the stream
                // once the rest of the request is drained.
                buf.set_filled(before);
                return this.drain(cx);
            }
        }
        result
    }
}

impl AsyncWrite for Guarded {
    fn poll_write(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        data: &[u8],
    ) -> Poll<io::Result<usize>> {
        let this = self.get_mut();
        if this.refused {
            return Poll::Ready(Ok(data.len()));
        }
        match Pin::new(&mut this.stream).poll_write(cx, data) {
            Poll::Pending => {
                let timeout = this.write_timeout;
                let stall = this
                    .stall
                    .get_or_insert_with(|| Box::pin(tokio::time::sleep(timeout)));
                if stall.as_mut().poll(cx).is_ready() {
                    return Poll::Ready(Err(io::Error::new(
                        io::ErrorKind::TimedOut,
                        format!(
                            "the client read nothing of the answer for {} s",
                            timeout.as_secs_f64()
                        ),
                    )));
                }
                Poll::Pending
            }
            ready => {
                this.stall = None;
                ready
            }
        }
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().stream).poll_flush(cx)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().stream).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_is_not_a_line_of_the_head() {
        let mut lines = Lines::default();
        // A POST whose body is one line longer than a head's line may be: passes.
        let body = "x".repeat(3 * MAX_LINE);
        let post = format!(
            "POST /api/fit HTTP/1.1\r\nHost: localhost\r\nContent-Length: {}\r\n\r\n{body}",
            body.len()
        );
        for chunk in post.as_bytes().chunks(1000) {
            assert_eq!(lines.too_large(chunk), None);
        }
        // The next request on the connection is followed again: a long request line is not.
        let get = format!("GET /api/steady?{} HTTP/1.1\r\n", "a".repeat(MAX_LINE));
        assert_eq!(lines.too_large(get.as_bytes()), Some(TooLarge::RequestLine));
        // A long header line, and a long request line of a first request.
        let mut lines = Lines::default();
        let head = format!("GET / HTTP/1.1\r\nX-Long: {}\r\n", "b".repeat(MAX_LINE));
        assert_eq!(lines.too_large(head.as_bytes()), Some(TooLarge::HeaderLine));
        assert_eq!(lines.line_number, 1);
        let mut lines = Lines::default();
        assert_eq!(
            lines.too_large("c".repeat(MAX_LINE + 1).as_bytes()),
            Some(TooLarge::RequestLine)
        );
        assert_eq!(lines.line_number, 0);
        // After a chunked body the connection is not followed.
        let mut lines = Lines::default();
        let chunked = format!(
            "POST /api/fit HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n{:x}\r\n{body}\r\n0\r\n\r\n",
            body.len()
        );
        assert_eq!(lines.too_large(chunked.as_bytes()), None);
    }

    #[test]
    fn too_many_header_lines_or_too_long_a_head_is_refused() {
        // MAX_HEADERS header lines pass, one more does not; the count starts again with the
        // next request on the connection.
        let head = |n: usize, size: usize| {
            let mut h = String::from("GET / HTTP/1.1\r\n");
            for k in 0..n {
                h.push_str(&format!("X-{k}: {}\r\n", "v".repeat(size)));
            }
            h
        };
        let mut lines = Lines::default();
        assert_eq!(lines.too_large(head(MAX_HEADERS, 8).as_bytes()), None);
        assert_eq!(lines.too_large(b"\r\n"), None);
        assert_eq!(lines.too_large(head(MAX_HEADERS, 8).as_bytes()), None);
        assert_eq!(
            lines.too_large(b"X-one-more: 1\r\n"),
            Some(TooLarge::Headers)
        );
        // 500 small headers: refused at the first one over.
        let mut lines = Lines::default();
        assert_eq!(
            lines.too_large(head(500, 1).as_bytes()),
            Some(TooLarge::Headers)
        );
        assert_eq!(lines.line_number - 1, MAX_HEADERS + 1);
        // Few lines, each under MAX_LINE, over MAX_HEAD in all.
        let mut lines = Lines::default();
        let n = MAX_HEAD / (MAX_LINE / 2) + 1;
        assert!(n <= MAX_HEADERS);
        assert_eq!(
            lines.too_large(head(n, MAX_LINE / 2).as_bytes()),
            Some(TooLarge::Head)
        );
        // Each refusal is JSON with the security headers.
        for why in [
            TooLarge::RequestLine,
            TooLarge::HeaderLine,
            TooLarge::Headers,
            TooLarge::Head,
        ] {
            let (status, message) = why.answer();
            let answer = raw_answer(status, &message);
            let (head, body) = answer.split_once("\r\n\r\n").unwrap();
            assert!(
                head.starts_with(&format!("HTTP/1.1 {status}\r\n")),
                "{head}"
            );
            for (name, value) in crate::headers::SECURITY_HEADERS {
                assert!(head.contains(&format!("{name}: {value}")), "{head}");
            }
            let body: serde_json::Value = serde_json::from_str(body).unwrap();
            assert_eq!(body["error"], message);
        }
    }
}
