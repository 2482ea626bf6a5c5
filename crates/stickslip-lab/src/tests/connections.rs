//! The real server (`serve::serve` on a loopback socket, with the router) asked over TCP from
//! several loopback addresses (127.0.0.2, … are this computer too): turns are shared by
//! address, one address holds at most its share of the connections, and a request head too
//! large is answered with the lab's JSON and headers. Nothing here waits for a clock: the
//! server's own time limits are far longer than the tests (600 s), and every check is of
//! order, counts and answers.

use crate::fair::Client;
use crate::router::{router, Lab, Settings};
use crate::serve::{serve, Limits, MAX_HEADERS};
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpSocket, TcpStream};
use tokio::sync::oneshot;

/// Longer than any test: no connection or computation ends by a clock while one runs.
const LONG: Duration = Duration::from_secs(600);

/// A lab served on a free loopback port until the sender is dropped.
struct Served {
    lab: Lab,
    address: SocketAddr,
    _stop: oneshot::Sender<()>,
}

async fn served(jobs: usize, per_address: usize, max_connections: usize) -> Served {
    let lab = Lab::new(Settings {
        time_limit: LONG,
        jobs,
        verbose: false,
        hosts: Vec::new(),
        hold: None,
    });
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap();
    let (stop, stopped) = oneshot::channel::<()>();
    let limits = Limits {
        header_timeout: LONG,
        write_timeout: LONG,
        max_connections,
        per_address,
    };
    tokio::spawn(serve(
        listener,
        router(lab.clone()),
        limits,
        false,
        async {
            let _ = stopped.await;
        },
        Duration::from_secs(1),
    ));
    Served {
        lab,
        address,
        _stop: stop,
    }
}

/// A connection to `to` from the loopback address 127.0.0.`host`.
async fn connect_from(host: u8, to: SocketAddr) -> TcpStream {
    let socket = TcpSocket::new_v4().unwrap();
    socket
        .bind(SocketAddr::new(
            IpAddr::V4(Ipv4Addr::new(127, 0, 0, host)),
            0,
        ))
        .unwrap();
    socket.connect(to).await.unwrap()
}

/// Send `request` whole and read the answer to the end (the server closes): status, head
/// and body; `None` if the connection was closed or reset without an answer.
async fn exchange(stream: &mut TcpStream, request: &str) -> Option<(u16, String, String)> {
    let _ = stream.write_all(request.as_bytes()).await;
    read_answer(stream).await
}

async fn read_answer(stream: &mut TcpStream) -> Option<(u16, String, String)> {
    let mut answer = Vec::new();
    let _ = stream.read_to_end(&mut answer).await;
    let answer = String::from_utf8_lossy(&answer).to_string();
    let (head, body) = answer.split_once("\r\n\r\n")?;
    let status = head.split(' ').nth(1)?.parse().ok()?;
    Some((status, head.to_string(), body.to_string()))
}

fn get(path: &str, headers: &str) -> String {
    format!("GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n{headers}Connection: close\r\n\r\n")
}

/// The lab's error answer: JSON with the security headers.
fn assert_lab_error(head: &str, body: &str, needle: &str) {
    let lower = head.to_ascii_lowercase();
    assert!(lower.contains("content-type: application/json"), "{head}");
    for (name, value) in crate::headers::SECURITY_HEADERS {
        assert!(lower.contains(&format!("{name}: {value}")), "{head}");
    }
    let body: serde_json::Value = serde_json::from_str(body).expect("JSON");
    let error = body["error"].as_str().expect("an error line");
    assert!(error.contains(needle), "'{needle}' not in '{error}'");
}

/// Wait until `done()` (the server's state, polled).
async fn until(mut done: impl FnMut() -> bool) {
    while !done() {
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
}

/// Issue 38, item 5: a script at one address, with thirty connections and no client id, each
/// asking for a map that takes minutes, gets the turns of one address: a student's page at
/// another address waits for at most one turn of the script's before each of its requests
/// (with a turn per connection, as before, it waited for about thirty).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_script_of_many_connections_gets_the_turns_of_one_address() {
    let lab = served(1, 32, 400).await;
    let map = get(
        "/api/map?preset=paper&model=shockley&w-steps=200&beta-steps=200",
        "",
    );
    let mut hogs = Vec::new();
    for _ in 0..30 {
        let mut s = connect_from(2, lab.address).await;
        s.write_all(map.as_bytes()).await.unwrap();
        hogs.push(s);
    }
    // Every map is queued or running.
    until(|| lab.lab.fair().held_at("127.0.0.2") == 30).await;
    let student = Client::new("127.0.0.1", "student-page");
    for _ in 0..5 {
        let mut s = connect_from(1, lab.address).await;
        let (status, _, body) = exchange(
            &mut s,
            &get(
                "/api/theory?preset=paper&w=0.95&beta=2.14",
                "X-Lab-Client: student-page\r\n",
            ),
        )
        .await
        .expect("an answer");
        assert_eq!(status, 200, "{body}");
    }
    let waits: Vec<u64> = lab
        .lab
        .fair()
        .waits()
        .into_iter()
        .filter(|(c, _)| *c == student)
        .map(|(_, others)| others)
        .collect();
    assert_eq!(
        waits.len(),
        5,
        "each request of the student waited for a turn"
    );
    assert!(
        waits.iter().all(|&n| n <= 1),
        "turns given to the script while the student waited: {waits:?}"
    );
    // The maps were never answered: they ran (or waited) all along.
    assert_eq!(lab.lab.fair().held_at("127.0.0.2"), 30);
    // The script goes away: its computations stop.
    drop(hogs);
    until(|| lab.lab.active() == 0 && lab.lab.fair().held_at("127.0.0.2") == 0).await;
}

/// Issue 38, item 5: 420 half-sent requests from one address (over the server's 400) hold
/// only that address's 32 connections; the others are answered with the lab's JSON 429 (or,
/// past the refusals the server writes at once, closed), and another address's request is
/// answered while the 32 stay open.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_address_holds_at_most_its_share_of_the_connections() {
    let lab = served(2, 32, 400).await;
    let mut half = Vec::new();
    for _ in 0..420 {
        let mut s = connect_from(2, lab.address).await;
        s.write_all(b"GET /api/presets HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Wait:")
            .await
            .unwrap();
        half.push(s);
    }
    let mut other = connect_from(1, lab.address).await;
    let (status, _, body) = exchange(&mut other, &get("/api/presets", ""))
        .await
        .expect("an answer");
    assert_eq!(status, 200, "{body}");
    // Now the half-sent requests are finished: the 32 admitted are answered; the others had
    // their 429 (or were closed) at once.
    let (mut answered, mut refused) = (0, 0);
    for s in &mut half {
        match exchange(s, " 1\r\nConnection: close\r\n\r\n").await {
            Some((200, _, _)) => answered += 1,
            Some((429, head, body)) => {
                assert_lab_error(&head, &body, "at most 32 open from one address");
                refused += 1;
            }
            Some((status, head, _)) => panic!("{status}: {head}"),
            None => {}
        }
    }
    assert_eq!(answered, 32);
    assert!(refused > 0, "no refusal was answered");
}

/// Issue 38, item 5: a request with 500 small headers is answered with the lab's JSON 431
/// and its security headers (not the parser's bare 431); 64 headers pass.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_request_with_500_headers_gets_the_labs_json_431() {
    let lab = served(2, 32, 400).await;
    let headers: String = (0..500).map(|k| format!("X-{k}: {k}\r\n")).collect();
    let mut s = connect_from(1, lab.address).await;
    let (status, head, body) = exchange(&mut s, &get("/api/presets", &headers))
        .await
        .expect("an answer");
    assert_eq!(status, 431, "{head}");
    assert_lab_error(
        &head,
        &body,
        &format!("more than {MAX_HEADERS} header lines"),
    );
    // At the cap (with Host and Connection): answered.
    let headers: String = (0..MAX_HEADERS - 2)
        .map(|k| format!("X-{k}: {k}\r\n"))
        .collect();
    let mut s = connect_from(1, lab.address).await;
    let (status, head, _) = exchange(&mut s, &get("/api/presets", &headers))
        .await
        .expect("an answer");
    assert_eq!(status, 200, "{head}");
}
