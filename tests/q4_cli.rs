//! The `hw3 irradiance` contract: JSON output, exact answers on analytic maps, exit status 2 on
//! every kind of invalid input with nothing on stdout.

use std::process::{Command, Output};

fn hw3(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hw3")).arg("irradiance").args(args).output().expect("the binary runs")
}

fn irradiance(args: &[&str]) -> [f64; 3] {
    let out = hw3(args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    let rgb = value["irradiance"].as_array().expect("an irradiance array");
    assert_eq!(rgb.len(), 3);
    [0, 1, 2].map(|i| rgb[i].as_f64().expect("a number"))
}

#[test]
fn every_method_answers_pi_l_on_a_constant_map() {
    for method in ["unweighted", "weighted", "uniform", "cosine", "map", "mis", "sh9"] {
        let e = irradiance(&[
            "--env",
            "constant:2",
            "--normal",
            "0,0,1",
            "--method",
            method,
            "--size",
            "32",
            "--samples",
            "4096",
            "--seed",
            "3",
            "--json",
        ]);
        assert_eq!(e[0], e[1], "grey map, equal channels");
        assert_eq!(e[1], e[2]);
        // Texel sums and SH9: discretisation ≤ 1 % at 32²; MC at N = 4096: well within 10 %.
        let tolerance = if ["uniform", "map", "mis"].contains(&method) { 0.1 } else { 0.01 };
        assert!((e[0] / (2.0 * std::f64::consts::PI) - 1.0).abs() < tolerance, "{method}: {e:?}");
    }
}

#[test]
fn sky_and_linear_maps_match_their_oracles() {
    let up = irradiance(&["--env", "sky", "--normal", "0,0,2", "--method", "sh9", "--size", "64", "--json"]);
    assert!((up[0] - std::f64::consts::PI).abs() < 2e-3, "{up:?}");
    let down = irradiance(&["--env", "sky", "--normal", "0,0,-1", "--method", "weighted", "--size", "64", "--json"]);
    assert!(down[0].abs() < 2e-3, "{down:?}");
    // L = 1 + 0.5 ω_z: E(+z) = π + (2π/3)·0.5.
    let linear =
        irradiance(&["--env", "linear:1,0.5", "--normal", "0,0,1", "--method", "weighted", "--size", "64", "--json"]);
    let exact = std::f64::consts::PI * (1.0 + 1.0 / 3.0);
    assert!((linear[0] / exact - 1.0).abs() < 2e-3, "{linear:?}");
}

#[test]
fn same_seed_same_answer() {
    let args = [
        "--env",
        "sky",
        "--normal",
        "1,0,1",
        "--method",
        "mis",
        "--size",
        "16",
        "--samples",
        "64",
        "--seed",
        "9",
        "--json",
    ];
    assert_eq!(irradiance(&args), irradiance(&args));
}

#[test]
fn invalid_input_exits_2_and_prints_nothing() {
    let cases = [
        "--env sky --normal 0,0,1 --method guess",
        "--env sky --normal 0,0 --method sh9",
        "--env sky --normal 0,0,0 --method sh9",
        "--env sky --normal nan,0,1 --method sh9",
        "--env constant:-1 --normal 0,0,1 --method sh9",
        "--env constant:inf --normal 0,0,1 --method sh9",
        "--env linear:1,2 --normal 0,0,1 --method sh9",
        "--env linear:1 --normal 0,0,1 --method sh9",
        "--env /no/such/map.hdr --normal 0,0,1 --method sh9",
        "--env sky --normal 0,0,1 --method sh9 --size 0",
        "--env sky --normal 0,0,1 --method cosine --samples 0",
        "--env sky --normal 0,0,1 --method cosine --samples -3",
        "--env sky --method sh9",
    ];
    for case in cases {
        let args: Vec<&str> = case.split_whitespace().collect();
        let out = hw3(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(out.stdout.is_empty(), "{args:?}");
        assert!(!out.stderr.is_empty(), "{args:?}");
    }
}

#[test]
fn a_vendored_hdr_file_is_read_as_a_lat_long_map() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data/q4/courtyard_256x128.hdr");
    let e = irradiance(&["--env", path, "--normal", "0,0,1", "--method", "weighted", "--json"]);
    assert!(e.iter().all(|c| c.is_finite() && *c > 0.0), "{e:?}");
    assert!(e[0] != e[1] || e[1] != e[2], "a real map has colour: {e:?}");
}

#[test]
fn a_truncated_hdr_file_exits_2() {
    let dir = std::env::temp_dir().join(format!("hw3-q4-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("truncated.hdr");
    let full = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data/q4/sunrise_256x128.hdr")).unwrap();
    std::fs::write(&path, &full[..full.len() / 2]).unwrap();
    let out = hw3(&["--env", path.to_str().unwrap(), "--normal", "0,0,1", "--method", "sh9"]);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The built-in maps are compiled into the binary: `hw3` reads them from any working directory
/// and needs no file of the source tree (as after `cargo install`). The probe-lit scene is lit by
/// the built-in `courtyard` map; it renders from an empty directory.
#[test]
fn a_built_in_map_is_read_from_any_working_directory() {
    let dir = std::env::temp_dir().join(format!("hw3-q4-cwd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_hw3"))
        .current_dir(&dir)
        .args(["render", "probe-lit", "--spp", "1", "--size", "16x12", "--out", "lit.png"])
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = std::fs::read(dir.join("lit.png")).expect("the PNG was written in the working directory");
    assert!(png.starts_with(b"\x89PNG"), "a PNG");
    std::fs::remove_dir_all(&dir).unwrap();
    // The CLI's code names no path to the maps' directory: none is baked in for it to read.
    let binary = std::fs::read(env!("CARGO_BIN_EXE_hw3")).unwrap();
    let needle = b"docs/data/q4";
    assert!(!binary.windows(needle.len()).any(|w| w == needle), "the binary names docs/data/q4");
}
