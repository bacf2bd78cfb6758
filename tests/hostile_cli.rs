//! Hostile input to the command line, one test per class of defect: whatever a user types, `hw3`
//! answers with exit status 0, 1, 2 or 3 (the README's table), at most one line on stderr for an
//! error, no panic, no raw control character, and nothing written unless it succeeded.

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn hw3(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hw3")).args(args).output().expect("the hw3 binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hw3-hostile-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Exit status 2, nothing on stdout, exactly one clean line on stderr; returns that line.
#[track_caller]
fn refused(output: &Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    assert!(output.stdout.is_empty(), "stdout: {}", String::from_utf8_lossy(&output.stdout));
    assert_eq!(stderr.lines().count(), 1, "one line, got: {stderr}");
    assert!(stderr.starts_with("hw3: "), "{stderr}");
    assert!(!stderr.trim_end().chars().any(char::is_control), "control character in {stderr:?}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let length = stderr.trim_end().chars().count();
    assert!(length <= hw3::cli::MESSAGE_CHARS, "{length} characters: {stderr}");
    stderr
}

#[test]
fn every_count_has_a_bound_named_in_its_message() {
    for (args, option) in [
        (&["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--size", "1000000000"][..], "--size"),
        (
            &["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--size", "18446744073709551615"],
            "--size",
        ),
        (
            &["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--size", "18446744073709551616"],
            "--size",
        ),
        (&["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--size", "1"], "--size"),
        (
            &["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "uniform", "--samples", "1000000000000"],
            "--samples",
        ),
        (&["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "uniform", "--samples", "0"], "--samples"),
        (&["render", "still", "--size", "4096x4096", "--spp", "65536", "--out", "x.png"], "--spp"),
        (&["render", "still", "--spp", "70000"], "--spp"),
        (&["render", "still", "--size", "0x5"], "--size"),
        (&["render", "still", "--size", "9000x1"], "--size"),
    ] {
        let line = refused(&hw3(args));
        assert!(line.contains(option), "{args:?}: {line}");
    }
    // Over the default limit but within --allow-large: the message says so.
    let line = refused(&hw3(&["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--size", "2048"]));
    assert!(line.contains("--allow-large"), "{line}");
}

#[test]
fn files_are_read_within_a_bound() {
    let line = refused(&hw3(&["check", "/dev/zero"]));
    assert!(line.contains("it is a device, not a regular file"), "{line}");
    let dir = scratch("bounded");
    let big = dir.join("big.toml");
    let mut text = String::from("[meta]\nseed = 0\n");
    while text.len() <= hw3::cli::ANSWERS_FILE_BYTES as usize {
        text.push_str("unknown_key_padding = 1\n");
    }
    std::fs::write(&big, text).unwrap();
    refused(&hw3(&["check", big.to_str().unwrap()]));
    refused(&hw3(&["check", dir.to_str().unwrap()]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_output_place_is_checked_before_the_work() {
    let dir = scratch("place");
    let file = dir.join("afile");
    std::fs::write(&file, b"keep").unwrap();
    // A render near the default limit (seconds of work) is refused at once for a bad place.
    for out in ["/nonexistent/dir/x.png", file.join("x.png").to_str().unwrap(), "image.jpg", dir.to_str().unwrap()] {
        let start = Instant::now();
        refused(&hw3(&["render", "fog", "--size", "2048x2048", "--spp", "1", "--out", out]));
        assert!(start.elapsed() < Duration::from_secs(5), "{out}: {:?}", start.elapsed());
    }
    refused(&hw3(&["figures", "--out", file.to_str().unwrap()]));
    assert_eq!(std::fs::read(&file).unwrap(), b"keep");
    assert!(!PathBuf::from("image.jpg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_render_replaces_its_file_whole_and_leaves_no_temporary() {
    let dir = scratch("atomic");
    let out = dir.join("good.png");
    std::fs::write(&out, b"old").unwrap();
    let output = hw3(&["render", "still", "--spp", "1", "--size", "8x8", "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let png = std::fs::read(&out).unwrap();
    assert!(png.starts_with(b"\x89PNG") && png.ends_with(&[0xae, 0x42, 0x60, 0x82]), "a whole PNG, IEND last");
    let names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, ["good.png"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Writing to a full device is an output failure: exit status 3 and one line, never a panic.
#[cfg(target_os = "linux")]
#[test]
fn a_full_stdout_is_exit_status_3_not_a_panic() {
    let template = scratch("full").join("t.toml");
    std::fs::write(&template, hw3(&["template", "--seed", "7"]).stdout).unwrap();
    for args in [
        &["scenes"][..],
        &["answers", "--question", "q3"],
        &["template"],
        &["sphere", "--origin", "-5,1,0", "--dir", "1,0,0", "--center", "0,0,0", "--radius", "2"],
        &["kd-trace", "--origin", "5,0", "--dir", "-1,1"],
        &["effects", "fog"],
        &["effects-table"],
        &["variant", "--question", "q2", "--seed", "1"],
        &["check", template.to_str().unwrap()],
        &["--help"],
    ] {
        let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let output = Command::new(env!("CARGO_BIN_EXE_hw3"))
            .args(args)
            .stdout(Stdio::from(full))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(3), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.contains("cannot write to stdout"), "{stderr}");
    }
    std::fs::remove_dir_all(template.parent().unwrap()).unwrap();
}

#[test]
fn every_seed_a_template_accepts_can_be_checked() {
    let dir = scratch("seeds");
    let file = dir.join("max.toml");
    let max = i64::MAX.to_string();
    let template = hw3(&["template", "--seed", &max]);
    assert!(template.status.success());
    std::fs::write(&file, &template.stdout).unwrap();
    // A blank template is all wrong (exit 1), but readable (not 2).
    assert_eq!(hw3(&["check", file.to_str().unwrap()]).status.code(), Some(1));
    assert_eq!(hw3(&["check", file.to_str().unwrap(), "--seed", &max]).status.code(), Some(1));
    for bad in ["9223372036854775808", "18446744073709551616", "-1", "1.5", ""] {
        for command in [&["template", "--seed", bad][..], &["variant", "--question", "q2", "--seed", bad]] {
            let line = refused(&hw3(command));
            assert!(line.contains("--seed") && line.contains("9223372036854775807"), "{line}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn files_of_the_wrong_kind_are_refused() {
    let dir = scratch("kinds");
    let png = dir.join("fake.hdr");
    std::fs::copy(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/figures/q1_clutter.png"), &png).unwrap();
    let tiny = dir.join("one.hdr");
    std::fs::write(&tiny, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x81").unwrap();
    let huge = dir.join("huge.hdr");
    std::fs::write(&huge, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n").unwrap();
    for (file, says) in [(&png, "not a Radiance"), (&tiny, "at least"), (&huge, "limit")] {
        let line =
            refused(&hw3(&["irradiance", "--env", file.to_str().unwrap(), "--normal", "0,0,1", "--method", "sh9"]));
        assert!(line.contains(says), "{line}");
    }
    let map = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data/q4/courtyard_256x128.hdr");
    assert!(hw3(&["irradiance", "--env", map, "--normal", "0,0,1", "--method", "sh9"]).status.success());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn usage_errors_are_one_line_and_negative_numbers_are_values() {
    for args in [
        &["answers", "--bogus"][..],
        &["sphere"],
        &["render"],
        &["nosuchcommand"],
        &["template", "--seed"],
        &["render", "still", "--spp", "-1"],
        &["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9", "--samples", "-5"],
        &["check", "x.toml", "--format", "xml"],
    ] {
        refused(&hw3(args));
    }
    let line = refused(&hw3(&["template", "--seed", "-1"]));
    assert!(line.contains("--seed") && line.contains("`-1`"), "{line}");
    let sphere = |origin: &[&str]| {
        let mut args = vec!["sphere"];
        args.extend_from_slice(origin);
        args.extend_from_slice(&["--dir", "1,0,0", "--center", "0,0,0", "--radius", "2", "--json"]);
        hw3(&args)
    };
    let spaced = sphere(&["--origin", "-5,1,0"]);
    let joined = sphere(&["--origin=-5,1,0"]);
    assert!(spaced.status.success() && joined.status.success());
    assert_eq!(spaced.stdout, joined.stdout);
    let negative =
        refused(&hw3(&["sphere", "--origin", "-5,1,0", "--dir", "1,0,0", "--center", "0,0,0", "--radius", "-2"]));
    assert!(negative.contains("radius"), "{negative}");
}

#[test]
fn messages_name_the_right_option_and_quote_little_input() {
    let line = refused(&hw3(&["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "foo"]));
    assert!(line.contains("--method") && !line.contains("--env"), "{line}");
    let line = refused(&hw3(&["kd-trace", "--origin", "5", "--dir", "-1,1"]));
    assert!(line.contains("--origin:"), "{line}");
    let line = refused(&hw3(&["kd-trace", "--origin", "5,0", "--dir", "1;1"]));
    assert!(line.contains("--dir:"), "{line}");
    let help = String::from_utf8(hw3(&["sphere", "--help"]).stdout).unwrap();
    assert!(help.contains("> 0") && !help.contains(">= 0"), "{help}");
    let long = "1".repeat(100_000);
    let escape = "\u{1b}[2J\u{7}1,2";
    for args in [
        &["sphere", "--origin", long.as_str(), "--dir", "1,0,0", "--center", "0,0,0", "--radius", "1"][..],
        &["kd-trace", "--origin", escape, "--dir", "1,0"],
        &["answers", "--question", long.as_str()],
        &["effects", escape],
    ] {
        let line = refused(&hw3(args));
        assert!(line.chars().count() < 400, "{} characters", line.chars().count());
    }
    // A student's file: a bad value quoted on stderr, and an answer echoed in the text report.
    let dir = scratch("messages");
    let file = dir.join("escapes.toml");
    let text = format!("[meta]\nseed = 0\n[q2a]\nt = \"\\u001b[31m{}\"\n", "x".repeat(30_000));
    std::fs::write(&file, text).unwrap();
    let line = refused(&hw3(&["check", file.to_str().unwrap()]));
    assert!(line.chars().count() < 400, "{line}");
    let file = dir.join("report.toml");
    std::fs::write(&file, "[meta]\nseed = 0\n[q3d]\nleaves = \"\\u001b[2J\\u0007 x>=3\"\n").unwrap();
    let output = hw3(&["check", file.to_str().unwrap()]);
    assert!(matches!(output.status.code(), Some(1 | 2)));
    let all = [output.stdout, output.stderr].concat();
    let all = String::from_utf8_lossy(&all);
    assert!(!all.chars().any(|c| c.is_control() && c != '\n'), "{all:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Defect class: an answers file whose sections have the wrong shape (`meta = 3`, `q2 = [1, 2]`) is
/// refused as bad input, never graded as if the section were absent; with `--seed` too.
#[test]
fn sections_of_the_wrong_shape_are_refused_not_graded() {
    let dir = scratch("shapes");
    for (name, text, says) in [
        ("meta-int", "meta = 3\n[q2]\na_t = 1.0\n", "`meta`: must be a table"),
        ("meta-array", "meta = [1, 2, 3]\n", "`meta`: must be a table"),
        ("question-string", "q2 = \"all of it\"\n", "`q2`: must be a table"),
    ] {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        for extra in [&[][..], &["--seed", "1"][..]] {
            let mut args = vec!["check", file.to_str().unwrap()];
            args.extend_from_slice(extra);
            let line = refused(&hw3(&args));
            assert!(line.contains(says), "{name}: {line}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `mkfifo`, for the tests that need a named pipe.
#[cfg(unix)]
fn named_pipe(path: &std::path::Path) {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path; mkfifo only creates a file.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo {path:?}");
}

/// Runs `hw3 args`, killed after `limit`: a command that waits on a pipe fails the test instead of
/// hanging it.
fn hw3_within(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hw3"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the hw3 binary runs");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            panic!("{args:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// A named pipe as an answers file, inside a class folder, or as a map: refused at once (a pipe
/// with no writer would block the read forever), and the rest of a class is still graded.
#[cfg(unix)]
#[test]
fn a_named_pipe_is_refused_without_waiting() {
    let dir = scratch("pipes");
    let (pipe, map) = (dir.join("pipe.toml"), dir.join("pipe.hdr"));
    named_pipe(&pipe);
    named_pipe(&map);
    let limit = Duration::from_secs(20);
    let line = refused(&hw3_within(&["check", pipe.to_str().unwrap()], limit));
    assert!(line.contains("it is a named pipe, not a regular file"), "{line}");
    let line = refused(&hw3_within(
        &["irradiance", "--env", map.to_str().unwrap(), "--normal", "0,0,1", "--method", "sh9"],
        limit,
    ));
    assert!(line.contains("named pipe"), "{line}");
    std::fs::write(dir.join("good.toml"), hw3(&["template", "--seed", "1"]).stdout).unwrap();
    let class = hw3_within(&["check", dir.to_str().unwrap(), "--format", "csv"], limit);
    assert_eq!(class.status.code(), Some(1), "{}", String::from_utf8_lossy(&class.stderr));
    let csv = String::from_utf8(class.stdout).unwrap();
    assert!(csv.contains("good.toml") && csv.contains("named pipe"), "{csv}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An `--out` that would destroy something, or whose file cannot exist, is refused before any
/// work, and nothing is created: the answers file itself (however spelled), a symbolic link (such
/// as `/dev/stdout`), a device, a pipe, a folder, a name longer than a file system allows.
#[cfg(unix)]
#[test]
fn an_output_that_would_damage_a_file_is_refused_before_any_work() {
    let dir = scratch("outputs");
    let answers = dir.join("s.toml");
    let template = hw3(&["template", "--seed", "3"]).stdout;
    std::fs::write(&answers, &template).unwrap();
    let spelled = dir.join(".").join("s.toml");
    let link = dir.join("link.txt");
    std::os::unix::fs::symlink("/proc/self/fd/1", &link).unwrap();
    let pipe = dir.join("pipe.txt");
    named_pipe(&pipe);
    let long = dir.join("a".repeat(256));
    let file = answers.to_str().unwrap();
    for (out, says) in [
        (spelled.to_str().unwrap(), "is the answers file"),
        (link.to_str().unwrap(), "symbolic link"),
        ("/dev/null", "it is a device"),
        (pipe.to_str().unwrap(), "it is a named pipe"),
        (dir.to_str().unwrap(), "it is a folder"),
        (long.to_str().unwrap(), "256 bytes"),
    ] {
        let line = refused(&hw3_within(&["check", file, "--out", out], Duration::from_secs(20)));
        assert!(line.contains("--out") && line.contains(says), "{out}: {line}");
    }
    assert_eq!(std::fs::read(&answers).unwrap(), template, "the answers file is untouched");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    // A render refuses a 256-byte name before rendering, and writes a 255-byte one.
    let png = |n: usize| dir.join(format!("{}.png", "b".repeat(n - 4)));
    let line = refused(&hw3(&["render", "still", "--spp", "1", "--size", "8x8", "--out", png(256).to_str().unwrap()]));
    assert!(line.contains("256 bytes"), "{line}");
    let made = hw3(&["render", "still", "--spp", "1", "--size", "8x8", "--out", png(255).to_str().unwrap()]);
    assert!(made.status.success() && png(255).is_file(), "{}", String::from_utf8_lossy(&made.stderr));
    // One results file per student: the folder is made only when there is something to write.
    let (twins, results) = (dir.join("twins"), dir.join("results"));
    for sub in ["a", "b"] {
        std::fs::create_dir_all(twins.join(sub)).unwrap();
        std::fs::write(twins.join(sub).join("x.toml"), &template).unwrap();
    }
    let (a, b) = (twins.join("a/x.toml"), twins.join("b/x.toml"));
    let args = ["check", a.to_str().unwrap(), b.to_str().unwrap(), "--format", "gradescope", "--out"];
    let line = refused(&hw3(&[&args[..], &[results.to_str().unwrap()]].concat()));
    assert!(line.contains("both write x.json"), "{line}");
    assert!(!results.exists(), "no folder made for nothing");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A closed stdout (`hw3 … >&-`) is exit status 3 in every command that prints, before any work;
/// `> /dev/null` is still a place to print to.
#[cfg(unix)]
#[test]
fn a_closed_stdout_is_exit_status_3_in_every_command() {
    use std::os::unix::process::CommandExt as _;
    let dir = scratch("closed");
    let answers = dir.join("t.toml");
    std::fs::write(&answers, hw3(&["template", "--seed", "2"]).stdout).unwrap();
    for args in [
        &["scenes"][..],
        &["answers", "--question", "q1"],
        &["template"],
        &["variant", "--question", "q3", "--seed", "4"],
        &["solution", "--seed", "4", "--question", "q2"],
        &["check", answers.to_str().unwrap()],
        &["sphere", "--origin", "-5,1,0", "--dir", "1,0,0", "--center", "0,0,0", "--radius", "2"],
        &["kd-trace", "--origin", "5,0", "--dir", "-1,1"],
        &["paths", "cornell"],
        &["effect-tables"],
        &["irradiance", "--env", "sky", "--normal", "0,0,1", "--method", "sh9"],
        &["--help"],
    ] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_hw3"));
        command.args(args).stdout(Stdio::inherit()).stderr(Stdio::piped());
        // SAFETY: close(2) is async-signal-safe, as pre_exec requires.
        unsafe {
            command.pre_exec(|| {
                libc::close(1);
                Ok(())
            });
        }
        let start = Instant::now();
        let output = command.output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(3), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.contains("stdout is closed"), "{stderr}");
        assert!(start.elapsed() < Duration::from_secs(5), "{args:?} worked before refusing");
        let null = Command::new(env!("CARGO_BIN_EXE_hw3")).args(args).stdout(Stdio::null()).output().unwrap();
        assert_ne!(null.status.code(), Some(3), "{args:?} > /dev/null");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A message longer than a line keeps what failed and why: long input is quoted shorter, then the
/// middle goes, never the reason at the end.
#[test]
fn long_messages_keep_their_reason() {
    let seed = "9".repeat(400);
    let line = refused(&hw3(&["template", "--seed", &seed]));
    assert!(line.contains("--seed") && line.contains("largest seed"), "{line}");
    let path = format!("{}x.toml", "d/".repeat(400));
    let line = refused(&hw3(&["check", &path]));
    assert!(line.trim_end().ends_with("No such file or directory"), "{line}");
    let dir = scratch("long-messages");
    let file = dir.join("long.toml");
    std::fs::write(&file, format!("[meta]\nseed = 0\n[q2a]\nt = \"{}\n", "x".repeat(5000))).unwrap();
    let line = refused(&hw3(&["check", file.to_str().unwrap()]));
    assert!(line.contains("line 4, column 5006") && line.contains("invalid basic string"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What a success summary shows of a user's input is escaped: no terminal escape, no
/// right-to-left override.
#[test]
fn success_summaries_show_input_escaped() {
    let dir = scratch("summaries");
    let out = dir.join("e\u{1b}[31mred\u{202e}gnp.png");
    let output = hw3(&["render", "still", "--spp", "1", "--size", "8x8", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(output.status.success() && out.is_file(), "{stderr}");
    assert!(!stderr.contains('\u{1b}') && !stderr.contains('\u{202e}'), "{stderr:?}");
    assert!(stderr.contains("\\u{1b}[31mred\\u{202e}gnp.png"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An interrupted command dies of the signal it got, at once, and leaves no temporary beside its
/// target. (Which temporaries are deleted is tested on the list itself in `hw3_core::fsio`: the
/// moment a write is under way is too short to hit from outside.)
#[cfg(unix)]
#[test]
fn an_interrupted_command_leaves_no_temporary() {
    use std::os::unix::process::ExitStatusExt as _;
    let dir = scratch("interrupted");
    let out = dir.join("slow.png");
    for signal in [libc::SIGTERM, libc::SIGINT, libc::SIGHUP] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_hw3"))
            .args([
                "render",
                "still",
                "--spp",
                "4096",
                "--size",
                "256x256",
                "--allow-large",
                "--out",
                out.to_str().unwrap(),
            ])
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(300));
        // SAFETY: kill(2) sends a signal to the child, whose pid is valid until it is waited for.
        unsafe {
            libc::kill(i32::try_from(child.id()).unwrap(), signal);
        }
        let start = Instant::now();
        let status = child.wait().unwrap();
        assert_eq!(status.signal(), Some(signal), "{status:?}");
        assert!(start.elapsed() < Duration::from_secs(5), "the signal ended the render");
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).map(|e| e.file_name()).collect();
        assert!(left.is_empty(), "{left:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Radiance at the edges of `f32`, the probe's texel type: a subnormal map's irradiance is
/// printed with its digits, not as 0; a constant too large for a texel is refused with that
/// reason; the largest that fits is answered (`E = πL`, summed in `f64`).
#[test]
fn irradiance_at_the_edges_of_f32_is_answered_or_refused_truly() {
    let dir = scratch("f32-edges");
    let map = dir.join("subnormal.hdr");
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n".to_vec();
    // Mantissa 3, exponent byte 1: about 7e-41 per channel, below f32's smallest normal 1.2e-38.
    bytes.extend(std::iter::repeat_n([3u8, 3, 3, 1], 16 * 8).flatten());
    std::fs::write(&map, bytes).unwrap();
    let irradiance = |env: &str, method: &str| -> f64 {
        let output = hw3(&["irradiance", "--env", env, "--normal", "0,0,1", "--method", method, "--json"]);
        assert!(output.status.success(), "{env} {method}: {}", String::from_utf8_lossy(&output.stderr));
        let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        json["irradiance"][0].as_f64().unwrap()
    };
    let (sh9, weighted) = (irradiance(map.to_str().unwrap(), "sh9"), irradiance(map.to_str().unwrap(), "weighted"));
    assert!(sh9 > 1e-41 && sh9 < 1e-39 && ((sh9 - weighted) / weighted).abs() < 0.05, "{sh9} {weighted}");
    let text = hw3(&["irradiance", "--env", map.to_str().unwrap(), "--normal", "0,0,1", "--method", "sh9"]);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.starts_with("E(n) = 2.") && text.contains("e-40"), "{text}");
    let line = refused(&hw3(&["irradiance", "--env", "constant:5e307", "--normal", "0,0,1", "--method", "sh9"]));
    assert!(line.contains("above 3.4028235e38") && line.contains("f32"), "{line}");
    let e = irradiance("constant:3e38", "sh9");
    assert!((e / (std::f64::consts::PI * 3e38) - 1.0).abs() < 1e-3, "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A student's answers and file names reach the terminal escaped in every report format: no
/// control character other than a line break, no bidirectional override (JSON keeps them as
/// `\uXXXX` escapes, which read back as the same strings).
#[test]
fn every_report_format_shows_a_students_text_escaped() {
    let dir = scratch("report-escapes");
    let text =
        "[meta]\nseed = 0\n[q2a]\ncase = \"out\\u202eside\\u001b[31m\\u0085\"\nt = 3.0\n[q5a]\na = \"n\\u2066o\"\n";
    let (one, other) = (dir.join("a.toml"), dir.join("b\u{202e}lmot.toml"));
    std::fs::write(&one, text).unwrap();
    std::fs::write(&other, text).unwrap();
    let raw = |c: char| (c.is_control() && c != '\n') || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}');
    for format in ["text", "json", "csv", "gradescope"] {
        for files in [&[one.to_str().unwrap()][..], &[one.to_str().unwrap(), other.to_str().unwrap()]] {
            let output = hw3(&[&["check", "--format", format][..], files].concat());
            assert_eq!(output.status.code(), Some(1), "{format}: {}", String::from_utf8_lossy(&output.stderr));
            let shown = String::from_utf8(output.stdout).unwrap();
            assert!(!shown.chars().any(raw), "{format} {}: {shown:?}", files.len());
            if format == "json" && files.len() == 1 {
                let json: serde_json::Value = serde_json::from_str(&shown).unwrap();
                let given = json["parts"].as_array().unwrap().iter().find(|p| p["key"] == "q2a.case").unwrap();
                assert!(given["given"].as_str().unwrap().contains('\u{202e}'), "{given}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A sphere input beyond `f32`'s range is refused as such, not as "must be finite, got -inf"
/// after the cast; a refusal never shows a NaN.
#[test]
fn sphere_inputs_beyond_a_precision_are_refused_truly() {
    let sphere = |origin: &str, radius: &str, precision: &str| {
        let args = ["sphere", "--origin", origin, "--dir", "1,0,0", "--center", "0,0,0", "--radius", radius];
        refused(&hw3(&[&args[..], &["--precision", precision]].concat()))
    };
    let line = sphere("-1e39,0,0", "1", "f32");
    assert!(line.contains("the origin has -1e39, beyond the largest f32 number, 3.4028235e38"), "{line}");
    let line = sphere("-1,0,0", "1e39", "f32");
    assert!(line.contains("the radius has 1e39"), "{line}");
    let line = sphere("-1e39,0,0", "1", "f64");
    assert!(!line.contains("NaN") && line.contains("f64 cannot solve this case"), "{line}");
}
