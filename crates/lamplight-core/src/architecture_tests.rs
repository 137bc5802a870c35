//! The import graph between the crate's folders, read from the sources, so that
//! a layering once untangled (issue 25, section 1) cannot grow back unnoticed.
//!
//! The lobes of `bsdfs/` are physics: they may import math, sampling and each
//! other, never the materials, scene, integrators, renderer, lights or shapes
//! above them (the materials map themselves to lobes, not the other way round).
//! The renderer runs the integrators, never the other way round.
//!
//! The check reads every `crate::...` and `super::...` path of a file (in `use`
//! lines, in code and in doc links), resolves `super` against the file's module
//! and the inline `mod` blocks around it, and names the top-level module each
//! path enters. It is a reader of rustfmt-formatted text, not a Rust parser: a
//! `use` group may span lines, an inline module closes at the `}` of its own
//! indentation.

use std::path::{Path, PathBuf};

/// A path in a source file that enters a top-level module of the crate.
#[derive(Debug)]
struct Reference {
    /// The file, relative to `src/`.
    file: String,
    /// 1-based line of the path's first segment.
    line: usize,
    /// The top-level module it enters (`materials`, `scene`, ...).
    module: String,
    /// Whether the path lies in a comment (doc or not).
    in_comment: bool,
    /// Whether the path lies in test code (a `tests` module or file, or `test_support`).
    in_test: bool,
    /// The source line, trimmed, for the message.
    text: String,
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut entries: Vec<_> =
        std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())).map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out
}

/// The module path of the file `rel` (relative to `src/`): `bsdfs/mod.rs` is
/// `[bsdfs]`, `bsdfs/principled/tests.rs` is `[bsdfs, principled, tests]`,
/// `lib.rs` is the root `[]`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    let stem = last.strip_suffix(".rs").unwrap();
    if !(stem == "mod" || (parts.is_empty() && (stem == "lib" || stem == "main"))) {
        parts.push(stem.to_string());
    }
    parts
}

fn is_ident_char(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The identifier at `bytes[i..]` (empty if none).
fn ident_at(bytes: &[u8], i: usize) -> &str {
    let end = (i..bytes.len()).find(|&j| !is_ident_char(bytes[j])).unwrap_or(bytes.len());
    std::str::from_utf8(&bytes[i..end]).unwrap()
}

fn skip_space(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && bytes[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

/// The first segments of the items of the `use` group opening at `bytes[open]`
/// (`{a::b, c, d::{e, f}}` gives `a`, `c`, `d`), each with its byte offset.
fn group_heads(bytes: &[u8], open: usize) -> Vec<(usize, String)> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut expect_head = true;
    let mut i = open;
    while i < bytes.len() {
        match bytes[i] {
            b'{' => {
                depth += 1;
                if depth == 1 {
                    expect_head = true;
                }
            }
            b'}' => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            b',' if depth == 1 => expect_head = true,
            c if depth == 1 && expect_head && is_ident_char(c) => {
                heads.push((i, ident_at(bytes, i).to_string()));
                expect_head = false;
            }
            c if depth == 1 && expect_head && c == b'*' => {
                heads.push((i, "*".to_string()));
                expect_head = false;
            }
            _ => {}
        }
        i += 1;
    }
    heads
}

/// For each line, the names of the inline `mod name {` blocks open on it.
fn inline_modules(lines: &[&str]) -> Vec<Vec<String>> {
    let mut open: Vec<(String, String)> = Vec::new(); // (name, closing line)
    let mut out = Vec::with_capacity(lines.len());
    for line in lines {
        if open.last().is_some_and(|(_, close)| line.trim_end() == close) {
            open.pop();
        }
        out.push(open.iter().map(|(name, _)| name.clone()).collect());
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        let decl = trimmed.strip_prefix("pub ").or_else(|| trimmed.strip_prefix("pub(crate) ")).unwrap_or(trimmed);
        if let Some(rest) = decl.strip_prefix("mod ") {
            if let Some(name) = rest.trim_end().strip_suffix('{') {
                open.push((name.trim().to_string(), format!("{indent}}}")));
            }
        }
    }
    out
}

/// Every path of the file `rel` that enters a top-level module, resolved.
fn references(rel: &Path, text: &str) -> Vec<Reference> {
    let file = rel.to_string_lossy().into_owned();
    let base = module_path(rel);
    let lines: Vec<&str> = text.lines().collect();
    let inline = inline_modules(&lines);
    let bytes = text.as_bytes();
    let line_of = |offset: usize| bytes[..offset].iter().filter(|&&b| b == b'\n').count();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = |word: &str| bytes[i..].starts_with(word.as_bytes());
        let boundary = i == 0 || !(is_ident_char(bytes[i - 1]) || bytes[i - 1] == b':');
        if !(boundary && (starts("crate::") || starts("super::"))) {
            i += 1;
            continue;
        }
        let first_line = line_of(i);
        let mut module: Vec<String> = base.iter().cloned().chain(inline[first_line].iter().cloned()).collect();
        let mut j = i;
        if starts("crate::") {
            module.clear();
            j += "crate::".len();
        } else {
            while bytes[j..].starts_with(b"super::") {
                module.pop();
                j += "super::".len();
            }
        }
        let heads = if bytes.get(j) == Some(&b'{') { group_heads(bytes, j) } else { vec![(j, ident_at(bytes, j).to_string())] };
        for (at, head) in heads {
            let top = match module.first() {
                Some(own) => own.clone(),
                None if head == "self" || head == "*" || head.is_empty() => continue,
                None => head,
            };
            let line = line_of(at);
            let source = lines[line];
            let comment_start = source.find("//").map(|c| c + bytes[..at].iter().rposition(|&b| b == b'\n').map_or(0, |n| n + 1));
            out.push(Reference {
                file: file.clone(),
                line: line + 1,
                module: top,
                in_comment: comment_start.is_some_and(|c| c <= at),
                in_test: base.iter().chain(&inline[first_line]).any(|m| m == "tests" || m == "test_support"),
                text: source.trim().to_string(),
            });
        }
        i = skip_space(bytes, j).max(i + 1);
    }
    out
}

/// The references of every file under `src/` (its top-level module first).
fn all_references() -> Vec<(String, Reference)> {
    let src = src_dir();
    let mut out = Vec::new();
    for path in rust_files(&src) {
        let rel = path.strip_prefix(&src).unwrap().to_path_buf();
        let own = module_path(&rel).first().cloned().unwrap_or_default();
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        out.extend(references(&rel, &text).into_iter().map(|r| (own.clone(), r)));
    }
    out
}

#[test]
fn bsdfs_import_only_math_sampling_and_themselves() {
    const ABOVE: [&str; 6] = ["materials", "scene", "integrators", "render", "lights", "shapes"];
    let refs = all_references();
    assert!(refs.iter().any(|(own, r)| own == "bsdfs" && r.module == "math"), "the reader finds the lobes' own imports");
    let bad: Vec<String> = refs
        .iter()
        .filter(|(own, r)| own == "bsdfs" && ABOVE.contains(&r.module.as_str()))
        .map(|(_, r)| format!("  src/{}:{} refers to `{}`: {}", r.file, r.line, r.module, r.text))
        .collect();
    assert!(
        bad.is_empty(),
        "bsdfs/ must import only math, sampling and its own files (issue 25, section 1); \
         the materials map themselves to lobes, not the other way round:\n{}",
        bad.join("\n")
    );
}

/// A lobe is its file and one line of the `lobes!` registry (issue 25,
/// section 1): outside the registry, `bsdfs/mod.rs` names no lobe variant but
/// the Lambertian one, whose fast path (a BSDF of one diffuse lobe) is the
/// path tracer's most common case. A match arm per lobe coming back fails here.
#[test]
fn bsdfs_mod_names_each_lobe_only_in_the_registry() {
    let text = std::fs::read_to_string(src_dir().join("bsdfs/mod.rs")).unwrap();
    let start = text.find("\nlobes! {").expect("bsdfs/mod.rs has the lobes! registry");
    let end = start + text[start..].find("\n}\n").expect("the registry closes");
    let variants: Vec<&str> = text[start..end]
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with("//") && l.ends_with("),"))
        .filter_map(|l| l.split_once('(').map(|(v, _)| v))
        .collect();
    assert!(variants.len() >= 10 && variants.contains(&"Principled"), "the reader finds the registry's lines: {variants:?}");
    let outside = format!("{}{}", &text[..start], &text[end..]);
    let named: Vec<String> = variants
        .iter()
        .filter(|v| **v != "Diffuse")
        .filter(|v| outside.contains(&format!("Lobe::{v}")))
        .map(|v| format!("Lobe::{v}"))
        .collect();
    assert!(
        named.is_empty(),
        "bsdfs/mod.rs names lobes outside the lobes! registry (each lobe's behaviour belongs in its file's `impl Scatter`): {named:?}"
    );
}

/// The renderer runs the integrators; an integrator never reaches back into
/// the renderer (what both need, such as `PixelWindow`, lives below both, in
/// `film/`). Code only: a doc link to the crate's `render()` is no import.
#[test]
fn integrators_and_render_do_not_import_each_other_in_a_circle() {
    let refs = all_references();
    let code = |from: &str, to: &str| -> Vec<String> {
        refs.iter()
            .filter(|(own, r)| own == from && r.module == to && !r.in_comment)
            .map(|(_, r)| format!("  src/{}:{} refers to `{}`: {}", r.file, r.line, r.module, r.text))
            .collect()
    };
    assert!(!code("render", "integrators").is_empty(), "the reader finds the renderer's imports of the integrators");
    let back = code("integrators", "render");
    assert!(
        back.is_empty(),
        "integrators/ must not import render/, which imports it (issue 25, section 1); \
         move what both need below both:\n{}",
        back.join("\n")
    );
}

/// The crate root's re-exports (`pub use scene::{Scene, SceneBuilder}` in
/// `lib.rs`): each name with the top-level module it comes from, so that a
/// path such as `crate::Scene` counts as entering `scene`.
fn root_reexports() -> std::collections::HashMap<String, String> {
    let lib = std::fs::read_to_string(src_dir().join("lib.rs")).unwrap();
    let mut out = std::collections::HashMap::new();
    for line in lib.lines().map(str::trim).filter(|l| l.starts_with("pub use ")) {
        let path = line.trim_start_matches("pub use ").trim_end_matches(';');
        let Some((module, rest)) = path.split_once("::") else { continue };
        if module == "crate" {
            continue; // the prelude's lines re-export what the lines above did
        }
        let names = match rest.rsplit_once("::{").map(|(_, g)| g).or_else(|| rest.strip_prefix('{')) {
            Some(group) => group.trim_end_matches('}').split(',').map(|n| n.trim().to_string()).collect(),
            None => vec![rest.rsplit("::").next().unwrap().to_string()],
        };
        for name in names.into_iter().filter(|n| !n.is_empty()) {
            out.insert(name, module.to_string());
        }
    }
    out
}

/// No two top-level modules import each other, directly or around a longer
/// circle, in code outside tests: each folder can be read knowing only those
/// below it (issue 25, section 1). Tests may build a scene to test a light.
#[test]
fn no_top_level_modules_import_each_other_in_a_circle() {
    use std::collections::{BTreeMap, BTreeSet};
    let reexports = root_reexports();
    assert_eq!(reexports.get("SceneBuilder").map(String::as_str), Some("scene"), "the reader finds the root's re-exports");
    let modules: BTreeSet<String> = all_references().iter().map(|(own, _)| own.clone()).filter(|o| !o.is_empty()).collect();
    // For each edge, the first reference that makes it, for the message.
    let mut edges: BTreeMap<(String, String), String> = BTreeMap::new();
    for (own, r) in all_references() {
        if own.is_empty() || r.in_comment || r.in_test {
            continue;
        }
        let target = reexports.get(&r.module).cloned().unwrap_or(r.module.clone());
        if target != own && modules.contains(&target) {
            edges.entry((own, target)).or_insert_with(|| format!("src/{}:{}: {}", r.file, r.line, r.text));
        }
    }
    assert!(edges.contains_key(&("scene".to_string(), "lights".to_string())), "the reader finds the scene's imports of the lights");
    // Depth-first search for a back edge; the circle is the stack from its target.
    fn visit<'a>(
        m: &'a str,
        edges: &'a BTreeMap<(String, String), String>,
        stack: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<&'a str>> {
        if let Some(at) = stack.iter().position(|&s| s == m) {
            return Some(stack[at..].to_vec());
        }
        if !done.insert(m) {
            return None;
        }
        stack.push(m);
        for ((from, to), _) in edges.range((m.to_string(), String::new())..) {
            if from != m {
                break;
            }
            if let Some(circle) = visit(to, edges, stack, done) {
                return Some(circle);
            }
        }
        stack.pop();
        None
    }
    let mut done = BTreeSet::new();
    for m in &modules {
        if let Some(circle) = visit(m, &edges, &mut Vec::new(), &mut done) {
            let mut steps = Vec::new();
            for (k, from) in circle.iter().enumerate() {
                let to = circle[(k + 1) % circle.len()];
                steps.push(format!("  {from} -> {to}: {}", edges[&(from.to_string(), to.to_string())]));
            }
            panic!("the top-level modules import each other in a circle (issue 25, section 1):\n{}", steps.join("\n"));
        }
    }
}

#[test]
fn the_reader_resolves_super_and_groups() {
    let text = "use super::super::materials::Material;\nuse crate::{lights::Light, math::Vec3};\nuse super::Lobe;\n\
                mod tests {\n    use super::super::super::shapes;\n}\n// crate::render is named in a comment\n";
    let refs = references(Path::new("bsdfs/principled.rs"), text);
    let got: Vec<(usize, &str, bool)> = refs.iter().map(|r| (r.line, r.module.as_str(), r.in_comment)).collect();
    assert_eq!(
        got,
        [(1, "materials", false), (2, "lights", false), (2, "math", false), (3, "bsdfs", false), (5, "shapes", false), (7, "render", true)]
    );
}
