//! The reader's checks and messages, word for word.

use super::*;

fn entry(key: &str, value: Value, at: usize) -> Entry {
    Entry { key: key.into(), key_loc: Loc::Span(at..at + key.len()), item: Item { value, loc: Loc::Span(at + 10..at + 11) } }
}

fn num(x: f64) -> Item {
    Item { value: Value::Number(x), loc: Loc::Unknown }
}

const SPHERE: &[Param] = &[
    Param::new("center", ParamType::Point, "[0, 0, 0]", "", "centre"),
    Param::new("radius", ParamType::Number, "1", "scene units", "radius"),
];

#[test]
fn typed_reads_check_and_mark() {
    let t = Table {
        entries: vec![
            entry("center", Value::Array(vec![num(1.0), num(2.0), num(3.0)]), 0),
            entry("radius", Value::String("big".into()), 20),
        ],
        loc: Loc::Span(0..1),
    };
    let mut p = Params::new("sphere", &t);
    assert_eq!(p.vec3("center").unwrap(), Some(Vec3::new(1.0, 2.0, 3.0)));
    let e = p.number("radius").unwrap_err();
    assert_eq!(e.message, "sphere: radius: expected a number, got a string \"big\"");
    assert_eq!(e.loc, Loc::Span(30..31), "at the value");
    assert_eq!(p.number("missing").unwrap(), None);
    assert_eq!(p.required_number("missing").unwrap_err().message, "sphere: needs `missing` (a number)");
    p.finish().unwrap();
}

#[test]
fn unknown_keys_get_a_suggestion_at_the_key() {
    let t = Table { entries: vec![entry("radious", Value::Integer(1), 40)], loc: Loc::Unknown };
    let e = Params::new("sphere", &t).check_keys(SPHERE, &["material"]).unwrap_err();
    assert_eq!(e.message, "sphere: unknown parameter 'radious' (did you mean 'radius'?)");
    assert_eq!(e.loc, Loc::Span(40..47));
    let t = Table { entries: vec![entry("zzz", Value::Integer(1), 0)], loc: Loc::Unknown };
    let e = Params::new("sphere", &t).check_keys(SPHERE, &[]).unwrap_err();
    assert_eq!(e.message, "sphere: unknown parameter 'zzz' (it takes: center, radius)");
}

#[test]
fn unread_keys_are_reported() {
    let t = Table { entries: vec![entry("radius", Value::Integer(1), 0)], loc: Loc::Unknown };
    let e = Params::new("disk", &t).finish().unwrap_err();
    assert_eq!(e.message, "disk: 'radius' has no effect with the other parameters given");
}

#[test]
fn colours_and_non_finite_numbers() {
    let t = Table {
        entries: vec![
            entry("a", Value::Integer(2), 0),
            entry("b", Value::Array(vec![num(0.1), num(0.2), num(0.3)]), 1),
            entry("c", Value::Number(f64::NAN), 2),
            entry("d", Value::Array(vec![num(f64::INFINITY), num(0.0), num(0.0)]), 3),
        ],
        loc: Loc::Unknown,
    };
    let mut p = Params::new("m", &t);
    assert_eq!(p.color("a").unwrap(), Some(Rgb::splat(2.0)));
    assert_eq!(p.color("b").unwrap(), Some(Rgb::new(0.1, 0.2, 0.3)));
    assert_eq!(p.number("c").unwrap_err().message, "m: c: must be a finite number, got NaN");
    assert_eq!(p.vec3("d").unwrap_err().message, "m: d: must be finite numbers, got [inf, 0, 0]");
}

#[test]
fn suggestions_are_only_for_near_misses() {
    assert_eq!(suggestion("radious", ["radius", "center"]), Some("radius"));
    assert_eq!(suggestion("centre", ["radius", "center"]), Some("center"));
    assert_eq!(suggestion("colour", ["color", "kd"]), Some("color"));
    assert_eq!(suggestion("qq", ["radius", "center"]), None);
}

#[test]
fn every_unknown_name_reads_alike_and_suggests_a_near_miss() {
    assert_eq!(
        "gausian".parse::<crate::film::Filter>().unwrap_err(),
        "unknown filter \"gausian\" (did you mean 'gaussian'? filters: box, tent, gaussian, mitchell, catmullrom, lanczos)"
    );
    assert_eq!(
        "pth".parse::<&crate::integrators::IntegratorEntry>().unwrap_err(),
        "unknown integrator \"pth\" (did you mean 'path'? integrators: whitted, path)"
    );
    assert_eq!(
        "filmik".parse::<crate::film::tonemap::ToneMap>().unwrap_err(),
        "unknown tone map \"filmik\" (did you mean 'filmic'? tone maps: clamp, filmic)"
    );
    assert_eq!(super::unknown("definition", "a", &[]), "unknown definition \"a\" (definitions: none defined)");
    assert_eq!(super::unknown_among("mesh", "bunni", &["bunny"], "meshes"), "unknown mesh \"bunni\" (did you mean 'bunny'? meshes: bunny)");
}
