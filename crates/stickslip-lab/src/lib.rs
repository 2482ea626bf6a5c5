//! The lab of stickslip (`stickslip lab`): a virtual oscilloscope and function generator in
//! the browser, served by this crate and computed by the `stickslip` library on request. The
//! page and its assets are embedded (no CDN, works offline); the JSON API is documented in
//! `docs/lab.md`. [`run`] serves it until asked to stop.
//!
//! - [`query`]: query strings → library types (the model keys are the flags without dashes);
//! - [`api`]: the endpoints' work, one file each (steady state, simulation, sweep, map,
//!   theory, presets), and what they share (the answers' parts, the keys of several, the caps);
//! - [`limit`]: the time limit and the stop of abandoned requests, inside the solvers;
//! - [`fair`]: fair turns at the workers, one queue per client, the clients of an address as one;
//! - [`router`]: routes, assets, the `Host` check, worker threads;
//! - [`serve`]: connections, their time limits and their number per address;
//! - [`headers`]: the headers of every answer, and the answers written before routing.

pub mod api;
pub mod fair;
pub mod headers;
pub mod limit;
pub mod query;
pub mod router;
pub mod serve;
#[cfg(test)]
mod tests;

use anyhow::{Context, Result};
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::Duration;
use stickslip::{OptionKey, Spelling};

/// How to serve the lab: what `stickslip lab` takes on its command line.
#[derive(Debug, Clone)]
pub struct Config {
    /// TCP port to listen on (0: any free port; the address printed says which).
    pub port: u16,
    /// Address to listen on: an IP address or `localhost` (127.0.0.1 serves this computer
    /// only, 0.0.0.0 every network the computer is on).
    pub host: String,
    /// Open the page in the default browser.
    pub open: bool,
    /// Time limit of one request in seconds, waiting for a worker included (0.1 to 600).
    pub time_limit: f64,
    /// Computations at once (1 to 256; `None`: the number of cores).
    pub jobs: Option<i64>,
    /// One line per request on standard error.
    pub verbose: bool,
    /// Further host names a request's `Host` header may name.
    pub allow_host: Vec<String>,
}

impl Default for Config {
    /// `stickslip lab` without flags: port 8080 on 127.0.0.1, 10 s per request.
    fn default() -> Self {
        Self {
            port: 8080,
            host: "127.0.0.1".into(),
            open: false,
            time_limit: 10.0,
            jobs: None,
            verbose: false,
            allow_host: Vec::new(),
        }
    }
}

/// A setting of [`Config`] out of its range: the message names the command-line flag and
/// what it allows (`stickslip lab` exits with a usage error on it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InvalidSetting(pub String);

impl std::fmt::Display for InvalidSetting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InvalidSetting {}

/// Fail with an [`InvalidSetting`] made of this message.
macro_rules! invalid {
    ($($arg:tt)*) => {
        return Err(anyhow::Error::new(InvalidSetting(format!($($arg)*))))
    };
}

/// The address to listen on: an IP address, or `localhost`.
fn host_address(host: &str) -> Result<IpAddr> {
    if host.eq_ignore_ascii_case("localhost") {
        return Ok(IpAddr::V4(Ipv4Addr::LOCALHOST));
    }
    match host.trim_matches(['[', ']']).parse() {
        Ok(ip) => Ok(ip),
        Err(_) => invalid!(
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

/// Serve the lab as `config` says until `stop()` returns true (checked every 100 ms; the
/// command-line tool passes its Ctrl-C flag). Prints the address on standard output and
/// what it serves on standard error.
///
/// # Errors
/// An [`InvalidSetting`] for a setting out of range; the port in use; the runtime.
pub fn run(config: Config, stop: impl Fn() -> bool + Send + 'static) -> Result<()> {
    serve_lab(config, None, stop)
}

/// [`run`] with the browser tests' hook: requests as `hold` says wait for the next request to
/// their path ([`router::Hold`]). Only the browser tests' server (the `lab_hold` example of
/// the command-line crate) calls this; `stickslip lab` calls [`run`], and has no flag or
/// variable that holds a request.
///
/// # Errors
/// As [`run`].
pub fn run_holding(
    config: Config,
    hold: router::Hold,
    stop: impl Fn() -> bool + Send + 'static,
) -> Result<()> {
    serve_lab(config, Some(hold), stop)
}

fn serve_lab(
    config: Config,
    hold: Option<router::Hold>,
    stop: impl Fn() -> bool + Send + 'static,
) -> Result<()> {
    let args = config;
    let ip = host_address(&args.host)?;
    if let Err(e) = OptionKey::LabTimeLimit.check(args.time_limit) {
        invalid!("{}", e.render(Spelling::Flag));
    }
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    let jobs = match args.jobs {
        None => cores,
        Some(n) => match OptionKey::LabJobs.check(n as f64) {
            Ok(_) => n as usize,
            Err(e) => invalid!("{}", e.render(Spelling::Flag)),
        },
    };
    let mut hosts = Vec::new();
    for name in &args.allow_host {
        let valid = !name.is_empty()
            && name.len() <= 253
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | ':'));
        if !valid {
            invalid!(
                "invalid --allow-host '{name}': a host name such as lab.school.example or an \
                 address, without scheme, port or path"
            );
        }
        hosts.push(name.trim_end_matches('.').to_ascii_lowercase());
    }
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
    // The addresses the students type: those of the computer's networks.
    let network: Vec<IpAddr> = if ip.is_unspecified() {
        interface_addresses(ip.is_ipv4())
    } else {
        vec![ip]
    };
    hosts.extend(network.iter().map(|ip| ip.to_string()));
    let settings = router::Settings {
        time_limit: Duration::from_secs_f64(args.time_limit),
        jobs,
        verbose: args.verbose,
        hosts,
        hold,
    };
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
    if ip.is_unspecified() {
        let urls: Vec<String> = network
            .iter()
            .filter(|a| !a.is_loopback())
            .map(|&a| url_of(SocketAddr::new(a, bound.port())))
            .collect();
        if urls.is_empty() {
            eprintln!(
                "lab: this computer has no network address but loopback: students cannot reach \
                 it (is it on the classroom network?)"
            );
        } else {
            eprintln!("lab: students on the same network open:");
            for url in urls {
                eprintln!("lab:   {url}");
            }
        }
    }
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
        // A computation that gave its turn away waits for the next one on its own blocking
        // thread: with fewer threads than computations in flight (at most one per connection),
        // a computation holding a turn could wait for a thread held by one waiting for a turn.
        .max_blocking_threads(serve::MAX_CONNECTIONS + jobs + 16)
        .enable_io()
        .enable_time()
        .build()
        .context("cannot start the server's runtime")?;
    runtime.block_on(async move {
        let app = router::router(router::Lab::new(settings));
        serve::serve(
            tokio::net::TcpListener::from_std(listener)?,
            app,
            serve::Limits::default(),
            args.verbose,
            async {
                while !stop() {
                    tokio::time::sleep(Duration::from_millis(100)).await;
                }
            },
            Duration::from_secs_f64(args.time_limit + 1.0),
        )
        .await
    })?;
    eprintln!("lab: stopped");
    Ok(())
}

/// This computer's addresses (IPv4 or IPv6), loopback included: on Linux every interface's,
/// elsewhere the one its default route uses.
fn interface_addresses(v4: bool) -> Vec<IpAddr> {
    let mut found: Vec<IpAddr> = Vec::new();
    if v4 {
        // The kernel's table of local IPv4 addresses: an address line, then "/32 host LOCAL".
        if let Ok(table) = std::fs::read_to_string("/proc/net/fib_trie") {
            let lines: Vec<&str> = table.lines().collect();
            for pair in lines.windows(2) {
                if pair[1].trim() == "/32 host LOCAL" {
                    let text = pair[0].trim().trim_start_matches(['|', '+', '-', ' ']);
                    if let Ok(ip) = text.trim().parse::<Ipv4Addr>() {
                        found.push(IpAddr::V4(ip));
                    }
                }
            }
        }
    } else if let Ok(table) = std::fs::read_to_string("/proc/net/if_inet6") {
        // 32 hex digits, interface index, prefix length, scope (00: global), flags, name.
        for line in table.lines() {
            let mut fields = line.split_whitespace();
            let (Some(hex), Some(scope)) = (fields.next(), fields.nth(2)) else {
                continue;
            };
            let global_or_loopback = scope == "00" || scope == "10";
            if let (true, Ok(bits)) = (global_or_loopback, u128::from_str_radix(hex, 16)) {
                found.push(IpAddr::V6(std::net::Ipv6Addr::from(bits)));
            }
        }
    }
    // The address of the default route: a UDP socket "connected" to a documentation address
    // (RFC 5737 / 3849) sends nothing and reports the local address it would use.
    let probe = if v4 { "192.0.2.1:9" } else { "[2001:db8::1]:9" };
    let any = if v4 { "0.0.0.0:0" } else { "[::]:0" };
    if let Ok(socket) = std::net::UdpSocket::bind(any) {
        if socket.connect(probe).is_ok() {
            if let Ok(local) = socket.local_addr() {
                found.push(local.ip());
            }
        }
    }
    found.push(if v4 {
        IpAddr::V4(Ipv4Addr::LOCALHOST)
    } else {
        IpAddr::V6(std::net::Ipv6Addr::LOCALHOST)
    });
    found.sort();
    found.dedup();
    found.retain(|a| !a.is_unspecified());
    found
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
