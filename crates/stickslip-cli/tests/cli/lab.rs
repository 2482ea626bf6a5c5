//! Tests of `stickslip lab`: the real server on a free loopback port, asked over TCP, against
//! the JSON of `stickslip steady` and `stickslip theory` for the same flags.

use crate::common::*;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

/// A running `stickslip lab`, stopped when dropped.
struct Lab {
    child: Child,
    /// `127.0.0.1:port`.
    address: String,
    /// The lines of its standard error as they come, and those already looked at.
    err: Receiver<String>,
    seen: Vec<String>,
}

impl Lab {
    /// `stickslip lab --port 0` with `args`; with a time limit of 600 s per request unless
    /// `args` set one, so that no answer of these tests depends on the machine's load.
    fn start(args: &[&str]) -> (Self, String) {
        let limit: &[&str] = if args.contains(&"--time-limit") {
            &[]
        } else {
            &["--time-limit", "600"]
        };
        let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args(["lab", "--port", "0"])
            .args(limit)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("stickslip lab starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .trim()
            .strip_prefix("stickslip lab: ")
            .unwrap_or_else(|| panic!("no address on the first line: {line}"))
            .to_string();
        let address = url
            .trim_start_matches("http://")
            .trim_end_matches('/')
            .to_string();
        let (lines, err) = channel();
        let stderr = BufReader::new(child.stderr.take().unwrap());
        std::thread::spawn(move || {
            for line in stderr.lines().map_while(Result::ok) {
                if lines.send(line).is_err() {
                    break;
                }
            }
        });
        (
            Self {
                child,
                address,
                err,
                seen: Vec::new(),
            },
            url,
        )
    }

    /// Wait for a line of standard error that contains `needle` (the verbose log says what
    /// the server did: no clock needed); at most 600 s, so that a test that fails ends.
    fn wait_for_log(&mut self, needle: &str) -> String {
        loop {
            match self.err.recv_timeout(Duration::from_secs(600)) {
                Ok(line) => {
                    self.seen.push(line.clone());
                    if line.contains(needle) {
                        return line;
                    }
                }
                Err(e) => panic!("no line with '{needle}' ({e}): {:?}", self.seen),
            }
        }
    }

    /// GET `path`: status and body.
    fn get(&self, path: &str) -> (u16, String) {
        let (status, _, body) = self.get_with(path, &format!("Host: {}\r\n", self.address));
        (status, body)
    }

    /// GET `path` with these header lines (each ending in CRLF): status, head and body.
    fn get_with(&self, path: &str, headers: &str) -> (u16, String, String) {
        self.get_from(1, path, headers)
    }

    /// A connection from the loopback address 127.0.0.`host` (the lab shares its turns and
    /// caps its connections by address).
    fn connect_from(&self, host: u8) -> TcpStream {
        let to: std::net::SocketAddr = self.address.parse().unwrap();
        let socket = socket2::Socket::new(socket2::Domain::IPV4, socket2::Type::STREAM, None)
            .expect("a socket");
        let from = std::net::SocketAddr::from(([127, 0, 0, host], 0));
        socket.bind(&from.into()).expect("bind a loopback address");
        socket.connect(&to.into()).expect("connect to the lab");
        socket.into()
    }

    /// [`Lab::get_with`] from the loopback address 127.0.0.`host`.
    fn get_from(&self, host: u8, path: &str, headers: &str) -> (u16, String, String) {
        let mut stream = self.connect_from(host);
        write!(
            stream,
            "GET {path} HTTP/1.1\r\n{headers}Connection: close\r\n\r\n"
        )
        .unwrap();
        let mut response = Vec::new();
        // The server may close while the rest of a long request is still being sent.
        let _ = stream.read_to_end(&mut response);
        let response = String::from_utf8_lossy(&response).to_string();
        let (head, body) = response.split_once("\r\n\r\n").expect("a response");
        let status = head.split(' ').nth(1).unwrap().parse().unwrap();
        (status, head.to_string(), body.to_string())
    }

    /// Standard error after Ctrl-C (all of it, the lines looked at before included).
    fn stop(mut self) -> String {
        // SIGINT as Ctrl-C would send it; the server stops gracefully.
        let _ = Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status();
        let status = self.child.wait().unwrap();
        // The reader ends at the end of the stream.
        let mut lines = std::mem::take(&mut self.seen);
        lines.extend(self.err.iter());
        let err = lines.join("\n");
        assert!(status.success(), "exit status {status}: {err}");
        err
    }
}

impl Drop for Lab {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn cli_json(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = run(args);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

#[test]
fn the_lab_answers_as_the_cli_does() {
    let (lab, url) = Lab::start(&[]);
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");
    let (status, body) = lab.get("/api/steady?preset=paper&freq=9.97k&amplitude=1.498");
    assert_eq!(status, 200, "{body}");
    let answer: serde_json::Value = serde_json::from_str(&body).unwrap();
    let cli = cli_json(&[
        "steady",
        "--preset",
        "paper",
        "--freq",
        "9.97k",
        "--amplitude",
        "1.498",
        "--json",
    ]);
    for (key, value) in cli.as_object().unwrap() {
        assert_eq!(&answer[key], value, "key {key}");
    }
    let (status, body) = lab.get("/api/theory?preset=paper&w=0.7&beta=1.2");
    assert_eq!(status, 200, "{body}");
    let theory: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(
        theory,
        cli_json(&["theory", "--preset", "paper", "--w", "0.7", "--beta", "1.2", "--json"])
    );
    let (status, body) = lab.get("/api/steady?preset=paper&freq=9.97k");
    assert_eq!(status, 400);
    assert!(body.contains("missing drive amplitude"), "{body}");
    let (status, _) = lab.get("/nowhere");
    assert_eq!(status, 404);
    let (status, page) = lab.get("/");
    assert_eq!(status, 200);
    assert!(page.contains(r#"name="freq""#));
    let err = lab.stop();
    assert!(err.contains("lab: stopped"), "{err}");
    assert!(!err.contains("warning"), "{err}");
}

#[test]
fn listening_on_every_network_warns() {
    let (lab, url) = Lab::start(&["--host", "0.0.0.0"]);
    // The address to open on this computer is loopback all the same.
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");
    let (status, _) = lab.get("/api/presets");
    assert_eq!(status, 200);
    let err = lab.stop();
    assert!(
        err.contains("warning: the lab listens on 0.0.0.0:")
            && err.contains("anyone who can reach this computer"),
        "{err}"
    );
    // The addresses students type, each with the port (or, on a computer without a
    // network, a line that says so).
    let port = url.trim_end_matches('/').rsplit(':').next().unwrap();
    if err.contains("students on the same network open:") {
        let urls: Vec<&str> = err
            .lines()
            .filter_map(|l| l.strip_prefix("lab:   "))
            .collect();
        assert!(!urls.is_empty(), "{err}");
        for u in urls {
            assert!(
                u.starts_with("http://") && u.ends_with(&format!(":{port}/")),
                "{u}"
            );
            assert!(!u.contains("127.0.0.1") && !u.contains("0.0.0.0"), "{u}");
        }
    } else {
        assert!(err.contains("no network address but loopback"), "{err}");
    }
}

#[test]
fn bad_flags_are_usage_errors() {
    for (args, needle) in [
        (&["lab", "--host", "example"][..], "invalid --host example"),
        (&["lab", "--time-limit", "0"][..], "invalid --time-limit 0"),
        (&["lab", "--jobs", "0"][..], "invalid --jobs 0"),
        (
            &["lab", "--allow-host", "http://x/"][..],
            "invalid --allow-host 'http://x/'",
        ),
    ] {
        let (dir, out) = run(args);
        assert_usage_error(dir.path(), &out, needle);
    }
}

/// The security headers of every answer are in `head`.
fn assert_security_headers(head: &str) {
    let head = head.to_ascii_lowercase();
    for needle in [
        "x-content-type-options: nosniff",
        "referrer-policy: no-referrer",
        "content-security-policy: default-src 'self'",
        "content-type: application/json",
    ] {
        assert!(head.contains(needle), "'{needle}' not in {head}");
    }
}

/// Issue 21, item 9: a 100 kB query gets JSON and the security headers, not a bare 414.
#[test]
fn a_query_far_too_long_is_refused_with_the_usual_headers() {
    let (lab, _) = Lab::start(&[]);
    let host = format!("Host: {}\r\n", lab.address);
    let long = format!(
        "/api/steady?preset=paper&w=1&beta=1&x={}",
        "9".repeat(100_000)
    );
    let (status, head, body) = lab.get_with(&long, &host);
    assert_eq!(status, 414, "{head}");
    assert_security_headers(&head);
    let body: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert!(
        body["error"]
            .as_str()
            .unwrap()
            .contains("the request line is longer than"),
        "{body}"
    );
    // Long, but not too long to read: the lab's own 400, with the same headers.
    let long = format!(
        "/api/steady?preset=paper&w=1&beta=1&x={}",
        "9".repeat(10_000)
    );
    let (status, head, body) = lab.get_with(&long, &host);
    assert_eq!(status, 400, "{head}");
    assert_security_headers(&head);
    assert!(body.contains("at most 4096 allowed"), "{body}");
    // A header line far too long: 431, the same way.
    let (status, head, _) = lab.get_with(
        "/api/presets",
        &format!("{host}X-Junk: {}\r\n", "j".repeat(40_000)),
    );
    assert_eq!(status, 431, "{head}");
    assert_security_headers(&head);
    // The server goes on.
    assert_eq!(lab.get("/api/presets").0, 200);
    lab.stop();
}

/// Issue 21, item 12, on the real server: another host name is refused, unless allowed.
#[test]
fn the_host_header_must_name_the_lab() {
    let (lab, _) = Lab::start(&["--allow-host", "Lab.School.Example"]);
    let port = lab.address.rsplit(':').next().unwrap().to_string();
    for (host, status) in [
        (format!("127.0.0.1:{port}"), 200),
        (format!("localhost:{port}"), 200),
        (format!("lab.school.example:{port}"), 200),
        (format!("rebound.example:{port}"), 403),
        ("attacker.example".to_string(), 403),
    ] {
        let (got, head, body) = lab.get_with("/api/presets", &format!("Host: {host}\r\n"));
        assert_eq!(got, status, "{host}: {body}");
        assert_security_headers(&head);
    }
    lab.stop();
}

/// Whether `stream` is open with nothing to read (the server has not answered or closed it).
fn open_and_silent(stream: &TcpStream) -> bool {
    stream.set_nonblocking(true).unwrap();
    let mut byte = [0u8; 1];
    let silent =
        matches!(stream.peek(&mut byte), Err(e) if e.kind() == std::io::ErrorKind::WouldBlock);
    stream.set_nonblocking(false).unwrap();
    silent
}

/// Read one answer (head and its `content-length` body) from `stream`: the status.
fn read_one_answer(stream: &mut BufReader<&TcpStream>) -> u16 {
    let mut line = String::new();
    stream.read_line(&mut line).unwrap();
    let status = line.split(' ').nth(1).unwrap().parse().unwrap();
    let mut length = 0;
    loop {
        line.clear();
        stream.read_line(&mut line).unwrap();
        if line.trim().is_empty() {
            break;
        }
        if let Some((name, value)) = line.split_once(':') {
            if name.eq_ignore_ascii_case("content-length") {
                length = value.trim().parse().unwrap();
            }
        }
    }
    let mut body = vec![0; length];
    stream.read_exact(&mut body).unwrap();
    status
}

/// Send `request` on a new connection from 127.0.0.`host`, after a request for the presets
/// on the same connection, and read the presets' answer: the lab has then read `request` too
/// (it came in the same write), and goes on to it (it may yet see the connection close
/// first, if it is closed now: see `aborted_requests_are_logged`). Its answer is not read.
fn send_from(lab: &Lab, host: u8, request: &str) -> TcpStream {
    let s = lab.connect_from(host);
    let presets = format!("GET /api/presets HTTP/1.1\r\nHost: {}\r\n\r\n", lab.address);
    (&s).write_all(format!("{presets}{request}").as_bytes())
        .unwrap();
    assert_eq!(read_one_answer(&mut BufReader::new(&s)), 200);
    s
}

/// Issue 21, item 10: while maps that take minutes run, another client's `/api/theory`
/// requests are answered between their turns. Four maps of one client and two of another
/// (200 × 200 with Shockley diodes, minutes each; `--jobs 2`, 600 s per request), from their
/// own addresses, all in the lab first; twenty small requests of a third client all answer
/// while every map is still running. With turns that a map kept to its end, the first small request would wait
/// minutes, for a map to end. (How long the small requests take is measured by
/// `bench/lab-load --hogs`, not asserted here: that depends on the machine's load.)
#[test]
fn maps_of_other_clients_do_not_hold_up_a_client() {
    let (lab, _) = Lab::start(&["--jobs", "2"]);
    let map = |id: &str| {
        format!(
            "GET /api/map?preset=paper&model=shockley&w-steps=200&beta-steps=200 HTTP/1.1\r\n\
             Host: {}\r\nX-Lab-Client: {id}\r\n\r\n",
            lab.address
        )
    };
    // Each map is in the lab (queued or running) once `send_from` returns.
    let mut holders: Vec<TcpStream> = (0..4).map(|_| send_from(&lab, 2, &map("maps-a"))).collect();
    holders.extend((0..2).map(|_| send_from(&lab, 3, &map("maps-b"))));
    for _ in 0..20 {
        let (status, _, body) = lab.get_with(
            "/api/theory?preset=paper&w=0.95&beta=2.14",
            &format!("Host: {}\r\nX-Lab-Client: student-7\r\n", lab.address),
        );
        assert_eq!(status, 200, "{body}");
    }
    // Every map is still running or waiting: not answered, not closed.
    for (k, h) in holders.iter().enumerate() {
        assert!(
            open_and_silent(h),
            "map {k} was answered before the small requests were"
        );
    }
    // The maps' clients go away: their computations stop, and the lab stops cleanly.
    drop(holders);
    lab.stop();
}

/// Issue 21, item 11 and issue 38, item 5: half-sent requests neither block a normal request
/// nor stay open past the header time limit (10 s); the verbose log says why they were
/// closed. From one address, 200 of them: the lab keeps 32 (its cap per address) and answers
/// the others at once with its JSON 429 (or closes them, past the refusals it writes at
/// once); a request from another address is answered while the 32 are open.
#[test]
fn half_sent_requests_are_closed_and_do_not_block_others() {
    use std::time::Instant;
    let (lab, _) = Lab::start(&["--verbose"]);
    let started = Instant::now();
    let half: Vec<TcpStream> = (0..200)
        .map(|_| {
            let mut s = lab.connect_from(2);
            // A refused connection may be closed already.
            let _ = write!(
                s,
                "GET /api/presets HTTP/1.1\r\nHost: {}\r\nX-Wait:",
                lab.address
            );
            s
        })
        .collect();
    let (status, _) = lab.get("/api/presets");
    assert_eq!(status, 200);
    // The lab accepts in order: the first 32 are kept, still open and unanswered now (the
    // header limit is 10 s).
    for (k, s) in half.iter().take(32).enumerate() {
        assert!(
            open_and_silent(s),
            "half-sent request {k} was closed before the limit"
        );
    }
    // The others: a JSON 429 with the security headers, or closed without a word.
    let mut refusals = 0;
    for mut s in half.iter().skip(32) {
        let mut answer = Vec::new();
        let _ = s.read_to_end(&mut answer);
        let answer = String::from_utf8_lossy(&answer);
        if let Some((head, body)) = answer.split_once("\r\n\r\n") {
            assert!(head.starts_with("HTTP/1.1 429 "), "{head}");
            assert_security_headers(head);
            assert!(body.contains("at most 32 open from one address"), "{body}");
            refusals += 1;
        }
    }
    assert!(refusals > 0, "no refusal was answered");
    // The 32 are closed by the server at the header limit: not before it (the end of the
    // stream, or a reset, comes after 10 s). A read waits for it, however long it takes.
    for mut s in half.iter().take(32) {
        let mut buf = [0u8; 64];
        match s.read(&mut buf) {
            Ok(_) => {}
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::ConnectionReset | std::io::ErrorKind::BrokenPipe
                ) => {}
            Err(e) => panic!("reading a half-sent connection: {e}"),
        }
    }
    let closed_after = started.elapsed();
    assert!(
        closed_after >= Duration::from_millis(9500),
        "closed after {closed_after:?}, before the limit"
    );
    drop(half);
    let err = lab.stop();
    assert!(err.contains("no complete request within 10 s"), "{err}");
    assert!(
        err.contains("refused: 32 open from its address already"),
        "{err}"
    );
}

/// Issue 21, item 11: a request whose client went away is in the verbose log, with its
/// path cut to a sane length and the client's address. No clock: the log is read as it comes
/// (a request in flight is logged before the end of its connection). A connection closed at
/// once after the presets' answer may reach the lab before it went on to the map; then it is
/// tried again.
#[test]
fn aborted_requests_are_logged() {
    let (mut lab, _) = Lab::start(&["--verbose", "--jobs", "1"]);
    let long_path = "/api/map?preset=paper&model=shockley&w-steps=100&beta-steps=100";
    let map = format!("GET {long_path} HTTP/1.1\r\nHost: {}\r\n\r\n", lab.address);
    // A map of minutes, whose client goes away.
    let mut attempts = 0;
    let line = loop {
        attempts += 1;
        assert!(
            attempts <= 100,
            "no map was in the lab when its client went away"
        );
        let s = send_from(&lab, 2, &map);
        let who = s.local_addr().unwrap().to_string();
        drop(s);
        let closed = lab.wait_for_log(&format!("connection from {who} closed"));
        let aborted = lab.seen[..lab.seen.len() - 1]
            .iter()
            .find(|l| l.contains(&format!("({who})")))
            .cloned();
        if let Some(line) = aborted {
            break line;
        }
        assert!(closed.contains("closed after"), "{closed}");
    };
    assert!(
        line.starts_with("lab: GET /api/map aborted after") && line.ends_with("went away"),
        "{line}"
    );
    let junk = format!("/{}", "p".repeat(300));
    assert_eq!(lab.get(&junk).0, 404);
    let err = lab.stop();
    let line = err
        .lines()
        .find(|l| l.contains("/ppp"))
        .expect("the 404 is logged");
    assert!(line.len() < 160, "{line}");
}
