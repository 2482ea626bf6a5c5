//! Load test of `stickslip lab`: many clients at once against `/api/steady` at the paper's
//! Fig. 3 points (PWL diodes, the page's own query), each on a kept-alive connection with a
//! client id of its own (as the page sends) and from a loopback address of its own
//! (127.0.1.k: as each student's computer has its address), for a fixed time; prints the
//! latency percentiles and the errors.
//!
//! ```text
//! cargo run --release -p stickslip-cli --example lab_load -- http://127.0.0.1:8080/ [clients] [seconds] [--hogs N] [--half-open N]
//! ```
//!
//! Two scripts that try to stall the class, from other addresses:
//! - `--hogs N`: N connections from 127.0.0.2 without a client id, each asking for the largest
//!   map (200 × 200 points) again and again, during the whole run (a connection refused or
//!   closed connects again a second later);
//! - `--half-open N`: before the clients start, N connections from 127.0.0.3 that send half a
//!   request and wait; then one request of a client is timed alone (the first line printed).
//!
//! `bench/lab-load` starts the server, runs this, and stops the server. Only loopback
//! addresses are accepted: the load goes nowhere else.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpStream};
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

/// A connection to `host` from the loopback address `from`.
fn connect_from(host: &str, from: Ipv4Addr) -> std::io::Result<TcpStream> {
    let to: SocketAddr = host
        .parse()
        .map_err(|_| std::io::Error::other(format!("{host} is not an address and port")))?;
    let socket = socket2::Socket::new(socket2::Domain::IPV4, socket2::Type::STREAM, None)?;
    socket.bind(&SocketAddr::new(IpAddr::V4(from), 0).into())?;
    socket.connect(&to.into())?;
    let stream: TcpStream = socket.into();
    stream.set_nodelay(true)?;
    Ok(stream)
}

/// One GET on a kept-alive connection, with the client id `id` (none: a script without
/// one): the status and the body.
fn get(
    stream: &mut BufReader<TcpStream>,
    host: &str,
    path: &str,
    id: Option<&str>,
) -> std::io::Result<(u16, Vec<u8>)> {
    let id = id.map_or(String::new(), |id| format!("X-Lab-Client: {id}\r\n"));
    write!(
        stream.get_mut(),
        "GET {path} HTTP/1.1\r\nHost: {host}\r\n{id}Connection: keep-alive\r\n\r\n"
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

/// The address of client `id`: 127.0.1.1, 127.0.1.2, ….
fn student_address(id: usize) -> Ipv4Addr {
    Ipv4Addr::new(127, 0, 1, (id % 250 + 1) as u8)
}

fn client(host: String, id: usize, stop: Arc<AtomicBool>) -> Tally {
    let mut tally = Tally::default();
    let mut k = id;
    let name = format!("student-{id}");
    let connect = || connect_from(&host, student_address(id)).map(BufReader::new);
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
        match get(&mut stream, &host, &path, Some(&name)) {
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

/// A script's connection without a client id, asking for the largest map until `stop`:
/// the maps it was answered (whole, or stopped by the time limit), and the refusals (429).
fn hog(host: String, stop: Arc<AtomicBool>) -> (usize, usize) {
    let path = "/api/map?preset=paper&w-steps=200&beta-steps=200";
    let (mut maps, mut refused) = (0, 0);
    while !stop.load(Ordering::Relaxed) {
        let Ok(stream) = connect_from(&host, Ipv4Addr::new(127, 0, 0, 2)) else {
            std::thread::sleep(Duration::from_millis(100));
            continue;
        };
        let mut stream = BufReader::new(stream);
        while !stop.load(Ordering::Relaxed) {
            match get(&mut stream, &host, path, None) {
                Ok((429, _)) => {
                    refused += 1;
                    break;
                }
                Ok(_) => maps += 1,
                Err(_) => break,
            }
        }
        // Refused (or closed): again a second later. The script runs on this computer too,
        // and a loop without a pause would measure its own use of the cores.
        std::thread::sleep(Duration::from_secs(1));
    }
    (maps, refused)
}

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut option = |name: &str| -> Option<usize> {
        let i = args.iter().position(|a| a == name)?;
        let value = args.get(i + 1).and_then(|v| v.parse().ok());
        args.drain(i..(i + 2).min(args.len()));
        value
    };
    let hogs = option("--hogs").unwrap_or(0);
    let half_open = option("--half-open").unwrap_or(0);
    let Some(url) = args.first() else {
        eprintln!("usage: lab_load URL [clients] [seconds] [--hogs N] [--half-open N]");
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
    // Half-sent requests, held open until the end.
    let mut held = Vec::new();
    for _ in 0..half_open {
        let Ok(mut s) = connect_from(&host, Ipv4Addr::new(127, 0, 0, 3)) else {
            break;
        };
        let _ = write!(s, "GET /api/presets HTTP/1.1\r\nHost: {host}\r\nX-Wait:");
        held.push(s);
    }
    if half_open > 0 {
        // The server accepts what it accepts; then one request of a student, timed alone.
        std::thread::sleep(Duration::from_millis(500));
        let t = Instant::now();
        let first = connect_from(&host, student_address(0))
            .map(BufReader::new)
            .and_then(|mut s| get(&mut s, &host, "/api/presets", Some("student-0")));
        println!(
            "after {} half-sent requests ({half_open} asked for): a new request answered {} in {:.1} ms",
            held.len(),
            first.map_or_else(|e| format!("with an error ({e})"), |(status, _)| format!("{status}")),
            t.elapsed().as_secs_f64() * 1e3
        );
    }
    let hog_threads: Vec<_> = (0..hogs)
        .map(|_| {
            let (host, stop) = (host.clone(), stop.clone());
            std::thread::spawn(move || hog(host, stop))
        })
        .collect();
    if hogs > 0 {
        // Let the maps fill the workers first.
        std::thread::sleep(Duration::from_secs(1));
    }
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
    // The maps' connections are closed as they are: their computations stop.
    drop(held);
    let (maps, refused) = hog_threads
        .into_iter()
        .map(|h| h.join().unwrap_or((0, 0)))
        .fold((0, 0), |(m, r), (a, b)| (m + a, r + b));
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
    if hogs > 0 {
        println!(
            "beside {hogs} connections without a client id asking for 200 x 200 maps ({maps} answered, {refused} connections refused)"
        );
    }
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
