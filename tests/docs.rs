//! The course notes are consistent with the code: every figure the chapters embed exists and is
//! exactly what the code generates now, and no chapter was built with a missing figure.

use std::path::Path;

const DOCS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs");

#[test]
fn committed_figures_are_what_the_code_generates() {
    let figures = hw3::all_figures().expect("figures draw");
    let mut stale = Vec::new();
    for figure in &figures {
        let path = Path::new(DOCS).join("figures").join(&figure.file_name);
        if std::fs::read(&path).ok().as_deref() != Some(&figure.bytes[..]) {
            stale.push(figure.file_name.clone());
        }
    }
    assert!(stale.is_empty(), "regenerate with `cargo run --release` and commit: {stale:?}");
    let mut names: Vec<_> = figures.iter().map(|f| f.file_name.clone()).collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), figures.len(), "figure names are unique");
}

#[test]
fn every_figure_a_chapter_embeds_exists() {
    for entry in std::fs::read_dir(DOCS).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for directive in text.split("{{").skip(1) {
            let Some((inner, _)) = directive.split_once("}}") else {
                continue;
            };
            let target = match inner.split_once(':') {
                Some(("figure", rest)) => {
                    format!("figures/{}", rest.split('|').next().unwrap().trim())
                }
                Some(("include", rest)) => rest.trim().to_string(),
                _ => continue,
            };
            assert!(Path::new(DOCS).join(&target).exists(), "{} embeds missing {target}", path.display());
        }
    }
}
