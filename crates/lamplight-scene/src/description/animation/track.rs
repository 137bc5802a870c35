//! One animated key: `animate.KEY = { frames = [...], values = [...],
//! interpolation = "...", in_tangents = [...], out_tangents = [...] }`, read
//! and checked ([`Track::read`]) and evaluated at a time ([`Track::at`]).

use lamplight_core::params::{Entry, Item, Loc, ParamError, ParamResult, Params, Table, Value};

use super::interpolate::{self, Interpolation, Segment};
use super::TRACK_PARAMS;

/// Most keys one track may have.
pub const MAX_KEYS: usize = 100_000;

/// The unit a track's times (and so its tangents) are in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeUnit {
    /// Frame numbers.
    Frames,
    /// Seconds from the first frame of `[animation] frames`.
    Seconds,
}

/// What a track's values are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A number.
    Number,
    /// `[x, y, z]` (a point, vector or colour).
    Vector,
    /// A rotation in any `rotate` form, interpolated as a unit quaternion.
    Rotation,
}

impl Shape {
    fn width(self) -> usize {
        match self {
            Shape::Number => 1,
            Shape::Vector => 3,
            Shape::Rotation => 4,
        }
    }
}

/// One animated key, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// The key it animates (`rotate`, `eye`, `intensity`).
    pub key: String,
    /// Where that key is written under `animate`.
    pub key_loc: Loc,
    /// The unit of `times`.
    pub unit: TimeUnit,
    /// The keys' times, strictly increasing.
    pub times: Vec<f64>,
    /// How values between keys are made.
    pub interpolation: Interpolation,
    /// What the values are.
    pub shape: Shape,
    /// Each key's value as numbers (a quaternion `[x, y, z, w]` for rotations).
    pub values: Vec<[f64; 4]>,
    /// Each key's value as written: the value given on a key's own time.
    pub items: Vec<Item>,
    /// Cubic spline: each key's in-tangent and out-tangent (per unit of time).
    pub tangents: Vec<([f64; 4], [f64; 4])>,
}

impl Track {
    /// Reads `animate.KEY` (`key`, `entry`), labelled `label` (the node's).
    pub fn read(label: &str, entry: &Entry) -> ParamResult<Track> {
        let label = format!("{label}: animate.{}", entry.key);
        let Value::Table(table) = &entry.item.value else {
            return Err(ParamError {
                loc: entry.item.loc.clone(),
                message: format!("{label}: expected a table {{ frames = [...], values = [...] }}, got {}", entry.item.value.describe()),
            });
        };
        let p = Params::new(label, table);
        p.read(TRACK_PARAMS, &[], |p| read_track(p, &entry.key, &entry.key_loc))
    }

    /// A track made in code (an importer's: glTF's animation channels), with
    /// `items` written from `values` as [`Track::at`] gives values between
    /// keys. `times` must be strictly increasing and finite, `values` (and
    /// `tangents`, for [`Interpolation::CubicSpline`]: each key's in- and
    /// out-tangent) one per time; the importer checks them first.
    pub fn new(
        key: &str,
        unit: TimeUnit,
        shape: Shape,
        interpolation: Interpolation,
        times: Vec<f64>,
        values: Vec<[f64; 4]>,
        tangents: Vec<([f64; 4], [f64; 4])>,
    ) -> Track {
        let mut track =
            Track { key: key.to_string(), key_loc: Loc::Unknown, unit, times, interpolation, shape, values, items: Vec::new(), tangents };
        track.items = track.values.iter().map(|&v| track.item(v)).collect();
        track
    }

    /// The value at time `t` (in the track's unit), as the static scene writes it.
    pub fn at(&self, t: f64) -> Item {
        match interpolate::segment(&self.times, t) {
            Segment::Key(k) => self.items[k].clone(),
            Segment::Between { k, .. } if self.interpolation == Interpolation::Step => self.items[k].clone(),
            Segment::Between { k, s } => self.item(self.between(k, s)),
        }
    }

    /// The value at time `t` as numbers (a unit quaternion `[x, y, z, w]` for rotations).
    pub fn value(&self, t: f64) -> [f64; 4] {
        match interpolate::segment(&self.times, t) {
            Segment::Key(k) => self.values[k],
            Segment::Between { k, s } => self.between(k, s),
        }
    }

    /// The value the fraction `s` (0 < s < 1) of the way from key `k` to key
    /// `k + 1`, by a linear or cubic-spline track.
    fn between(&self, k: usize, s: f64) -> [f64; 4] {
        let (a, b) = (self.values[k], self.values[k + 1]);
        match (self.interpolation, self.shape) {
            // Each value holds until the next key.
            (Interpolation::Step, _) => a,
            (Interpolation::Linear, Shape::Rotation) => interpolate::slerp(a, b, s),
            (Interpolation::Linear, _) => interpolate::lerp(a, b, s),
            (Interpolation::CubicSpline, shape) => {
                let dt = self.times[k + 1] - self.times[k];
                let v = interpolate::hermite(a, self.tangents[k].1, b, self.tangents[k + 1].0, s, dt);
                if shape == Shape::Rotation {
                    interpolate::normalized(v)
                } else {
                    v
                }
            }
        }
    }

    /// `v` as the static scene writes a value of this track.
    fn item(&self, v: [f64; 4]) -> Item {
        let loc = self.key_loc.clone();
        let number = |x: f64| Item { value: Value::Number(x), loc: loc.clone() };
        let array = |n: usize| Value::Array(v[..n].iter().map(|&x| number(x)).collect());
        let value = match self.shape {
            Shape::Number => Value::Number(v[0]),
            Shape::Vector => array(3),
            Shape::Rotation => Value::Table(Table {
                entries: vec![Entry { key: "quaternion".into(), key_loc: loc.clone(), item: Item { value: array(4), loc: loc.clone() } }],
                loc: loc.clone(),
            }),
        };
        Item { value, loc }
    }
}

fn read_track(p: &mut Params<'_>, key: &str, key_loc: &Loc) -> ParamResult<Track> {
    let (unit, times_key) = match (p.has("frames"), p.has("seconds")) {
        (true, true) => return Err(p.error("takes either frames or seconds, not both")),
        (false, false) => return Err(p.error("needs `frames` or `seconds` (the keys' times)")),
        (true, false) => (TimeUnit::Frames, "frames"),
        (false, true) => (TimeUnit::Seconds, "seconds"),
    };
    let times = times(p, times_key)?;
    let interpolation = Interpolation::from_name(p.choice("interpolation", Interpolation::NAMES)?).expect("one of the names");
    let values_item = p.item("values").ok_or_else(|| p.error("needs `values` (one per key)"))?;
    let items = list(p, "values", values_item, times.len(), "values", times_key)?;
    let shape = if key == "rotate" { Shape::Rotation } else { shape_of(p, &items[0])? };
    let mut values = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        values.push(value(p, shape, i, item)?);
    }
    let mut tangents = Vec::new();
    if interpolation == Interpolation::CubicSpline {
        let mut read = |name: &str| -> ParamResult<Vec<[f64; 4]>> {
            match p.item(name) {
                None => Ok(vec![[0.0; 4]; times.len()]),
                Some(item) => list(p, name, item, times.len(), "tangents", times_key)?.iter().map(|t| tangent(p, shape, name, t)).collect(),
            }
        };
        let (ins, outs) = (read("in_tangents")?, read("out_tangents")?);
        tangents = ins.into_iter().zip(outs).collect();
    }
    Ok(Track { key: key.to_string(), key_loc: key_loc.clone(), unit, times, interpolation, shape, values, items: items.to_vec(), tangents })
}

/// The key times: finite numbers, strictly increasing, 1 to [`MAX_KEYS`].
fn times(p: &mut Params<'_>, key: &str) -> ParamResult<Vec<f64>> {
    let item = p.item(key).expect("present");
    let Value::Array(items) = &item.value else {
        return Err(p.key_error(key, format!("expected an array of times, got {}", item.value.describe())));
    };
    if items.is_empty() || items.len() > MAX_KEYS {
        return Err(p.key_error(key, format!("has {} keys, expected 1 to {MAX_KEYS}", items.len())));
    }
    let mut times: Vec<f64> = Vec::with_capacity(items.len());
    for (i, t) in items.iter().enumerate() {
        let x = match t.value {
            Value::Number(x) if x.is_finite() => x,
            Value::Integer(n) => n as f64,
            _ => return Err(at(p, t, format!("{key}[{i}]: expected a finite number, got {}", t.value.describe()))),
        };
        if let Some(&before) = times.last() {
            if x <= before {
                return Err(at(p, t, format!("{key}[{i}]: must be later than {key}[{}] = {before}, got {x}", i - 1)));
            }
        }
        times.push(x);
    }
    Ok(times)
}

/// The array `item` of `name`, one element per key.
fn list<'a>(p: &Params<'_>, name: &str, item: &'a Item, keys: usize, what: &str, times_key: &str) -> ParamResult<&'a [Item]> {
    match &item.value {
        Value::Array(items) if items.len() == keys => Ok(items),
        Value::Array(items) => Err(p.key_error(name, format!("has {} {what} for {keys} {times_key}, expected one per key", items.len()))),
        other => Err(p.key_error(name, format!("expected an array, one per key, got {}", other.describe()))),
    }
}

/// The shape the first value gives the track.
fn shape_of(p: &Params<'_>, first: &Item) -> ParamResult<Shape> {
    match &first.value {
        Value::Number(_) | Value::Integer(_) => Ok(Shape::Number),
        Value::Array(a) if a.len() == 3 => Ok(Shape::Vector),
        other => Err(at(p, first, format!("values[0]: expected a number or [x, y, z], got {}", other.describe()))),
    }
}

/// Key `i`'s value as numbers.
fn value(p: &Params<'_>, shape: Shape, i: usize, item: &Item) -> ParamResult<[f64; 4]> {
    if shape == Shape::Rotation {
        let one = Table {
            entries: vec![Entry { key: format!("values[{i}]"), key_loc: item.loc.clone(), item: item.clone() }],
            loc: item.loc.clone(),
        };
        let mut r = Params::new(p.label().to_string(), &one);
        let q = crate::description::rotation::read(&mut r, &format!("values[{i}]"))?.quaternion();
        return Ok(q.to_array());
    }
    numbers(&item.value, shape.width()).ok_or_else(|| {
        let like = if shape == Shape::Number { "a number" } else { "[x, y, z]" };
        at(p, item, format!("values[{i}]: expected {like}, as values[0], got {}", item.value.describe()))
    })
}

/// A tangent: as the values, rotations' as quaternions `[x, y, z, w]`.
fn tangent(p: &Params<'_>, shape: Shape, name: &str, item: &Item) -> ParamResult<[f64; 4]> {
    numbers(&item.value, shape.width()).ok_or_else(|| {
        let like = match shape {
            Shape::Number => "a number",
            Shape::Vector => "[x, y, z]",
            Shape::Rotation => "[x, y, z, w] (a quaternion's rate of change)",
        };
        at(p, item, format!("{name}: expected {like} for each key, got {}", item.value.describe()))
    })
}

/// `width` finite numbers: a number, or an array of `width`.
fn numbers(value: &Value, width: usize) -> Option<[f64; 4]> {
    let number = |v: &Value| match *v {
        Value::Number(x) if x.is_finite() => Some(x),
        Value::Integer(n) => Some(n as f64),
        _ => None,
    };
    let mut out = [0.0; 4];
    match value {
        Value::Array(items) if items.len() == width && width > 1 => {
            for (o, i) in out.iter_mut().zip(items) {
                *o = number(&i.value)?;
            }
        }
        v if width == 1 => out[0] = number(v)?,
        _ => return None,
    }
    Some(out)
}

/// An error at `item`, labelled as `p`'s.
fn at(p: &Params<'_>, item: &Item, message: String) -> ParamError {
    ParamError { loc: item.loc.clone(), message: format!("{}: {message}", p.label()) }
}
