//! The command-line contract: output shapes other tools rely on, and exit status 2 with a one-line
//! message (and no panic) for every kind of bad input.

use std::process::{Command, Output};

fn hw3(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hw3")).args(args).output().expect("the hw3 binary runs")
}

fn json(output: &Output) -> serde_json::Value {
    assert!(output.status.success(), "stderr: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("stdout is one JSON value")
}

fn assert_usage_error(output: &Output) {
    assert_eq!(output.status.code(), Some(2), "stderr: {}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(output.stdout.is_empty(), "nothing on stdout for bad input");
}

#[test]
fn sphere_json_has_the_contract_fields() {
    let out = hw3(&["sphere", "--origin", "-5,1,0", "--dir", "1,0,0", "--center", "0,0,0", "--radius", "2", "--json"]);
    let value = json(&out);
    assert_eq!(value["hit"], true);
    let t = value["t"].as_f64().unwrap();
    assert!((t - (5.0 - 3f64.sqrt())).abs() < 1e-12);
    assert_eq!(value["closest_approach_t"], 5.0);
    for key in ["point", "normal", "reflected_dir", "point_error", "normal_error", "reflected_dir_error"] {
        assert_eq!(value[key].as_array().map(Vec::len), Some(3), "{key}");
    }
    let r = value["reflected_dir"].as_array().unwrap();
    assert!((r[0].as_f64().unwrap() + 0.5).abs() < 1e-12);
    let t_error = value["t_error"].as_f64().unwrap();
    assert!(t_error >= (t - (5.0 - 3f64.sqrt())).abs() && t_error < 1e-15, "{t_error:e}");
    assert!(value["warning"].is_null());
}

/// A unit sphere 10⁵, 10⁶ and 10⁷ away in f32 (the far small sphere of the Q2 chapter): answered,
/// each with a bound that holds, in text and in JSON; the homework's formula gets it wrong and
/// says so.
#[test]
fn sphere_f32_answers_a_far_small_sphere_with_its_bound() {
    for distance in ["1e5", "1e6", "1e7"] {
        let origin = format!("-{distance},0.5,0");
        let args = |method: &'static str, json: bool| {
            let mut args = vec!["sphere", "--precision", "f32", "--method", method, "--origin", origin.as_str()];
            args.extend(["--dir", "1,0,0", "--center", "0,0,0", "--radius", "1"]);
            if json {
                args.push("--json");
            }
            hw3(&args)
        };
        let stable = json(&args("stable", true));
        let exact = distance.parse::<f64>().unwrap() - 0.75f64.sqrt();
        let (t, t_error) = (stable["t"].as_f64().unwrap(), stable["t_error"].as_f64().unwrap());
        assert!((t - exact).abs() <= t_error && t_error < 0.5, "{distance}: {stable}");
        let point: Vec<f64> = stable["point"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let bound: Vec<f64> = stable["point_error"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        for (i, exact) in [-(0.75f64.sqrt()), 0.5, 0.0].into_iter().enumerate() {
            assert!((point[i] - exact).abs() <= bound[i], "{distance}: {stable}");
        }
        let text = args("stable", false);
        assert!(text.status.success());
        let text = String::from_utf8(text.stdout).unwrap();
        assert!(text.contains(&format!("t = {t} ± ")) && text.contains("point = ("), "{text}");
        let naive = json(&args("naive", true));
        let warning = naive["warning"].as_str().unwrap();
        assert!(warning.starts_with("the homework's formula is off by at least"), "{warning}");
    }
}

/// A refusal says what rounding leaves undecided, with the numbers: the eye typed as (0.6, 0.8, 0)
/// is 2e-17 off the unit sphere after parsing, and f·f − r² rounds to 0.
#[test]
fn sphere_refuses_only_what_rounding_leaves_undecided() {
    let out = hw3(&["sphere", "--origin", "0.6,0.8,0", "--dir", "-1,0,0", "--center", "0,0,0", "--radius", "1"]);
    assert_usage_error(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("the eye is within rounding of the sphere: the root t = 0e0 ± "), "{stderr}");
}

#[test]
fn sphere_json_miss_has_nulls_and_still_a_closest_approach() {
    let out = hw3(&["sphere", "--origin", "0,2,-5", "--dir", "0,0,1", "--center", "0,0,0", "--radius", "1", "--json"]);
    let value = json(&out);
    assert_eq!(value["hit"], false);
    for key in ["t", "point", "normal", "reflected_dir"] {
        assert!(value[key].is_null(), "{key}");
    }
    assert_eq!(value["closest_approach_t"], 5.0);
}

#[test]
fn sphere_naive_f32_misses_a_far_sphere_the_stable_one_hits() {
    // A unit sphere 1e4 away, aimed 0.9 r off-centre; see the Q2 far-sphere sweep.
    let args = |method: &'static str| {
        hw3(&[
            "sphere",
            "--origin",
            "0,0,0",
            "--dir",
            "0,0,1",
            "--center",
            "0.9,0,10000",
            "--radius",
            "1",
            "--precision",
            "f32",
            "--method",
            method,
            "--json",
        ])
    };
    let stable = json(&args("stable"));
    assert_eq!(stable["hit"], true);
    assert!((stable["t"].as_f64().unwrap() - (1e4 - 0.19f64.sqrt())).abs() < 1e-2);
    let naive = json(&args("naive"));
    let naive_t = naive["t"].as_f64();
    // Either a miss or a hit point off by a large fraction of the radius, and never silently.
    assert!(naive_t.is_none_or(|t| (t - (1e4 - 0.19f64.sqrt())).abs() > 0.05), "{naive}");
    assert!(naive["warning"].as_str().is_some_and(|w| w.starts_with("the homework's formula")), "{naive}");
}

#[test]
fn sphere_rejects_bad_input_with_exit_2() {
    for args in [
        &["sphere", "--origin", "0,0", "--dir", "0,0,1", "--center", "0,0,5", "--radius", "1"][..],
        &["sphere", "--origin", "0,0,0", "--dir", "0,0,0", "--center", "0,0,5", "--radius", "1"],
        &["sphere", "--origin", "nan,0,0", "--dir", "0,0,1", "--center", "0,0,5", "--radius", "1"],
        &["sphere", "--origin", "0,0,0", "--dir", "0,0,1", "--center", "0,0,5", "--radius", "-1"],
        &["sphere", "--origin", "0,0,0", "--dir", "0,0,1", "--center", "0,0,5", "--radius", "inf"],
        &[
            "sphere",
            "--origin",
            "0,0,0",
            "--dir",
            "0,0,1e-30",
            "--center",
            "0,0,5",
            "--radius",
            "1",
            "--precision",
            "f32",
        ],
        &["sphere", "--origin", "0,0,0", "--dir", "0,0,1", "--center", "0,0,5"],
        &["sphere", "--origin", "0,0,0", "--dir", "0,0,1", "--center", "0,0,5", "--radius", "1", "--method", "magic"],
        &["no-such-command"],
        &["answers", "--question", "q9"],
    ] {
        assert_usage_error(&hw3(args));
    }
}

#[test]
fn answers_for_one_question() {
    let out = hw3(&["answers", "--question", "q2"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("== Q2"), "{text}");
}

#[test]
fn kd_trace_json_has_the_contract_fields() {
    let value = json(&hw3(&["kd-trace", "--origin", "5,0", "--dir", "-1,1", "--json"]));
    assert_eq!(
        value["leaves"],
        serde_json::json!([
            {"path": ["x>=3", "y<3"], "tmin": 0.0, "tmax": 2.0},
            {"path": ["x<3", "y>=1"], "tmin": 2.0, "tmax": "inf"},
        ])
    );
    assert_eq!(value["steps"].as_array().map(Vec::len), Some(9));
}

#[test]
fn kd_trace_bad_input_exits_2() {
    for args in [
        ["--origin", "nan,0", "--dir", "1,1"],
        ["--origin", "0,0", "--dir", "0,-0"],
        ["--origin", "1", "--dir", "1,1"],
        ["--origin", "0,inf", "--dir", "1,1"],
    ] {
        let mut all = vec!["kd-trace", "--json"];
        all.extend(args);
        assert_usage_error(&hw3(&all));
    }
}

/// `(name, description)` pairs of a `Commands:` listing, with wrapped lines joined.
fn command_listing(text: &str) -> Vec<(String, String)> {
    let mut commands: Vec<(String, String)> = Vec::new();
    let block = text.split("Commands:").nth(1).unwrap_or_default();
    for line in block.lines().skip(1) {
        if line.trim().is_empty() || line.starts_with("Options") || line.starts_with("```") {
            break;
        }
        let trimmed = line.trim();
        let indent = line.len() - line.trim_start().len();
        match (indent, commands.last_mut()) {
            (i, Some(last)) if i > 4 => {
                last.1.push(' ');
                last.1.push_str(trimmed);
            }
            _ => {
                let (name, description) = trimmed.split_once(char::is_whitespace).unwrap_or((trimmed, ""));
                commands.push((name.to_string(), description.trim().to_string()));
            }
        }
    }
    commands.retain(|(name, _)| name != "help");
    commands
}

/// `paths` and `effect-tables` were `effects` and `effects-table`: the old names still run the
/// same commands (same help, same output) but `--help` no longer lists them.
#[test]
fn renamed_commands_keep_their_old_names_as_hidden_aliases() {
    let help = String::from_utf8(hw3(&["--help"]).stdout).unwrap();
    for (name, old) in [("paths", "effects"), ("effect-tables", "effects-table")] {
        let listed = command_listing(&help);
        assert!(listed.iter().any(|(n, _)| n == name), "{name} missing from --help");
        assert!(!listed.iter().any(|(n, _)| n == old), "{old} listed in --help");
        let (new_help, old_help) = (hw3(&[name, "--help"]), hw3(&[old, "--help"]));
        assert!(new_help.status.success() && old_help.status.success(), "{name} / {old} --help");
        let text = |out: &Output| String::from_utf8_lossy(&out.stdout).replace(old, name);
        assert_eq!(text(&old_help), text(&new_help), "{old} is {name}");
    }
    let (new, old) = (hw3(&["paths", "fog", "--json"]), hw3(&["effects", "fog", "--json"]));
    assert_eq!(json(&new), json(&old));
    assert_usage_error(&hw3(&["effects", "nope"]));
}

#[test]
fn a_closed_pipe_ends_quietly_without_a_panic() {
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_hw3"))
        .args(["answers"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap(); // then drop: the pipe closes
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
}
