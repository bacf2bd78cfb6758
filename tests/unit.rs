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
use std::backtrace::Backtrace;
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
    // libtest reads `RUST_TEST_THREADS` when `--test-threads` is not given; libtest-mimic does not,
    // and with 0 threads it would wait forever: refused, as libtest refuses it.
    if args.test_threads.is_none()
        && let Ok(text) = std::env::var("RUST_TEST_THREADS")
    {
        args.test_threads = Some(text.parse().unwrap_or(0));
    }
    if args.test_threads == Some(0) {
        eprintln!("error: the number of test threads (--test-threads or RUST_TEST_THREADS) must be a positive integer");
        std::process::exit(101);
    }
    // A panic in a test's body is kept for its report, as libtest keeps the test thread's output,
    // with a backtrace when `RUST_BACKTRACE` asks for one (`full`: every frame). Any other panic
    // (a rayon worker's, the runner's own) is printed by the default hook as it happens; libtest
    // would capture a worker's message too when the test started the thread, and here a test that
    // fails through a worker's panic reports its message without the place.
    let backtrace = std::env::var("RUST_BACKTRACE").ok().filter(|value| value != "0");
    let default_hook = panic::take_hook();
    panic::set_hook(Box::new(move |info| {
        if IN_TEST.get() {
            let text = match backtrace.as_deref() {
                Some("full") => format!("{info}\n{:#}", Backtrace::force_capture()),
                Some(_) => format!("{info}\n{}", Backtrace::force_capture()),
                None => info.to_string(),
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
    let report = |payload: &(dyn Any + Send)| {
        LAST_PANIC.take().unwrap_or_else(|| format!("panicked: {}", message(payload).unwrap_or("(no message)")))
    };
    match (outcome, test.should_panic) {
        (Ok(()), None) => Ok(()),
        (Err(payload), None) => Err(report(&*payload).into()),
        (Ok(()), Some(_)) => Err("test did not panic as expected".into()),
        (Err(_), Some("")) => Ok(()),
        (Err(payload), Some(expected)) if message(&*payload).is_some_and(|m| m.contains(expected)) => Ok(()),
        (Err(payload), Some(expected)) => {
            Err(format!("panic did not contain expected string\n  expected: {expected:?}\n  {}", report(&*payload))
                .into())
        }
    }
}

/// A panic payload's message: `panic!` makes a `&str` or a `String`; `None` for any other payload
/// (`panic_any`), which an expected text never matches, as under libtest.
fn message(payload: &(dyn Any + Send)) -> Option<&str> {
    payload.downcast_ref::<&str>().copied().or_else(|| payload.downcast_ref::<String>().map(String::as_str))
}

/// Registration is by the linker (a `linkme` distributed slice), so a test it dropped would be
/// missing without a word: every `#[unit_test]` line in `src/` must be one registered test, and no
/// name may be registered twice. And a `#[test]` in `src/` would never run (the library is not
/// compiled by `rustc --test`), so there must be none but the one signpost in `lib.rs` that
/// `cargo test --lib` finds.
fn every_unit_test_is_registered() -> Result<(), Failed> {
    /// The lines of every `.rs` file under `dir` that are exactly `#[unit_test]` and `#[test]`,
    /// read in one pass.
    fn count(dir: &Path) -> (usize, usize) {
        std::fs::read_dir(dir).unwrap().map(|entry| entry.unwrap().path()).fold((0, 0), |(unit, plain), path| {
            let (u, p) = match path.extension() {
                _ if path.is_dir() => count(&path),
                Some(ext) if ext == "rs" => {
                    std::fs::read_to_string(&path).unwrap().lines().fold((0, 0), |(u, p), line| {
                        (u + usize::from(line.trim() == "#[unit_test]"), p + usize::from(line.trim() == "#[test]"))
                    })
                }
                _ => (0, 0),
            };
            (unit + u, plain + p)
        })
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    let signposts = lib.lines().filter(|line| line.trim() == "#[test]").count();
    let signpost_kept = signposts == 1 && lib.contains("fn unit_tests_run_with_cargo_test_test_unit()");
    // Whole lines only: the crate writes each attribute on a line of its own (rustfmt's layout).
    let (written, all_plain) = count(&src);
    let plain = all_plain - signposts;
    let mut names: Vec<&str> = UNIT_TESTS.iter().map(|test| test.name).collect();
    names.sort_unstable();
    names.dedup();
    if written == UNIT_TESTS.len() && names.len() == UNIT_TESTS.len() && plain == 0 && signpost_kept {
        Ok(())
    } else {
        Err(format!(
            "{written} `#[unit_test]` lines in src/, {} tests registered, {} distinct names; \
             {plain} `#[test]` lines outside lib.rs's signpost (a `#[test]` in src/ never runs: write \
             `#[unit_test]`); the signpost {}",
            UNIT_TESTS.len(),
            names.len(),
            if signpost_kept { "kept" } else { "missing or doubled" }
        )
        .into())
    }
}

/// The judging above on made-up tests: a pass, a failure that reports where it panicked, and the
/// ways a `should_panic` test can end.
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
        (
            "should_panic: a panic without a message fails a text",
            failure(&test(|| std::panic::panic_any(5_u32), Some("panic"))).is_some(),
        ),
    ];
    let wrong: Vec<&str> = checks.iter().filter(|(_, ok)| !ok).map(|(what, _)| *what).collect();
    if wrong.is_empty() { Ok(()) } else { Err(format!("misjudged: {wrong:?}").into()) }
}
