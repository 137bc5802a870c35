//! A PLY file's other scalar properties as named attributes, grouped and named
//! as Mitsuba 3 names them, for its `mesh_attribute` texture.
//!
//! A property `P_S` with the suffix `S` one of `x y z`, `0 1 2 ...` or `r g b`
//! is channel `S` of the attribute `P` (`P_color` for `r g b`); bare `r g b` and
//! `red green blue` are `color` (all three, or none: a lone `red` is no
//! attribute). The element's name is the prefix: vertex
//! property `color_0` is channel 0 of `vertex_color`, face property
//! `weight_0` all of `face_weight`. An attribute has 1 channel (read as a grey)
//! or 3; others, and properties without a suffix, are not attributes (Mitsuba
//! 3.9.1 ignores them with a warning, and so does the reader). Values are read
//! as they are, integers too: Mitsuba does not scale 8-bit values (measured:
//! `uchar red = 128` gives 128). The one exception is a vertex's `red green
//! blue`, which the PLY reader takes first as the file's colours (integers as
//! sRGB fractions of their maximum, lamplight's meaning for every PLY file;
//! `vertex_color` then falls back to them: [`MeshData::with_color_attribute`]),
//! since no scene means an albedo of 128. The names follow Mitsuba's `write_ply`
//! (`color_0 color_1 color_2`, `weight_0`), checked against 3.9.1.
//!
//! A face attribute holds one value per triangle (a polygon's value repeated
//! for each triangle of its fan or strip), so that the mesh reads it by its
//! triangle index.

use lamplight_core::math::Rgb;
use lamplight_core::shapes::VertexAttributes;

use super::MeshData;

/// One attribute: `vertex_NAME` (a value per vertex) or `face_NAME` (per triangle).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedAttribute {
    /// Mitsuba's name, with its element prefix.
    pub name: String,
    /// One channel is a grey.
    pub values: Vec<Rgb>,
}

/// The properties (by index among the element's) that make one attribute.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Group {
    /// Mitsuba's name, with its element prefix.
    pub name: String,
    /// Property indices in channel order (1 or 3 of them).
    pub props: Vec<usize>,
}

impl Group {
    /// The attribute's value from the element's values of one item (`values[i]` the property `i`'s).
    pub fn value(&self, values: &[f64]) -> Rgb {
        match self.props.as_slice() {
            [a] => Rgb::splat(values[*a]),
            [a, b, c] => Rgb::new(values[*a], values[*b], values[*c]),
            _ => unreachable!("groups have 1 or 3 channels"),
        }
    }
}

/// The channel of a property name: (attribute name without the element
/// prefix, order, whether it is a colour's `r g b`, which needs all three).
fn channel(name: &str) -> Option<(String, usize, bool)> {
    match name {
        "r" | "red" => return Some(("color".into(), 0, true)),
        "g" | "green" => return Some(("color".into(), 1, true)),
        "b" | "blue" => return Some(("color".into(), 2, true)),
        _ => {}
    }
    let (prefix, suffix) = name.rsplit_once('_')?;
    if prefix.is_empty() {
        return None;
    }
    let order = match suffix {
        "x" | "r" => 0,
        "y" | "g" => 1,
        "z" | "b" => 2,
        digits => digits.parse::<usize>().ok()?,
    };
    let rgb = matches!(suffix, "r" | "g" | "b");
    let base = if rgb { format!("{prefix}_color") } else { prefix.to_string() };
    Some((base, order, rgb))
}

/// A group being collected: its base name, whether its members are colour
/// channels, and each member's (channel order, property index).
type PendingGroup = (String, bool, Vec<(usize, usize)>);

/// Groups the scalar properties `props` (index, name) of element `element`;
/// returns the groups and the names of the properties in none.
pub(super) fn group(element: &str, props: &[(usize, &str)]) -> (Vec<Group>, Vec<String>) {
    let mut found: Vec<PendingGroup> = Vec::new();
    let mut ignored = Vec::new();
    for &(i, name) in props {
        match channel(name) {
            Some((base, order, rgb)) => match found.iter_mut().find(|(b, _, _)| *b == base) {
                Some((_, _, members)) => members.push((order, i)),
                None => found.push((base, rgb, vec![(order, i)])),
            },
            None => ignored.push(name.to_string()),
        }
    }
    let mut groups = Vec::new();
    for (base, rgb, mut members) in found {
        if members.len() == 3 || (members.len() == 1 && !rgb) {
            members.sort_unstable();
            groups.push(Group { name: format!("{element}_{base}"), props: members.into_iter().map(|(_, i)| i).collect() });
        } else {
            ignored.extend(members.iter().map(|&(_, i)| props.iter().find(|p| p.0 == i).map_or(String::new(), |p| p.1.to_string())));
        }
    }
    (groups, ignored)
}

impl MeshData {
    /// The vertex attributes with the colour taken from the attribute `name`
    /// (`vertex_...` interpolated, `face_...` constant per face); `vertex_color`
    /// falls back to the file's `red green blue` colours. The message lists the
    /// attributes the file has.
    pub fn with_color_attribute(&self, name: &str) -> Result<VertexAttributes, String> {
        let mut attributes = VertexAttributes { colors: None, face_colors: None, ..self.attributes.clone() };
        match self.named.iter().find(|a| a.name == name) {
            Some(a) if name.starts_with("face_") => attributes.face_colors = Some(a.values.clone()),
            Some(a) => attributes.colors = Some(a.values.clone()),
            None if name == "vertex_color" && self.attributes.colors.is_some() => attributes.colors = self.attributes.colors.clone(),
            None => {
                let mut names: Vec<&str> = self.named.iter().map(|a| a.name.as_str()).collect();
                if self.attributes.colors.is_some() && !names.contains(&"vertex_color") {
                    names.push("vertex_color");
                }
                let has = if names.is_empty() { "none".to_string() } else { names.join(", ") };
                return Err(format!("has no attribute \"{name}\" (it has: {has})"));
            }
        }
        Ok(attributes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(groups: &[Group]) -> Vec<(&str, Vec<usize>)> {
        groups.iter().map(|g| (g.name.as_str(), g.props.clone())).collect()
    }

    #[test]
    fn properties_group_as_mitsuba_names_them() {
        let props = [(3, "color_2"), (4, "color_0"), (5, "color_1"), (6, "weight_0"), (7, "foo_r"), (8, "foo_g"), (9, "foo_b")];
        let (groups, ignored) = group("face", &props);
        assert_eq!(names(&groups), vec![("face_color", vec![4, 5, 3]), ("face_weight", vec![6]), ("face_foo_color", vec![7, 8, 9])]);
        assert!(ignored.is_empty());
        let (groups, ignored) = group("vertex", &[(0, "r"), (1, "g"), (2, "b"), (3, "n_x"), (4, "n_y"), (5, "n_z"), (6, "quality")]);
        assert_eq!(names(&groups), vec![("vertex_color", vec![0, 1, 2]), ("vertex_n", vec![3, 4, 5])]);
        assert_eq!(ignored, vec!["quality"]);
        // Two channels are not an attribute, nor a bare suffix.
        let (groups, ignored) = group("vertex", &[(0, "uv_0"), (1, "uv_1"), (2, "_x")]);
        assert!(groups.is_empty());
        assert_eq!(ignored, vec!["_x", "uv_0", "uv_1"]);
        let (groups, ignored) = group("vertex", &[(0, "red")]);
        assert!(groups.is_empty());
        assert_eq!(ignored, vec!["red"]);
    }

    #[test]
    fn the_colour_comes_from_the_named_attribute() {
        let grey = NamedAttribute { name: "face_weight".into(), values: vec![Rgb::splat(0.3), Rgb::splat(0.6)] };
        let mesh = MeshData { named: vec![grey], ..MeshData::default() };
        let a = mesh.with_color_attribute("face_weight").unwrap();
        assert_eq!(a.face_colors, Some(vec![Rgb::splat(0.3), Rgb::splat(0.6)]));
        assert_eq!(a.colors, None);
        assert_eq!(mesh.with_color_attribute("vertex_color").unwrap_err(), "has no attribute \"vertex_color\" (it has: face_weight)");
    }
}
