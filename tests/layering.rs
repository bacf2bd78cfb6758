//! What Cargo cannot see of the layers. The core crates (`hw3-core`, `hw3-render`) cannot import
//! the questions: they do not depend on `hw3`, and Cargo refuses it. Inside a crate it cannot tell
//! one module from another, so this test reads the sources:
//!
//! - a question module (`q1_…` … `q5_…`) never imports another question, the checker, the worked
//!   solutions, the notes pages or an item of the crate root;
//! - the modules of one folder never import each other in a cycle, test code included, so each
//!   file can be read after the ones it uses. A module's node is its file and everything below it.
//!
//! Paths are read as text: every `crate::…`, `super::…` and `self::…` path (use trees expanded),
//! with comments and string literals removed, resolved to the deepest module file it names, and
//! through a module's `pub use child::…` re-exports to the child that defines the item.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The code of `text`: comments, string and character literals blanked out.
fn code(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            i += text[i..].find("*/").map_or(b.len() - i, |e| e + 2);
        } else if b[i] == b'r' && (b[i + 1..].starts_with(b"\"") || b[i + 1..].starts_with(b"#")) {
            let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
            let close = format!("\"{}", "#".repeat(hashes));
            let start = i + 2 + hashes;
            i = start + text.get(start..).and_then(|t| t.find(&close)).map_or(0, |e| e + close.len());
            out.push(' ');
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push(' ');
        } else if b[i] == b'\'' && b.get(i + 2) == Some(&b'\'') || b[i..].starts_with(b"'\\") {
            i += text[i + 1..].find('\'').map_or(1, |e| e + 2);
        } else {
            let c = text[i..].chars().next().unwrap();
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// Tokens: identifiers, `::`, and the punctuation a use tree needs.
fn tokens(code: &str) -> Vec<String> {
    let mut tokens = Vec::new();
    let mut chars = code.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c.is_alphanumeric() || c == '_' {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek().filter(|(_, d)| d.is_alphanumeric() || *d == '_') {
                end = j + d.len_utf8();
                chars.next();
            }
            tokens.push(code[i..end].to_string());
        } else if c == ':' && chars.peek().is_some_and(|&(_, d)| d == ':') {
            chars.next();
            tokens.push("::".into());
        } else if "{},;*".contains(c) {
            tokens.push(c.to_string());
        } else if !c.is_whitespace() {
            tokens.push(".".into());
        }
    }
    tokens
}

/// The paths of a use tree starting at `tokens[at]` (after a `::`), each appended to `prefix`.
fn use_tree(tokens: &[String], mut at: usize, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
    let mut path = prefix.to_vec();
    while at < tokens.len() {
        match tokens[at].as_str() {
            "{" => {
                at += 1;
                while at < tokens.len() && tokens[at] != "}" {
                    at = use_tree(tokens, at, &path, out);
                    if tokens.get(at).is_some_and(|t| t == ",") {
                        at += 1;
                    }
                }
                return at + 1;
            }
            "*" => {
                out.push(path);
                return at + 1;
            }
            t if t.chars().all(|c| c.is_alphanumeric() || c == '_') => {
                path.push(t.to_string());
                if tokens.get(at + 1).is_some_and(|t| t == "::") {
                    at += 2;
                } else {
                    out.push(path);
                    return at + 1;
                }
            }
            _ => {
                out.push(path);
                return at;
            }
        }
    }
    out.push(path);
    at
}

/// Every `crate::`, `super::` and `self::` path of `file`'s code, made absolute from `module` (and
/// from the inline modules, `mod tests { … }`, a path stands in).
fn paths(text: &str, module: &[String]) -> Vec<Vec<String>> {
    let tokens = tokens(&code(text));
    let mut found = Vec::new();
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0;
    for i in 0..tokens.len() {
        match tokens[i].as_str() {
            "{" => {
                depth += 1;
                if i >= 2 && tokens[i - 2] == "mod" {
                    inline.push((tokens[i - 1].clone(), depth));
                }
            }
            "}" => {
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
                depth -= 1;
            }
            _ => {}
        }
        let module: Vec<String> = module.iter().cloned().chain(inline.iter().map(|(name, _)| name.clone())).collect();
        let start = tokens[i].as_str();
        if !["crate", "super", "self"].contains(&start) || tokens.get(i + 1).is_none_or(|t| t != "::") {
            continue;
        }
        if i > 0 && (tokens[i - 1] == "::" || tokens[i - 1] == "super") {
            continue;
        }
        let mut base: Vec<String> = if start == "crate" { vec![] } else { module.to_vec() };
        let mut at = i;
        while tokens.get(at).is_some_and(|t| t == "super") && tokens.get(at + 1).is_some_and(|t| t == "::") {
            base.pop();
            at += 2;
        }
        if start != "super" {
            at = i + 2;
        }
        use_tree(&tokens, at, &base, &mut found);
    }
    found
}

/// A crate's module files by module path (`["checker", "q2"]` → `src/checker/q2.rs`).
fn modules(root: &Path) -> BTreeMap<Vec<String>, PathBuf> {
    fn walk(dir: &Path, module: &[String], out: &mut BTreeMap<Vec<String>, PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            let mut child = module.to_vec();
            child.push(name);
            if path.is_dir() {
                walk(&path, &child, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.insert(child, path);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(root, &[], &mut out);
    out.remove(&vec!["main".to_string()]);
    let lib = out.remove(&vec!["lib".to_string()]).unwrap();
    out.insert(vec![], lib);
    out
}

/// The module `path` leads to: the deepest module file it names, then through that module's
/// `pub use child::…` to the child that defines the next segment.
fn resolve(
    path: &[String],
    modules: &BTreeMap<Vec<String>, PathBuf>,
    texts: &BTreeMap<PathBuf, String>,
) -> Vec<String> {
    let mut target: Vec<String> = vec![];
    for segment in path {
        let mut next = target.clone();
        next.push(segment.clone());
        if modules.contains_key(&next) {
            target = next;
            continue;
        }
        let parent = code(&texts[&modules[&target]]);
        for statement in parent.split(';').filter(|s| s.trim_start().starts_with("pub")) {
            let Some(rest) = statement.split("use ").nth(1) else { continue };
            let child = rest.split("::").next().unwrap_or("").trim().to_string();
            let names: Vec<&str> = rest.split(|c: char| !(c.is_alphanumeric() || c == '_')).collect();
            let mut module = target.clone();
            module.push(child);
            if modules.contains_key(&module) && names.contains(&segment.as_str()) {
                return module;
            }
        }
        break;
    }
    target
}

/// Import edges between the modules of each folder (a module's node is its file and every file
/// below it), and the forbidden imports of question modules.
fn check(root: &Path) -> (Vec<String>, Vec<String>) {
    let modules = modules(root);
    let texts: BTreeMap<PathBuf, String> =
        modules.values().map(|p| (p.clone(), std::fs::read_to_string(p).unwrap())).collect();
    let is_question = |m: &str| m.len() > 3 && m.starts_with('q') && m.as_bytes()[2] == b'_';
    // Names the crate root takes from another crate (`pub use hw3_core::{…}`, or a module of its
    // own that re-exports one, `pub mod render { … }`): Cargo already keeps those below.
    let root = code(&texts[&modules[&vec![]]]);
    let external: BTreeSet<String> = root
        .split(';')
        .filter(|s| s.contains("use hw3_"))
        .flat_map(|s| s.split(|c: char| !(c.is_alphanumeric() || c == '_')).map(str::to_string).collect::<Vec<_>>())
        .chain(
            root.split("pub mod ").skip(1).filter_map(|r| r.split_once('{').map(|(name, _)| name.trim().to_string())),
        )
        .collect();
    let mut forbidden = Vec::new();
    let mut edges: BTreeMap<Vec<String>, BTreeSet<(String, String)>> = BTreeMap::new();
    for (module, file) in &modules {
        for path in paths(&texts[file], module) {
            if path.first().is_some_and(|p| external.contains(p)) {
                continue;
            }
            let target = resolve(&path, &modules, &texts);
            let common = module.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if let Some(own) = module.first().filter(|m| is_question(m)) {
                let other = target.first().map_or("the crate root", String::as_str);
                let allowed = other == own
                    || !(is_question(other) || ["checker", "solution", "notes", "the crate root"].contains(&other));
                if !allowed && path.first().is_none_or(|p| p != "testing") {
                    forbidden.push(format!("{}: imports {}", file.display(), path.join("::")));
                }
            }
            if common < module.len() && common < target.len() {
                let folder = module[..common].to_vec();
                edges.entry(folder).or_default().insert((module[common].clone(), target[common].clone()));
            }
        }
    }
    let mut cycles = Vec::new();
    for (folder, edges) in &edges {
        // A node is on a cycle when it reaches itself.
        for (start, _) in edges {
            let mut seen = BTreeSet::new();
            let mut stack = vec![start.clone()];
            while let Some(node) = stack.pop() {
                for (from, to) in edges.iter().filter(|(from, _)| *from == node) {
                    if to == start {
                        cycles.push(format!("{}/: {start} reaches itself through {from}", folder.join("/")));
                    } else if seen.insert(to.clone()) {
                        stack.push(to.clone());
                    }
                }
            }
        }
    }
    cycles.sort();
    cycles.dedup();
    (forbidden, cycles)
}

#[test]
fn questions_stay_apart_and_no_folder_has_an_import_cycle() {
    let top = Path::new(env!("CARGO_MANIFEST_DIR"));
    for root in ["src", "crates/core/src", "crates/render/src"] {
        let (forbidden, cycles) = check(&top.join(root));
        assert!(forbidden.is_empty(), "{root}: forbidden imports:\n{}", forbidden.join("\n"));
        assert!(cycles.is_empty(), "{root}: import cycles:\n{}", cycles.join("\n"));
    }
}

#[test]
fn a_planted_cycle_and_a_planted_question_import_are_found() {
    let dir = std::env::temp_dir().join(format!("hw3-layering-{}", std::process::id()));
    let write = |path: &str, text: &str| {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    };
    write("lib.rs", "mod a;\nmod q1_x;\nmod q2_y;\npub fn root_item() {}\n");
    write("a.rs", "mod b;\nmod c;\npub use b::Thing;\n");
    write(
        "a/b.rs",
        "pub struct Thing;\n#[cfg(test)]\nmod tests {\n    use crate::a::c::Other; // test code counts\n}\n",
    );
    write("a/c.rs", "pub struct Other;\nuse super::{Thing as _};\nfn f() { let s = \"crate::q2_y\"; }\n");
    write("q1_x.rs", "use crate::{a, q2_y::Item};\n");
    write("q2_y.rs", "pub struct Item;\nfn g() { crate::root_item(); }\n");
    let (forbidden, cycles) = check(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(cycles, ["a/: b reaches itself through c", "a/: c reaches itself through b"]);
    assert_eq!(forbidden.len(), 2, "{forbidden:?}");
    assert!(forbidden[0].ends_with("q1_x.rs: imports q2_y::Item") && forbidden[1].ends_with("imports root_item"));
}
