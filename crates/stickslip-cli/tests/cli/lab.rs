//! Tests of `stickslip lab`: the real server on a free loopback port, asked over TCP, against
//! the JSON of `stickslip steady` and `stickslip theory` for the same flags.

use crate::common::*;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A running `stickslip lab`, stopped when dropped.
struct Lab {
    child: Child,
    /// `127.0.0.1:port`.
    address: String,
}

impl Lab {
    fn start(args: &[&str]) -> (Self, String) {
        let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args(["lab", "--port", "0"])
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
        (Self { child, address }, url)
    }

    /// GET `path`: status and body.
    fn get(&self, path: &str) -> (u16, String) {
        let mut stream = TcpStream::connect(&self.address).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(60)))
            .unwrap();
        write!(
            stream,
            "GET {path} HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n",
            self.address
        )
        .unwrap();
        let mut response = String::new();
        stream.read_to_string(&mut response).unwrap();
        let (head, body) = response.split_once("\r\n\r\n").expect("a response");
        let status = head.split(' ').nth(1).unwrap().parse().unwrap();
        (status, body.to_string())
    }

    /// Standard error after Ctrl-C.
    fn stop(mut self) -> String {
        // SIGINT as Ctrl-C would send it; the server stops gracefully.
        let _ = Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status();
        let status = self.child.wait().unwrap();
        let mut err = String::new();
        self.child
            .stderr
            .take()
            .unwrap()
            .read_to_string(&mut err)
            .unwrap();
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
}

#[test]
fn bad_flags_are_usage_errors() {
    for (args, needle) in [
        (&["lab", "--host", "example"][..], "invalid --host example"),
        (&["lab", "--time-limit", "0"][..], "invalid --time-limit 0"),
        (&["lab", "--jobs", "0"][..], "invalid --jobs 0"),
    ] {
        let (dir, out) = run(args);
        assert_usage_error(dir.path(), &out, needle);
    }
}
