//! Structure-aware mutations of model files: a seed file is parsed as a `toml::Value`, 1–4
//! random mutations are applied to the tree (wrong types, extreme and non-finite numbers,
//! empty, huge and wrong-length arrays, deleted keys, duplicated items, dangling names,
//! degenerate geometry, unknown keys, long and unicode strings, values copied from elsewhere in
//! the file), the tree is written back as text, and sometimes the text itself is damaged (byte
//! flips, truncation, deleted or repeated lines) to reach the TOML parser.
//!
//! Deterministic: case `i` of seed `s` is always the same input ([`Rng::for_case`]). Depends on
//! `toml` and `std` only, so that `tests/fuzz_model_files.rs` of the root package includes this
//! file as a module (`#[path]`) and the test and `cargo xtask fuzz` generate the same inputs.

#![allow(dead_code)]

use toml::Value;

/// SplitMix64 (Steele, Lea & Flood 2014): small, fast, good enough to pick mutations.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The generator of case `index` of the run seeded with `seed` (cases are independent, so
    /// any case can be replayed alone).
    pub fn for_case(seed: u64, index: u64) -> Self {
        let mut r = Self(seed ^ index.wrapping_mul(0xA076_1D64_78BD_642F));
        r.next_u64();
        r
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform integer in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }

    /// A uniform float in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// One element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// A seed model file.
#[derive(Debug, Clone)]
pub struct Seed {
    /// Where it came from (for reports).
    pub name: String,
    /// Its text.
    pub text: String,
    /// Its parsed tree (`None` when the seed is not valid TOML: text mutations only).
    pub value: Option<Value>,
}

impl Seed {
    /// A seed from its text.
    pub fn new(name: &str, text: String) -> Self {
        let value = text.parse::<toml::Table>().ok().map(Value::Table);
        Self {
            name: name.to_string(),
            text,
            value,
        }
    }
}

/// The seeds: every `.toml` file of `dirs` (sorted by path, so runs are reproducible).
pub fn seeds_from_dirs(dirs: &[std::path::PathBuf]) -> Vec<Seed> {
    let mut paths = Vec::new();
    for d in dirs {
        if let Ok(rd) = std::fs::read_dir(d) {
            for e in rd.flatten() {
                let p = e.path();
                if p.extension().is_some_and(|x| x == "toml") {
                    paths.push(p);
                }
            }
        }
    }
    paths.sort();
    paths
        .into_iter()
        .filter_map(|p| {
            let text = std::fs::read_to_string(&p).ok()?;
            let name = p
                .components()
                .rev()
                .take(3)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            Some(Seed::new(&name, text))
        })
        .collect()
}

/// One generated input: the text and what was done to the seed.
#[derive(Debug, Clone)]
pub struct Input {
    /// Seed file name.
    pub seed: String,
    /// The mutations applied, one short description each.
    pub mutations: Vec<String>,
    /// The model file text.
    pub text: String,
}

/// Generate case `index` of the run `seed` from the seeds.
pub fn generate(seeds: &[Seed], seed: u64, index: u64) -> Input {
    let mut rng = Rng::for_case(seed, index);
    let s = rng.pick(seeds);
    let mut mutations = Vec::new();
    let mut text = match &s.value {
        Some(v) if !rng.chance(0.04) => {
            let mut v = v.clone();
            let n = 1 + rng.below(4);
            for _ in 0..n {
                mutations.push(mutate(&mut v, &mut rng));
            }
            match toml::to_string(&v) {
                Ok(t) => t,
                Err(e) => {
                    mutations.push(format!("(not serializable: {e}; seed text used)"));
                    s.text.clone()
                }
            }
        }
        _ => s.text.clone(),
    };
    if rng.chance(0.08) || mutations.is_empty() {
        let n = 1 + rng.below(3);
        for _ in 0..n {
            let (t, what) = mutate_text(&text, &mut rng);
            text = t;
            mutations.push(what);
        }
    }
    Input {
        seed: s.name.clone(),
        mutations,
        text,
    }
}

/// A step of a path in the tree.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// A table key.
    Key(String),
    /// An array index.
    Index(usize),
}

/// Every node's path (the root excluded), depth first.
pub fn paths(v: &Value) -> Vec<Vec<Step>> {
    fn walk(v: &Value, cur: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
        match v {
            Value::Table(t) => {
                for (k, x) in t {
                    cur.push(Step::Key(k.clone()));
                    out.push(cur.clone());
                    walk(x, cur, out);
                    cur.pop();
                }
            }
            Value::Array(a) => {
                // huge arrays: visit a few elements only
                for (i, x) in a.iter().enumerate().take(64) {
                    cur.push(Step::Index(i));
                    out.push(cur.clone());
                    walk(x, cur, out);
                    cur.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(v, &mut Vec::new(), &mut out);
    out
}

/// The node at `path`, read only.
pub fn get<'a>(v: &'a Value, path: &[Step]) -> Option<&'a Value> {
    let mut cur = v;
    for s in path {
        cur = match (s, cur) {
            (Step::Key(k), Value::Table(t)) => t.get(k)?,
            (Step::Index(i), Value::Array(a)) => a.get(*i)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// The node at `path`.
pub fn get_mut<'a>(v: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let mut cur = v;
    for s in path {
        cur = match (s, cur) {
            (Step::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (Step::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(cur)
}

fn render(path: &[Step]) -> String {
    let mut s = String::new();
    for p in path {
        match p {
            Step::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Step::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Numbers that break things.
pub const EXTREMES: [f64; 16] = [
    0.0,
    -0.0,
    1e308,
    -1e308,
    1e-308,
    5e-324,
    -1.0,
    1.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e30,
    -1e30,
    1e-30,
    9007199254740993.0,
    0.5,
];

/// Integers that break things.
pub const INT_EXTREMES: [i64; 9] = [
    0,
    -1,
    1,
    i64::MIN,
    i64::MAX,
    1 << 40,
    -(1 << 40),
    1_000_000_000,
    10_000,
];

/// Strings that break things (a very long one is made on demand).
pub const STRINGS: [&str; 11] = [
    "",
    " ",
    "x",
    "ground",
    "nan",
    "ß∂ƒ😀\u{202e}é",
    "\u{0}",
    "a.b[0]",
    "revolute",
    "-1",
    "\"quoted\" `back` 'single'\n\tnewline",
];

/// Keys whose values are lengths, masses or counts (degenerate geometry is tried on them).
const GEOMETRY: [&str; 24] = [
    "radius",
    "bearing_radius",
    "journal_radius",
    "mass",
    "inertia",
    "length",
    "elements",
    "height",
    "width",
    "slider_height",
    "slider_length",
    "gap",
    "thickness",
    "area",
    "youngs_modulus",
    "density",
    "modes",
    "rtol",
    "atol",
    "t_end",
    "dt",
    "max_steps",
    "max_order",
    "restitution",
];

fn random_float(rng: &mut Rng) -> f64 {
    match rng.below(4) {
        0 => *rng.pick(&EXTREMES),
        1 => (rng.unit() - 0.5) * 10f64.powi(rng.below(40) as i32 - 20),
        2 => rng.below(20) as f64,
        _ => f64::from_bits(rng.next_u64()),
    }
}

fn long_string(rng: &mut Rng) -> String {
    let unit = *rng.pick(&["x", "é", "😀", "ab "]);
    unit.repeat(1000 + rng.below(100_000))
}

/// A random value of a random kind (`depth` limits nesting).
fn random_value(rng: &mut Rng, doc: &Value, depth: usize) -> Value {
    match rng.below(if depth > 2 { 5 } else { 8 }) {
        0 => Value::Float(random_float(rng)),
        1 => Value::Integer(*rng.pick(&INT_EXTREMES)),
        2 => Value::Boolean(rng.chance(0.5)),
        3 => Value::String(if rng.chance(0.1) {
            long_string(rng)
        } else {
            (*rng.pick(&STRINGS)).to_string()
        }),
        4 => {
            // a value copied from elsewhere in the document
            let ps = paths(doc);
            if ps.is_empty() {
                return Value::Boolean(true);
            }
            let p = rng.pick(&ps).clone();
            get(doc, &p).cloned().unwrap_or(Value::Boolean(false))
        }
        5 => Value::Array(Vec::new()),
        6 => {
            let n = rng.below(4);
            Value::Array((0..n).map(|_| random_value(rng, doc, depth + 1)).collect())
        }
        _ => {
            let mut t = toml::Table::new();
            for _ in 0..rng.below(3) {
                t.insert(
                    (*rng.pick(&["type", "name", "body", "at", "law", "x", "é"])).to_string(),
                    random_value(rng, doc, depth + 1),
                );
            }
            Value::Table(t)
        }
    }
}

/// Rough size of a value as text (bytes).
fn size(v: &Value) -> usize {
    match v {
        Value::String(s) => s.len() + 2,
        Value::Array(a) => a.iter().map(size).sum::<usize>() + 2,
        Value::Table(t) => t.iter().map(|(k, x)| k.len() + 3 + size(x)).sum(),
        _ => 8,
    }
}

fn kind(v: &Value) -> usize {
    match v {
        Value::String(_) => 0,
        Value::Integer(_) | Value::Float(_) => 1,
        Value::Boolean(_) => 2,
        Value::Array(_) => 3,
        Value::Table(_) => 4,
        Value::Datetime(_) => 5,
    }
}

/// Every string value in the document (the names items refer to).
fn strings(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::String(s) => out.push(s.clone()),
        Value::Array(a) => a.iter().for_each(|x| strings(x, out)),
        Value::Table(t) => t.values().for_each(|x| strings(x, out)),
        _ => {}
    }
}

/// Apply one random mutation to the document; returns what was done.
pub fn mutate(doc: &mut Value, rng: &mut Rng) -> String {
    let all = paths(doc);
    if all.is_empty() {
        *doc = Value::Table(toml::Table::new());
        return "empty document".into();
    }
    let snapshot = doc.clone();
    let op = rng.below(15);
    // degenerate geometry aims at the keys of GEOMETRY
    let path = if op == 9 {
        let geo: Vec<&Vec<Step>> = all
            .iter()
            .filter(|p| matches!(p.last(), Some(Step::Key(k)) if GEOMETRY.contains(&k.as_str())))
            .collect();
        if geo.is_empty() {
            rng.pick(&all).clone()
        } else {
            (*rng.pick(&geo)).clone()
        }
    } else {
        rng.pick(&all).clone()
    };
    let at = render(&path);
    let Some(node) = get_mut(doc, &path) else {
        return "no-op".into();
    };
    match op {
        // a value of another type
        0 | 1 => {
            let k = kind(node);
            let mut v = random_value(rng, &snapshot, 0);
            for _ in 0..8 {
                if kind(&v) != k {
                    break;
                }
                v = random_value(rng, &snapshot, 0);
            }
            *node = v;
            format!("{at}: other type")
        }
        // extreme or non-finite numbers
        2 | 3 => {
            *node = if matches!(node, Value::Integer(_)) && rng.chance(0.5) {
                Value::Integer(*rng.pick(&INT_EXTREMES))
            } else {
                Value::Float(*rng.pick(&EXTREMES))
            };
            format!("{at}: extreme {node}")
        }
        // scaled number
        4 => {
            let f = *rng.pick(&[-1.0, 0.0, 1e-9, 1e9, 1.0 + 1e-15, -1e-12]);
            match node {
                Value::Float(x) => *x *= f,
                Value::Integer(i) => *i = i.saturating_mul(*rng.pick(&[-1, 0, 1000, 1 << 20])),
                Value::Array(a) => {
                    for x in a.iter_mut() {
                        if let Value::Float(y) = x {
                            *y *= f;
                        }
                    }
                }
                _ => *node = Value::Float(f),
            }
            format!("{at}: scaled by {f}")
        }
        // array shapes: empty, huge, one element more or less
        5 => {
            if let Value::Array(a) = node {
                match rng.below(4) {
                    0 => a.clear(),
                    1 => {
                        let item = a.first().cloned().unwrap_or(Value::Float(1.0));
                        // up to 10 000 elements, and about 4 MB of text at most (a long
                        // string repeated 10 000 times would only test the parser's speed)
                        let n = (1000 + rng.below(9001)).min(4_000_000 / size(&item).max(1));
                        *a = vec![item; n.max(2)];
                    }
                    2 => {
                        a.pop();
                    }
                    _ => {
                        let item = a.last().cloned().unwrap_or(Value::Float(0.0));
                        a.push(item);
                    }
                }
                format!("{at}: array of {} elements", a.len())
            } else {
                *node = Value::Array(Vec::new());
                format!("{at}: empty array")
            }
        }
        // delete a key (or an array element)
        6 | 7 => {
            let (last, parent) = path.split_last().expect("paths are not empty");
            match (last, get_mut(doc, parent)) {
                (Step::Key(k), Some(Value::Table(t))) => {
                    t.remove(k);
                }
                (Step::Index(i), Some(Value::Array(a))) => {
                    a.remove(*i);
                }
                _ => {}
            }
            format!("{at}: deleted")
        }
        // duplicate an element of an array (duplicate names)
        8 => {
            let (last, parent) = path.split_last().expect("paths are not empty");
            if let (Step::Index(i), Some(Value::Array(a))) = (last, get_mut(doc, parent)) {
                let item = a[*i].clone();
                a.insert(*i, item);
                return format!("{at}: duplicated");
            }
            // else duplicate an item of a random array of tables
            if let Value::Table(t) = doc {
                let arrays: Vec<String> = t
                    .iter()
                    .filter(|(_, v)| matches!(v, Value::Array(a) if !a.is_empty()))
                    .map(|(k, _)| k.clone())
                    .collect();
                if !arrays.is_empty() {
                    let k = rng.pick(&arrays).clone();
                    if let Some(Value::Array(a)) = t.get_mut(&k) {
                        let i = rng.below(a.len());
                        let item = a[i].clone();
                        a.push(item);
                        return format!("{k}[{i}]: duplicated");
                    }
                }
            }
            "nothing to duplicate".into()
        }
        // degenerate geometry
        9 => {
            let v = *rng.pick(&[0.0, -1.0, -1e-3, 1e-300, f64::NAN, 1e300]);
            *node = match node {
                Value::Integer(_) => Value::Integer(*rng.pick(&[0, -1, 1, 100_000, 1 << 31])),
                Value::Array(a) => Value::Array(vec![Value::Float(v); a.len()]),
                _ => Value::Float(v),
            };
            // a journal radius equal to or above the bearing radius
            if let Some(Step::Key(k)) = path.last() {
                if k == "journal_radius" && rng.chance(0.5) {
                    let (_, parent) = path.split_last().expect("not empty");
                    if let Some(Value::Table(t)) = get_mut(doc, parent) {
                        let b = t.get("bearing_radius").cloned();
                        if let Some(b) = b {
                            t.insert("journal_radius".into(), b);
                        }
                    }
                }
            }
            format!("{at}: degenerate")
        }
        // dangling reference: change a string (names, bodies, points, laws)
        10 => {
            let mut names = Vec::new();
            strings(&snapshot, &mut names);
            *node = match node {
                Value::String(s) if rng.chance(0.5) => Value::String(format!("{s}_x")),
                _ if !names.is_empty() && rng.chance(0.7) => {
                    Value::String(rng.pick(&names).clone())
                }
                _ => Value::String((*rng.pick(&STRINGS)).to_string()),
            };
            format!("{at}: renamed")
        }
        // unknown key
        11 => {
            let key =
                (*rng.pick(&["mas", "extra", "type", "name", "é", "", "a.b", "0"])).to_string();
            let val = random_value(rng, &snapshot, 1);
            match node {
                Value::Table(t) => {
                    t.insert(key.clone(), val);
                }
                _ => {
                    let (_, parent) = path.split_last().expect("not empty");
                    if let Some(Value::Table(t)) = get_mut(doc, parent) {
                        t.insert(key.clone(), val);
                    }
                }
            }
            format!("{at}: unknown key `{key}`")
        }
        // long or unicode strings
        12 => {
            *node = Value::String(if rng.chance(0.5) {
                long_string(rng)
            } else {
                (*rng.pick(&STRINGS)).to_string()
            });
            format!("{at}: string")
        }
        // coincident points: copy a sibling array (a position or an anchor)
        13 => {
            let arrays: Vec<Vec<Step>> = all
                .iter()
                .filter(|p| matches!(get(&snapshot, p), Some(Value::Array(a)) if a.len() == 2))
                .cloned()
                .collect();
            if !arrays.is_empty() {
                let p = rng.pick(&arrays).clone();
                if let Some(v) = get(&snapshot, &p).cloned() {
                    *node = v;
                }
            } else {
                *node = Value::Array(vec![Value::Float(0.0), Value::Float(0.0)]);
            }
            format!("{at}: copied a point")
        }
        // a whole new random value
        _ => {
            *node = random_value(rng, &snapshot, 0);
            format!("{at}: random value")
        }
    }
}

/// Damage the text itself; returns it and what was done.
pub fn mutate_text(text: &str, rng: &mut Rng) -> (String, String) {
    let mut b = text.as_bytes().to_vec();
    let what = match rng.below(6) {
        0 if !b.is_empty() => {
            let i = rng.below(b.len());
            b[i] ^= 1 << rng.below(8);
            format!("bit flip at byte {i}")
        }
        1 if !b.is_empty() => {
            let i = rng.below(b.len());
            b.truncate(i);
            format!("truncated at byte {i}")
        }
        2 => {
            let i = rng.below(b.len() + 1);
            let options: [&[u8]; 12] = [
                b"[",
                b"]",
                b"\"",
                b"=",
                b"\n[[body]]\n",
                b"\n[model]\n",
                b"{",
                b"'''",
                b"\\u",
                b"\xff",
                b"\n",
                b"#",
            ];
            let ins = *rng.pick(&options);
            b.splice(i..i, ins.iter().copied());
            format!("inserted {:?} at byte {i}", String::from_utf8_lossy(ins))
        }
        3 => {
            let lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return (String::new(), "empty".into());
            }
            let k = rng.below(lines.len());
            let out: Vec<&str> = lines
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != k)
                .map(|(_, l)| *l)
                .collect();
            return (out.join("\n"), format!("deleted line {}", k + 1));
        }
        4 => {
            let lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return (String::new(), "empty".into());
            }
            let k = rng.below(lines.len());
            let mut out = lines.clone();
            out.insert(k, lines[k]);
            return (out.join("\n"), format!("repeated line {}", k + 1));
        }
        _ => {
            let i = rng.below(b.len() + 1);
            let n = rng.below(8);
            for _ in 0..n {
                b.insert(i.min(b.len()), rng.below(256) as u8);
            }
            format!("{n} random bytes at byte {i}")
        }
    };
    (String::from_utf8_lossy(&b).into_owned(), what)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cases_are_reproducible() {
        let seeds = vec![Seed::new(
            "s",
            "[model]\nname = \"m\"\n[[body]]\nname = \"b\"\nmass = 1.0\n".into(),
        )];
        for i in 0..200 {
            let a = generate(&seeds, 7, i);
            let b = generate(&seeds, 7, i);
            assert_eq!(a.text, b.text);
            assert!(!a.mutations.is_empty());
        }
    }
}
