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
    assert!(line.contains("limit"), "{line}");
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
