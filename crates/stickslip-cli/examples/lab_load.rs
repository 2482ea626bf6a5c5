//! Load test of `stickslip lab`: many clients at once against `/api/steady` at the paper's
//! Fig. 3 points (PWL diodes, the page's own query), each on a kept-alive connection, for a
//! fixed time; prints the latency percentiles and the errors.
//!
//! ```text
//! cargo run --release -p stickslip-cli --example lab_load -- http://127.0.0.1:8080/ [clients] [seconds]
//! ```
//!
//! `bench/lab-load` starts the server, runs this, and stops the server. Only loopback
//! addresses are accepted: the load goes nowhere else.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The paper's Fig. 3 points (w = Ω/ω0, β), panels (1a)–(2c).
const POINTS: [(f64, f64); 6] = [
    (0.29, 1.07),
    (0.95, 1.07),
    (1.43, 1.07),
    (0.29, 2.14),
    (0.95, 2.14),
    (1.43, 2.14),
];

/// What one client saw.
#[derive(Default)]
struct Tally {
    latencies: Vec<Duration>,
    errors: Vec<String>,
}

/// One GET on a kept-alive connection: the status and the body.
fn get(
    stream: &mut BufReader<TcpStream>,
    host: &str,
    path: &str,
) -> std::io::Result<(u16, Vec<u8>)> {
    write!(
        stream.get_mut(),
        "GET {path} HTTP/1.1\r\nHost: {host}\r\nConnection: keep-alive\r\n\r\n"
    )?;
    let mut line = String::new();
    stream.read_line(&mut line)?;
    let status: u16 = line
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| std::io::Error::other(format!("bad status line {line:?}")))?;
    let mut length = None;
    loop {
        line.clear();
        stream.read_line(&mut line)?;
        let header = line.trim_end();
        if header.is_empty() {
            break;
        }
        if let Some((name, value)) = header.split_once(':') {
            if name.eq_ignore_ascii_case("content-length") {
                length = value.trim().parse::<usize>().ok();
            }
        }
    }
    let length = length.ok_or_else(|| std::io::Error::other("no content-length"))?;
    let mut body = vec![0; length];
    stream.read_exact(&mut body)?;
    Ok((status, body))
}

fn client(host: String, id: usize, stop: Arc<AtomicBool>) -> Tally {
    let mut tally = Tally::default();
    let mut k = id;
    let connect = || TcpStream::connect(&host).map(BufReader::new);
    let mut stream = match connect() {
        Ok(s) => s,
        Err(e) => {
            tally.errors.push(format!("connect: {e}"));
            return tally;
        }
    };
    while !stop.load(Ordering::Relaxed) {
        let (w, beta) = POINTS[k % POINTS.len()];
        k += 1;
        let path = format!("/api/steady?preset=paper&w={w}&beta={beta}&samples=512");
        let started = Instant::now();
        match get(&mut stream, &host, &path) {
            Ok((200, body)) if body.starts_with(b"{\"class\":") => {
                tally.latencies.push(started.elapsed())
            }
            Ok((status, body)) => tally.errors.push(format!(
                "{path}: status {status}: {}",
                String::from_utf8_lossy(&body[..body.len().min(200)])
            )),
            Err(e) => {
                tally.errors.push(format!("{path}: {e}"));
                match connect() {
                    Ok(s) => stream = s,
                    Err(_) => return tally,
                }
            }
        }
    }
    tally
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(url) = args.first() else {
        eprintln!("usage: lab_load URL [clients] [seconds]");
        return ExitCode::from(2);
    };
    let host = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .to_string();
    let is_loopback = host.starts_with("127.") || host.starts_with("localhost:");
    if !is_loopback {
        eprintln!(
            "lab_load: {host} is not a loopback address; the load test only loads this computer"
        );
        return ExitCode::from(2);
    }
    let clients: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    let seconds: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(30.0);
    let stop = Arc::new(AtomicBool::new(false));
    let started = Instant::now();
    let workers: Vec<_> = (0..clients)
        .map(|id| {
            let (host, stop) = (host.clone(), stop.clone());
            std::thread::spawn(move || client(host, id, stop))
        })
        .collect();
    std::thread::sleep(Duration::from_secs_f64(seconds));
    stop.store(true, Ordering::Relaxed);
    let mut latencies = Vec::new();
    let mut errors = Vec::new();
    for worker in workers {
        let tally = worker.join().expect("a client thread");
        latencies.extend(tally.latencies);
        errors.extend(tally.errors);
    }
    let elapsed = started.elapsed().as_secs_f64();
    latencies.sort();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let pct = |p: f64| {
        latencies
            .get(((p / 100.0) * latencies.len() as f64) as usize)
            .or(latencies.last())
            .map_or(f64::NAN, |&d| ms(d))
    };
    println!(
        "lab_load: {clients} clients for {seconds} s against /api/steady at the six Fig. 3 points (PWL, 512 samples per period)"
    );
    println!(
        "requests {}, {:.0} per second, errors {}",
        latencies.len(),
        latencies.len() as f64 / elapsed,
        errors.len()
    );
    println!(
        "latency ms: p50 {:.1}, p95 {:.1}, p99 {:.1}, max {:.1}",
        pct(50.0),
        pct(95.0),
        pct(99.0),
        latencies.last().map_or(f64::NAN, |&d| ms(d))
    );
    for e in errors.iter().take(5) {
        eprintln!("error: {e}");
    }
    if errors.is_empty() && !latencies.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
