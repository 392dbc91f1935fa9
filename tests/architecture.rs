//! The shape of the code, checked: no two files of `src/` import each other
//! through a loop of `crate::…` paths, and the emulators never reach the
//! project model (an emulated board stores what a real one stores: protocol
//! records, not a project). Each `crate::a::b::Name` path — in a `use` line,
//! brace groups expanded, or written out in code — is an arrow from its file
//! to the file of the deepest module it names. Comments and in-file test
//! modules do not count. And no public function is left that nothing calls.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, as paths relative to `src`.
fn sources(src: &Path, dir: &Path, into: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().map(|entry| entry.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            sources(src, &path, into);
        } else if path.extension().is_some_and(|ext| ext == "rs") {
            into.push(path.strip_prefix(src).unwrap().to_path_buf());
        }
    }
}

/// The text that is code: comments removed, the in-file test module cut off.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests {") {
        Some(at) => &text[..at],
        None => text,
    };
    text.lines().map(|line| line.find("//").map_or(line, |at| &line[..at])).collect::<Vec<_>>().join("\n")
}

/// `a::{b, c::{d, e}}` → `a::b`, `a::c::d`, `a::c::e` (whitespace removed).
fn expand(tree: &str) -> Vec<String> {
    let Some(open) = tree.find('{') else { return vec![tree.to_string()] };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (at, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..at]);
                start = at + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts.into_iter().filter(|part| !part.is_empty()).flat_map(|part| expand(&format!("{prefix}{part}"))).collect()
}

/// Every `crate::…` path the code names, and every `super::…` path made
/// whole from `module` (the file's module path), as segments after `crate`.
fn crate_paths(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    for (prefix, base) in [("crate::", Vec::new()), ("super::", module.to_vec())] {
        let mut rest = code;
        while let Some(at) = rest.find(prefix) {
            let before = &rest[..at];
            let mut tail = &rest[at + prefix.len()..];
            if before.chars().next_back().is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                rest = tail;
                continue;
            }
            let mut base = base.clone();
            if prefix == "super::" {
                base.pop();
                while let Some(further) = tail.strip_prefix("super::") {
                    base.pop();
                    tail = further;
                }
            }
            let is_use = before.trim_end().ends_with("use");
            let end = if is_use {
                tail.find(';').unwrap_or(tail.len())
            } else {
                tail.find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':')).unwrap_or(tail.len())
            };
            for path in use_paths(&tail[..end]) {
                paths.push(base.iter().cloned().chain(path).collect());
            }
            rest = &tail[end..];
        }
    }
    paths
}

/// A file's module path: `protocol/servo/mod.rs` → `protocol::servo`.
fn module_of(file: &Path) -> Vec<String> {
    let mut segments: Vec<String> =
        file.with_extension("").iter().map(|segment| segment.to_string_lossy().into_owned()).collect();
    if segments.last().is_some_and(|last| last == "mod" || last == "lib") {
        segments.pop();
    }
    segments
}

/// The paths a use tree names (`a::{b as c, d}` → `a::b`, `a::d`).
fn use_paths(tree: &str) -> Vec<Vec<String>> {
    let tree = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    expand(&tree)
        .into_iter()
        .map(|path| {
            let path = path.split(" as ").next().unwrap_or_default();
            path.split("::").map(str::trim).filter(|s| !s.is_empty()).map(str::to_string).collect()
        })
        .collect()
}

/// What a module file re-exports from its own child modules (`pub use
/// child::Name;`): each name, and the child file it comes from.
fn reexports(src: &Path, module: &Path) -> BTreeMap<String, PathBuf> {
    let Ok(text) = std::fs::read_to_string(src.join(module)) else { return BTreeMap::new() };
    let dir = if module.ends_with("mod.rs") || module == Path::new("lib.rs") {
        module.parent().unwrap_or(Path::new("")).to_path_buf()
    } else {
        module.with_extension("")
    };
    let code = code(&text);
    let mut names = BTreeMap::new();
    for statement in code.split(';') {
        let Some(at) = statement.find("pub use ") else { continue };
        for path in use_paths(&statement[at + "pub use ".len()..]) {
            let (Some(first), Some(name)) = (path.first(), path.last()) else { continue };
            if src.join(&dir).join(format!("{first}.rs")).is_file()
                || src.join(&dir).join(first).join("mod.rs").is_file()
            {
                let mut child_dir = dir.clone();
                let mut file = module.to_path_buf();
                for segment in &path[..path.len() - 1] {
                    let flat = child_dir.join(format!("{segment}.rs"));
                    let folder = child_dir.join(segment).join("mod.rs");
                    if src.join(&flat).is_file() {
                        file = flat;
                    } else if src.join(&folder).is_file() {
                        file = folder;
                    } else {
                        break;
                    }
                    child_dir = child_dir.join(segment);
                }
                names.insert(name.clone(), file);
            }
        }
    }
    names
}

/// The file of the deepest module `path` names (relative to `src`), or of
/// the child module the item it names is re-exported from.
fn module_file(src: &Path, path: &[String]) -> PathBuf {
    let mut file = PathBuf::from("lib.rs");
    let mut dir = PathBuf::new();
    for segment in path {
        let flat = dir.join(format!("{segment}.rs"));
        let folder = dir.join(segment).join("mod.rs");
        if src.join(&flat).is_file() {
            file = flat;
        } else if src.join(&folder).is_file() {
            file = folder;
        } else {
            // An item: the module may only re-export it from a child (followed as far as it goes).
            let mut seen = BTreeSet::new();
            while let Some(child) = reexports(src, &file).remove(segment) {
                if child == file || !seen.insert(child.clone()) {
                    break;
                }
                file = child;
            }
            break;
        }
        dir = dir.join(segment);
    }
    file
}

/// Every file's arrows to the files it imports from.
fn arrows() -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &src, &mut files);
    let mut arrows = BTreeMap::new();
    for file in files {
        if file.file_name().is_some_and(|name| name == "tests.rs" || name == "props.rs") {
            continue;
        }
        let text = std::fs::read_to_string(src.join(&file)).unwrap();
        let targets: BTreeSet<PathBuf> = crate_paths(&code(&text), &module_of(&file))
            .iter()
            .map(|path| module_file(&src, path))
            .filter(|target| *target != file && target != Path::new("lib.rs"))
            .collect();
        arrows.insert(file, targets);
    }
    arrows
}

/// The loops (strongly connected groups of more than one file), by Tarjan.
fn loops(arrows: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    struct State<'a> {
        arrows: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        index: BTreeMap<&'a Path, (usize, usize)>,
        stack: Vec<&'a Path>,
        on_stack: BTreeSet<&'a Path>,
        found: Vec<Vec<PathBuf>>,
    }
    fn visit<'a>(state: &mut State<'a>, file: &'a Path) {
        let next = state.index.len();
        state.index.insert(file, (next, next));
        state.stack.push(file);
        state.on_stack.insert(file);
        for target in state.arrows.get(file).into_iter().flatten() {
            if !state.index.contains_key(target.as_path()) {
                visit(state, target);
                let low = state.index[target.as_path()].1;
                let entry = state.index.get_mut(file).unwrap();
                entry.1 = entry.1.min(low);
            } else if state.on_stack.contains(target.as_path()) {
                let low = state.index[target.as_path()].0;
                let entry = state.index.get_mut(file).unwrap();
                entry.1 = entry.1.min(low);
            }
        }
        let (index, low) = state.index[file];
        if index == low {
            let mut group = Vec::new();
            while let Some(member) = state.stack.pop() {
                state.on_stack.remove(member);
                group.push(member.to_path_buf());
                if member == file {
                    break;
                }
            }
            if group.len() > 1 {
                group.sort();
                state.found.push(group);
            }
        }
    }
    let mut state =
        State { arrows, index: BTreeMap::new(), stack: Vec::new(), on_stack: BTreeSet::new(), found: Vec::new() };
    for file in arrows.keys() {
        if !state.index.contains_key(file.as_path()) {
            visit(&mut state, file);
        }
    }
    state.found
}

fn under(file: &Path, folders: &[&str]) -> bool {
    folders.iter().any(|folder| file.starts_with(folder))
}

/// Not in `src/ui`, `src/device` or `src/sim` — nor anywhere else in `src`.
#[test]
fn no_file_is_in_an_import_loop() {
    let arrows = arrows();
    assert!(arrows.len() > 100, "the sources were read ({} files)", arrows.len());
    let found = loops(&arrows);
    assert!(found.is_empty(), "import loops: {found:#?}");
}

/// The public functions `code` defines (`pub fn`, `pub(crate) fn`…), by
/// name, each with whether it exists only for tests (`#[cfg(test)]`, or the
/// `test-api` feature the tests turn on) as the attributes above it say.
fn public_functions(code: &str) -> Vec<(String, bool)> {
    let mut found = Vec::new();
    for (at, _) in code.match_indices("pub") {
        if code[..at].chars().next_back().is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[at + 3..];
        let rest = if rest.starts_with('(') { rest.split_once(')').map_or("", |(_, after)| after) } else { rest };
        let rest = rest.trim_start();
        let rest = rest.strip_prefix("const ").unwrap_or(rest).trim_start();
        let Some(named) = rest.strip_prefix("fn ") else { continue };
        let name: String = named.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let above = code[..at]
            .lines()
            .rev()
            .skip(1)
            .map(str::trim)
            .take_while(|line| line.is_empty() || line.starts_with("#[") || line.starts_with("///"));
        let for_tests = above.into_iter().any(|line| line.contains("cfg(test)") || line.contains("\"test-api\""));
        if !name.is_empty() {
            found.push((name, for_tests));
        }
    }
    found
}

/// `text` as the app is built from it: its in-file test modules
/// (`#[cfg(test)] mod … {`, to the brace closing it at a line's start) cut out.
fn built(text: &str) -> String {
    let mut kept = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("#[cfg(test)]\nmod ") {
        kept.push_str(&rest[..at]);
        rest = rest[at..].find("\n}\n").map_or("", |end| &rest[at + end + 3..]);
    }
    kept.push_str(rest);
    kept
}

/// How many times each word (letters, digits, `_`) is written in `text`.
fn word_counts(text: &str) -> BTreeMap<&str, usize> {
    let mut counts = BTreeMap::new();
    for word in text.split(|c: char| !(c.is_alphanumeric() || c == '_')).filter(|word| !word.is_empty()) {
        *counts.entry(word).or_insert(0) += 1;
    }
    counts
}

/// Every public function of `src/` has a caller outside the tests: it is
/// named, besides its definition, in the code the app is built from or in
/// a benchmark. One the tests alone reach exists only for them (`cfg(test)`,
/// or the `test-api` feature the tests turn on: absent from the app). Files
/// only tests compile (the test-only echo family, `tests.rs` modules) call nothing.
#[test]
fn every_public_function_has_a_caller_outside_the_tests() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let listed = |dir: &str| {
        let mut files = Vec::new();
        sources(&root.join(dir), &root.join(dir), &mut files);
        files.into_iter().map(|file| root.join(dir).join(file)).collect::<Vec<PathBuf>>()
    };
    let test_only = |file: &PathBuf| file.ends_with("tests.rs") || file.starts_with(root.join("src/ui/echo"));
    let app: Vec<(PathBuf, String)> = listed("src")
        .into_iter()
        .filter(|file| !test_only(file))
        .map(|file| {
            let text = built(&std::fs::read_to_string(&file).unwrap());
            (
                file,
                text.lines().map(|line| line.find("//").map_or(line, |at| &line[..at])).collect::<Vec<_>>().join("\n"),
            )
        })
        .collect();
    let benches: String = listed("benches").iter().map(|file| std::fs::read_to_string(file).unwrap()).collect();
    let everything: String =
        app.iter().map(|(_, code)| code.as_str()).chain([benches.as_str()]).collect::<Vec<_>>().join("\n");
    let counts = word_counts(&everything);
    let mut uncalled = Vec::new();
    for (file, code) in &app {
        for (name, for_tests) in public_functions(code) {
            if !for_tests && counts.get(name.as_str()).copied().unwrap_or(0) < 2 {
                uncalled.push(format!("{}: {name}", file.strip_prefix(root).unwrap().display()));
            }
        }
    }
    assert!(app.len() > 300, "the sources were read ({} files)", app.len());
    assert!(uncalled.is_empty(), "public functions nothing outside the tests calls: {uncalled:#?}");
}

/// The reading of that: definitions, what only tests get, what the app is built from.
#[test]
fn public_functions_and_their_gates_are_read_as_written() {
    let code = "pub fn a() {}\npub(crate) fn b_2() {}\n#[cfg(test)]\n/// c\npub const fn c() {}\npub struct D;\nrepub fn e() {}\n\
                #[cfg(any(test, feature = \"test-api\"))]\n    pub fn f(&self) {}\n";
    let found = public_functions(code);
    let expected = [("a", false), ("b_2", false), ("c", true), ("f", true)];
    assert_eq!(found, expected.map(|(name, gated)| (name.to_string(), gated)));
    assert_eq!(word_counts("a_b a ab a(\nxa").get("a"), Some(&2));
    assert_eq!(built("fn x() {}\n#[cfg(test)]\nmod tests {\n    fn y() {}\n}\nfn z() {}\n"), "fn x() {}\nfn z() {}\n");
}

#[test]
fn the_emulators_never_reach_the_project_model() {
    let arrows = arrows();
    // Breadth first from every emulator file, remembering the way.
    let mut way: BTreeMap<PathBuf, Option<PathBuf>> = BTreeMap::new();
    let mut queue: Vec<PathBuf> = arrows.keys().filter(|file| under(file, &["sim"])).cloned().collect();
    for file in &queue {
        way.insert(file.clone(), None);
    }
    while let Some(file) = queue.pop() {
        if under(&file, &["project"]) {
            let mut chain = vec![file.clone()];
            while let Some(Some(from)) = way.get(chain.last().unwrap()) {
                chain.push(from.clone());
            }
            chain.reverse();
            panic!("an emulator reaches the project model: {chain:?}");
        }
        for target in arrows.get(&file).into_iter().flatten() {
            if !way.contains_key(target) {
                way.insert(target.clone(), Some(file.clone()));
                queue.push(target.clone());
            }
        }
    }
}

/// The reading itself: brace groups, renames, paths in code, comments.
#[test]
fn the_reader_finds_the_paths_a_file_names() {
    let text =
        "use crate::a::{b::{C, D}, e as f};\n// use crate::x::Y;\nfn g() { crate::h::i(); }\nuse super::super::k::L;\n";
    let module = module_of(Path::new("p/q/r.rs"));
    assert_eq!(module, ["p", "q", "r"]);
    let paths = crate_paths(&code(text), &module);
    let joined: Vec<String> = paths.iter().map(|path| path.join("::")).collect();
    assert_eq!(joined, ["a::b::C", "a::b::D", "a::e", "h::i", "p::k::L"]);
    assert_eq!(module_of(Path::new("p/q/mod.rs")), ["p", "q"]);
}

/// Loops are found whole, and only loops.
#[test]
fn a_loop_is_found_with_every_file_in_it() {
    let file = |name: &str| PathBuf::from(name);
    let arrows: BTreeMap<PathBuf, BTreeSet<PathBuf>> = [
        ("a.rs", vec!["b.rs"]),
        ("b.rs", vec!["c.rs", "d.rs"]),
        ("c.rs", vec!["a.rs"]),
        ("d.rs", vec![]),
        ("e.rs", vec!["d.rs"]),
    ]
    .into_iter()
    .map(|(from, to)| (file(from), to.into_iter().map(file).collect()))
    .collect();
    assert_eq!(loops(&arrows), vec![vec![file("a.rs"), file("b.rs"), file("c.rs")]]);
}

/// A test that needs `../shared` skips without it on a developer's clone, and
/// fails naming what is missing where it is required (CI).
#[test]
fn a_missing_shared_folder_skips_only_where_it_is_not_required() {
    let empty = tempfile::tempdir().unwrap();
    assert_eq!(crate::common::shared_in(empty.path(), "plen2/motions", false), None);
    let required = std::panic::catch_unwind(|| crate::common::shared_in(empty.path(), "plen2/motions", true));
    let message = required.expect_err("required: a failure, not a skip");
    let text = message.downcast_ref::<String>().cloned().unwrap_or_default();
    assert!(text.contains("plen2/motions is missing"), "{text}");
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    assert_eq!(crate::common::shared_in(here, "tests", true), Some(here.join("tests")), "present: found");
}

/// The build graph for this machine with the default features: the
/// resolver's graph from `cargo metadata` (normal, build and dev
/// dependencies alike: the graph `cargo test` builds), offline — only what a
/// fresh machine's `cargo test` has downloaded is there to read.
fn default_graph() -> serde_json::Value {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = std::process::Command::new(rustc).arg("-vV").output().unwrap();
    let version = String::from_utf8(version.stdout).unwrap();
    let host = version.lines().find_map(|line| line.strip_prefix("host: ")).unwrap().to_string();
    let output = std::process::Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--locked", "--offline", "--filter-platform", &host])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(output.status.success(), "cargo metadata: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).unwrap()
}

/// The packages of a graph (`cargo metadata`'s JSON) that are resolved into
/// it and declare a native library they link (`links` in their manifest).
fn linking_packages(metadata: &serde_json::Value) -> Vec<String> {
    let packages = metadata["packages"].as_array().unwrap();
    let resolved: BTreeSet<&str> =
        metadata["resolve"]["nodes"].as_array().unwrap().iter().map(|node| node["id"].as_str().unwrap()).collect();
    packages
        .iter()
        .filter(|package| resolved.contains(package["id"].as_str().unwrap()) && !package["links"].is_null())
        .map(|package| format!("{} (links {})", package["name"].as_str().unwrap(), package["links"]))
        .collect()
}

/// A fresh machine with only the Rust toolchain builds the tests: nothing in
/// the default graph links a system library at build time (no `-dev`
/// package needed). The graph is read offline, so this also fails if it
/// needed a crate the default build never downloads (`.ci/run` runs it with
/// a cargo home holding only those).
#[test]
fn the_default_build_links_no_system_library() {
    let graph = default_graph();
    let resolved = graph["resolve"]["nodes"].as_array().unwrap();
    assert!(resolved.len() > 100, "the whole default graph was read: {} packages", resolved.len());
    assert_eq!(linking_packages(&graph), Vec::<String>::new(), "the default graph links a system library");
}

/// The check sees a linking package where there is one (the `cpal`
/// feature's ALSA binding, as `cargo metadata` lists it), and only a resolved one.
#[test]
fn a_package_that_links_a_system_library_is_seen_only_when_resolved() {
    let metadata = serde_json::json!({
        "packages": [
            { "id": "alsa-sys 0.3.1", "name": "alsa-sys", "links": "alsa" },
            { "id": "x11-dl 2.21.0", "name": "x11-dl", "links": null },
            { "id": "ring 0.17.0", "name": "ring", "links": "ring_core" },
        ],
        "resolve": { "nodes": [ { "id": "alsa-sys 0.3.1" }, { "id": "x11-dl 2.21.0" } ] },
    });
    assert_eq!(linking_packages(&metadata), ["alsa-sys (links \"alsa\")"]);
}
