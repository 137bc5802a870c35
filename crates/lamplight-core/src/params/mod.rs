//! Scene parameters as the kind that reads them sees them (pbrt-v4's
//! `ParameterDictionary`, Mitsuba's `Properties`).
//!
//! A scene entity (a shape, a light, a material, a camera...) arrives as a
//! [`Table`]: keys with plain values ([`Value`]), each value and each key with
//! the place it came from ([`Loc`]: a byte span of a scene file's text, or the
//! key path of a Python dict). The kind's builder reads it through [`Params`],
//! typed getters that check the value, mark the key as read and say what was
//! expected at that key's own place. Each kind lists what it reads in a
//! [`Param`] table, the single source of its documentation and of the
//! suggestion offered for a mistyped key ([`Params::check_keys`]).
//!
//! Nothing here knows a file format: the formats build tables, the kinds read
//! them.

use std::fmt;

use crate::math::{Mat4, Rgb, Vec3};

mod table;
#[cfg(test)]
mod tests;

pub use table::{Entry, Item, Loc, Table, Value};

/// Largest magnitude of a colour channel, an emission, a light's intensity or a
/// scale factor a scene may give: `f32`'s largest, `3.4028235e38` (a value
/// that rounds to a finite `f32` is accepted, [`fits_f32`]). This is the one
/// input bound on brightness, and deliberately loose: a physically consistent
/// scene needs intensities that grow as the square of its size (a point light
/// `s` times farther away needs `s^2` times the intensity for the same image,
/// so a scene scaled by `1e6` needs `1e12` times the intensity), and the
/// renderer computes radiance in `f64`, where products of a few such values
/// stay finite. What must stay finite is the pixel, so that is guarded where
/// radiance reaches the film ([`crate::film::MAX_RADIANCE`]): a sample that is
/// NaN, infinite or beyond it is replaced by black and counted. Only a value
/// that cannot be stored in an `f32` at all (`1e39`) is refused here.
pub const MAX_COLOR: f64 = f32::MAX as f64;

/// Whether `x` rounds to a finite `f32` (`|x| <= MAX_COLOR` up to the half
/// unit in the last place that rounds down to [`MAX_COLOR`]): the bound every
/// colour, emission, intensity and scale factor is checked against.
#[inline]
pub fn fits_f32(x: f64) -> bool {
    (x as f32).is_finite()
}

/// A parameter's type, as the reference documentation names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamType {
    /// A finite number (integers accepted).
    Number,
    /// A whole number.
    Integer,
    /// `true` or `false`.
    Bool,
    /// A string.
    String,
    /// `[x, y, z]`, a position.
    Point,
    /// `[x, y, z]`, a direction or offset.
    Vector,
    /// A number `v` (meaning `[v, v, v]`) or `[r, g, b]`, linear.
    Color,
    /// A colour, or a texture table `{ type = ..., ... }`.
    Texture,
    /// A number, or a texture table (a scalar read from a texture's first channel).
    ScalarTexture,
    /// The name of a `[materials]` entry, or a material table `{ type = ..., ... }`.
    Material,
    /// `[a, b]`, two numbers (texture coordinates).
    Pair,
    /// Four rows of four numbers.
    Matrix,
    /// A table whose keys the description gives.
    Table,
    /// An array whose elements the description gives.
    Array,
}

impl fmt::Display for ParamType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ParamType::Number => "number",
            ParamType::Integer => "integer",
            ParamType::Bool => "boolean",
            ParamType::String => "string",
            ParamType::Point => "point",
            ParamType::Vector => "vector",
            ParamType::Color => "colour",
            ParamType::Texture => "colour or texture",
            ParamType::ScalarTexture => "number or texture",
            ParamType::Material => "material name or table",
            ParamType::Pair => "[a, b]",
            ParamType::Matrix => "4x4 matrix",
            ParamType::Table => "table",
            ParamType::Array => "array",
        })
    }
}

/// One row of a kind's parameter table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Param {
    /// The key.
    pub name: &'static str,
    /// Its type.
    pub ty: ParamType,
    /// The default as the docs show it; `""` for a required parameter.
    pub default: &'static str,
    /// Unit or range (`"scene units"`, `"degrees, 0 to 180"`); may be empty.
    pub unit: &'static str,
    /// One line of documentation.
    pub doc: &'static str,
}

impl Param {
    /// A parameter row (a `const fn`, so tables are `static` data).
    pub const fn new(name: &'static str, ty: ParamType, default: &'static str, unit: &'static str, doc: &'static str) -> Param {
        Param { name, ty, default, unit, doc }
    }
}

/// A registered kind: its name, a one-line summary, its parameter table and
/// how to build it (`B`, a function whose signature depends on the role).
#[derive(Debug)]
pub struct Kind<B: 'static> {
    /// The `type` that names it in scene files.
    pub name: &'static str,
    /// One line for the reference.
    pub summary: &'static str,
    /// What it reads.
    pub params: &'static [Param],
    /// Builds it.
    pub build: B,
}

impl<B: 'static> Kind<B> {
    /// The kind called `name` among `kinds` (a registry's list).
    pub fn find<'a>(kinds: &[&'a Kind<B>], name: &str) -> Option<&'a Kind<B>> {
        kinds.iter().copied().find(|k| k.name == name)
    }
}

/// The message for a `type` that no kind of `kinds` has, `what` naming them:
/// `unknown texture "checkers" (did you mean 'checker'? textures: checker)`.
pub fn unknown_kind<B: 'static>(what: &str, name: &str, kinds: &[&Kind<B>]) -> String {
    let names: Vec<&str> = kinds.iter().map(|k| k.name).collect();
    unknown(what, name, &names)
}

/// The one wording of a name that is none of `known`, `what` saying what it
/// names: `unknown filter "gauss" (did you mean 'gaussian'? filters: box, tent,
/// gaussian)`, the hint only for a near miss ([`suggestion`]), `none defined`
/// when nothing is known. Every "unknown X" of the program reads so.
pub fn unknown(what: &str, name: &str, known: &[&str]) -> String {
    unknown_among(what, name, known, &format!("{what}s"))
}

/// [`unknown`] with the list labelled `label` (`built-in scenes`).
pub fn unknown_among(what: &str, name: &str, known: &[&str], label: &str) -> String {
    let hint = suggestion(name, known.iter().copied()).map(|s| format!("did you mean '{s}'? ")).unwrap_or_default();
    let list = if known.is_empty() { "none defined".to_string() } else { known.join(", ") };
    format!("unknown {what} \"{name}\" ({hint}{label}: {list})")
}

/// A parameter could not be read: where, and what was expected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParamError {
    /// The place to report (the key's value, or the table when a key is missing).
    pub loc: Loc,
    /// The whole message, starting with the entity's label (`sphere: ...`).
    pub message: String,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ParamError {}

/// The key among `valid` nearest to `key`, when it is close enough to be a typo:
/// at most a third of the longer name changed (at least one edit), and never the
/// whole of `key` (`w` is no typo of `x`).
pub fn suggestion<'a>(key: &str, valid: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    valid
        .into_iter()
        .map(|v| (strsim::damerau_levenshtein(key, v), v))
        .filter(|(d, v)| *d <= (v.len().max(key.len()) / 3).max(1) && *d < key.chars().count())
        .min_by_key(|(d, _)| *d)
        .map(|(_, v)| v)
}

/// Typed, read-tracking access to one [`Table`]; see the module documentation.
#[derive(Debug)]
pub struct Params<'a> {
    label: String,
    table: &'a Table,
    read: Vec<bool>,
}

/// A result of a parameter read.
pub type ParamResult<T> = Result<T, ParamError>;

impl<'a> Params<'a> {
    /// Reads `table` on behalf of `label` (the kind's name, or `material "m"`),
    /// which starts every message.
    pub fn new(label: impl Into<String>, table: &'a Table) -> Params<'a> {
        Params { label: label.into(), read: vec![false; table.entries.len()], table }
    }

    /// The label messages start with.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// Where the table starts.
    pub fn loc(&self) -> &Loc {
        &self.table.loc
    }

    /// Whether `key` is present (it is not marked as read).
    pub fn has(&self, key: &str) -> bool {
        self.table.get(key).is_some()
    }

    /// An error about the entity as a whole, at its table.
    pub fn error(&self, message: impl fmt::Display) -> ParamError {
        ParamError { loc: self.table.loc.clone(), message: format!("{}: {message}", self.label) }
    }

    /// An error about `key`, at its value (or at the table when it is absent).
    pub fn key_error(&self, key: &str, message: impl fmt::Display) -> ParamError {
        let loc = self.table.get(key).map_or_else(|| self.table.loc.clone(), |e| e.item.loc.clone());
        ParamError { loc, message: format!("{}: {key}: {message}", self.label) }
    }

    /// A core constructor's error: at the key it names when that key is present.
    pub fn core_error(&self, e: crate::Error) -> ParamError {
        match &e {
            crate::Error::InvalidParameter { name, .. } if self.has(name) => {
                let loc = self.table.get(name).map(|e| e.item.loc.clone()).unwrap_or_default();
                ParamError { loc, message: format!("{}: {e}", self.label) }
            }
            _ => self.error(e),
        }
    }

    /// The raw item of `key`, marked as read.
    pub fn item(&mut self, key: &str) -> Option<&'a Item> {
        let i = self.table.entries.iter().position(|e| e.key == key)?;
        self.read[i] = true;
        Some(&self.table.entries[i].item)
    }

    fn typed<T>(&mut self, key: &str, expected: &str, read: impl Fn(&Value) -> Option<T>) -> ParamResult<Option<T>> {
        match self.item(key) {
            None => Ok(None),
            Some(item) => match read(&item.value) {
                Some(v) => Ok(Some(v)),
                None => Err(self.key_error(key, format!("expected {expected}, got {}", item.value.describe()))),
            },
        }
    }

    fn missing(&self, key: &str, what: &str) -> ParamError {
        self.error(format!("needs `{key}` ({what})"))
    }

    /// A finite number.
    pub fn number(&mut self, key: &str) -> ParamResult<Option<f64>> {
        let v = self.typed(key, "a number", as_number)?;
        match v {
            Some(x) if !x.is_finite() => Err(self.key_error(key, format!("must be a finite number, got {x}"))),
            v => Ok(v),
        }
    }

    /// A finite number, required.
    pub fn required_number(&mut self, key: &str) -> ParamResult<f64> {
        self.number(key)?.ok_or_else(|| self.missing(key, "a number"))
    }

    /// A finite number, `default` when absent.
    pub fn number_or(&mut self, key: &str, default: f64) -> ParamResult<f64> {
        Ok(self.number(key)?.unwrap_or(default))
    }

    /// A whole number in `range`.
    pub fn integer(&mut self, key: &str, range: std::ops::RangeInclusive<i64>) -> ParamResult<Option<i64>> {
        let v = self.typed(key, "a whole number", |v| match v {
            Value::Integer(i) => Some(*i),
            _ => None,
        })?;
        match v {
            Some(i) if !range.contains(&i) => {
                Err(self.key_error(key, format!("must be between {} and {}, got {i}", range.start(), range.end())))
            }
            v => Ok(v),
        }
    }

    /// `true` or `false`.
    pub fn boolean(&mut self, key: &str) -> ParamResult<Option<bool>> {
        self.typed(key, "true or false", |v| match v {
            Value::Bool(b) => Some(*b),
            _ => None,
        })
    }

    /// A string.
    pub fn string(&mut self, key: &str) -> ParamResult<Option<&'a str>> {
        match self.item(key) {
            None => Ok(None),
            Some(Item { value: Value::String(s), .. }) => Ok(Some(s.as_str())),
            Some(item) => Err(self.key_error(key, format!("expected a string, got {}", item.value.describe()))),
        }
    }

    /// A string, required.
    pub fn required_string(&mut self, key: &str) -> ParamResult<&'a str> {
        self.string(key)?.ok_or_else(|| self.missing(key, "a string"))
    }

    /// One of `choices` (the first is the default when absent).
    pub fn choice(&mut self, key: &str, choices: &[&'static str]) -> ParamResult<&'static str> {
        Ok(self.choice_opt(key, choices)?.unwrap_or(choices[0]))
    }

    /// One of `choices`, required.
    pub fn required_choice(&mut self, key: &str, choices: &[&'static str]) -> ParamResult<&'static str> {
        self.choice_opt(key, choices)?.ok_or_else(|| self.missing(key, &quoted(choices)))
    }

    fn choice_opt(&mut self, key: &str, choices: &[&'static str]) -> ParamResult<Option<&'static str>> {
        let Some(s) = self.string(key)? else { return Ok(None) };
        let found = choices.iter().find(|c| **c == s).copied();
        found.map(Some).ok_or_else(|| self.key_error(key, unknown("value", s, choices)))
    }

    /// `[x, y, z]` of finite numbers.
    pub fn vec3(&mut self, key: &str) -> ParamResult<Option<Vec3>> {
        let v = self.typed(key, "[x, y, z]", |v| numbers::<3>(v).map(Vec3::from_array))?;
        self.finite_vec(key, v)
    }

    /// `[a, b]` of finite numbers.
    pub fn pair(&mut self, key: &str) -> ParamResult<Option<[f64; 2]>> {
        match self.typed(key, "[a, b]", numbers::<2>)? {
            Some(v) if !(v[0].is_finite() && v[1].is_finite()) => Err(self.key_error(key, format!("must be finite numbers, got {v:?}"))),
            v => Ok(v),
        }
    }

    /// `[x, y, z]`, required.
    pub fn required_vec3(&mut self, key: &str) -> ParamResult<Vec3> {
        self.vec3(key)?.ok_or_else(|| self.missing(key, "[x, y, z]"))
    }

    fn finite_vec(&self, key: &str, v: Option<Vec3>) -> ParamResult<Option<Vec3>> {
        match v {
            Some(v) if !v.is_finite() => Err(self.key_error(key, format!("must be finite numbers, got {}", show(v.to_array())))),
            v => Ok(v),
        }
    }

    /// A colour: a number `v` (`[v, v, v]`) or `[r, g, b]`, finite, each
    /// channel at most [`MAX_COLOR`] in magnitude ([`fits_f32`]; colours,
    /// emission, light intensities and scale factors all read through here).
    pub fn color(&mut self, key: &str) -> ParamResult<Option<Rgb>> {
        let v =
            self.typed(key, "a number or [r, g, b]", |v| as_number(v).map(Rgb::splat).or_else(|| numbers::<3>(v).map(Rgb::from_array)))?;
        match self.finite_vec(key, v)? {
            Some(c) if !c.to_array().iter().all(|&x| fits_f32(x)) => {
                let message = format!("must be at most {:e} in magnitude (f32's largest), got {}", f32::MAX, show_large(c.to_array()));
                Err(self.key_error(key, message))
            }
            v => Ok(v),
        }
    }

    /// A colour, `default` when absent.
    pub fn color_or(&mut self, key: &str, default: Rgb) -> ParamResult<Rgb> {
        Ok(self.color(key)?.unwrap_or(default))
    }

    /// Four rows of four finite numbers, as the matrix they write (rows).
    pub fn matrix(&mut self, key: &str) -> ParamResult<Option<Mat4>> {
        let rows = self.typed(key, "4 rows of 4 numbers", |v| match v {
            Value::Array(rows) if rows.len() == 4 => {
                let mut out = [[0.0; 4]; 4];
                for (o, row) in out.iter_mut().zip(rows) {
                    *o = numbers::<4>(&row.value)?;
                }
                Some(out)
            }
            _ => None,
        })?;
        match rows {
            Some(r) if !r.iter().flatten().all(|x| x.is_finite()) => Err(self.key_error(key, "must be finite numbers")),
            Some(r) => Ok(Some(Mat4::from_cols_array_2d(&r).transpose())),
            None => Ok(None),
        }
    }

    /// An array of `[x, y, z]` points.
    pub fn vec3_list(&mut self, key: &str) -> ParamResult<Option<Vec<Vec3>>> {
        let list: Option<Vec<Vec3>> = self.typed(key, "an array of [x, y, z]", |v| match v {
            Value::Array(items) => items.iter().map(|i| numbers::<3>(&i.value).map(Vec3::from_array)).collect(),
            _ => None,
        })?;
        match list {
            Some(l) if !l.iter().all(|p| p.is_finite()) => Err(self.key_error(key, "must be finite numbers")),
            l => Ok(l),
        }
    }

    /// A sub-table, read by its own [`Params`] labelled `LABEL: key`.
    pub fn table(&mut self, key: &str) -> ParamResult<Option<Params<'a>>> {
        let label = format!("{}: {key}", self.label);
        match self.item(key) {
            None => Ok(None),
            Some(Item { value: Value::Table(t), .. }) => Ok(Some(Params::new(label, t))),
            Some(item) => Err(self.key_error(key, format!("expected a table, got {}", item.value.describe()))),
        }
    }

    /// An array of tables, each read by its own [`Params`] labelled `LABEL: key[i]`.
    pub fn tables(&mut self, key: &str) -> ParamResult<Vec<Params<'a>>> {
        let label = self.label.clone();
        match self.item(key) {
            None => Ok(Vec::new()),
            Some(Item { value: Value::Array(items), .. }) => items
                .iter()
                .enumerate()
                .map(|(i, item)| match &item.value {
                    Value::Table(t) => Ok(Params::new(format!("{label}: {key}[{i}]"), t)),
                    other => Err(ParamError {
                        loc: item.loc.clone(),
                        message: format!("{label}: {key}[{i}]: expected a table, got {}", other.describe()),
                    }),
                })
                .collect(),
            Some(item) => Err(self.key_error(key, format!("expected an array of tables, got {}", item.value.describe()))),
        }
    }

    /// Fails at the first key not named in `params` (or `extra`), offering the
    /// nearest valid one: `sphere: unknown parameter 'radious' (did you mean 'radius'?)`.
    /// Run before building, so a typo is reported rather than the parameter it hides.
    pub fn check_keys(&self, params: &[Param], extra: &[&str]) -> ParamResult<()> {
        let valid = || params.iter().map(|p| p.name).chain(extra.iter().copied());
        for entry in &self.table.entries {
            if let Some(param) = params.iter().find(|p| p.name == entry.key) {
                if let Some(expected) = mismatch(param.ty, &entry.item.value) {
                    return Err(ParamError {
                        loc: entry.item.loc.clone(),
                        message: format!("{}: {}: expected {expected}, got {}", self.label, entry.key, entry.item.value.describe()),
                    });
                }
                continue;
            }
            if valid().any(|v| v == entry.key) {
                continue;
            }
            let hint = match suggestion(&entry.key, valid()) {
                Some(s) => format!(" (did you mean '{s}'?)"),
                None => {
                    let names: Vec<&str> = valid().collect();
                    if names.is_empty() {
                        " (it takes no parameters)".to_string()
                    } else {
                        format!(" (it takes: {})", names.join(", "))
                    }
                }
            };
            return Err(ParamError {
                loc: entry.key_loc.clone(),
                message: format!("{}: unknown parameter '{}'{hint}", self.label, entry.key),
            });
        }
        Ok(())
    }

    /// Reads the table as a kind whose parameters are `params` (and `extra`):
    /// checks its keys ([`Params::check_keys`]), builds with `build`, then fails
    /// at any key left unread ([`Params::finish`]).
    pub fn read<T>(mut self, params: &[Param], extra: &[&str], build: impl FnOnce(&mut Params<'a>) -> ParamResult<T>) -> ParamResult<T> {
        self.check_keys(params, extra)?;
        let made = build(&mut self)?;
        self.finish()?;
        Ok(made)
    }

    /// Fails at the first present key the builder did not read: it is valid for
    /// the kind but has no effect in this combination.
    pub fn finish(self) -> ParamResult<()> {
        match self.table.entries.iter().zip(&self.read).find(|(_, read)| !**read) {
            None => Ok(()),
            Some((entry, _)) => Err(ParamError {
                loc: entry.key_loc.clone(),
                message: format!("{}: '{}' has no effect with the other parameters given", self.label, entry.key),
            }),
        }
    }
}

/// What a value of type `ty` must be, when `value` is not of that shape.
fn mismatch(ty: ParamType, value: &Value) -> Option<&'static str> {
    let ok = match ty {
        ParamType::Number => as_number(value).is_some(),
        ParamType::Integer => matches!(value, Value::Integer(_)),
        ParamType::Bool => matches!(value, Value::Bool(_)),
        ParamType::String => matches!(value, Value::String(_)),
        ParamType::Point | ParamType::Vector => numbers::<3>(value).is_some(),
        ParamType::Color => as_number(value).is_some() || numbers::<3>(value).is_some(),
        ParamType::Texture => as_number(value).is_some() || numbers::<3>(value).is_some() || matches!(value, Value::Table(_)),
        ParamType::ScalarTexture => as_number(value).is_some() || matches!(value, Value::Table(_)),
        ParamType::Material => matches!(value, Value::String(_) | Value::Table(_)),
        ParamType::Pair => numbers::<2>(value).is_some(),
        ParamType::Matrix => {
            matches!(value, Value::Array(rows) if rows.len() == 4 && rows.iter().all(|r| numbers::<4>(&r.value).is_some()))
        }
        ParamType::Table | ParamType::Array => true,
    };
    (!ok).then_some(match ty {
        ParamType::Number => "a number",
        ParamType::Integer => "a whole number",
        ParamType::Bool => "true or false",
        ParamType::String => "a string",
        ParamType::Point | ParamType::Vector => "[x, y, z]",
        ParamType::Color => "a number or [r, g, b]",
        ParamType::Texture => "a number, [r, g, b] or a texture table { type = ..., ... }",
        ParamType::ScalarTexture => "a number or a texture table { type = ..., ... }",
        ParamType::Material => "a material name or a material table { type = ..., ... }",
        ParamType::Pair => "[a, b]",
        ParamType::Matrix => "4 rows of 4 numbers",
        ParamType::Table | ParamType::Array => "",
    })
}

fn as_number(v: &Value) -> Option<f64> {
    match v {
        Value::Number(x) => Some(*x),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn numbers<const N: usize>(v: &Value) -> Option<[f64; N]> {
    match v {
        Value::Array(items) if items.len() == N => {
            let mut out = [0.0; N];
            for (o, item) in out.iter_mut().zip(items) {
                *o = as_number(&item.value)?;
            }
            Some(out)
        }
        _ => None,
    }
}

fn show(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

/// `[1e300, 1e300, 1e300]`: large numbers in exponent form, not 300 digits.
fn show_large(v: [f64; 3]) -> String {
    let n = |x: f64| if x.abs() >= 1e15 { format!("{x:e}") } else { format!("{x}") };
    format!("[{}, {}, {}]", n(v[0]), n(v[1]), n(v[2]))
}

fn quoted(choices: &[&str]) -> String {
    let list: Vec<String> = choices.iter().map(|c| format!("\"{c}\"")).collect();
    one_of(&list)
}

/// `"a"`, `"a" or "b"`, `"a", "b" or "c"`.
pub fn one_of(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} or {last}", rest.join(", ")),
    }
}
