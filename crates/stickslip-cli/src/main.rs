//! The `stickslip` command-line tool.
fn main() {}
