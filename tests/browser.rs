//! The course notes as a reader sees them, in a real browser (headless Chromium).
//!
//! Ignored by default because it needs Chromium and a docs build:
//!
//! ```text
//! cargo doc --no-deps && cargo test --test browser -- --ignored
//! ```
//!
//! It installs Debian's `chromium` package when it is missing and the test runs as root; otherwise
//! it fails with the command to install it. For every page of the notes (the crate root and every
//! module) it asserts that math rendered (MathML present, no TeX left in the prose), every image
//! loaded with a non-zero size, every figure has a picture and a caption, no figure placeholder is
//! left, and no relative link points at a missing file or anchor; it saves a screenshot of the top
//! of each chapter and notes page under `target/browser/` (not with `HW3_BROWSER_SHOTS=0`, as in
//! `.ci/run`), and, with `HW3_BROWSER_SECTIONS=1`, one
//! per section (each `h2`/`h3` heading, 1280×2400 from the heading down) under
//! `target/browser/sections/` and one per figure (the figure, its caption and the text around it,
//! at the displayed size) under `target/browser/figures/`, so that every chapter can be read whole,
//! as a student sees it (`HW3_BROWSER_FIGURES=1` takes the figure shots alone).

use std::path::{Path, PathBuf};
use std::process::Command;

fn doc_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("target/doc")
}

fn chromium() -> PathBuf {
    for candidate in ["/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"] {
        if Path::new(candidate).exists() {
            return PathBuf::from(candidate);
        }
    }
    let is_root = Command::new("id").arg("-u").output().is_ok_and(|o| o.stdout.starts_with(b"0"));
    assert!(is_root, "Chromium is missing: install it with `apt-get install chromium` and rerun");
    let _ = Command::new("apt-get").args(["update", "-qq"]).status();
    let status = Command::new("apt-get").args(["install", "-y", "-qq", "chromium"]).status().expect("apt-get runs");
    assert!(status.success(), "apt-get install chromium failed");
    PathBuf::from("/usr/bin/chromium")
}

fn headless(browser: &Path) -> Command {
    let mut command = Command::new(browser);
    command.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
    ]);
    command
}

/// Every page of the notes: the crate root and each module's page.
fn pages() -> Vec<PathBuf> {
    let crate_dir = doc_root().join("hw3");
    assert!(crate_dir.join("index.html").exists(), "build the docs first: cargo doc --no-deps");
    let mut pages = vec![crate_dir.join("index.html")];
    let mut stack = vec![crate_dir];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() && path.join("index.html").exists() {
                pages.push(path.join("index.html"));
                stack.push(path);
            }
        }
    }
    pages.sort();
    pages
}

/// The ids of a page's section headings (`h2` and `h3`), in page order.
fn section_ids(html: &str) -> Vec<String> {
    let mut ids = Vec::new();
    for piece in html.split("<h").skip(1) {
        let level = piece.as_bytes().first().copied();
        if !matches!(level, Some(b'2' | b'3')) {
            continue;
        }
        if let Some(rest) = piece[1..].trim_start().strip_prefix("id=\"")
            && let Some(id) = rest.split('"').next()
        {
            ids.push(id.to_string());
        }
    }
    ids
}

/// Screenshots of every section of `page`: a wrapper page loads it in a frame and scrolls the
/// frame to the heading (headless Chromium does not honour `#fragment` in a screenshot).
fn section_screenshots(browser: &Path, page: &Path, name: &str, out_dir: &Path) {
    let html = std::fs::read_to_string(page).unwrap();
    let dir = out_dir.join("sections");
    std::fs::create_dir_all(&dir).unwrap();
    let wrapper = dir.join("wrapper.html");
    std::fs::write(&wrapper, include_str!("browser/section.html")).unwrap();
    for (number, id) in section_ids(&html).iter().enumerate() {
        let shot = dir.join(format!("{}__{number:02}_{id}.png", name.replace('/', "_").replace(".html", "")));
        let _ = headless(browser)
            .args(["--allow-file-access-from-files", "--window-size=1280,2400", "--virtual-time-budget=5000"])
            .arg(format!("--screenshot={}", shot.display()))
            .arg(format!("file://{}?page={}&id={id}", wrapper.display(), page.display()))
            .output();
    }
}

/// Text shown above and below each figure in its screenshot: about a paragraph or two, enough to
/// see whether the prose before the figure defines the terms it uses.
const FIGURE_CONTEXT_ABOVE: u64 = 600;
const FIGURE_CONTEXT_BELOW: u64 = 300;

/// Screenshots of every figure of `page` with its caption and the text around it, at the width a
/// reader sees (1280 px window), under `target/browser/figures/`; returns a line per figure for
/// `figures.txt` there (natural and displayed size, so a scaled-down render shows up in the list).
fn figure_screenshots(
    browser: &Path,
    page: &Path,
    name: &str,
    figures: &[serde_json::Value],
    out_dir: &Path,
) -> String {
    let dir = out_dir.join("figures");
    std::fs::create_dir_all(&dir).unwrap();
    let wrapper = dir.join("wrapper.html");
    std::fs::write(&wrapper, include_str!("browser/section.html")).unwrap();
    let stem = name.replace('/', "_").replace(".html", "");
    let mut listing = String::new();
    for (number, figure) in figures.iter().enumerate() {
        let height = figure["height"].as_u64().unwrap_or(0);
        let window = (height + FIGURE_CONTEXT_ABOVE + FIGURE_CONTEXT_BELOW).min(6000);
        let shot = dir.join(format!("{stem}__fig{number:02}.png"));
        let _ = headless(browser)
            .args(["--allow-file-access-from-files", "--virtual-time-budget=5000"])
            .arg(format!("--window-size=1280,{window}"))
            .arg(format!("--screenshot={}", shot.display()))
            .arg(format!(
                "file://{}?page={}&figure={number}&before={FIGURE_CONTEXT_ABOVE}",
                wrapper.display(),
                page.display()
            ))
            .output();
        let caption: String = figure["caption"].as_str().unwrap_or("").chars().take(70).collect();
        listing.push_str(&format!(
            "{}\t{} {}x{} shown {}x{}\t{caption}\n",
            shot.file_name().unwrap().to_string_lossy(),
            figure["kind"].as_str().unwrap_or("none"),
            figure["natural_width"],
            figure["natural_height"],
            figure["shown_width"],
            figure["shown_height"],
        ));
    }
    listing
}

/// Relative `href`s of a page that point at files, or `#anchors`, that do not exist.
fn broken_links(page: &Path) -> Vec<String> {
    let html = std::fs::read_to_string(page).unwrap();
    let mut broken = Vec::new();
    for piece in html.split("href=\"").skip(1) {
        let target = piece.split('"').next().unwrap_or("");
        let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
        if target.contains("${") || file.contains("://") || file.starts_with("mailto:") || file.starts_with("data:") {
            continue;
        }
        let resolved = if file.is_empty() { page.to_path_buf() } else { page.parent().unwrap().join(file) };
        let exists = resolved.exists();
        let line_range = anchor.chars().all(|c| c.is_ascii_digit() || c == '-');
        let anchored = anchor.is_empty()
            || line_range
            || resolved.extension().is_none_or(|e| e != "html")
            || std::fs::read_to_string(&resolved).is_ok_and(|t| t.contains(&format!("id=\"{anchor}\"")));
        if !exists || !anchored {
            broken.push(target.to_string());
        }
    }
    broken
}

#[test]
#[ignore = "needs Chromium and `cargo doc`; run: cargo doc --no-deps && cargo test --test browser -- --ignored"]
fn notes_render_in_a_real_browser() {
    let pages = pages();
    let browser = chromium();
    let out_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/browser");
    std::fs::create_dir_all(&out_dir).unwrap();

    let urls: Vec<String> = pages.iter().map(|p| format!("file://{}", p.display())).collect();
    let harness = include_str!("browser/harness.html").replace("/*PAGES*/[]", &serde_json::to_string(&urls).unwrap());
    let harness_path = out_dir.join("harness.html");
    std::fs::write(&harness_path, harness).unwrap();
    let dump = headless(&browser)
        .args(["--allow-file-access-from-files", "--virtual-time-budget=60000", "--dump-dom"])
        .arg(format!("file://{}", harness_path.display()))
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&dump.stdout);
    let json = dom
        .split("<pre id=\"out\">")
        .nth(1)
        .and_then(|rest| rest.split("</pre>").next())
        .expect("the harness wrote its results")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let results: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{e}: {json:.300}"));
    assert_eq!(results.len(), pages.len());
    std::fs::write(out_dir.join("results.json"), serde_json::to_string_pretty(&results).unwrap()).unwrap();

    // The screenshots are for review by eye; no assertion reads them. Each costs a Chromium start
    // and a full-page raster (about 8 CPU-seconds here, against 27 for checking all 67 pages in one
    // start), so `.ci/run`, whose clean checkout nobody looks at, turns them off with
    // `HW3_BROWSER_SHOTS=0`; the checks below are the same either way.
    let shots = std::env::var_os("HW3_BROWSER_SHOTS").is_none_or(|v| v != "0");
    let mut problems = Vec::new();
    let mut figure_listing = String::new();
    for (page, result) in pages.iter().zip(&results) {
        let name = page.strip_prefix(doc_root()).unwrap().display().to_string();
        let html = std::fs::read_to_string(page).unwrap();
        let is_chapter = html.contains("class=\"math-display\"") || html.contains("<figure>");
        let is_notes = name.starts_with("hw3/notes/") && name != "hw3/notes/index.html";
        if is_chapter || is_notes || page.ends_with("hw3/index.html") {
            // A screenshot of every chapter (and the table of contents) for review by eye.
            if shots {
                let shot = out_dir.join(name.replace('/', "_").replace(".html", ".png"));
                let _ = headless(&browser)
                    .args(["--window-size=1280,5000", "--virtual-time-budget=5000"])
                    .arg(format!("--screenshot={}", shot.display()))
                    .arg(format!("file://{}", page.display()))
                    .output();
            }
            // One Chromium start per section (about 180 in all) costs minutes: a review by eye
            // asks for them (`HW3_BROWSER_SECTIONS=1`).
            let sections = std::env::var_os("HW3_BROWSER_SECTIONS").is_some();
            if sections {
                section_screenshots(&browser, page, &name, &out_dir);
            }
            if sections || std::env::var_os("HW3_BROWSER_FIGURES").is_some() {
                let figures = result["figures"].as_array().map_or(&[][..], Vec::as_slice);
                figure_listing.push_str(&figure_screenshots(&browser, page, &name, figures, &out_dir));
            }
        }
        if result.get("error").is_some() {
            problems.push(format!("{name}: {}", result["error"]));
            continue;
        }
        if html.contains("class=\"math-display\"") && result["math"].as_u64() == Some(0) {
            problems.push(format!("{name}: chapter has no rendered math"));
        }
        if result["math_zero_width"].as_u64() != Some(0) {
            problems.push(format!("{name}: {} math elements rendered with zero width", result["math_zero_width"]));
        }
        if !result["raw_tex"].is_null() {
            problems.push(format!("{name}: TeX left in the prose: {}", result["raw_tex"]));
        }
        if result["broken_images"].as_array().is_some_and(|a| !a.is_empty()) {
            problems.push(format!("{name}: images that did not load: {}", result["broken_images"]));
        }
        for (number, figure) in result["figures"].as_array().into_iter().flatten().enumerate() {
            if figure["kind"].is_null() {
                problems.push(format!("{name}: figure {number} has no image"));
            } else if figure["natural_width"].as_f64() == Some(0.0) || figure["shown_width"].as_u64() == Some(0) {
                problems.push(format!("{name}: figure {number} has zero size"));
            }
            let caption = figure["caption"].as_str().unwrap_or("");
            if caption.is_empty() {
                problems.push(format!("{name}: figure {number} has no caption"));
            }
            // A caption is plain text (the build escapes it): Markdown or TeX would show as typed.
            if let Some(markup) = ["`", "**", "$", "\\"].iter().find(|m| caption.contains(*m)) {
                problems.push(format!("{name}: figure {number}'s caption shows {markup} as typed: {caption:.60}"));
            }
        }
        if result["missing_assets"].as_u64() != Some(0) {
            problems.push(format!("{name}: figure placeholders left: rerun cargo run --release"));
        }
        for link in broken_links(page) {
            problems.push(format!("{name}: broken link {link}"));
        }
    }
    if !figure_listing.is_empty() {
        std::fs::write(out_dir.join("figures/figures.txt"), figure_listing).unwrap();
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
