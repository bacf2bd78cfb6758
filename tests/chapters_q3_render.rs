//! Claims of the chapters recomputed from first principles or from the committed data (one
//! module per group of chapters; `tests/docs.rs` holds the older ones).

#![allow(unused_imports)]
use std::path::Path;

const DOCS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs");

#[allow(dead_code)]
fn chapter(name: &str) -> String {
    std::fs::read_to_string(Path::new(DOCS).join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A source file of the crate, for the messages the checker prints.
fn source(path: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The text of the section under `heading` (a whole heading line, without its `#`s), up to the
/// next heading of the same or a higher level.
fn section(text: &str, heading: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    // The heading level of each line outside fenced code (a `# comment` in code is no heading).
    let mut in_fence = false;
    let levels: Vec<Option<usize>> = lines
        .iter()
        .map(|line| {
            if line.trim_start().starts_with("```") {
                in_fence = !in_fence;
                return None;
            }
            let level = line.chars().take_while(|&c| c == '#').count();
            (!in_fence && level > 0 && line[level..].starts_with(' ')).then_some(level)
        })
        .collect();
    let start = (0..lines.len())
        .find(|&i| levels[i].is_some() && lines[i].trim_start_matches('#').trim() == heading)
        .unwrap_or_else(|| panic!("no heading {heading:?}"));
    let level = levels[start].unwrap();
    let end = (start + 1..lines.len()).find(|&i| levels[i].is_some_and(|l| l <= level)).unwrap_or(lines.len());
    lines[start + 1..end].join("\n")
}

/// The fenced code blocks of `text` whose fence names `language`.
fn code_blocks(text: &str, language: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<&str>> = None;
    for line in text.lines() {
        let trimmed = line.trim_start();
        match current.as_mut() {
            Some(lines) if trimmed.starts_with("```") => {
                blocks.push(lines.join("\n"));
                current = None;
            }
            Some(lines) => lines.push(line),
            None if trimmed.starts_with("```") && trimmed[3..].trim() == language => current = Some(Vec::new()),
            None => {}
        }
    }
    blocks
}

// ---------------------------------------------------------------------------------------------
// Q3: the worked traces, the checker's messages, the cost lesson.

mod q3 {
    use super::*;
    use hw3::q3_kd_traversal::{Node2, Ray2, Step, traverse};

    /// One entry of a `planes` list: node path, `t` (`None` for "parallel"), first child.
    type Plane = (Vec<String>, Option<f64>, String);
    /// One entry of a `descents` or `leaves` list: path, tmin, tmax.
    type Piece = (Vec<String>, f64, f64);

    /// The three lists of the answers file for `ray`, as the traversal gives them.
    fn key(ray: &Ray2) -> (Vec<Plane>, Vec<Piece>, Vec<Piece>) {
        let trace = traverse(&Node2::homework(), ray);
        let names = |path: &[hw3::q3_kd_traversal::Branch]| path.iter().map(ToString::to_string).collect::<Vec<_>>();
        let (mut planes, mut descents, mut leaves) = (Vec::new(), Vec::new(), Vec::new());
        for (i, step) in trace.steps.iter().enumerate() {
            match step {
                Step::Plane { path, t, .. } => {
                    let Some(Step::Descend { path: child, .. }) = trace.steps.get(i + 1) else {
                        panic!("a plane is followed by the descent into its first child")
                    };
                    planes.push((names(path), *t, child.last().unwrap().to_string()));
                }
                Step::Descend { path, interval } => descents.push((names(path), interval.t_min, interval.t_max)),
                Step::Leaf { path, interval } => leaves.push((names(path), interval.t_min, interval.t_max)),
            }
        }
        (planes, descents, leaves)
    }

    fn number(value: &toml::Value) -> f64 {
        match value {
            toml::Value::Integer(i) => *i as f64,
            toml::Value::Float(x) => *x,
            toml::Value::String(s) if s == "inf" => f64::INFINITY,
            other => panic!("not a bound: {other}"),
        }
    }

    fn path(value: &toml::Value) -> Vec<String> {
        value.as_array().unwrap().iter().map(|b| b.as_str().unwrap().to_string()).collect()
    }

    fn pieces(value: &toml::Value) -> Vec<Piece> {
        let entries = value.as_array().unwrap();
        entries.iter().map(|e| (path(&e["path"]), number(&e["tmin"]), number(&e["tmax"]))).collect()
    }

    fn planes(value: &toml::Value) -> Vec<Plane> {
        let entries = value.as_array().unwrap();
        entries
            .iter()
            .map(|e| {
                let t = match &e["t"] {
                    toml::Value::String(s) if s == "parallel" => None,
                    other => Some(number(other)),
                };
                (path(&e["node"]), t, e["first"].as_str().unwrap().to_string())
            })
            .collect()
    }

    /// `(x, y)` from `"(x, y)"`.
    fn pair(text: &str) -> [f64; 2] {
        let inner = text.trim().trim_start_matches('(').trim_end_matches(')');
        let mut parts = inner.split(',').map(|p| p.trim().parse::<f64>().unwrap());
        [parts.next().unwrap(), parts.next().unwrap()]
    }

    /// The worked examples of parts q3d and q3e: each TOML block whose first line names its ray
    /// (`[q3d]  # e = (x, y), d = (x, y)`) holds exactly the lists the traversal gives for that ray, in
    /// the answers file's form; the examples cover a ray parallel to a split, one lying in a
    /// split, one starting on a split (t = 0), and one through a corner; and none is a variant's.
    #[test]
    fn worked_traces_are_the_traversals_and_no_variants() {
        let text = section(&chapter("q3_kd_traversal.md"), "Parts q3d and q3e: tracing a ray through the tree");
        let mut rays = Vec::new();
        for block in code_blocks(&text, "toml") {
            let first = block.lines().next().unwrap();
            let Some((_, ray_text)) = first.split_once("  # e = ") else { continue };
            let (e, d) = ray_text.split_once(", d = ").unwrap();
            let ray = Ray2::new(pair(e), pair(d)).unwrap();
            let answers: toml::Table = block.parse().unwrap_or_else(|e| panic!("{block}\n{e}"));
            assert_eq!(answers.len(), 1, "one table per example");
            let (table, lists) = answers.iter().next().unwrap();
            assert!(table == "q3d" || table == "q3e", "{table}");
            let (key_planes, key_descents, key_leaves) = key(&ray);
            let lists = lists.as_table().unwrap();
            assert!(lists.contains_key("planes") && lists.contains_key("leaves"), "{first}");
            assert_eq!(planes(&lists["planes"]), key_planes, "{first}: planes");
            if let Some(descents) = lists.get("descents") {
                assert_eq!(pieces(descents), key_descents, "{first}: descents");
            }
            assert_eq!(pieces(&lists["leaves"]), key_leaves, "{first}: leaves");
            rays.push((ray, key_planes, key_leaves));
        }
        assert!(rays.len() >= 5, "{} worked traces", rays.len());
        let parallel = rays.iter().any(|(_, planes, _)| planes.iter().any(|p| p.1.is_none()));
        let lying_in_a_plane = rays.iter().any(|(ray, planes, _)| {
            planes[0].1.is_none() && (ray.origin[0] == 3.0 || ray.origin[1] == 1.0 || ray.origin[1] == 3.0)
        });
        let starting_on_a_plane = rays.iter().filter(|(_, planes, _)| planes.iter().any(|p| p.1 == Some(0.0))).count();
        // A ray through a corner: two planes crossed at the same t, where one leaf ends.
        let corner = rays.iter().any(|(_, planes, leaves)| {
            planes.iter().filter_map(|p| p.1).any(|t| {
                t > 0.0 && planes.iter().filter(|p| p.1 == Some(t)).count() >= 2 && leaves.iter().any(|l| l.2 == t)
            })
        });
        assert!(parallel && lying_in_a_plane && starting_on_a_plane >= 2 && corner);
        // No worked ray is a variant's (the variants' rays have integer coordinates).
        for seed in 0..500 {
            let statement = hw3::checker::variant("q3", seed).unwrap().statement;
            for (ray, _, _) in &rays {
                let ([ex, ey], [dx, dy]) = (ray.origin, ray.dir);
                let shown = format!("e = ({ex}, {ey}), d = ({dx}, {dy})");
                assert!(!statement.contains(&shown), "seed {seed} asks {shown}");
            }
        }
    }

    /// The worked numbers of parts q3b and q3c: the formulas' checks on the example ray.
    #[test]
    fn worked_plane_parameters_are_right() {
        let q3 = chapter("q3_kd_traversal.md");
        let (e, d) = ([0.5, 2.0], [2.0, -1.0]);
        let t = (4.5 - e[0]) / d[0];
        let point = [e[0] + d[0] * t, e[1] + d[1] * t];
        assert_eq!((t, point), (2.0, [4.5, 0.0]));
        assert!(q3.contains("t = (4.5 − 0.5)/2 = 2, and at t = 2 the ray is at (0.5 + 2 · 2, 2 − 2) = (4.5, 0)"));
        let q3c = section(&q3, "Part q3c: the plane parameter in the left child");
        let (root, child) = ((3.0 - e[0]) / d[0], (1.0 - e[1]) / d[1]);
        assert_eq!((root, child), (1.25, 1.0));
        assert!(q3c.contains("piece [0, 1.25]") && q3c.contains("t = (1 − 2)/(−1) = 1"));
    }

    /// Every mistake the checker names for Q3 is in the chapter, with the checker's own words:
    /// the formula parts' mal-rules and every trace and plane message.
    #[test]
    fn every_mistake_the_checker_names_is_taught() {
        let q3 = chapter("q3_kd_traversal.md");
        let traces = source("src/checker/traces.rs");
        let grading = source("src/checker/grading.rs");
        let rules = source("src/checker/q3.rs");
        let in_section = |heading: &str, phrases: &[&str], sources: &[&str]| {
            let text = section(&q3, heading);
            let text = text.split("**Mistakes the checker recognises.**").nth(1).expect("the mistakes lead-in");
            let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
            for phrase in phrases {
                assert!(sources.iter().any(|s| s.contains(phrase)), "the checker no longer says {phrase:?}");
                assert!(text.contains(phrase), "{heading}: {phrase:?} not taught");
            }
        };
        in_section("Part q3b: the root plane's parameter", &["sign error", "the origin is missing"], &[&rules]);
        in_section(
            "Part q3c: the plane parameter in the left child",
            &["sign error", "that is the x-axis: the plane y = 1 uses e_y and d_y"],
            &[&rules],
        );
        in_section(
            "Parts q3d and q3e: tracing a ray through the tree",
            &[
                "tmin should be",
                "you kept tmin at 0 after crossing the plane",
                "not where it enters this cell",
                "tmin is where the ray enters this cell",
                "tmax should be",
                "the interval was not clipped at the plane the ray leaves by",
                "not where it leaves this cell",
                "tmax is where the ray leaves this cell",
                "wrong cell: the ray is in",
                "missing: the ray goes on into",
                "is extra: the ray has left the tree's last cell",
                "follow from that bound (error carried forward)",
                "right for the value you had (error",
                "missing: the traversal goes on to",
                "is extra: the traversal has no more nodes",
                "the traversal splits at",
                "the ray is parallel to this plane, so there is no t (write",
                "the ray is not parallel to this plane: t =",
                "sign error: t = (s - e_a)/d_a =",
                "comes first: the child the ray is in just after tmin",
            ],
            &[&traces, &grading],
        );
    }

    /// The fixed-k rows of the committed benchmark CSV, by column name.
    fn fixed_k() -> Vec<std::collections::HashMap<String, String>> {
        let csv = std::fs::read_to_string(Path::new(DOCS).join("data/q3_kdtree_perf.csv")).unwrap();
        let mut lines = csv.lines();
        let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
        lines
            .map(|line| header.iter().cloned().zip(line.split(',').map(str::to_string)).collect())
            .filter(|row: &std::collections::HashMap<String, String>| row["density"] == "fixed_k")
            .collect()
    }

    /// The cost lesson's numbers are the committed benchmark data's.
    #[test]
    fn cost_lesson_numbers_are_the_benchmark_data() {
        let q3 = section(&chapter("q3_kd_traversal.md"), "Cost against scene size");
        let rows = fixed_k();
        let at = |n: &str, column: &str| -> f64 {
            rows.iter().find(|r| r["n"] == n).unwrap()[column].parse().unwrap_or_else(|_| panic!("{n} {column}"))
        };
        let brute_fall = at("100", "brute_camera_mrays") / at("10000", "brute_camera_mrays");
        assert!(q3.contains(&format!("rate falls {:.0}-fold", brute_fall)), "{brute_fall}");
        let (tests_first, tests_last) = (at("100", "camera_tests_per_ray"), at("1000000", "camera_tests_per_ray"));
        assert!(q3.contains(&format!("sphere\ntests {:.0} → {:.0}", tests_first, tests_last)));
        let speedup = at("10000", "camera_mrays") / at("10000", "brute_camera_mrays");
        assert!(q3.contains(&format!("traces {:.0} times as many rays", speedup)), "{speedup}");
        // "its rate halves, as its node steps and sphere tests double"
        let rate = at("100000", "camera_mrays") / at("1000000", "camera_mrays");
        let steps = at("1000000", "camera_nodes_per_ray") / at("100000", "camera_nodes_per_ray");
        let tests = at("1000000", "camera_tests_per_ray") / at("100000", "camera_tests_per_ray");
        assert!([rate, steps, tests].iter().all(|r| (1.85..2.15).contains(r)), "{rate} {steps} {tests}");
        assert!(q3.contains("its rate halves, as its node steps and sphere tests double"));
        // The build's time in camera rays at N = 10^5, to the nearest 10 000.
        let rays = at("100000", "build_ms") * 1e-3 * at("100000", "camera_mrays") * 1e6;
        let shown = format!("{} 000", (rays / 1e4).round() as u64 * 10);
        assert!(q3.contains(&format!("tracing {shown} of these camera\nrays")), "{rays}");
        // Fixed volume: the node steps grow by about the same number per decade (log N).
        let volume = std::fs::read_to_string(Path::new(DOCS).join("data/q3_kdtree_perf.csv")).unwrap();
        let steps: Vec<f64> = volume
            .lines()
            .filter(|l| l.starts_with("fixed_volume,"))
            .map(|l| l.split(',').nth(6).unwrap().parse().unwrap())
            .collect();
        let increments: Vec<f64> = steps.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(increments.iter().all(|d| (3.0..8.0).contains(d)), "{increments:?}");
    }
}
