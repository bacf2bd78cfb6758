//! The integration tests, in one test binary: each file in `tests/` is a module here, so the
//! dependencies are linked once instead of once per file (`Cargo.toml`, `autotests = false`).
//! Run one file's tests with its module name as the filter, e.g.
//! `cargo test --test integration hostile_fuzz::`. Two binaries of their own: the browser test
//! (`tests/browser.rs`), ignored by default and run alone, and the runner of the unit tests in
//! `src/` (`tests/unit.rs`, a harness of its own).

mod common;

#[path = "chapters_q1_q2.rs"]
mod chapters_q1_q2;
#[path = "chapters_q3_render.rs"]
mod chapters_q3_render;
#[path = "chapters_q4_q5.rs"]
mod chapters_q4_q5;
#[path = "checker_cli.rs"]
mod checker_cli;
#[path = "checker_policy.rs"]
mod checker_policy;
#[path = "cli.rs"]
mod cli;
#[path = "cli_render.rs"]
mod cli_render;
#[path = "docs.rs"]
mod docs;
#[path = "hostile_cli.rs"]
mod hostile_cli;
#[path = "hostile_fuzz.rs"]
mod hostile_fuzz;
#[path = "layering.rs"]
mod layering;
#[path = "notes.rs"]
mod notes;
#[path = "q4_cli.rs"]
mod q4_cli;
#[path = "readme.rs"]
mod readme;
#[path = "solution_cli.rs"]
mod solution_cli;
#[path = "sphere_bounds.rs"]
mod sphere_bounds;
#[path = "threads.rs"]
mod threads;
