//! A plugin's properties: `<float>`, `<integer>`, `<boolean>`, `<string>`,
//! `<point>`, `<vector>`, `<rgb>`, `<spectrum>` and `<transform>` children
//! read by name, and its nested objects (`<bsdf>`, `<texture>`, `<ref>`, ...).
//!
//! Every value keeps the place of its `value` attribute (of the element when it
//! has none). A property no reader asks for is reported once as a warning, at
//! its place, by [`Plugin::finish`].

use lamplight_core::math::{Mat4, Rgb, Vec3};
use lamplight_core::params::{Loc, ParamError};

use super::xml::El;
use super::{spectra, transforms};

/// The tags that are properties (the rest are objects).
pub const PROPERTY_TAGS: &[&str] = &["float", "integer", "boolean", "string", "point", "vector", "rgb", "color", "spectrum", "transform"];

/// A property's value, as its tag says.
#[derive(Clone, Debug, PartialEq)]
pub enum PropValue {
    /// `<float>`.
    Float(f64),
    /// `<integer>`.
    Integer(i64),
    /// `<boolean>`.
    Bool(bool),
    /// `<string>`.
    Str(String),
    /// `<point>` or `<vector>`.
    Vec3(Vec3),
    /// `<rgb>`, or `<spectrum>` converted as `scalar_rgb` does.
    Color(Rgb),
    /// `<transform>`.
    Transform(Mat4),
}

impl PropValue {
    /// What the value is, for messages ("a float", ...).
    pub fn describe(&self) -> &'static str {
        match self {
            PropValue::Float(_) => "a float",
            PropValue::Integer(_) => "an integer",
            PropValue::Bool(_) => "a boolean",
            PropValue::Str(_) => "a string",
            PropValue::Vec3(_) => "a point or vector",
            PropValue::Color(_) => "a colour",
            PropValue::Transform(_) => "a transform",
        }
    }
}

/// One named property.
#[derive(Clone, Debug)]
pub struct Prop {
    /// Its `name`.
    pub name: String,
    /// Its value.
    pub value: PropValue,
    /// Where the value is written.
    pub loc: Loc,
    used: bool,
}

/// A plugin element read: its type, properties and nested objects.
#[derive(Debug)]
pub struct Plugin<'a> {
    /// The element.
    pub el: &'a El,
    /// `type`.
    pub kind: String,
    /// `<shape type="sphere">` as messages name it.
    pub label: String,
    props: Vec<Prop>,
    /// Nested object elements and `<ref>`s, in order.
    pub objects: Vec<&'a El>,
}

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

impl<'a> Plugin<'a> {
    /// Reads the properties of `el` (which needs a `type`).
    pub fn new(el: &'a El) -> Result<Plugin<'a>, ParamError> {
        let kind = el.require("type")?.value.clone();
        let label = format!("{} \"{kind}\"", el.tag);
        let mut props: Vec<Prop> = Vec::new();
        let mut objects = Vec::new();
        for child in &el.children {
            if !PROPERTY_TAGS.contains(&child.tag.as_str()) || (child.tag == "spectrum" && child.get("type").is_some()) {
                objects.push(child);
                continue;
            }
            let name = child.require("name")?;
            if props.iter().any(|p| p.name == name.value) {
                return Err(err(&name.loc, format!("{label}: property \"{}\" is given twice", name.value)));
            }
            let (value, loc) = property(child, el.tag == "emitter")
                .map_err(|e| ParamError { message: format!("{label}: {}: {}", name.value, e.message), ..e })?;
            props.push(Prop { name: name.value.clone(), value, loc, used: false });
        }
        Ok(Plugin { el, kind, label, props, objects })
    }

    /// The property `name`, marked used.
    pub fn take(&mut self, name: &str) -> Option<Prop> {
        let p = self.props.iter_mut().find(|p| p.name == name)?;
        p.used = true;
        Some(p.clone())
    }

    /// Whether `name` is given.
    pub fn has(&self, name: &str) -> bool {
        self.props.iter().any(|p| p.name == name) || self.objects.iter().any(|o| o.get("name") == Some(name))
    }

    fn typed<T>(&mut self, name: &str, what: &str, f: impl Fn(&PropValue) -> Option<T>) -> Result<Option<(T, Loc)>, ParamError> {
        let label = self.label.clone();
        match self.take(name) {
            None => Ok(None),
            Some(p) => match f(&p.value) {
                Some(v) => Ok(Some((v, p.loc))),
                None => Err(err(&p.loc, format!("{label}: {name}: expected {what}, got {}", p.value.describe()))),
            },
        }
    }

    /// A `<float>` (or `<integer>`).
    pub fn number(&mut self, name: &str) -> Result<Option<(f64, Loc)>, ParamError> {
        self.typed(name, "a float", |v| match v {
            PropValue::Float(f) => Some(*f),
            PropValue::Integer(i) => Some(*i as f64),
            _ => None,
        })
    }

    /// A `<float>` or its default.
    pub fn number_or(&mut self, name: &str, default: f64) -> Result<(f64, Loc), ParamError> {
        Ok(self.number(name)?.unwrap_or((default, self.el.loc.clone())))
    }

    /// An `<integer>`.
    pub fn integer(&mut self, name: &str) -> Result<Option<(i64, Loc)>, ParamError> {
        self.typed(name, "an integer", |v| match v {
            PropValue::Integer(i) => Some(*i),
            _ => None,
        })
    }

    /// A `<boolean>`.
    pub fn boolean(&mut self, name: &str) -> Result<Option<(bool, Loc)>, ParamError> {
        self.typed(name, "a boolean", |v| match v {
            PropValue::Bool(b) => Some(*b),
            _ => None,
        })
    }

    /// A `<string>`.
    pub fn string(&mut self, name: &str) -> Result<Option<(String, Loc)>, ParamError> {
        self.typed(name, "a string", |v| match v {
            PropValue::Str(s) => Some(s.clone()),
            _ => None,
        })
    }

    /// A `<point>` or `<vector>`.
    pub fn vec3(&mut self, name: &str) -> Result<Option<(Vec3, Loc)>, ParamError> {
        self.typed(name, "a point or vector", |v| match v {
            PropValue::Vec3(p) => Some(*p),
            _ => None,
        })
    }

    /// An `<rgb>`, `<spectrum>` or `<float>` (a grey).
    pub fn color(&mut self, name: &str) -> Result<Option<(Rgb, Loc)>, ParamError> {
        self.typed(name, "a colour (<rgb>, <spectrum> or <float>)", |v| match v {
            PropValue::Color(c) => Some(*c),
            PropValue::Float(f) => Some(Rgb::splat(*f)),
            PropValue::Integer(i) => Some(Rgb::splat(*i as f64)),
            _ => None,
        })
    }

    /// A `<transform>`.
    pub fn transform(&mut self, name: &str) -> Result<Option<(Mat4, Loc)>, ParamError> {
        self.typed(name, "a <transform>", |v| match v {
            PropValue::Transform(m) => Some(*m),
            _ => None,
        })
    }

    /// The nested object (or `<ref>`) whose `name` is `name`.
    pub fn object(&self, name: &str) -> Option<&'a El> {
        self.objects.iter().copied().find(|o| o.get("name") == Some(name))
    }

    /// The properties no reader asked for, as warnings (`LOC`, message).
    pub fn finish(self) -> Vec<(Loc, String)> {
        self.props
            .iter()
            .filter(|p| !p.used)
            .map(|p| (p.loc.clone(), format!("{}: property \"{}\" is not supported, ignored", self.label, p.name)))
            .collect()
    }
}

/// A property element's value and the place of its `value` attribute.
fn property(el: &El, emission: bool) -> Result<(PropValue, Loc), ParamError> {
    let attr = el.attr("value");
    let loc = attr.map_or(el.loc.clone(), |a| a.loc.clone());
    let value_of = || el.require("value").map(|a| a.value.trim());
    let value = match el.tag.as_str() {
        "float" => PropValue::Float(parse_float(value_of()?, &loc)?),
        "integer" => {
            let v = value_of()?;
            PropValue::Integer(v.parse().map_err(|_| err(&loc, format!("expected an integer, got \"{v}\"")))?)
        }
        "boolean" => match value_of()?.to_ascii_lowercase().as_str() {
            "true" => PropValue::Bool(true),
            "false" => PropValue::Bool(false),
            v => return Err(err(&loc, format!("expected true or false, got \"{v}\""))),
        },
        "string" => PropValue::Str(el.require("value")?.value.clone()),
        "point" | "vector" => PropValue::Vec3(vec3(el, &loc)?),
        "rgb" | "color" => {
            let v = value_of()?;
            let n = numbers(v, &loc)?;
            match n.as_slice() {
                [g] => PropValue::Color(Rgb::splat(*g)),
                [r, g, b] => PropValue::Color(Rgb::new(*r, *g, *b)),
                _ => return Err(err(&loc, format!("expected one or three numbers, got \"{v}\""))),
            }
        }
        "spectrum" => PropValue::Color(spectra::spectrum(el, &loc, emission)?),
        "transform" => PropValue::Transform(transforms::transform(el)?),
        other => return Err(err(&el.loc, format!("<{other}> is not a property"))),
    };
    Ok((value, loc))
}

/// A point from `value="x, y, z"` (or one number for all three) or `x`, `y`, `z` attributes (0 when absent).
pub fn vec3(el: &El, loc: &Loc) -> Result<Vec3, ParamError> {
    if let Some(v) = el.get("value") {
        let n = numbers(v, loc)?;
        return match n.as_slice() {
            [a] => Ok(Vec3::splat(*a)),
            [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
            _ => Err(err(loc, format!("expected three numbers \"x, y, z\", got \"{v}\""))),
        };
    }
    let mut p = [0.0; 3];
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        if let Some(a) = el.attr(axis) {
            p[i] = parse_float(&a.value, &a.loc)?;
        }
    }
    Ok(Vec3::from_array(p))
}

/// Numbers separated by commas and/or white space.
pub fn numbers(text: &str, loc: &Loc) -> Result<Vec<f64>, ParamError> {
    text.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).map(|s| parse_float(s, loc)).collect()
}

/// A finite number.
pub fn parse_float(text: &str, loc: &Loc) -> Result<f64, ParamError> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(err(loc, format!("expected a finite number, got \"{}\"", text.trim()))),
    }
}
