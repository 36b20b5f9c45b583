//! The layering checker of `runtime/tests/layering.rs` (which describes the rules), shared with
//! `codegen/tests/layering.rs`: each includes this file as its module `checker`.
//!
//! [`check`] reads `src/**/*.rs` from `lib.rs` down along the `mod` declarations, resolves every
//! path to the module that defines the item, and finds the import circles of the module graph
//! (Tarjan's strongly connected components), printed with the lines that close them. Besides
//! the circles it checks that every module is mounted where its file is (no `#[path]`, no file
//! left unreached), that a module with child modules imports no module (one path per module),
//! that every path was resolved and, when the tree has one ([`Rules::bottom`]), that a bottom
//! layer imports nothing from above it.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Lexing: tokens without comments, strings and character literals.

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    /// An identifier or keyword (`$crate` included), with its line.
    Ident(String, usize),
    /// `::`.
    Path(usize),
    /// Any other punctuation character.
    Punct(char, usize),
}

impl Tok {
    fn line(&self) -> usize {
        match self {
            Tok::Ident(_, l) | Tok::Path(l) | Tok::Punct(_, l) => *l,
        }
    }
    fn is_ident(&self, s: &str) -> bool {
        matches!(self, Tok::Ident(i, _) if i == s)
    }
    fn is_punct(&self, c: char) -> bool {
        matches!(self, Tok::Punct(p, _) if *p == c)
    }
    fn ident(&self) -> Option<&str> {
        match self {
            Tok::Ident(i, _) => Some(i),
            _ => None,
        }
    }
}

fn lex(src: &str) -> Vec<Tok> {
    let c: Vec<char> = src.chars().collect();
    let (mut i, mut line, mut out) = (0, 1, Vec::new());
    let at = |i: usize, s: &str| s.chars().enumerate().all(|(k, ch)| c.get(i + k) == Some(&ch));
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if at(i, "//") {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if at(i, "/*") {
            let mut depth = 0;
            while i < c.len() {
                if at(i, "/*") {
                    depth += 1;
                    i += 2;
                } else if at(i, "*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    line += usize::from(c[i] == '\n');
                    i += 1;
                }
            }
        } else if ch == 'r' && (at(i, "r\"") || at(i, "r#")) && !prev_is_ident(&c, i) {
            // A raw string: r"...", r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if c.get(j) != Some(&'"') {
                // `r#ident`: a raw identifier.
                let start = j;
                while j < c.len() && (c[j].is_alphanumeric() || c[j] == '_') {
                    j += 1;
                }
                out.push(Tok::Ident(c[start..j].iter().collect(), line));
                i = j;
                continue;
            }
            j += 1;
            let close: String = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            while j < c.len() && !at(j, &close) {
                line += usize::from(c[j] == '\n');
                j += 1;
            }
            i = j + close.chars().count();
        } else if ch == '"' || (ch == 'b' && at(i, "b\"")) {
            let mut j = if ch == 'b' { i + 2 } else { i + 1 };
            while j < c.len() && c[j] != '"' {
                if c[j] == '\\' {
                    j += 1;
                }
                line += usize::from(c.get(j) == Some(&'\n'));
                j += 1;
            }
            i = j + 1;
        } else if ch == '\'' {
            // A character literal ('x', '\n', '\u{..}') or a lifetime ('a).
            if c.get(i + 1) == Some(&'\\') {
                // Past the escaped character, which may be a quote.
                let mut j = i + 3;
                while j < c.len() && c[j] != '\'' {
                    j += 1;
                }
                i = j + 1;
            } else if c.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                // A lifetime, with its name (`'static` names no item).
                i += 1;
                while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                    i += 1;
                }
            }
        } else if ch.is_alphabetic() || ch == '_' || (ch == '$' && at(i, "$crate")) {
            let start = i;
            i += 1;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(c[start..i].iter().collect(), line));
        } else if ch.is_ascii_digit() {
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_' || c[i] == '.') {
                // `1..n`: a range, not a fraction.
                if c[i] == '.' && c.get(i + 1) == Some(&'.') {
                    break;
                }
                i += 1;
            }
        } else if at(i, "::") {
            out.push(Tok::Path(line));
            i += 2;
        } else {
            out.push(Tok::Punct(ch, line));
            i += 1;
        }
    }
    out
}

fn prev_is_ident(c: &[char], i: usize) -> bool {
    i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_')
}

// ---------------------------------------------------------------------------------------------
// Parsing: modules, their `use` declarations, the items they define, and every path.

/// A module path from the crate root, `["solvers", "newton"]` (the root is `[]`).
pub type ModPath = Vec<String>;

#[derive(Debug, Default)]
struct Module {
    /// The file that holds it, relative to the source directory.
    file: String,
    /// The file module it belongs to (itself, unless it is an inline module such as `tests`).
    file_module: ModPath,
    /// Whether it is compiled only for tests (`#[cfg(test)]`, or inside such a module).
    test: bool,
    /// Child modules by name (file or inline).
    children: BTreeSet<String>,
    /// Names brought in by top-level `use` declarations, to their full path (`[kw, ...]`,
    /// unresolved: the first segment is `crate`, `super`, `self` or a child module).
    uses: BTreeMap<String, Vec<String>>,
    /// Glob imports (`use x::*`), unresolved.
    globs: Vec<Vec<String>>,
    /// Items defined at its top level.
    items: BTreeSet<String>,
}

/// A path met in a module, to resolve once every module is known.
#[derive(Debug)]
struct Reference {
    from: ModPath,
    /// Made under `#[cfg(test)]` (a `use` so marked; a test module's references are marked by
    /// their module).
    test: bool,
    /// A re-export (`pub use`, `pub(crate) use`): of a descendant's item, the parent's face,
    /// not an import.
    reexport: bool,
    segments: Vec<String>,
    file: String,
    line: usize,
}

#[derive(Debug, Default)]
struct Crate {
    modules: BTreeMap<ModPath, Module>,
    references: Vec<Reference>,
    /// `#[path]` attributes met (file, line).
    path_attributes: Vec<(String, usize)>,
    /// Source files under the directory that no `mod` declaration reaches.
    unreached: Vec<String>,
}

const ITEM_KEYWORDS: [&str; 8] = ["fn", "struct", "enum", "trait", "type", "const", "static", "union"];

impl Crate {
    fn read(src: &Path) -> Crate {
        let mut krate = Crate::default();
        krate.parse_file(src, &src.join("lib.rs"), Vec::new(), false);
        let reached: BTreeSet<String> = krate.modules.values().map(|m| m.file.clone()).collect();
        let mut all = Vec::new();
        collect_rs(src, src, &mut all);
        krate.unreached = all.into_iter().filter(|f| !reached.contains(f)).collect();
        krate
    }

    /// Parses the file `path` as module `module`; its `mod x;` children are parsed in turn.
    fn parse_file(&mut self, src: &Path, path: &Path, module: ModPath, test: bool) {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let file = path.strip_prefix(src).unwrap().to_string_lossy().replace('\\', "/");
        let name = path.file_name().unwrap().to_string_lossy();
        // Where `mod x;` looks for `x.rs`: beside `lib.rs` and `mod.rs`, in `name/` otherwise.
        let child_dir = if name == "lib.rs" || name == "mod.rs" {
            path.parent().unwrap().to_path_buf()
        } else {
            path.with_extension("")
        };
        let toks = lex(&text);
        let mut files: Vec<(PathBuf, ModPath, bool)> = Vec::new();
        // The open inline modules: (module path, brace depth of its body).
        let mut stack: Vec<(ModPath, usize)> = vec![(module.clone(), 0)];
        self.modules.insert(
            module.clone(),
            Module { file: file.clone(), file_module: module.clone(), test, ..Default::default() },
        );
        let (mut depth, mut cfg_test, mut path_attr) = (0usize, false, None::<String>);
        let mut i = 0;
        while i < toks.len() {
            let (current, body) = stack.last().cloned().unwrap();
            let top = depth == body;
            let t = &toks[i];
            if t.is_punct('#') && toks.get(i + 1).is_some_and(|t| t.is_punct('[')) {
                let end = matching(&toks, i + 1, '[', ']');
                let attr: Vec<&str> = toks[i + 2..end].iter().filter_map(Tok::ident).collect();
                if attr == ["cfg", "test"] {
                    cfg_test = true;
                }
                if attr.first() == Some(&"path") {
                    self.path_attributes.push((file.clone(), t.line()));
                    path_attr = Some(attr_string(&text, t.line()));
                }
                i = end + 1;
                continue;
            }
            if t.is_ident("mod") && toks.get(i + 1).and_then(Tok::ident).is_some() {
                let name = toks[i + 1].ident().unwrap().to_string();
                let mut child = current.clone();
                child.push(name.clone());
                self.modules.get_mut(&current).unwrap().children.insert(name.clone());
                let child_test = self.modules[&current].test || cfg_test;
                if toks.get(i + 2).is_some_and(|t| t.is_punct(';')) {
                    let at = match path_attr.take() {
                        Some(p) => path.parent().unwrap().join(p),
                        None => {
                            let flat = child_dir.join(format!("{name}.rs"));
                            if flat.exists() { flat } else { child_dir.join(&name).join("mod.rs") }
                        }
                    };
                    files.push((at, child, child_test));
                    i += 3;
                } else {
                    // An inline module: `mod tests { ... }`.
                    self.modules.insert(
                        child.clone(),
                        Module {
                            file: file.clone(),
                            file_module: module.clone(),
                            test: child_test,
                            ..Default::default()
                        },
                    );
                    depth += 1;
                    stack.push((child, depth));
                    i += 3;
                }
                cfg_test = false;
                continue;
            }
            // A visibility (`pub(crate)`, `pub(super)`, `pub(in crate::emit)`): its path names
            // where an item may be seen from, not something the module uses.
            if t.is_ident("pub") && toks.get(i + 1).is_some_and(|t| t.is_punct('(')) {
                i = matching(&toks, i + 1, '(', ')') + 1;
                continue;
            }
            if t.is_ident("use") {
                let reexport = match toks[..i].last() {
                    Some(p) if p.is_ident("pub") => true,
                    Some(p) if p.is_punct(')') => (0..i)
                        .rev()
                        .find(|&k| toks[k].is_punct('('))
                        .is_some_and(|k| k > 0 && toks[k - 1].is_ident("pub")),
                    _ => false,
                };
                let end = (i..toks.len()).find(|&k| toks[k].is_punct(';')).unwrap_or(toks.len());
                let mut trees = Vec::new();
                use_tree(&toks[i + 1..end], Vec::new(), &mut trees);
                for (segments, name) in trees {
                    self.references.push(Reference {
                        from: current.clone(),
                        test: cfg_test,
                        reexport,
                        segments: segments.clone(),
                        file: file.clone(),
                        line: t.line(),
                    });
                    if top {
                        let m = self.modules.get_mut(&current).unwrap();
                        match name {
                            Some(n) => {
                                m.uses.insert(n, segments);
                            }
                            None => m.globs.push(segments),
                        }
                    }
                }
                cfg_test = false;
                i = end + 1;
                continue;
            }
            if top
                && ITEM_KEYWORDS.iter().any(|k| t.is_ident(k))
                && let Some(n) = toks.get(i + 1).and_then(Tok::ident)
            {
                self.modules.get_mut(&current).unwrap().items.insert(n.to_string());
            }
            if top && t.is_ident("macro_rules") {
                // `#[macro_export]` macros live at the crate root; others are textual.
                if let Some(n) = toks.get(i + 2).and_then(Tok::ident) {
                    self.modules.get_mut(&Vec::new()).unwrap().items.insert(n.to_string());
                }
            }
            // An inline path: `crate::kin::Kin`, `super::closed::root_offset`, `restarts::after`
            // (a child module), not a segment of a longer path.
            if let Some(first) = t.ident()
                && toks.get(i + 1) == Some(&Tok::Path(t.line()))
                && (i == 0 || !matches!(toks[i - 1], Tok::Path(_)))
                && (matches!(first, "crate" | "$crate" | "super" | "self")
                    || self.modules[&current].children.contains(first))
            {
                let mut segments = vec![first.to_string()];
                let mut k = i + 1;
                while matches!(toks.get(k), Some(Tok::Path(_))) {
                    match toks.get(k + 1).and_then(Tok::ident) {
                        Some(s) => segments.push(s.to_string()),
                        None => break,
                    }
                    k += 2;
                }
                let r = Reference {
                    from: current.clone(),
                    test: false,
                    reexport: false,
                    segments,
                    file: file.clone(),
                    line: t.line(),
                };
                self.references.push(r);
                i = k;
                continue;
            }
            if t.is_punct('{') {
                depth += 1;
            } else if t.is_punct('}') {
                if depth == body && stack.len() > 1 {
                    stack.pop();
                }
                depth = depth.saturating_sub(1);
            }
            if t.is_punct('{') || t.is_punct('}') || t.is_punct(';') {
                cfg_test = false;
            }
            i += 1;
        }
        for (at, child, child_test) in files {
            self.parse_file(src, &at, child, child_test);
        }
    }
}

/// The index of the bracket closing the one at `open`.
fn matching(toks: &[Tok], open: usize, l: char, r: char) -> usize {
    let mut depth = 0;
    for (k, t) in toks.iter().enumerate().skip(open) {
        if t.is_punct(l) {
            depth += 1;
        } else if t.is_punct(r) {
            depth -= 1;
            if depth == 0 {
                return k;
            }
        }
    }
    toks.len() - 1
}

/// The string of a `#[path = "..."]` attribute on line `line`.
fn attr_string(text: &str, line: usize) -> String {
    let l = text.lines().nth(line - 1).unwrap_or("");
    l.split('"').nth(1).unwrap_or("").to_string()
}

/// Expands a use tree (`a::{b, c::d as e, f::*}`) into its paths with the name each brings in
/// (`None` for a glob). `self` in a group names the prefix.
fn use_tree(toks: &[Tok], prefix: Vec<String>, out: &mut Vec<(Vec<String>, Option<String>)>) {
    let mut path = prefix;
    let mut k = 0;
    while k < toks.len() {
        match &toks[k] {
            Tok::Ident(s, _) if s == "as" => {
                // `use x as _` brings in no name (a trait's methods only), but is a reference.
                let alias = toks.get(k + 1).and_then(Tok::ident).unwrap_or("_").to_string();
                out.push((path.clone(), Some(alias)));
                return;
            }
            Tok::Ident(s, _) if s == "self" && k == 0 && !path.is_empty() => {
                let name = path.last().cloned();
                out.push((path.clone(), name));
                return;
            }
            Tok::Ident(s, _) => path.push(s.clone()),
            Tok::Path(_) => {}
            Tok::Punct('*', _) => {
                out.push((path.clone(), None));
                return;
            }
            Tok::Punct('{', _) => {
                let end = matching(toks, k, '{', '}');
                let inner = &toks[k + 1..end];
                let mut start = 0;
                let mut depth = 0;
                for (j, t) in inner.iter().enumerate() {
                    if t.is_punct('{') {
                        depth += 1;
                    } else if t.is_punct('}') {
                        depth -= 1;
                    } else if t.is_punct(',') && depth == 0 {
                        if j > start {
                            use_tree(&inner[start..j], path.clone(), out);
                        }
                        start = j + 1;
                    }
                }
                if inner.len() > start {
                    use_tree(&inner[start..], path.clone(), out);
                }
                return;
            }
            _ => {}
        }
        k += 1;
    }
    let name = path.last().cloned();
    if !path.is_empty() {
        out.push((path, name));
    }
}

fn collect_rs(src: &Path, dir: &Path, out: &mut Vec<String>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            collect_rs(src, &p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p.strip_prefix(src).unwrap().to_string_lossy().replace('\\', "/"));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Resolution and the module graph.

/// Where a path leads: the module holding the item, and whether the whole path named a module.
#[derive(Debug, PartialEq)]
struct Target {
    module: ModPath,
    is_module: bool,
}

impl Crate {
    /// The absolute module path a path's first segment starts from, and the rest; `None` for a
    /// path into another crate.
    fn anchor(&self, from: &ModPath, segments: &[String]) -> Option<(ModPath, usize)> {
        let first = segments.first()?.as_str();
        match first {
            "crate" | "$crate" => Some((Vec::new(), 1)),
            "self" => Some((from.clone(), 1)),
            "super" => {
                let mut m = from.clone();
                let mut k = 0;
                while segments.get(k).map(String::as_str) == Some("super") {
                    m.pop();
                    k += 1;
                }
                Some((m, k))
            }
            _ if self.modules[from].children.contains(first) => Some((from.clone(), 0)),
            _ => None,
        }
    }

    fn resolve(&self, from: &ModPath, segments: &[String], hops: usize) -> Option<Target> {
        if hops > 32 {
            return None;
        }
        let (mut cur, start) = self.anchor(from, segments)?;
        for (k, seg) in segments.iter().enumerate().skip(start) {
            let m = self.modules.get(&cur)?;
            if m.children.contains(seg) {
                cur.push(seg.clone());
                continue;
            }
            if let Some(target) = m.uses.get(seg) {
                let mut path = target.clone();
                path.extend(segments[k + 1..].iter().cloned());
                return self.resolve(&cur, &path, hops + 1);
            }
            if m.items.contains(seg) {
                return Some(Target { module: cur, is_module: false });
            }
            for glob in &m.globs {
                let mut path = glob.clone();
                path.extend(segments[k..].iter().cloned());
                if let Some(t) = self.resolve(&cur, &path, hops + 1)
                    && (t.module != cur)
                {
                    return Some(t);
                }
            }
            // An item the scan does not see (a variant, an associated item, a generated name).
            return Some(Target { module: cur, is_module: false });
        }
        Some(Target { module: cur, is_module: true })
    }
}

/// One import between two file modules, with the first place it is made.
#[derive(Clone, Debug)]
struct Edge {
    file: String,
    line: usize,
    /// Only tests make it.
    test: bool,
}

struct Graph {
    nodes: Vec<ModPath>,
    edges: BTreeMap<(ModPath, ModPath), Edge>,
    /// References that lead to the crate root itself (not through a re-export): a resolution
    /// the scan got wrong.
    unresolved: Vec<String>,
}

fn graph(krate: &Crate) -> Graph {
    let nodes: Vec<ModPath> =
        krate.modules.iter().filter(|(p, m)| **p == m.file_module).map(|(p, _)| p.clone()).collect();
    let mut edges: BTreeMap<(ModPath, ModPath), Edge> = BTreeMap::new();
    let mut unresolved = Vec::new();
    for r in &krate.references {
        let Some(t) = krate.resolve(&r.from, &r.segments, 0) else { continue };
        let from = &krate.modules[&r.from];
        let to = krate.modules[&t.module].file_module.clone();
        // The crate root defines no items but the exported macros: a path that ends there is
        // one the scan misread.
        let root_item = r.segments.last().is_some_and(|s| krate.modules[&Vec::new()].items.contains(s));
        if to.is_empty() && !(t.is_module && r.segments.len() == 1) && !root_item {
            unresolved.push(format!("{}:{}: {}", r.file, r.line, r.segments.join("::")));
            continue;
        }
        if to == from.file_module || to.is_empty() || (r.reexport && to.starts_with(&from.file_module)) {
            continue;
        }
        let edge = Edge { file: r.file.clone(), line: r.line, test: from.test || r.test };
        edges
            .entry((from.file_module.clone(), to))
            .and_modify(|e| {
                if e.test && !edge.test {
                    *e = edge.clone();
                }
            })
            .or_insert(edge);
    }
    Graph { nodes, edges, unresolved }
}

/// Tarjan's strongly connected components of the graph of the edges `keep` admits: the import
/// circles (components of more than one module), each sorted, in order.
fn circles(g: &Graph, keep: impl Fn(&Edge) -> bool) -> Vec<Vec<ModPath>> {
    struct Tarjan {
        adj: Vec<Vec<usize>>,
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    impl Tarjan {
        fn visit(&mut self, v: usize) {
            self.index[v] = Some(self.next);
            self.low[v] = self.next;
            self.next += 1;
            self.stack.push(v);
            self.on_stack[v] = true;
            for w in self.adj[v].clone() {
                match self.index[w] {
                    None => {
                        self.visit(w);
                        self.low[v] = self.low[v].min(self.low[w]);
                    }
                    Some(iw) if self.on_stack[w] => self.low[v] = self.low[v].min(iw),
                    Some(_) => {}
                }
            }
            if Some(self.low[v]) == self.index[v] {
                let mut scc = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack[w] = false;
                    scc.push(w);
                    if w == v {
                        break;
                    }
                }
                self.out.push(scc);
            }
        }
    }
    let id: BTreeMap<&ModPath, usize> = g.nodes.iter().enumerate().map(|(k, p)| (p, k)).collect();
    let mut adj = vec![Vec::new(); g.nodes.len()];
    for ((a, b), e) in &g.edges {
        if keep(e)
            && let (Some(&x), Some(&y)) = (id.get(a), id.get(b))
        {
            adj[x].push(y);
        }
    }
    let n = g.nodes.len();
    let mut t = Tarjan {
        adj,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            t.visit(v);
        }
    }
    let mut out: Vec<Vec<ModPath>> = t
        .out
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| {
            let mut m: Vec<ModPath> = c.into_iter().map(|k| g.nodes[k].clone()).collect();
            m.sort();
            m
        })
        .collect();
    out.sort();
    out
}

/// A module's path as written in Rust (`crate` for the root).
pub fn name(p: &ModPath) -> String {
    if p.is_empty() { "crate".into() } else { p.join("::") }
}

fn under(p: &ModPath, top: &str) -> bool {
    p.first().is_some_and(|f| f == top)
}

/// A bottom layer: the modules under `top` import nothing from above them, that is nothing but
/// themselves and the leaves `may_use` (and everything below those), which import only each
/// other.
pub struct BottomLayer<'a> {
    /// The top-level module of the layer (`solvers`).
    pub top: &'a str,
    /// The top-level modules it may use besides itself.
    pub may_use: &'a [&'a str],
}

/// What a source tree is checked against besides the circles and the mounting of its modules.
pub struct Rules<'a> {
    /// Its bottom layer, if it has one (the runtime's solvers); without one, no module is
    /// checked for importing from above it.
    pub bottom: Option<BottomLayer<'a>>,
    /// Modules of the crate root's `use` declarations that may name a module, with why each
    /// stays.
    pub module_aliases_allowed: &'a [(&'a str, &'a str)],
}

/// What is wrong with the layering of the sources in `src`, and the circles, printed.
pub struct Findings {
    /// The import circles (test-only imports left out), each sorted.
    pub circles: Vec<Vec<ModPath>>,
    /// Every rule broken, one line each.
    pub problems: Vec<String>,
    /// The summary and the circles with the lines that close them, to print.
    pub text: String,
    graph: Graph,
}

impl Findings {
    /// Whether a module whose path starts with `from` imports one whose path starts with `to`
    /// (`"kin"`, `"solvers::"`): a test that the scan read what it should.
    pub fn imports(&self, from: &str, to: &str) -> bool {
        self.graph.edges.keys().any(|(x, y)| name(x).starts_with(from) && name(y).starts_with(to))
    }
}

/// Checks the sources in `src` against `rules`.
pub fn check(src: &Path, rules: &Rules) -> Findings {
    let krate = Crate::read(src);
    let g = graph(&krate);
    let circles = circles(&g, |e| !e.test);
    let mut text = String::new();
    let mut problems = Vec::new();
    writeln!(text, "{} file modules, {} imports between them, in {}", g.nodes.len(), g.edges.len(), src.display())
        .unwrap();
    writeln!(text, "{} import circle(s) (test-only imports left out):", circles.len()).unwrap();
    for (k, c) in circles.iter().enumerate() {
        let names: Vec<String> = c.iter().map(name).collect();
        writeln!(text, "circle {}: {} modules: {}", k + 1, c.len(), names.join(", ")).unwrap();
        for ((a, b), e) in &g.edges {
            if !e.test && c.contains(a) && c.contains(b) {
                writeln!(text, "    {} -> {}  ({}:{})", name(a), name(b), e.file, e.line).unwrap();
            }
        }
    }
    // (a) The bottom layer (the solvers) uses only itself and the allowed leaves, which use only
    // each other.
    let in_bottom = |p: &ModPath| rules.bottom.as_ref().is_some_and(|l| under(p, l.top));
    if let Some(layer) = &rules.bottom {
        let allowed = |p: &ModPath| layer.may_use.iter().any(|m| under(p, m));
        for ((a, b), e) in &g.edges {
            let bad = (in_bottom(a) && !in_bottom(b) && !allowed(b)) || (allowed(a) && !allowed(b));
            if bad {
                problems.push(format!(
                    "{} imports {} ({}:{}{}), above the {}' layer",
                    name(a),
                    name(b),
                    e.file,
                    e.line,
                    if e.test { ", in its tests" } else { "" },
                    layer.top
                ));
            }
        }
        // (b) No circle runs through the bottom layer.
        for c in &circles {
            if c.iter().any(in_bottom) {
                let names: Vec<String> = c.iter().map(name).collect();
                problems.push(format!("an import circle runs through the {}: {}", layer.top, names.join(", ")));
            }
        }
    }
    // (c) Nor any other circle: a module that needs another's item and is needed by it holds
    // the wrong half of something (a type beside the functions of a layer above it, a method
    // beside the wrong module's data); the cure is to move that half, not to accept the loop.
    for c in &circles {
        if !c.iter().any(in_bottom) {
            let names: Vec<String> = c.iter().map(name).collect();
            problems.push(format!("an import circle: {}", names.join(", ")));
        }
    }
    // (d) Every module is mounted where its file is.
    for (file, line) in &krate.path_attributes {
        problems.push(format!("{file}:{line}: a module mounted by `#[path]`"));
    }
    for file in &krate.unreached {
        problems.push(format!("{file}: no `mod` declaration reaches it"));
    }
    // (e) One path per module: a module with children imports no module (which its descendants
    // could then name through it, `crate::newton` beside `crate::solvers::newton`).
    for (p, m) in &krate.modules {
        let file_children = m.children.iter().any(|c| {
            let mut child = p.clone();
            child.push(c.clone());
            krate.modules.get(&child).is_some_and(|cm| cm.file_module == child)
        });
        if !file_children || m.file_module != *p {
            continue;
        }
        for (alias, target) in &m.uses {
            let Some(t) = krate.resolve(p, target, 0) else { continue };
            let allowed = p.is_empty() && rules.module_aliases_allowed.iter().any(|(a, _)| a == alias);
            if t.is_module && !allowed && alias != "_" {
                problems.push(format!(
                    "{}: `use` of module {} as {}::{alias}: a second path to it",
                    m.file,
                    name(&t.module),
                    name(p)
                ));
            }
        }
    }
    for u in &g.unresolved {
        problems.push(format!("{u}: not resolved to a module (the scan misreads it)"));
    }
    Findings { circles, problems, text, graph: g }
}
