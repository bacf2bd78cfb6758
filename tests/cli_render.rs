//! The renderer's subcommands as a user runs them: exit status, output, and nothing written on
//! bad input.

use std::process::Command;

fn hw3(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_hw3")).args(args).output().expect("the hw3 binary runs")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hw3-cli-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn scenes_lists_every_built_in_scene() {
    let out = hw3(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for name in ["clutter", "fog", "mirrors", "motion", "cornell"] {
        assert!(text.contains(name), "{name} missing from:\n{text}");
    }
}

#[test]
fn paths_prints_text_and_valid_json() {
    let out = hw3(&["paths", "motion"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("time_sampling      run"));
    let out = hw3(&["paths", "motion", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["plan"]["time_sampling"], true);
    assert_eq!(json["plan"]["specular_recursion"], false);
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let path = scratch("still.png");
    let out = hw3(&["render", "still", "--spp", "1", "--size", "20x10", "--out", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let image = hw3::plot::decode_png(&std::fs::read(&path).unwrap()).unwrap();
    assert_eq!((image.width(), image.height()), (20, 10));
}

#[test]
fn bad_input_exits_2_with_one_line_and_writes_nothing() {
    let path = scratch("never.png");
    let target = path.to_str().unwrap();
    for args in [
        vec!["render", "nope", "--out", target],
        vec!["render", "still", "--size", "0x10", "--out", target],
        vec!["render", "still", "--size", "100000x100000", "--out", target],
        vec!["render", "still", "--size", "ten", "--out", target],
        vec!["render", "still", "--spp", "0", "--out", target],
        vec!["render", "still", "--effects", "some", "--out", target],
        vec!["paths", "nope"],
    ] {
        let out = hw3(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(!path.exists(), "{args:?} wrote a file");
    }
}

/// Off a terminal (stderr is a pipe here) a render long enough for a progress bar writes only
/// the one-line summary to stderr: no bar, no carriage returns, no escape sequences.
#[test]
fn render_off_a_terminal_writes_no_progress() {
    let path = scratch("long.png");
    let out = hw3(&["render", "still", "--spp", "1", "--size", "520x510", "--out", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("still: 520x510 at 1 spp"), "{stderr}");
    assert!(!stderr.contains(['\r', '\u{1b}']) && !stderr.contains("rendering"), "{stderr:?}");
    assert!(out.stdout.is_empty());
}
