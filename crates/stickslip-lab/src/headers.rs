//! The headers of every answer, and the answers the server writes to a socket itself, before
//! any router sees a request (a request head too long, too many connections from one address):
//! the same JSON error line and the same headers as every other answer.

/// Headers on every answer: no sniffing, no referrer, and a page that loads only its own
/// scripts (ES modules, same origin) and style (no CDN, no inline code).
pub const SECURITY_HEADERS: [(&str, &str); 3] = [
    ("x-content-type-options", "nosniff"),
    ("referrer-policy", "no-referrer"),
    (
        "content-security-policy",
        "default-src 'self'; img-src 'self' data: blob:; connect-src 'self'; \
         object-src 'none'; base-uri 'none'; frame-ancestors 'none'",
    ),
];

/// A whole HTTP/1.1 answer with `status` (`431 Request Header Fields Too Large`) and the JSON
/// `{"error": message}`, the security headers, and `connection: close` (the server closes
/// the connection after it).
pub fn raw_answer(status: &str, message: &str) -> String {
    let body = serde_json::json!({ "error": message }).to_string();
    let mut response = format!("HTTP/1.1 {status}\r\ncontent-type: application/json\r\n");
    for (name, value) in SECURITY_HEADERS {
        response.push_str(&format!("{name}: {value}\r\n"));
    }
    response.push_str(&format!(
        "cache-control: no-store\r\nconnection: close\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    ));
    response
}
