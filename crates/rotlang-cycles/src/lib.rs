//! Finds cycles between the files (modules) of a crate: issue 21 asks for none, and
//! `tests/workspace.rs` checks every crate of the repository with this.
//!
//! The graph has a node per source file reachable from a crate root (`src/lib.rs`,
//! `src/main.rs`) through `mod NAME;`, and an edge from a file to the file that defines
//! what it names: `use crate::…`, `use super::…`, `use self::…` and `use child::…` trees,
//! and the same paths written in code (`crate::plot::escape(s)`). A name is followed
//! through re-exports (`pub use region::Region` in `infill/mod.rs` sends `super::Region`
//! to `infill/region.rs`), so a module that only re-exports its children is a facade, not a
//! party to their cycles. Declaring a child (`mod x;`) is not an edge, and a re-export is not
//! an edge of the file that holds it. Inline modules (`mod tests { use super::*; }`) belong
//! to their file.
//!
//! It reads the text with a small tokenizer of its own (comments, strings and character
//! literals skipped), not a Rust parser: macros are not followed. `#[path = "file.rs"]` on
//! `mod NAME;` is followed as rustc does (the path relative to the directory of the file
//! that declares it, or of the inline module it is in; the file's own `mod` children are
//! its siblings); on an inline module (`#[path = "dir"] mod m { … }`) it is an error, as
//! is a `mod` whose file is missing.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A directed graph of named nodes (files, relative to the crate's `src/`).
pub type Graph = BTreeMap<String, BTreeSet<String>>;

/// The cycles of `graph`: each strongly connected component of two or more nodes, sorted,
/// in a sorted list. Edges from a node to itself are not cycles here (a file may use its
/// own items through `crate::` paths).
pub fn cycles(graph: &Graph) -> Vec<Vec<String>> {
    // Tarjan's algorithm, iterative so that deep graphs cannot overflow the stack.
    let names: Vec<&String> = graph
        .keys()
        .chain(graph.values().flatten())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let index_of: BTreeMap<&String, usize> =
        names.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let succ: Vec<Vec<usize>> = names
        .iter()
        .map(|n| {
            graph
                .get(*n)
                .map(|s| s.iter().map(|m| index_of[m]).collect())
                .unwrap_or_default()
        })
        .collect();
    let n = names.len();
    let (mut index, mut low, mut on_stack) = (vec![usize::MAX; n], vec![0; n], vec![false; n]);
    let (mut stack, mut next, mut found) = (Vec::new(), 0, Vec::new());
    for start in 0..n {
        if index[start] != usize::MAX {
            continue;
        }
        let mut work = vec![(start, 0usize)];
        while let Some(&mut (v, ref mut edge)) = work.last_mut() {
            if *edge == 0 && index[v] == usize::MAX {
                index[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on_stack[v] = true;
            }
            if let Some(&w) = succ[v].get(*edge) {
                *edge += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(names[w].clone());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    found.push(component);
                }
            }
        }
    }
    found.sort();
    found
}

/// The file graph of the crate whose sources are in `src` (roots `lib.rs` and `main.rs`,
/// each its own module tree). Unreadable files are errors; files no root reaches are not
/// in the graph.
pub fn crate_graph(src: &Path) -> Result<Graph, String> {
    let mut graph = Graph::new();
    for root in ["lib.rs", "main.rs"] {
        let path = src.join(root);
        if path.is_file() {
            let tree = Tree::load(src, &path)?;
            for (from, to) in tree.edges() {
                let from = tree.files[from].clone();
                let to = tree.files[to].clone();
                let entry = graph.entry(from.clone()).or_default();
                if from != to {
                    entry.insert(to);
                }
            }
        }
    }
    Ok(graph)
}

/// Why each edge of the crate in `src` is there: `(from, to)` → the paths as written in
/// `from` that resolve to `to`. For finding the back-edge of a cycle
/// (`cargo run -p rotlang-cycles --example graph -- DIR/src` prints them per cycle).
pub fn crate_reasons(src: &Path) -> Result<BTreeMap<(String, String), BTreeSet<String>>, String> {
    let mut reasons: BTreeMap<(String, String), BTreeSet<String>> = BTreeMap::new();
    for root in ["lib.rs", "main.rs"] {
        let path = src.join(root);
        if path.is_file() {
            let tree = Tree::load(src, &path)?;
            for r in &tree.references {
                if let Some(to) = tree
                    .resolve(r.module, &r.path, 0)
                    .filter(|&to| to != r.file)
                {
                    reasons
                        .entry((tree.files[r.file].clone(), tree.files[to].clone()))
                        .or_default()
                        .insert(r.path.join("::"));
                }
            }
        }
    }
    Ok(reasons)
}

// ---------------------------------------------------------------------------------------
// Tokens

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    PathSep,
    Punct(char),
    /// A string literal's text as written (escapes not read): for `#[path = "…"]`.
    Str(String),
}

/// The identifiers, punctuation and string literals of Rust source, without comments,
/// characters and lifetimes (enough to read `mod`, `use`, `#[path]`, item names and paths).
fn tokenize(text: &str) -> Vec<Tok> {
    let b: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == '/' && b.get(i + 1) == Some(&'/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && b.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == '"' {
            let start = i + 1;
            i = skip_string(&b, start, 0);
            out.push(Tok::Str(
                b[start..i.saturating_sub(1).max(start)].iter().collect(),
            ));
        } else if (c == 'r' || c == 'b' || c == 'c') && raw_string_start(&b, i).is_some() {
            let (start, hashes) = raw_string_start(&b, i).unwrap_or((i, 0));
            i = skip_string(&b, start, hashes);
            let end = i.saturating_sub(hashes.max(1)).max(start);
            out.push(Tok::Str(b[start..end].iter().collect()));
        } else if c == '\'' {
            // A character literal ('a', '\n', '\u{1F600}') or a lifetime ('a): skip either.
            if b.get(i + 1) == Some(&'\\') {
                i += 2;
                while i < b.len() && b[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if b.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                i += 1;
                while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                    i += 1;
                }
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            let word: String = b[start..i].iter().collect();
            // `r#type`: a raw identifier.
            let word = word.strip_prefix("r#").map(str::to_owned).unwrap_or(word);
            out.push(Tok::Ident(word));
        } else if c.is_ascii_digit() {
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_' || b[i] == '.') {
                i += 1;
            }
        } else if c == ':' && b.get(i + 1) == Some(&':') {
            out.push(Tok::PathSep);
            i += 2;
        } else {
            if !c.is_whitespace() {
                out.push(Tok::Punct(c));
            }
            i += 1;
        }
    }
    out
}

/// Where the text of a raw or byte string starting at `i` begins, and its `#` count:
/// `r"`, `r#"`, `b"`, `br#"`, `c"`, `cr"`.
fn raw_string_start(b: &[char], i: usize) -> Option<(usize, usize)> {
    if i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_') {
        return None;
    }
    let mut j = i;
    if b[j] == 'b' || b[j] == 'c' {
        j += 1;
    }
    let raw = b.get(j) == Some(&'r');
    if raw {
        j += 1;
    }
    let mut hashes = 0;
    while raw && b.get(j) == Some(&'#') {
        hashes += 1;
        j += 1;
    }
    (b.get(j) == Some(&'"') && (raw || j > i)).then_some((j + 1, if raw { hashes + 1 } else { 0 }))
}

/// The index past a string whose text starts at `i`. `raw` is 0 for an escaped string,
/// else one more than the number of `#` that close it.
fn skip_string(b: &[char], mut i: usize, raw: usize) -> usize {
    while i < b.len() {
        if raw == 0 && b[i] == '\\' {
            i += 2;
            continue;
        }
        if b[i] == '"' {
            let hashes = raw.saturating_sub(1);
            if (1..=hashes).all(|k| b.get(i + k) == Some(&'#')) {
                return i + 1 + hashes;
            }
        }
        i += 1;
    }
    i
}

// ---------------------------------------------------------------------------------------
// Module trees

#[derive(Default)]
struct Module {
    file: usize,
    parent: Option<usize>,
    children: BTreeMap<String, usize>,
    items: BTreeSet<String>,
    /// Names brought in by `use` (re-exports included): name → path as written.
    uses: BTreeMap<String, Vec<String>>,
    /// Modules whose names `use path::*` brings in, as written.
    globs: Vec<Vec<String>>,
}

/// A reference from a file: the path as written, read in `module`.
struct Reference {
    file: usize,
    module: usize,
    path: Vec<String>,
}

struct Tree {
    files: Vec<String>,
    modules: Vec<Module>,
    references: Vec<Reference>,
}

const ITEM_KEYWORDS: [&str; 8] = [
    "fn", "struct", "enum", "trait", "type", "const", "static", "union",
];

impl Tree {
    fn load(src: &Path, root: &Path) -> Result<Tree, String> {
        let mut tree = Tree {
            files: Vec::new(),
            modules: vec![Module::default()],
            references: Vec::new(),
        };
        tree.read_file(src, root, 0, root.parent().unwrap_or(src).to_path_buf())?;
        Ok(tree)
    }

    /// Reads `path` as the body of `module`, whose child files live in `dir`.
    fn read_file(
        &mut self,
        src: &Path,
        path: &Path,
        module: usize,
        dir: PathBuf,
    ) -> Result<(), String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        // Named relative to `src`, both without `..` (a `#[path]` may climb out and back).
        let (full, root) = (normalize(path), normalize(src));
        let name = full
            .strip_prefix(&root)
            .unwrap_or(&full)
            .to_string_lossy()
            .replace('\\', "/");
        let file = self.files.len();
        self.files.push(name);
        self.modules[module].file = file;
        let toks = tokenize(&text);
        // Frames of braces: Some(module) for a module body, None for any other block.
        let mut frames: Vec<Option<usize>> = vec![Some(module)];
        // (child, its name, the folder of its default file, its `#[path]` file if any).
        let mut pending_children: Vec<(usize, String, PathBuf, Option<PathBuf>)> = Vec::new();
        // A `#[path = "…"]` read, for the `mod` that follows it.
        let mut path_attribute: Option<String> = None;
        let mut i = 0;
        let current =
            |frames: &[Option<usize>]| frames.iter().rev().find_map(|f| *f).unwrap_or(module);
        while i < toks.len() {
            let at_module_level = frames.last().copied().flatten().is_some();
            let here = current(&frames);
            match &toks[i] {
                Tok::Punct('#') if at_module_level => {
                    if let [
                        Tok::Punct('['),
                        Tok::Ident(attr),
                        Tok::Punct('='),
                        Tok::Str(value),
                        Tok::Punct(']'),
                    ] = toks.get(i + 1..i + 6).unwrap_or_default()
                        && attr == "path"
                    {
                        path_attribute = Some(value.clone());
                        i += 6;
                        continue;
                    }
                }
                Tok::Punct('{') => frames.push(None),
                Tok::Punct('}') if frames.len() > 1 => {
                    frames.pop();
                }
                Tok::Ident(kw) if kw == "mod" && at_module_level => {
                    if let Some(Tok::Ident(name)) = toks.get(i + 1) {
                        let child = self.modules.len();
                        self.modules.push(Module {
                            file,
                            parent: Some(here),
                            ..Module::default()
                        });
                        self.modules[here].children.insert(name.clone(), child);
                        let attribute = path_attribute.take();
                        match toks.get(i + 2) {
                            Some(Tok::Punct('{')) => {
                                if let Some(p) = attribute {
                                    return Err(format!(
                                        "{}: `#[path = {p:?}]` on the inline `mod {name}` is not followed",
                                        self.files[file]
                                    ));
                                }
                                frames.push(Some(child));
                                i += 3;
                                continue;
                            }
                            Some(Tok::Punct(';')) => {
                                // Files of `here`'s children: `dir/name.rs` or `dir/name/mod.rs`,
                                // where `dir` is this file's directory for a mod.rs, lib.rs or
                                // main.rs, else the directory named after this file.
                                let base = if here == module {
                                    dir.clone()
                                } else {
                                    dir.join(self.inline_path(here, module))
                                };
                                // `#[path]` at the file's level is relative to the file's
                                // folder; inside an inline module, to that module's folder.
                                let explicit = attribute.map(|p| {
                                    let from = if here == module {
                                        path.parent().unwrap_or(src).to_path_buf()
                                    } else {
                                        base.clone()
                                    };
                                    normalize(&from.join(p))
                                });
                                pending_children.push((child, name.clone(), base, explicit));
                            }
                            _ => {}
                        }
                        i += 2;
                        continue;
                    }
                }
                Tok::Ident(kw) if kw == "use" => {
                    path_attribute = None;
                    let end = toks[i..]
                        .iter()
                        .position(|t| *t == Tok::Punct(';'))
                        .map_or(toks.len(), |p| i + p);
                    let public = i > 0 && matches!(toks[i - 1], Tok::Ident(ref p) if p == "pub")
                        || i > 3
                            && toks[i - 1] == Tok::Punct(')')
                            && matches!(toks[i - 4], Tok::Ident(ref p) if p == "pub");
                    let mut trees = Vec::new();
                    use_tree(&toks[i + 1..end], &mut Vec::new(), &mut trees);
                    for (binding, path) in trees {
                        match binding {
                            Some(binding) if at_module_level => {
                                self.modules[here].uses.insert(binding, path.clone());
                            }
                            None if at_module_level => self.modules[here].globs.push(path.clone()),
                            _ => {}
                        }
                        if !public || !at_module_level {
                            self.references.push(Reference {
                                file,
                                module: here,
                                path,
                            });
                        }
                    }
                    i = end + 1;
                    continue;
                }
                Tok::Ident(kw)
                    if at_module_level
                        && (ITEM_KEYWORDS.contains(&kw.as_str()) || kw == "macro_rules") =>
                {
                    path_attribute = None;
                    let mut j = i + 1;
                    if kw == "macro_rules" && toks.get(j) == Some(&Tok::Punct('!')) {
                        j += 1;
                    }
                    // `const fn name`, `unsafe fn`, `const _: () = …`.
                    while let Some(Tok::Ident(w)) = toks.get(j) {
                        if ITEM_KEYWORDS.contains(&w.as_str())
                            || w == "unsafe"
                            || w == "async"
                            || w == "extern"
                        {
                            j += 1;
                        } else {
                            self.modules[here].items.insert(w.clone());
                            break;
                        }
                    }
                }
                Tok::Ident(first)
                    if toks.get(i + 1) == Some(&Tok::PathSep)
                        && !matches!(toks.get(i.wrapping_sub(1)), Some(Tok::PathSep)) =>
                {
                    // A path in code: `crate::a::b`, `super::x`, `self::x`, `child::x`.
                    let mut path = vec![first.clone()];
                    let mut j = i + 1;
                    while toks.get(j) == Some(&Tok::PathSep) {
                        match toks.get(j + 1) {
                            Some(Tok::Ident(seg)) => path.push(seg.clone()),
                            _ => break,
                        }
                        j += 2;
                    }
                    self.references.push(Reference {
                        file,
                        module: here,
                        path,
                    });
                    i = j;
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
        for (child, name, base, explicit) in pending_children {
            let (flat, nested) = (
                base.join(format!("{name}.rs")),
                base.join(&name).join("mod.rs"),
            );
            let (path, child_dir) = if let Some(path) = explicit {
                // As rustc reads a `#[path]` file: like a mod.rs, its children are siblings.
                if !path.is_file() {
                    return Err(format!(
                        "{}: no file {} for `#[path] mod {name};`",
                        self.files[file],
                        path.display()
                    ));
                }
                let dir = path.parent().unwrap_or(src).to_path_buf();
                (path, dir)
            } else if flat.is_file() {
                (flat, base.join(&name))
            } else if nested.is_file() {
                (nested, base.join(&name))
            } else {
                return Err(format!("{}: no file for `mod {name};`", self.files[file]));
            };
            self.read_file(src, &path, child, child_dir)?;
        }
        Ok(())
    }

    /// The directory path of inline module `m` below the file's own module `top`.
    fn inline_path(&self, m: usize, top: usize) -> PathBuf {
        let mut names = Vec::new();
        let mut cur = m;
        while cur != top {
            let parent = self.modules[cur].parent.unwrap_or(top);
            if let Some((name, _)) = self.modules[parent]
                .children
                .iter()
                .find(|(_, c)| **c == cur)
            {
                names.push(name.clone());
            }
            cur = parent;
        }
        names.iter().rev().collect()
    }

    /// The module a path's first segment starts from, and the segments left, or `None`
    /// for a path outside the crate (`std::…`, another crate).
    fn start<'p>(&self, module: usize, path: &'p [String]) -> Option<(usize, &'p [String])> {
        let mut cur = module;
        let mut rest = path;
        match rest.first().map(String::as_str) {
            Some("crate") => return Some((0, &rest[1..])),
            Some("self") => rest = &rest[1..],
            Some("super") => {
                while rest.first().map(String::as_str) == Some("super") {
                    cur = self.modules[cur].parent?;
                    rest = &rest[1..];
                }
            }
            Some(first) if self.modules[cur].children.contains_key(first) => {}
            Some(first) if self.modules[cur].uses.contains_key(first) => {}
            _ => return None,
        }
        Some((cur, rest))
    }

    /// The file that defines what `path` names when read in `module`.
    fn resolve(&self, module: usize, path: &[String], depth: usize) -> Option<usize> {
        let (mut cur, rest) = self.start(module, path)?;
        for (k, seg) in rest.iter().enumerate() {
            let m = &self.modules[cur];
            if let Some(&child) = m.children.get(seg) {
                cur = child;
            } else if m.items.contains(seg) {
                return Some(m.file);
            } else if let Some(target) = m.uses.get(seg).filter(|_| depth < 16) {
                let mut next = target.clone();
                next.extend(rest[k + 1..].iter().cloned());
                // A re-export of another crate's item (`pub use rotlang::*`) ends here.
                return self.resolve(cur, &next, depth + 1).or(Some(m.file));
            } else {
                return self.through_globs(cur, &rest[k..], depth);
            }
        }
        Some(self.modules[cur].file)
    }

    /// A name `module` does not define nor import by name: the module of a glob import
    /// that has it (`pub use ir::*` at a crate root), else nothing when a glob brings in
    /// another crate (`use rotlang::*`: the name is that crate's), else `module`'s file.
    fn through_globs(&self, module: usize, rest: &[String], depth: usize) -> Option<usize> {
        let m = &self.modules[module];
        let mut outside = false;
        for glob in m.globs.iter().filter(|_| depth < 16) {
            match self.start(module, glob) {
                Some((from, within)) => {
                    let mut target = from;
                    for seg in within {
                        match self.modules[target].children.get(seg) {
                            Some(&child) => target = child,
                            None => break,
                        }
                    }
                    let t = &self.modules[target];
                    let name = &rest[0];
                    if t.children.contains_key(name)
                        || t.items.contains(name)
                        || t.uses.contains_key(name)
                    {
                        let mut path = glob.clone();
                        path.extend(rest.iter().cloned());
                        return self.resolve(module, &path, depth + 1);
                    }
                }
                None => outside = true,
            }
        }
        if outside { None } else { Some(m.file) }
    }

    /// Every edge `(from file, to file)` of the tree's references.
    fn edges(&self) -> BTreeSet<(usize, usize)> {
        let mut edges: BTreeSet<(usize, usize)> = (0..self.files.len()).map(|f| (f, f)).collect();
        for r in &self.references {
            if let Some(to) = self.resolve(r.module, &r.path, 0) {
                edges.insert((r.file, to));
            }
        }
        edges
    }
}

/// `a/b/../c` as `a/c`, without touching the file system (a `#[path]` may climb out of
/// the folder that declares it).
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir
                if matches!(
                    out.components().next_back(),
                    Some(std::path::Component::Normal(_))
                ) =>
            {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// Reads a use tree (`a::{b, c::d as e, f::*}`) into (binding, full path) pairs; a glob
/// has no binding and its path is the module's.
fn use_tree(toks: &[Tok], prefix: &mut Vec<String>, out: &mut Vec<(Option<String>, Vec<String>)>) {
    let mut i = 0;
    let len = prefix.len();
    // A leading `::` (`use ::std::x`) names an outside crate.
    if toks.first() == Some(&Tok::PathSep) {
        return;
    }
    while i < toks.len() {
        match &toks[i] {
            Tok::Ident(seg) if seg == "as" => {
                if let (Some(Tok::Ident(alias)), Some(last)) = (toks.get(i + 1), out.last_mut()) {
                    last.0 = Some(alias.clone()).filter(|a| a != "_");
                }
                i += 2;
            }
            Tok::Ident(seg) => {
                prefix.push(seg.clone());
                let at_end = !matches!(toks.get(i + 1), Some(Tok::PathSep));
                if at_end {
                    let binding = if seg == "self" {
                        prefix.iter().rev().nth(1).cloned()
                    } else {
                        Some(seg.clone())
                    };
                    let path: Vec<String> = if seg == "self" {
                        prefix[..prefix.len() - 1].to_vec()
                    } else {
                        prefix.clone()
                    };
                    out.push((binding, path));
                    prefix.truncate(len);
                }
                i += 1;
            }
            Tok::PathSep => i += 1,
            Tok::Punct('*') => {
                out.push((None, prefix.clone()));
                prefix.truncate(len);
                i += 1;
            }
            Tok::Punct('{') => {
                // The group's extent, then each comma-separated subtree.
                let mut depth = 0;
                let mut end = i;
                for (k, t) in toks.iter().enumerate().skip(i) {
                    match t {
                        Tok::Punct('{') => depth += 1,
                        Tok::Punct('}') => {
                            depth -= 1;
                            if depth == 0 {
                                end = k;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                let inner = &toks[i + 1..end.max(i + 1)];
                let mut start = 0;
                let mut d = 0;
                for k in 0..=inner.len() {
                    match inner.get(k) {
                        Some(Tok::Punct('{')) => d += 1,
                        Some(Tok::Punct('}')) => d -= 1,
                        Some(Tok::Punct(',')) if d == 0 => {
                            use_tree(&inner[start..k], prefix, out);
                            start = k + 1;
                        }
                        None => use_tree(&inner[start..k], prefix, out),
                        _ => {}
                    }
                }
                prefix.truncate(len);
                i = end + 1;
            }
            _ => i += 1,
        }
    }
    prefix.truncate(len);
}

#[cfg(test)]
mod tests;
