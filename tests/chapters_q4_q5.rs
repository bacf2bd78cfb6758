//! Claims of the chapters recomputed from first principles or from the committed data (one
//! module per group of chapters; `tests/docs.rs` holds the older ones).

#![allow(unused_imports)]
use std::path::Path;

const DOCS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs");

#[allow(dead_code)]
fn chapter(name: &str) -> String {
    std::fs::read_to_string(Path::new(DOCS).join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}
