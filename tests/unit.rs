//! The runner of hw3's unit tests: the functions in `src/` marked `#[unit_test]`.
//!
//! They are compiled into the library under the `unit-tests` feature, which `cargo test` turns on,
//! so that the library is compiled once for `cargo test` and not a second time as Cargo's
//! "lib test" build (`hw3::testing` says why); `#[unit_test]` registers each one in
//! `hw3::testing::UNIT_TESTS`. This runner gives them libtest's command line and report
//! (libtest-mimic): `cargo test --test unit -- FILTER`, `--exact`, `--ignored`, `--list`,
//! `--test-threads N`, names as libtest would print them (`kdtree::stack::tests::…`).
//!
//! What libtest does and is done here: a `should_panic` test passes only if it panics with the
//! expected text in its message; a panic in a test's body is kept for the report (with a backtrace
//! under `RUST_BACKTRACE`) instead of being printed while the tests run, so a passing test that
//! panics on purpose prints nothing; `RUST_TEST_THREADS` is read. Not done: standard output is not
//! captured (only the ignored, on-demand measurements print), an ignored test's reason is not
//! printed, and the runner's threads run one test after another, so a test must leave its
//! thread-local state as it found it, even when it fails.

use std::any::Any;
use std::backtrace::{Backtrace, BacktraceStatus};
use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};
use std::path::Path;

use hw3::testing::{UNIT_TESTS, UnitTest};
use libtest_mimic::{Arguments, Failed, Trial};

thread_local! {
    /// Whether this thread is running a test's body ([`run`]).
    static IN_TEST: Cell<bool> = const { Cell::new(false) };
    /// The last panic of a test's body on this thread, as the default hook would have printed it.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

fn main() {
    let mut args = Arguments::from_args();
    // libtest reads `RUST_TEST_THREADS` when `--test-threads` is not given; libtest-mimic does not.
    if args.test_threads.is_none() {
        args.test_threads = std::env::var("RUST_TEST_THREADS").ok().and_then(|n| n.parse().ok()).filter(|&n| n > 0);
    }
    // A panic in a test's body is kept for its report, as libtest keeps the test thread's output;
    // any other (a rayon worker's, the runner's own) is printed by the default hook, as under
    // libtest.
    let default_hook = panic::take_hook();
    panic::set_hook(Box::new(move |info| {
        if IN_TEST.get() {
            let backtrace = Backtrace::capture();
            let text = match backtrace.status() {
                BacktraceStatus::Captured => format!("{info}\n{backtrace}"),
                _ => info.to_string(),
            };
            LAST_PANIC.set(Some(text));
        } else {
            default_hook(info);
        }
    }));
    let mut tests: Vec<&'static UnitTest> = UNIT_TESTS.iter().collect();
    tests.sort_by_key(|test| test.name);
    let mut trials: Vec<Trial> = tests
        .into_iter()
        .map(|test| {
            Trial::test(test.name.strip_prefix("hw3::").unwrap_or(test.name), move || run(test))
                .with_ignored_flag(test.ignore.is_some())
        })
        .collect();
    trials.push(Trial::test("runner::every_unit_test_in_src_is_registered_once", every_unit_test_is_registered));
    trials.push(Trial::test("runner::judges_like_libtest", judges_like_libtest));
    libtest_mimic::run(&args, trials).exit();
}

/// Runs one test and judges it, `should_panic` included.
fn run(test: &UnitTest) -> Result<(), Failed> {
    LAST_PANIC.take();
    IN_TEST.set(true);
    let outcome = panic::catch_unwind(AssertUnwindSafe(test.run));
    IN_TEST.set(false);
    let report =
        |payload: &(dyn Any + Send)| LAST_PANIC.take().unwrap_or_else(|| format!("panicked: {}", message(payload)));
    match (outcome, test.should_panic) {
        (Ok(()), None) => Ok(()),
        (Err(payload), None) => Err(report(&*payload).into()),
        (Ok(()), Some(_)) => Err("test did not panic as expected".into()),
        (Err(payload), Some(expected)) if message(&*payload).contains(expected) => Ok(()),
        (Err(payload), Some(expected)) => {
            Err(format!("panic did not contain expected string\n  expected: {expected:?}\n  {}", report(&*payload))
                .into())
        }
    }
}

/// A panic payload's message: `panic!` makes a `&str` or a `String`.
fn message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

/// Registration is by the linker (a `linkme` distributed slice), so a test it dropped would be
/// missing without a word: every `#[unit_test]` line in `src/` must be one registered test, and no
/// name may be registered twice. And a `#[test]` in `src/` would never run (the library is not
/// compiled by `rustc --test`), so there must be none but the signpost in `lib.rs` that
/// `cargo test --lib` finds.
fn every_unit_test_is_registered() -> Result<(), Failed> {
    fn count(dir: &Path, attribute: &str) -> usize {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|entry| entry.unwrap().path())
            .map(|path| match path.extension() {
                _ if path.is_dir() => count(&path, attribute),
                Some(ext) if ext == "rs" => {
                    std::fs::read_to_string(&path).unwrap().lines().filter(|line| line.trim() == attribute).count()
                }
                _ => 0,
            })
            .sum()
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let (written, plain) = (count(&src, "#[unit_test]"), count(&src, "#[test]"));
    let mut names: Vec<&str> = UNIT_TESTS.iter().map(|test| test.name).collect();
    names.sort_unstable();
    names.dedup();
    if written == UNIT_TESTS.len() && names.len() == UNIT_TESTS.len() && plain == 1 {
        Ok(())
    } else {
        Err(format!(
            "{written} `#[unit_test]` lines in src/, {} tests registered, {} distinct names; \
             {plain} `#[test]` lines in src/, where only lib.rs's signpost may be one (a `#[test]` \
             there never runs: write `#[unit_test]`)",
            UNIT_TESTS.len(),
            names.len()
        )
        .into())
    }
}

/// The judging above on made-up tests: a pass, a failure that reports where it panicked, and the
/// three ways a `should_panic` test can end.
fn judges_like_libtest() -> Result<(), Failed> {
    let test = |body: fn(), should_panic| UnitTest { name: "made_up", run: body, ignore: None, should_panic };
    let failure = |test: &UnitTest| run(test).err().map(|failed| failed.message().unwrap_or_default().to_string());
    let checks = [
        ("a test that returns passes", failure(&test(|| {}, None)).is_none()),
        (
            "a panic fails, reported with its place and message",
            failure(&test(|| panic!("boom"), None)).is_some_and(|m| m.contains("tests/unit.rs") && m.contains("boom")),
        ),
        ("should_panic: no panic fails", failure(&test(|| {}, Some("boom"))).is_some()),
        ("should_panic: the expected text passes", failure(&test(|| panic!("a boom here"), Some("boom"))).is_none()),
        (
            "should_panic: another message fails",
            failure(&test(|| panic!("bang"), Some("boom"))).is_some_and(|m| m.contains("bang")),
        ),
        ("should_panic: any panic passes without a text", failure(&test(|| panic!("bang"), Some(""))).is_none()),
    ];
    let wrong: Vec<&str> = checks.iter().filter(|(_, ok)| !ok).map(|(what, _)| *what).collect();
    if wrong.is_empty() { Ok(()) } else { Err(format!("misjudged: {wrong:?}").into()) }
}
