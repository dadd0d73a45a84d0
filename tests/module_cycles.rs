//! No module cycles at any level: within every crate of the workspace, the
//! modules that share a parent must form an acyclic graph, where `a -> b` means
//! some non-test code in `a` (or below it) names an item of `b` (or below it)
//! through a `crate::`, `super::` or `self::` path. Cycles between sibling
//! modules make a folder impossible to read bottom-up and to split into crates,
//! so the project forbids them; this test finds them from the source text
//! alone (std only, no build of the workspace) and prints, per cycle, one
//! reference for each of its edges.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------- lexing ---

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    Sep,
    Punct(char),
    Str(String),
    /// Numbers, chars, lifetimes: nothing this checker reads.
    Other,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    line: usize,
}

fn ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

fn ident_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

fn at(c: &[char], i: usize) -> char {
    c.get(i).copied().unwrap_or('\0')
}

/// Splits Rust source into tokens, dropping comments (doc comments included)
/// and keeping string literals as single `Str` tokens.
fn lex(src: &str) -> Vec<Token> {
    let c: Vec<char> = src.chars().collect();
    let (mut i, mut line, mut out) = (0, 1, Vec::new());
    while i < c.len() {
        let start = i;
        let tok = match (c[i], at(&c, i + 1)) {
            (ch, _) if ch.is_whitespace() => {
                i += 1;
                None
            }
            ('/', '/') => {
                while i < c.len() && c[i] != '\n' {
                    i += 1;
                }
                None
            }
            ('/', '*') => {
                i = skip_block_comment(&c, i);
                None
            }
            (':', ':') => {
                i += 2;
                Some(Tok::Sep)
            }
            _ => Some(lex_one(&c, &mut i)),
        };
        if let Some(tok) = tok {
            out.push(Token { tok, line });
        }
        line += c[start..i].iter().filter(|&&ch| ch == '\n').count();
    }
    out
}

fn lex_one(c: &[char], i: &mut usize) -> Tok {
    if let Some((text, end)) = string_literal(c, *i) {
        *i = end;
        return Tok::Str(text);
    }
    let ch = c[*i];
    if ch == '\'' || (ch == 'b' && at(c, *i + 1) == '\'') {
        *i = skip_char_or_lifetime(c, if ch == 'b' { *i + 1 } else { *i });
        return Tok::Other;
    }
    if ident_start(ch) {
        if ch == 'r' && at(c, *i + 1) == '#' && ident_start(at(c, *i + 2)) {
            *i += 2; // raw identifier r#name
        }
        let s = *i;
        while *i < c.len() && ident_char(c[*i]) {
            *i += 1;
        }
        return Tok::Ident(c[s..*i].iter().collect());
    }
    if ch.is_ascii_digit() {
        while *i < c.len()
            && (ident_char(c[*i]) || (c[*i] == '.' && at(c, *i + 1).is_ascii_digit()))
        {
            *i += 1;
        }
        return Tok::Other;
    }
    *i += 1;
    Tok::Punct(ch)
}

/// Index just past a (nested) block comment starting at `i`.
fn skip_block_comment(c: &[char], mut i: usize) -> usize {
    let mut depth = 0;
    while i < c.len() {
        match (c[i], at(c, i + 1)) {
            ('/', '*') => {
                depth += 1;
                i += 2;
            }
            ('*', '/') => {
                depth -= 1;
                i += 2;
                if depth == 0 {
                    return i;
                }
            }
            _ => i += 1,
        }
    }
    i
}

/// A string literal (`"…"`, `b"…"`, `c"…"`, `r#"…"#`, `br"…"`, …) at `i`:
/// its raw contents and the index just past it.
fn string_literal(c: &[char], i: usize) -> Option<(String, usize)> {
    let mut p = i;
    if matches!(at(c, p), 'b' | 'c') {
        p += 1;
    }
    let raw = at(c, p) == 'r';
    if raw {
        p += 1;
    }
    let hashes = c[p.min(c.len())..]
        .iter()
        .take_while(|&&h| h == '#')
        .count();
    if at(c, p + hashes) != '"' || (!raw && hashes > 0) {
        return None;
    }
    let body = p + hashes + 1;
    let mut j = body;
    while j < c.len() {
        if !raw && c[j] == '\\' {
            j += 2;
            continue;
        }
        if c[j] == '"' && (0..hashes).all(|k| at(c, j + 1 + k) == '#') {
            return Some((c[body..j].iter().collect(), j + 1 + hashes));
        }
        j += 1;
    }
    Some((c[body.min(c.len())..].iter().collect(), c.len()))
}

/// Index just past a char literal or a lifetime starting at the quote `i`.
fn skip_char_or_lifetime(c: &[char], i: usize) -> usize {
    if at(c, i + 1) == '\\' {
        let mut j = i + 3;
        while j < c.len() && c[j] != '\'' && c[j] != '\n' {
            j += 1;
        }
        return j + 1;
    }
    if at(c, i + 2) == '\'' {
        return i + 3;
    }
    let mut j = i + 1;
    while j < c.len() && ident_char(c[j]) {
        j += 1;
    }
    j.max(i + 1)
}

// --------------------------------------------------------------- scanning ---

fn is_ident(t: &[Token], i: usize, word: &str) -> bool {
    matches!(t.get(i), Some(Token { tok: Tok::Ident(w), .. }) if w == word)
}

fn is_punct(t: &[Token], i: usize, ch: char) -> bool {
    matches!(t.get(i), Some(Token { tok: Tok::Punct(p), .. }) if *p == ch)
}

fn is_sep(t: &[Token], i: usize) -> bool {
    matches!(t.get(i), Some(Token { tok: Tok::Sep, .. }))
}

fn ident_at(t: &[Token], i: usize) -> Option<&str> {
    match t.get(i) {
        Some(Token {
            tok: Tok::Ident(w), ..
        }) => Some(w),
        _ => None,
    }
}

/// A path found in the source: `crate::a::B`, or one leaf of a `use` tree.
#[derive(Clone, Debug)]
struct Ref {
    segs: Vec<String>,
    line: usize,
    alias: Option<String>,
    glob: bool,
}

impl Ref {
    /// The name this leaf brings into scope, when it is a `use` leaf.
    fn name(&self) -> Option<&str> {
        match &self.alias {
            Some(a) if a == "_" => None,
            Some(a) => Some(a),
            None => self.segs.last().map(String::as_str),
        }
    }
}

/// A `mod name;` (or inline `mod name { … }`) declaration.
#[derive(Debug)]
struct ModDecl {
    name: String,
    line: usize,
    path_attr: Option<String>,
    inline: Option<Vec<Token>>,
}

/// What one module body holds, test code excluded.
#[derive(Debug, Default)]
struct Body {
    /// The body has `#![cfg(test)]`: the whole module is test code.
    test: bool,
    mods: Vec<ModDecl>,
    /// `crate::`/`super::`/`self::` paths anywhere in the body.
    refs: Vec<Ref>,
    /// The module-level `use` leaves (any path form), for name resolution.
    imports: Vec<Ref>,
    /// Names of the items the module declares at its top level.
    items: BTreeSet<String>,
}

#[derive(Default)]
struct Attrs {
    test: bool,
    path: Option<String>,
}

/// Scans one module body (a whole file, or the inside of an inline module).
fn scan(t: &[Token]) -> Body {
    let (mut body, mut attrs, mut depth, mut i) = (Body::default(), Attrs::default(), 0usize, 0);
    while i < t.len() {
        if is_punct(t, i, '#') {
            if let Some((inner, test, path, next)) = parse_attr(t, i) {
                if inner && test && depth == 0 {
                    body.test = true;
                    return body;
                }
                attrs.test |= test && !inner;
                attrs.path = path.or(attrs.path.take());
                i = next;
                continue;
            }
        }
        if attrs.test {
            i = skip_item(t, i);
            attrs = Attrs::default();
            continue;
        }
        i = scan_token(t, i, &mut body, &mut attrs, &mut depth);
    }
    body
}

/// Handles the token at `i`; returns the index to continue from.
fn scan_token(
    t: &[Token],
    i: usize,
    body: &mut Body,
    attrs: &mut Attrs,
    depth: &mut usize,
) -> usize {
    match &t[i].tok {
        Tok::Punct('{') => *depth += 1,
        Tok::Punct('}') => *depth = depth.saturating_sub(1),
        Tok::Ident(w) if w == "mod" && *depth == 0 => {
            if let Some((decl, next)) = parse_mod(t, i, attrs.path.take()) {
                body.mods.push(decl);
                *attrs = Attrs::default();
                return next;
            }
        }
        Tok::Ident(w) if w == "use" => {
            let (leaves, next) = parse_use(t, i + 1);
            for leaf in leaves {
                if is_anchor(&leaf.segs) {
                    body.refs.push(leaf.clone());
                }
                if *depth == 0 {
                    body.imports.push(leaf);
                }
            }
            *attrs = Attrs::default();
            return next;
        }
        Tok::Ident(w) if is_anchor_word(w) && is_sep(t, i + 1) && !is_sep(t, i.wrapping_sub(1)) => {
            let (r, next) = parse_expr_path(t, i);
            body.refs.push(r);
            return next;
        }
        Tok::Ident(w) if *depth == 0 && ITEM_KEYWORDS.contains(&w.as_str()) => {
            if let Some(name) = ident_at(t, i + 1 + is_punct(t, i + 1, '!') as usize) {
                body.items.insert(name.to_string());
            }
        }
        _ => {}
    }
    if matches!(t[i].tok, Tok::Punct(';' | '{' | '}')) {
        *attrs = Attrs::default();
    }
    i + 1
}

const ITEM_KEYWORDS: &[&str] = &[
    "fn",
    "struct",
    "enum",
    "trait",
    "type",
    "const",
    "static",
    "union",
    "macro_rules",
];

fn is_anchor_word(w: &str) -> bool {
    matches!(w, "crate" | "super" | "self")
}

fn is_anchor(segs: &[String]) -> bool {
    segs.first().is_some_and(|s| is_anchor_word(s))
}

/// An attribute `#[…]` or `#![…]` at `i`: (inner, is cfg(test), #[path] value, next index).
fn parse_attr(t: &[Token], i: usize) -> Option<(bool, bool, Option<String>, usize)> {
    let inner = is_punct(t, i + 1, '!');
    let open = i + 1 + inner as usize;
    if !is_punct(t, open, '[') {
        return None;
    }
    let close = matching(t, open, '[', ']');
    let content = &t[open + 1..close.min(t.len())];
    let path = match content {
        [Token {
            tok: Tok::Ident(p), ..
        }, Token {
            tok: Tok::Punct('='),
            ..
        }, Token {
            tok: Tok::Str(s), ..
        }] if p == "path" => Some(s.clone()),
        _ => None,
    };
    Some((inner, is_cfg_test(content), path, close + 1))
}

/// `cfg(test)` or `cfg(all(…, test, …))`.
fn is_cfg_test(content: &[Token]) -> bool {
    let text: String = content
        .iter()
        .map(|t| match &t.tok {
            Tok::Ident(w) => w.clone(),
            Tok::Punct(p) => p.to_string(),
            Tok::Sep => "::".into(),
            Tok::Str(s) => format!("{s:?}"),
            Tok::Other => "?".into(),
        })
        .collect();
    if text == "cfg(test)" {
        return true;
    }
    match text
        .strip_prefix("cfg(all(")
        .and_then(|r| r.strip_suffix("))"))
    {
        Some(args) => top_level_split(args).contains(&"test"),
        None => false,
    }
}

fn top_level_split(s: &str) -> Vec<&str> {
    let (mut parts, mut depth, mut from) = (Vec::new(), 0i32, 0);
    for (k, ch) in s.char_indices() {
        match ch {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&s[from..k]);
                from = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&s[from..]);
    parts
}

/// Index of the token closing the bracket opened at `open` (or `t.len()`).
fn matching(t: &[Token], open: usize, o: char, c: char) -> usize {
    let mut depth = 0;
    for (k, tok) in t.iter().enumerate().skip(open) {
        match tok.tok {
            Tok::Punct(p) if p == o => depth += 1,
            Tok::Punct(p) if p == c => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// Skips the item (or field, arm, statement) starting at `i`; returns the next index.
fn skip_item(t: &[Token], mut i: usize) -> usize {
    let item = ident_at(t, skip_visibility(t, i)).is_some_and(|w| {
        ITEM_KEYWORDS.contains(&w)
            || matches!(
                w,
                "mod" | "use" | "impl" | "extern" | "unsafe" | "async" | "let"
            )
    });
    let mut depth = 0i32;
    while i < t.len() {
        match t[i].tok {
            Tok::Punct('(' | '[') => depth += 1,
            Tok::Punct(')' | ']') => depth -= 1,
            Tok::Punct('{') => {
                i = matching(t, i, '{', '}') + 1;
                if depth == 0 {
                    return i + is_punct(t, i, ';') as usize;
                }
                continue;
            }
            Tok::Punct('}') if depth <= 0 => return i,
            Tok::Punct(';') if depth <= 0 => return i + 1,
            Tok::Punct(',') if depth <= 0 && !item => return i + 1,
            _ => {}
        }
        i += 1;
    }
    i
}

/// The index just past a `pub`, `pub(crate)`, `pub(in …)` at `i` (or `i`).
fn skip_visibility(t: &[Token], i: usize) -> usize {
    match (is_ident(t, i, "pub"), is_punct(t, i + 1, '(')) {
        (true, true) => matching(t, i + 1, '(', ')') + 1,
        (true, false) => i + 1,
        _ => i,
    }
}

/// `mod name;` or `mod name { … }` at `i` (the `mod` keyword).
fn parse_mod(t: &[Token], i: usize, path_attr: Option<String>) -> Option<(ModDecl, usize)> {
    let name = ident_at(t, i + 1)?.to_string();
    let line = t[i].line;
    if is_punct(t, i + 2, ';') {
        return Some((
            ModDecl {
                name,
                line,
                path_attr,
                inline: None,
            },
            i + 3,
        ));
    }
    if !is_punct(t, i + 2, '{') {
        return None;
    }
    let close = matching(t, i + 2, '{', '}');
    let inner = t[i + 3..close.min(t.len())].to_vec();
    Some((
        ModDecl {
            name,
            line,
            path_attr,
            inline: Some(inner),
        },
        close + 1,
    ))
}

/// The leaves of the `use` tree starting at `i` (just after `use`), and the index past its `;`.
fn parse_use(t: &[Token], i: usize) -> (Vec<Ref>, usize) {
    let mut end = i;
    let mut depth = 0i32;
    while end < t.len() && !(depth == 0 && is_punct(t, end, ';')) {
        depth += is_punct(t, end, '{') as i32 - is_punct(t, end, '}') as i32;
        if depth < 0 {
            break;
        }
        end += 1;
    }
    let mut out = Vec::new();
    let mut j = i;
    use_tree(&t[..end], &mut j, Vec::new(), &mut out);
    (out, end + 1)
}

fn use_tree(t: &[Token], j: &mut usize, prefix: Vec<String>, out: &mut Vec<Ref>) {
    let mut segs = prefix;
    if is_sep(t, *j) {
        segs.push("::".into()); // `use ::ext::…`: an extern path, never resolved
        *j += 1;
    }
    while *j < t.len() {
        let line = t[*j].line;
        match &t[*j].tok {
            Tok::Punct('{') => return use_group(t, j, segs, out),
            Tok::Punct('*') => {
                *j += 1;
                return out.push(Ref {
                    segs,
                    line,
                    alias: None,
                    glob: true,
                });
            }
            Tok::Ident(w) => {
                *j += 1;
                if !(w == "self" && !segs.is_empty() && !is_sep(t, *j)) {
                    segs.push(w.clone());
                }
                if is_sep(t, *j) {
                    *j += 1;
                    continue;
                }
                let alias =
                    is_ident(t, *j, "as").then(|| ident_at(t, *j + 1).unwrap_or("_").to_string());
                *j += 2 * alias.is_some() as usize;
                return out.push(Ref {
                    segs,
                    line,
                    alias,
                    glob: false,
                });
            }
            _ => {
                *j += 1;
                return;
            }
        }
    }
}

fn use_group(t: &[Token], j: &mut usize, segs: Vec<String>, out: &mut Vec<Ref>) {
    *j += 1;
    while *j < t.len() && !is_punct(t, *j, '}') {
        if is_punct(t, *j, ',') {
            *j += 1;
            continue;
        }
        use_tree(t, j, segs.clone(), out);
    }
    *j += 1;
}

/// `crate::a::b`, `super::super::x`, `self::m::f` in an expression or type.
fn parse_expr_path(t: &[Token], mut i: usize) -> (Ref, usize) {
    let line = t[i].line;
    let mut segs = Vec::new();
    while let Some(w) = ident_at(t, i) {
        segs.push(w.to_string());
        i += 1;
        if !(is_sep(t, i) && ident_at(t, i + 1).is_some()) {
            break;
        }
        i += 1;
    }
    (
        Ref {
            segs,
            line,
            alias: None,
            glob: false,
        },
        i,
    )
}

// ------------------------------------------------------------ module tree ---

#[derive(Debug)]
struct Module {
    /// Path below the crate root (empty for the root).
    path: Vec<String>,
    file: PathBuf,
    /// Where `mod x;` declared here looks for `x.rs` / `x/mod.rs`.
    child_dir: PathBuf,
    inline: bool,
    children: BTreeMap<String, usize>,
    body: Body,
}

#[derive(Debug, Default)]
struct Tree {
    mods: Vec<Module>,
    errors: Vec<String>,
}

type Reader<'a> = &'a dyn Fn(&Path) -> Option<String>;

/// The module tree below the crate root file `root`, test modules excluded.
fn build_tree(root: &Path, read: Reader) -> Tree {
    let mut tree = Tree::default();
    match read(root) {
        Some(src) => {
            let dir = root.parent().unwrap_or(Path::new("")).to_path_buf();
            let m = Module {
                path: vec![],
                file: root.into(),
                child_dir: dir,
                inline: false,
                children: BTreeMap::new(),
                body: Body::default(),
            };
            add_module(&mut tree, None, m, &lex(&src), read);
        }
        None => tree
            .errors
            .push(format!("cannot read crate root {}", root.display())),
    }
    tree
}

fn add_module(tree: &mut Tree, parent: Option<usize>, mut m: Module, toks: &[Token], read: Reader) {
    m.body = scan(toks);
    if m.body.test {
        return;
    }
    let decls = std::mem::take(&mut m.body.mods);
    let id = tree.mods.len();
    if let Some(p) = parent {
        tree.mods[p]
            .children
            .insert(m.path.last().cloned().unwrap_or_default(), id);
    }
    tree.mods.push(m);
    for decl in decls {
        add_child(tree, id, decl, read);
    }
}

fn add_child(tree: &mut Tree, id: usize, decl: ModDecl, read: Reader) {
    let parent = &tree.mods[id];
    let mut path = parent.path.clone();
    path.push(decl.name.clone());
    let (file, child_dir) = (parent.file.clone(), parent.child_dir.join(&decl.name));
    if let Some(toks) = decl.inline {
        let m = Module {
            path,
            file,
            child_dir,
            inline: true,
            children: BTreeMap::new(),
            body: Body::default(),
        };
        return add_module(tree, Some(id), m, &toks, read);
    }
    let base = if parent.inline {
        parent.child_dir.clone()
    } else {
        file.parent().unwrap_or(Path::new("")).to_path_buf()
    };
    let candidates = match &decl.path_attr {
        Some(p) => vec![base.join(p)],
        None => vec![
            parent.child_dir.join(format!("{}.rs", decl.name)),
            parent.child_dir.join(&decl.name).join("mod.rs"),
        ],
    };
    let found = candidates
        .iter()
        .find_map(|c| read(c).map(|src| (c.clone(), src)));
    let Some((cfile, src)) = found else {
        let tried: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
        let at = format!("{}:{}", file.display(), decl.line);
        return tree.errors.push(format!(
            "{at}: cannot read module `{}` (tried {})",
            decl.name,
            tried.join(", ")
        ));
    };
    let child_dir = child_dir_of(&cfile, decl.path_attr.is_some());
    let m = Module {
        path,
        file: cfile,
        child_dir,
        inline: false,
        children: BTreeMap::new(),
        body: Body::default(),
    };
    add_module(tree, Some(id), m, &lex(&src), read);
}

/// `dir/` for `dir/mod.rs` (and `#[path]` files), `dir/stem/` for `dir/stem.rs`.
fn child_dir_of(file: &Path, by_path_attr: bool) -> PathBuf {
    let dir = file.parent().unwrap_or(Path::new("")).to_path_buf();
    match file.file_stem().and_then(|s| s.to_str()) {
        Some("mod") | None => dir,
        Some(_) if by_path_attr => dir,
        Some(stem) => dir.join(stem),
    }
}

// ------------------------------------------------------------- resolution ---

/// The crate-relative path a path written in module `m` stands for.
fn absolutize(tree: &Tree, m: usize, segs: &[String]) -> Option<Vec<String>> {
    let module = &tree.mods[m];
    let first = segs.first()?;
    let (mut cur, mut k) = match first.as_str() {
        "crate" => (vec![], 1),
        "self" | "super" => (module.path.clone(), 0),
        _ if module.children.contains_key(first) => (module.path.clone(), 0),
        _ => return None,
    };
    while k < segs.len() && (segs[k] == "self" || segs[k] == "super") {
        if segs[k] == "super" {
            cur.pop()?;
        }
        k += 1;
    }
    cur.extend(segs[k..].iter().cloned());
    Some(cur)
}

/// The deepest module whose path is a prefix of `abs`, and how many segments it used.
fn deepest(tree: &Tree, abs: &[String]) -> (usize, usize) {
    let (mut cur, mut used) = (0, 0);
    while let Some(&c) = abs.get(used).and_then(|s| tree.mods[cur].children.get(s)) {
        cur = c;
        used += 1;
    }
    (cur, used)
}

/// Resolves a path written in module `from` to a module, following the
/// module-level imports (re-exports included) of the modules it passes.
fn resolve(tree: &Tree, from: usize, segs: &[String]) -> Option<usize> {
    let mut abs = absolutize(tree, from, segs)?;
    for _ in 0..16 {
        let (m, used) = deepest(tree, &abs);
        let next = abs.get(used).and_then(|name| import_target(tree, m, name));
        match next {
            Some(mut target) if target != abs => {
                target.extend(abs[used + 1..].iter().cloned());
                abs = target;
            }
            _ => return Some(m),
        }
    }
    Some(deepest(tree, &abs).0)
}

/// The crate-relative path of what `name` is imported from in module `m`.
fn import_target(tree: &Tree, m: usize, name: &str) -> Option<Vec<String>> {
    let module = &tree.mods[m];
    if module.body.items.contains(name) {
        return None;
    }
    let imports = &module.body.imports;
    if let Some(leaf) = imports.iter().find(|l| !l.glob && l.name() == Some(name)) {
        return absolutize(tree, m, &leaf.segs);
    }
    imports.iter().filter(|l| l.glob).find_map(|l| {
        let g = absolutize(tree, m, &l.segs)?;
        let (gm, used) = deepest(tree, &g);
        let inner = &tree.mods[gm];
        let has = inner.body.items.contains(name)
            || inner.children.contains_key(name)
            || inner
                .body
                .imports
                .iter()
                .any(|i| !i.glob && i.name() == Some(name));
        (used == g.len() && gm != m && has).then(|| [g, vec![name.to_string()]].concat())
    })
}

// ------------------------------------------------------------------ graph ---

/// One reference that creates an edge: `file:line: path`.
#[derive(Clone, Debug)]
struct Example {
    file: PathBuf,
    line: usize,
    path: String,
}

/// Sibling edges per parent module: parent path -> (from child, to child) -> example.
type SiblingGraphs = BTreeMap<Vec<String>, BTreeMap<(String, String), Example>>;

fn sibling_graphs(tree: &Tree) -> SiblingGraphs {
    let mut graphs = SiblingGraphs::new();
    for (a, module) in tree.mods.iter().enumerate() {
        for r in &module.body.refs {
            let Some(b) = resolve(tree, a, &r.segs) else {
                continue;
            };
            let (pa, pb) = (&module.path, &tree.mods[b].path);
            let k = pa.iter().zip(pb).take_while(|(x, y)| x == y).count();
            if k == pa.len() || k == pb.len() {
                continue; // self, ancestor or descendant
            }
            let example = Example {
                file: module.file.clone(),
                line: r.line,
                path: r.segs.join("::"),
            };
            let edges = graphs.entry(pa[..k].to_vec()).or_default();
            edges
                .entry((pa[k].clone(), pb[k].clone()))
                .or_insert(example);
        }
    }
    graphs
}

/// Strongly connected components of more than one node (Tarjan).
fn cyclic_components(edges: &BTreeMap<(String, String), Example>) -> Vec<Vec<String>> {
    let mut adj: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        adj.entry(a).or_default().push(b);
        adj.entry(b).or_default();
    }
    let mut st = Tarjan {
        adj: &adj,
        index: HashMap::new(),
        low: HashMap::new(),
        stack: vec![],
        on: BTreeSet::new(),
        out: vec![],
    };
    for &v in adj.keys() {
        if !st.index.contains_key(v) {
            st.visit(v);
        }
    }
    st.out
}

struct Tarjan<'a> {
    adj: &'a BTreeMap<&'a str, Vec<&'a str>>,
    index: HashMap<&'a str, usize>,
    low: HashMap<&'a str, usize>,
    stack: Vec<&'a str>,
    on: BTreeSet<&'a str>,
    out: Vec<Vec<String>>,
}

impl<'a> Tarjan<'a> {
    fn visit(&mut self, v: &'a str) {
        let n = self.index.len();
        self.index.insert(v, n);
        self.low.insert(v, n);
        self.stack.push(v);
        self.on.insert(v);
        let adj = self.adj;
        for &w in &adj[v] {
            if !self.index.contains_key(w) {
                self.visit(w);
                let lw = self.low[w];
                self.low.entry(v).and_modify(|l| *l = (*l).min(lw));
            } else if self.on.contains(w) {
                let iw = self.index[w];
                self.low.entry(v).and_modify(|l| *l = (*l).min(iw));
            }
        }
        if self.low[v] == self.index[v] {
            self.pop_component(v);
        }
    }

    fn pop_component(&mut self, v: &str) {
        let mut comp = Vec::new();
        while let Some(w) = self.stack.pop() {
            self.on.remove(w);
            comp.push(w.to_string());
            if w == v {
                break;
            }
        }
        if comp.len() > 1 {
            comp.sort();
            self.out.push(comp);
        }
    }
}

/// A shortest cycle through `start` inside the component `comp` (BFS).
fn shortest_cycle(
    edges: &BTreeMap<(String, String), Example>,
    comp: &[String],
    start: &str,
) -> Vec<String> {
    let inside = |s: &str| comp.iter().any(|c| c == s);
    let mut prev: BTreeMap<String, String> = BTreeMap::new();
    let mut queue = std::collections::VecDeque::from([start.to_string()]);
    while let Some(v) = queue.pop_front() {
        for (_, w) in edges.keys().filter(|(a, b)| *a == v && inside(b)) {
            if w == start {
                let mut cycle = vec![v.clone()];
                while let Some(p) = prev.get(cycle.last().unwrap_or(&v)) {
                    cycle.push(p.clone());
                }
                cycle.reverse();
                return cycle;
            }
            if !prev.contains_key(w) && w != start {
                prev.insert(w.clone(), v.clone());
                queue.push_back(w.clone());
            }
        }
    }
    vec![start.to_string()]
}

/// The report of every sibling cycle of one crate tree.
fn cycle_reports(label: &str, tree: &Tree) -> Vec<String> {
    let mut reports = Vec::new();
    for (parent, edges) in sibling_graphs(tree) {
        for comp in cyclic_components(&edges) {
            reports.push(describe(label, &parent, &edges, &comp));
        }
    }
    reports
}

fn describe(
    label: &str,
    parent: &[String],
    edges: &BTreeMap<(String, String), Example>,
    comp: &[String],
) -> String {
    let owner = if parent.is_empty() {
        "crate".to_string()
    } else {
        format!("crate::{}", parent.join("::"))
    };
    let mut text = format!(
        "{label}: in `{owner}`, cycle among {{{}}}\n",
        comp.join(", ")
    );
    let mut covered = BTreeSet::new();
    for member in comp {
        if covered.contains(member) {
            continue;
        }
        let cycle = shortest_cycle(edges, comp, member);
        text += &format!("  {} -> {}\n", cycle.join(" -> "), cycle[0]);
        for (k, a) in cycle.iter().enumerate() {
            let b = &cycle[(k + 1) % cycle.len()];
            if let Some(e) = edges.get(&(a.clone(), b.clone())) {
                text += &format!(
                    "    {a} -> {b}: {}:{}: {}\n",
                    e.file.display(),
                    e.line,
                    e.path
                );
            }
            covered.insert(a.clone());
        }
    }
    text
}

// -------------------------------------------------------------- workspace ---

/// `[section]` -> key -> raw value, from a Cargo.toml (arrays may span lines;
/// `[[bin]]` sections are numbered `bin#0`, `bin#1`, …).
fn toml_sections(text: &str) -> Vec<(String, BTreeMap<String, String>)> {
    let mut sections: Vec<(String, BTreeMap<String, String>)> =
        vec![(String::new(), BTreeMap::new())];
    let mut pending: Option<(String, String)> = None;
    for raw in text.lines() {
        let line = strip_toml_comment(raw).trim();
        if let Some((key, mut value)) = pending.take() {
            value.push_str(line);
            match value.contains(']') {
                true => insert_last(&mut sections, key, value),
                false => pending = Some((key, value)),
            }
        } else if line.starts_with('[') {
            let name = line
                .trim_matches(|c| c == '[' || c == ']')
                .trim()
                .to_string();
            sections.push((name, BTreeMap::new()));
        } else if let Some((k, v)) = line.split_once('=') {
            let (key, value) = (k.trim().to_string(), v.trim().to_string());
            match value.starts_with('[') && !value.contains(']') {
                true => pending = Some((key, value)),
                false => insert_last(&mut sections, key, value),
            }
        }
    }
    sections
}

fn insert_last(sections: &mut [(String, BTreeMap<String, String>)], key: String, value: String) {
    if let Some(last) = sections.last_mut() {
        last.1.insert(key, value);
    }
}

fn strip_toml_comment(line: &str) -> &str {
    let mut in_str = false;
    for (k, ch) in line.char_indices() {
        match ch {
            '"' => in_str = !in_str,
            '#' if !in_str => return &line[..k],
            _ => {}
        }
    }
    line
}

fn quoted(value: &str) -> Vec<String> {
    value
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

fn section_value(
    sections: &[(String, BTreeMap<String, String>)],
    name: &str,
    key: &str,
) -> Option<String> {
    sections
        .iter()
        .find(|(n, _)| n == name)
        .and_then(|(_, kv)| kv.get(key))
        .and_then(|v| quoted(v).into_iter().next())
}

/// Workspace member directories (relative to the root), `fuzz` skipped; the
/// root package itself when the root manifest has a `[package]`.
fn members(root: &Path, manifest: &str) -> Vec<PathBuf> {
    let sections = toml_sections(manifest);
    let listed = sections
        .iter()
        .find(|(n, _)| n == "workspace")
        .and_then(|(_, kv)| kv.get("members"));
    let mut dirs: Vec<PathBuf> = Vec::new();
    if sections.iter().any(|(n, _)| n == "package") {
        dirs.push(PathBuf::new());
    }
    for entry in listed.map(|v| quoted(v)).unwrap_or_default() {
        match entry.strip_suffix("/*") {
            Some(dir) => dirs.extend(glob_members(root, dir)),
            None => dirs.push(PathBuf::from(entry)),
        }
    }
    dirs.retain(|d| d.file_name().and_then(|f| f.to_str()) != Some("fuzz"));
    dirs
}

fn glob_members(root: &Path, dir: &str) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(root.join(dir))
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| e.path().join("Cargo.toml").is_file())
        .map(|e| Path::new(dir).join(e.file_name()))
        .collect();
    found.sort();
    found
}

/// (label, root file relative to the workspace root) of each crate of a member.
fn crate_roots(root: &Path, member: &Path, manifest: &str) -> Vec<(String, PathBuf)> {
    let sections = toml_sections(manifest);
    let name =
        section_value(&sections, "package", "name").unwrap_or_else(|| member.display().to_string());
    let mut roots = Vec::new();
    let lib = section_value(&sections, "lib", "path").unwrap_or_else(|| "src/lib.rs".into());
    if root.join(member).join(&lib).is_file() {
        roots.push((format!("{name} (lib)"), member.join(lib)));
    }
    if root.join(member).join("src/main.rs").is_file() {
        roots.push((format!("{name} (bin)"), member.join("src/main.rs")));
    }
    for (_, kv) in sections.iter().filter(|(n, _)| n == "bin") {
        if let Some(path) = kv.get("path").and_then(|v| quoted(v).into_iter().next()) {
            let bin = kv
                .get("name")
                .and_then(|v| quoted(v).into_iter().next())
                .unwrap_or_default();
            roots.push((format!("{name} (bin {bin})"), member.join(path)));
        }
    }
    roots
}

fn workspace_root() -> Option<PathBuf> {
    let dir = option_env!("CARGO_MANIFEST_DIR")
        .map(String::from)
        .or_else(|| std::env::var("SHROUD_ROOT").ok());
    dir.map(PathBuf::from)
}

/// Every problem found in the workspace: unreadable files, then cycles.
fn workspace_problems(root: &Path) -> (Vec<String>, Vec<String>) {
    let read = |p: &Path| std::fs::read_to_string(root.join(p)).ok();
    let (mut errors, mut cycles) = (Vec::new(), Vec::new());
    let Some(manifest) = read(Path::new("Cargo.toml")) else {
        return (
            vec![format!("cannot read {}", root.join("Cargo.toml").display())],
            cycles,
        );
    };
    for member in members(root, &manifest) {
        let Some(m) = read(&member.join("Cargo.toml")) else {
            errors.push(format!(
                "cannot read {}",
                member.join("Cargo.toml").display()
            ));
            continue;
        };
        for (label, file) in crate_roots(root, &member, &m) {
            let tree = build_tree(&file, &read);
            errors.extend(tree.errors.iter().cloned());
            cycles.extend(cycle_reports(&label, &tree));
        }
    }
    (errors, cycles)
}

#[test]
fn no_module_cycles() {
    let Some(root) = workspace_root() else {
        panic!(
            "no workspace root: neither CARGO_MANIFEST_DIR (compile time) nor SHROUD_ROOT is set"
        );
    };
    let (errors, cycles) = workspace_problems(&root);
    let mut report = String::new();
    for e in &errors {
        report += &format!("error: {e}\n");
    }
    report += &format!("{} module cycle(s)\n", cycles.len());
    for c in &cycles {
        report += &format!("\n{c}");
    }
    assert!(
        errors.is_empty() && cycles.is_empty(),
        "module cycles (the project allows none):\n{report}"
    );
}

// ------------------------------------------------- tests of the checker ---

#[cfg(test)]
mod checker {
    use super::*;

    fn tree_of(files: &[(&str, &str)]) -> Tree {
        let map: HashMap<PathBuf, String> = files
            .iter()
            .map(|(p, s)| (PathBuf::from(p), s.to_string()))
            .collect();
        let read = |p: &Path| map.get(p).cloned();
        build_tree(Path::new("src/lib.rs"), &read)
    }

    fn module(tree: &Tree, path: &str) -> usize {
        let segs: Vec<String> = path
            .split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect();
        tree.mods
            .iter()
            .position(|m| m.path == segs)
            .unwrap_or_else(|| panic!("no module {path}"))
    }

    fn edges(tree: &Tree, parent: &str) -> Vec<String> {
        let segs: Vec<String> = parent
            .split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect();
        let graphs = sibling_graphs(tree);
        graphs
            .get(&segs)
            .map(|e| e.keys().map(|(a, b)| format!("{a}->{b}")).collect())
            .unwrap_or_default()
    }

    #[test]
    fn grouped_multi_line_use_tree() {
        let (leaves, _) = parse_use(
            &lex("use crate::{a::b, c::{d, e as f},\n  g::{self, *}};"),
            1,
        );
        let got: Vec<String> = leaves
            .iter()
            .map(|l| format!("{}{}", l.segs.join("::"), if l.glob { "::*" } else { "" }))
            .collect();
        assert_eq!(
            got,
            [
                "crate::a::b",
                "crate::c::d",
                "crate::c::e",
                "crate::g",
                "crate::g::*"
            ]
        );
        assert_eq!(leaves[2].name(), Some("f"));
        assert_eq!(leaves[4].line, 2);
    }

    #[test]
    fn comments_strings_and_chars_are_not_code() {
        let src = "// crate::a\n/* crate::b /* nested */ crate::c */ let s = \"crate::d {\"; let r = r#\"crate::e\"#;\nlet c = '{'; fn f<'a>(x: &'a u8) { crate::g::h() }";
        let body = scan(&lex(src));
        let refs: Vec<String> = body
            .refs
            .iter()
            .map(|r| format!("{}@{}", r.segs.join("::"), r.line))
            .collect();
        assert_eq!(refs, ["crate::g::h@3"]);
    }

    #[test]
    fn super_through_a_re_export_reaches_the_sibling() {
        let tree = tree_of(&[
            ("src/lib.rs", "pub mod m;"),
            (
                "src/m/mod.rs",
                "mod a;\nmod b;\npub use b::{X, Y};\npub use self::c::*;\nmod c { pub fn z() {} }",
            ),
            ("src/m/a.rs", "use super::X;\nfn f() { super::z(); }"),
            ("src/m/b.rs", "pub struct X; pub struct Y;"),
        ]);
        assert!(tree.errors.is_empty(), "{:?}", tree.errors);
        let a = module(&tree, "m::a");
        assert_eq!(
            resolve(&tree, a, &["super".into(), "X".into()]),
            Some(module(&tree, "m::b"))
        );
        assert_eq!(edges(&tree, "m"), ["a->b", "a->c"]);
    }

    #[test]
    fn cfg_test_code_is_skipped() {
        let tree = tree_of(&[
            ("src/lib.rs", "mod a;\nmod b;"),
            ("src/a.rs", "#[cfg(test)]\nmod tests;\n#[cfg(test)]\n#[allow(x)]\nmod inline { fn f() { let s = \"}\"; crate::b::g(); } }\n#[cfg(test)]\nuse crate::b::{G, H};\n#[cfg(all(test, unix))]\nfn t() { crate::b::g() }\npub fn keep() {}"),
            ("src/b.rs", "pub fn g() { crate::a::keep() }"),
        ]);
        assert!(tree.errors.is_empty(), "{:?}", tree.errors); // a/tests.rs never read
        assert_eq!(edges(&tree, ""), ["b->a"]);
        assert!(cycle_reports("t", &tree).is_empty());
    }

    #[test]
    fn sibling_cycle_is_reported_with_examples() {
        let tree = tree_of(&[
            ("src/lib.rs", "mod a;\nmod b;\nmod c;"),
            ("src/a.rs", "use crate::b::B;"),
            (
                "src/b.rs",
                "pub struct B;\nfn f() -> crate::c::deep::D { todo!() }",
            ),
            ("src/c.rs", "pub mod deep;\nuse super::a;"),
            ("src/c/deep.rs", "pub struct D;"),
        ]);
        let reports = cycle_reports("t", &tree);
        assert_eq!(reports.len(), 1, "{reports:?}");
        assert!(
            reports[0].contains("cycle among {a, b, c}"),
            "{}",
            reports[0]
        );
        assert!(
            reports[0].contains("b -> c: src/b.rs:2: crate::c::deep::D"),
            "{}",
            reports[0]
        );
    }

    #[test]
    fn parent_child_edges_are_ignored_and_cousins_projected() {
        let tree = tree_of(&[
            (
                "src/lib.rs",
                "pub mod p;\npub mod q;\npub fn top() { p::x::f(); }",
            ),
            (
                "src/p/mod.rs",
                "pub mod x;\npub fn g() { self::x::f(); crate::top(); }",
            ),
            ("src/p/x.rs", "pub fn f() { super::g(); crate::q::r::h(); }"),
            ("src/q/mod.rs", "pub mod r;\nuse crate::p::g;"),
            ("src/q/r.rs", "pub fn h() {}"),
        ]);
        assert!(edges(&tree, "p").is_empty());
        assert_eq!(edges(&tree, ""), ["p->q", "q->p"]);
        assert_eq!(cycle_reports("t", &tree).len(), 1);
    }

    #[test]
    fn path_attribute_and_missing_file() {
        let tree = tree_of(&[
            ("src/lib.rs", "#[path = \"other/z.rs\"]\nmod y;\nmod gone;"),
            ("src/other/z.rs", ""),
        ]);
        assert_eq!(module(&tree, "y"), 1);
        assert_eq!(tree.mods[1].file, PathBuf::from("src/other/z.rs"));
        assert_eq!(tree.errors.len(), 1);
        assert!(tree.errors[0].contains("src/lib.rs:3"), "{:?}", tree.errors);
    }

    #[test]
    fn workspace_manifest_members() {
        let manifest = "[workspace]\nmembers = [\"core\", # c\n \"fuzz\",\n \"nodes\"]\n[package]\nname = \"x\"\n[[bin]]\nname = \"b\"\npath = \"nodes/bin/b.rs\"\n";
        assert_eq!(
            members(Path::new("/nonexistent"), manifest),
            [PathBuf::new(), "core".into(), "nodes".into()]
        );
        let roots = crate_roots(Path::new("/nonexistent"), Path::new(""), manifest);
        assert_eq!(
            roots,
            [("x (bin b)".to_string(), PathBuf::from("nodes/bin/b.rs"))]
        );
    }
}
