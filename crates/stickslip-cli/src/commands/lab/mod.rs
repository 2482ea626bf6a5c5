//! `stickslip lab`: a virtual oscilloscope and function generator in the browser, served by
//! this binary and computed by the library on request. The page and its assets are embedded
//! (no CDN, works offline); the JSON API is documented in `docs/lab.md`.
//!
//! - [`query`]: query strings → library types (the model keys are the flags without dashes);
//! - [`api`]: the endpoints' work (steady state, simulation, sweep, map, theory);
//! - [`limit`]: the time limit and the stop of abandoned requests, inside the solvers;
//! - [`router`]: routes, assets, worker threads.

pub mod api;
pub mod limit;
pub mod query;
pub mod router;
#[cfg(test)]
mod tests;

use crate::output::usage;
use anyhow::{Context, Result};
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::Duration;

/// Serve the lab: an oscilloscope and a function generator in the browser, on the exact solver.
///
/// A two-channel scope and a function generator on the RLC-diode circuit (or its mechanical
/// twin), computed by the library on request. The page opens on the paper's circuit at its Fig. 3 point Ω/ω0 = 0.95, β = 2.14:
/// generator (frequency, amplitude, phase), circuit (L, C, R, PWL or Shockley diodes,
/// presets) or mass-spring-friction view, scope (Y-T, X-Y, FFT; steady cycle or transient
/// from rest; cursors), measurements beside the paper's series values and the exact orbit's,
/// the gain swept up and down, the (w, β) map, CSV and PNG export.
///
/// The server listens on 127.0.0.1 (this computer only) unless --host says otherwise, and
/// prints the address to open. It reads no files; each request is capped in size and time.
/// The JSON API under /api/ takes the model flags without dashes as query keys
/// (e.g. /api/steady?preset=paper&freq=9.97k&amplitude=1.498): see docs/lab.md.
///
/// Examples:
///   stickslip lab --open
///   stickslip lab --port 0            # any free port
///   stickslip lab --host 0.0.0.0      # the whole classroom network (a warning says so)
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// TCP port to listen on (0: any free port; the address printed says which).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Address to listen on: 127.0.0.1 serves this computer only; 0.0.0.0 every network
    /// the computer is on.
    #[arg(long, default_value = "127.0.0.1")]
    host: String,
    /// Open the page in the default browser.
    #[arg(long)]
    open: bool,
    /// Time limit of one request in seconds, waiting for a worker included (0.1 to 600).
    #[arg(long = "time-limit", default_value_t = 10.0, value_parser = crate::model::finite, allow_hyphen_values = true)]
    time_limit: f64,
    /// Computations at once; further requests wait for a turn within their time limit
    /// [default: the number of cores].
    #[arg(long, allow_hyphen_values = true)]
    jobs: Option<i64>,
    /// Print one line per request on standard error (method, path, status, milliseconds).
    #[arg(long)]
    verbose: bool,
}

/// The address to listen on: an IP address, or `localhost`.
fn host_address(host: &str) -> Result<IpAddr> {
    if host.eq_ignore_ascii_case("localhost") {
        return Ok(IpAddr::V4(Ipv4Addr::LOCALHOST));
    }
    match host.trim_matches(['[', ']']).parse() {
        Ok(ip) => Ok(ip),
        Err(_) => usage!(
            "invalid --host {host}: an IP address such as 127.0.0.1 (this computer only) or \
             0.0.0.0 (every network)"
        ),
    }
}

/// The URL a browser on this computer opens for a server bound to `addr`.
fn url_of(addr: SocketAddr) -> String {
    let ip = match addr.ip() {
        ip if ip.is_unspecified() && ip.is_ipv4() => IpAddr::V4(Ipv4Addr::LOCALHOST),
        ip if ip.is_unspecified() => IpAddr::V6(std::net::Ipv6Addr::LOCALHOST),
        ip => ip,
    };
    match ip {
        IpAddr::V4(v4) => format!("http://{v4}:{}/", addr.port()),
        IpAddr::V6(v6) => format!("http://[{v6}]:{}/", addr.port()),
    }
}

/// Run `stickslip lab` until Ctrl-C.
pub fn run(args: Args) -> Result<()> {
    let ip = host_address(&args.host)?;
    if !(args.time_limit >= 0.1 && args.time_limit <= 600.0) {
        usage!(
            "invalid --time-limit {}: must be from 0.1 to 600 (seconds)",
            args.time_limit
        );
    }
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    let jobs = match args.jobs {
        None => cores,
        Some(n) if (1..=256).contains(&n) => n as usize,
        Some(n) => usage!("invalid --jobs {n}: must be from 1 to 256"),
    };
    let settings = router::Settings {
        time_limit: Duration::from_secs_f64(args.time_limit),
        jobs,
        verbose: args.verbose,
    };
    let addr = SocketAddr::new(ip, args.port);
    let listener = std::net::TcpListener::bind(addr).with_context(|| {
        format!(
            "cannot listen on {addr}{}",
            if args.port != 0 {
                " (is the port in use? --port 0 picks a free one)"
            } else {
                ""
            }
        )
    })?;
    listener.set_nonblocking(true)?;
    let bound = listener.local_addr()?;
    let url = url_of(bound);
    if !ip.is_loopback() {
        eprintln!(
            "warning: the lab listens on {bound}: anyone who can reach this computer over the \
             network can use it (it reads no files and limits each request to {} s); use \
             --host 127.0.0.1 to serve this computer only",
            args.time_limit
        );
    }
    // The address on standard output, alone on its line, for people and for scripts.
    println!("stickslip lab: {url}");
    std::io::stdout().flush()?;
    eprintln!(
        "lab: {jobs} computation(s) at once, {} s per request; Ctrl-C stops the server",
        args.time_limit
    );
    if args.open {
        if let Err(e) = open_browser(&url) {
            eprintln!("warning: could not open a browser ({e}); open {url} yourself");
        }
    }

    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .max_blocking_threads(jobs + 16)
        .enable_io()
        .enable_time()
        .build()
        .context("cannot start the server's runtime")?;
    runtime.block_on(async move {
        use axum::serve::ListenerExt;
        // Answers go out at once, not held back to be merged with later writes.
        let listener = tokio::net::TcpListener::from_std(listener)?.tap_io(|tcp| {
            let _ = tcp.set_nodelay(true);
        });
        let app = router::router(router::Lab::new(settings));
        axum::serve(listener, app)
            .with_graceful_shutdown(async {
                while !crate::output::interrupted() {
                    tokio::time::sleep(Duration::from_millis(100)).await;
                }
            })
            .await
    })?;
    eprintln!("lab: stopped");
    Ok(())
}

/// Open `url` in the default browser, without waiting for it.
fn open_browser(url: &str) -> std::io::Result<()> {
    use std::process::{Command, Stdio};
    #[cfg(target_os = "macos")]
    let mut command = Command::new("open");
    #[cfg(target_os = "windows")]
    let mut command = {
        let mut c = Command::new("cmd");
        c.args(["/C", "start", ""]);
        c
    };
    #[cfg(not(any(target_os = "macos", target_os = "windows")))]
    let mut command = Command::new("xdg-open");
    let mut child = command
        .arg(url)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()?;
    // Reap the opener when it exits.
    std::thread::spawn(move || child.wait());
    Ok(())
}
