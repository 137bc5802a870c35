//! `<shape>` to nodes. Mitsuba's shapes are unit shapes placed by `to_world`,
//! which becomes the node's `matrix`:
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `sphere` `center` (0), `radius` (1) | `sphere` |
//! | `rectangle` (`[-1, 1]^2` at `z = 0`, normal `+z`) | `rectangle` corner `[-1, 1, 0]`, edges `[2, 0, 0]`, `[0, -2, 0]`, `flip_normals` (see below) |
//! | `disk` (radius 1 at `z = 0`, normal `+z`) | `disk` with `uv_layout = "radial"` |
//! | `cube` (`[-1, 1]^3`) | `box` with `uv_layout = "mitsuba"` (the cube mesh's texture coordinates) |
//! | `cylinder` `p0` (0), `p1` (`[0, 0, 1]`), `radius` (1), open | `cylinder` |
//! | `obj`, `ply` `filename` | a `[meshes]` entry and a `mesh` node |
//! | `serialized` `filename`, `shape_index` ([`super::serialized`]) | an inline `[meshes]` entry |
//! | `shapegroup` (with an `id`) and `instance` | `[definitions]` and `instance` nodes |
//! | `merge` | its nested shapes, each read on its own |
//! | `sdfgrid` `filename` (a `.vol` grid, [`super::volume`]), `normals` | `sdfgrid` with the grid's `resolution` and `values` |
//! | a nested `<bsdf>` or `<ref>` | `material` (default: Mitsuba's diffuse 0.5, black on an emitter) |
//! | a nested `<emitter type="area">` | the material with `emission` |
//!
//! Texture coordinates follow Mitsuba's with lamplight's `v = 1 - v_mitsuba`
//! (as [`super::textures`] reads every Mitsuba `v`). Mitsuba's rectangle has
//! `uv = ((x + 1) / 2, (y + 1) / 2)` (measured with 3.9.1: the point `(0.3, 0.5)`
//! has `uv = (0.65, 0.75)`), so lamplight's `v` is `(1 - y) / 2`: the edges run
//! `+x` and `-y` from the corner `(-1, 1)`. Their cross product, lamplight's
//! outward normal, is then `-z`, so the node is flipped (a Mitsuba
//! `flip_normals` unflips it) to keep Mitsuba's `+z` side the front. Mitsuba's
//! disk has `uv = (r, phi / 2 pi)` with `phi` from its local `x` axis: the disk's
//! `radial` layout.
//!
//! `flip_normals` is lamplight's `flip_normals` (one-sided BSDFs and area
//! emitters act on the other side; ignored with a warning on an instance). A mesh's
//! `face_normals = true` is `shading = "flat"`; without it a mesh that has no
//! normals is `shading = "smooth"` (angle-weighted vertex normals, as Mitsuba computes them).

use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Item, Loc, ParamError, Value};

use super::properties::Plugin;
use super::xml::El;
use super::{bsdfs, emitters, entry, matrix, num, table, table_of, text, vec3, Ctx};

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// Reads `el` and pushes its node(s) to `out`.
pub fn read<'a>(ctx: &mut Ctx<'a>, el: &'a El, out: &mut Vec<Item>) -> Result<(), ParamError> {
    let mut p = Plugin::new(el)?;
    let loc = el.loc.clone();
    let mut node: Vec<(&str, Item)> = Vec::new();
    // The `[meshes]` entry of a PLY shape, which a mesh_attribute names its colour in.
    let mut ply_mesh = None;
    match p.kind.as_str() {
        "shapegroup" => return shapegroup(ctx, el, p),
        "merge" => return merge(ctx, p, out),
        "instance" => {
            let target = p.objects.iter().copied().find(|o| o.tag == "ref" || o.tag == "shape");
            let target = target.ok_or_else(|| err(&loc, "shape \"instance\": needs a <ref id=\"...\"/> to a shapegroup"))?;
            let group = ctx.deref(target)?;
            let id = group.get("id").filter(|_| group.get("type") == Some("shapegroup"));
            let id = id.ok_or_else(|| err(&target.loc, "shape \"instance\": the reference must name a shapegroup"))?;
            node.push(("type", text("instance", &loc)));
            node.push(("of", text(id, &target.loc)));
        }
        "sphere" => {
            let (c, cloc) = p.vec3("center")?.unwrap_or((Vec3::ZERO, loc.clone()));
            let (r, rloc) = p.number_or("radius", 1.0)?;
            node.push(("type", text("sphere", &loc)));
            node.push(("center", vec3(c, &cloc)));
            node.push(("radius", num(r, &rloc)));
        }
        "rectangle" => {
            node.push(("type", text("rectangle", &loc)));
            node.push(("corner", vec3(Vec3::new(-1.0, 1.0, 0.0), &loc)));
            node.push(("edge_u", vec3(Vec3::new(2.0, 0.0, 0.0), &loc)));
            node.push(("edge_v", vec3(Vec3::new(0.0, -2.0, 0.0), &loc)));
        }
        "disk" => {
            node.push(("type", text("disk", &loc)));
            node.push(("center", vec3(Vec3::ZERO, &loc)));
            node.push(("normal", vec3(Vec3::Z, &loc)));
            node.push(("radius", num(1.0, &loc)));
            node.push(("uv_layout", text("radial", &loc)));
        }
        "cube" => {
            node.push(("type", text("box", &loc)));
            node.push(("min", vec3(Vec3::splat(-1.0), &loc)));
            node.push(("max", vec3(Vec3::splat(1.0), &loc)));
            // The cube mesh's texture coordinates, and so its dp/du (anisotropic BSDFs).
            node.push(("uv_layout", text("mitsuba", &loc)));
        }
        "cylinder" => {
            let (a, aloc) = p.vec3("p0")?.unwrap_or((Vec3::ZERO, loc.clone()));
            let (b, bloc) = p.vec3("p1")?.unwrap_or((Vec3::Z, loc.clone()));
            let (r, rloc) = p.number_or("radius", 1.0)?;
            node.push(("type", text("cylinder", &loc)));
            node.push(("from", vec3(a, &aloc)));
            node.push(("to", vec3(b, &bloc)));
            node.push(("radius", num(r, &rloc)));
        }
        "obj" | "ply" => {
            let (f, floc) = p.string("filename")?.ok_or_else(|| err(&loc, format!("{}: needs filename", p.label)))?;
            let file = ctx.file(&f, &floc)?;
            let name = mesh_name(ctx, el);
            let shading = shading(&mut p)?;
            ctx.meshes.push(entry(&name, table_of(vec![("file", text(&file, &floc)), ("shading", shading)], &floc)));
            node.push(("type", text("mesh", &loc)));
            node.push(("mesh", text(&name, &floc)));
            ply_mesh = (p.kind == "ply").then_some(name);
        }
        "serialized" => {
            let (f, floc) = p.string("filename")?.ok_or_else(|| err(&loc, format!("{}: needs filename", p.label)))?;
            let file = ctx.file(&f, &floc)?;
            let (index, iloc) = p.integer("shape_index")?.unwrap_or((0, loc.clone()));
            let mesh = super::serialized::read(&ctx.full_path(&file), index).map_err(|m| err(&iloc, format!("{}: {m}", p.label)))?;
            let name = mesh_name(ctx, el);
            let shading = shading(&mut p)?;
            ctx.meshes.push(entry(&name, mesh.table(&floc, shading)));
            node.push(("type", text("mesh", &loc)));
            node.push(("mesh", text(&name, &floc)));
        }
        "sdfgrid" => sdf_grid(ctx, &mut p, &mut node)?,
        other => {
            ctx.warn(&p.el.require("type")?.loc, format!("shape \"{other}\": not supported, skipped"));
            return Ok(());
        }
    }
    if let Some((m, mloc)) = p.transform("to_world")? {
        if m != Mat4::IDENTITY {
            node.push(("matrix", matrix(&m, &mloc)));
        }
    }
    // The rectangle's edges give lamplight's normal -z (module documentation): flipped once more.
    let turned = p.kind == "rectangle";
    match p.boolean("flip_normals")? {
        Some((_, bloc)) if p.kind == "instance" => {
            ctx.warn(&bloc, format!("{}: flip_normals on an instance is not supported, ignored", p.label));
        }
        Some((flip, bloc)) if flip != turned => node.push(("flip_normals", Item { value: Value::Bool(true), loc: bloc })),
        None if turned => node.push(("flip_normals", Item { value: Value::Bool(true), loc: loc.clone() })),
        _ => {}
    }
    // Read by the meshes above; the other shapes have their own normals.
    let _ = p.boolean("face_normals")?;
    if p.kind != "instance" {
        let material = material(ctx, &p)?;
        mesh_colour(ctx, &p, &material, ply_mesh.as_deref())?;
        node.push(("material", text(&material, &loc)));
    }
    for o in p.objects.clone() {
        if !matches!(o.tag.as_str(), "bsdf" | "emitter" | "ref") {
            ctx.warn(&o.loc, format!("{}: nested <{}> is not supported, ignored", p.label, o.tag));
        } else if o.tag == "ref" {
            // A reference to a medium (a shape's interior or exterior) changes the
            // image as a nested one does: said, not dropped.
            // (An instance's reference names its shapegroup.)
            let target = ctx.deref(o)?;
            if !matches!(target.tag.as_str(), "bsdf" | "emitter" | "shape") {
                let id = o.get("id").unwrap_or_default();
                ctx.warn(&o.loc, format!("{}: <ref id=\"{id}\"> names a <{}>, which is not supported, ignored", p.label, target.tag));
            }
        }
    }
    ctx.finish(p);
    out.push(table_of(node, &loc));
    Ok(())
}

/// `sdfgrid`: the grid file's samples as the node's `resolution` and `values`
/// (errors in them point at `filename`); Mitsuba's `grid` tensor can only be
/// given from Python, so a scene file names a file.
fn sdf_grid<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, node: &mut Vec<(&str, Item)>) -> Result<(), ParamError> {
    let (loc, label) = (p.el.loc.clone(), p.label.clone());
    let needs = || err(&loc, format!("{label}: needs filename (a .vol grid; a `grid` tensor can only be given from Python)"));
    let (f, floc) = p.string("filename")?.ok_or_else(needs)?;
    let file = ctx.file(&f, &floc)?;
    let grid = super::volume::read(&ctx.full_path(&file)).map_err(|m| err(&floc, format!("{label}: \"{f}\": {m}")))?;
    let at = |value: Value| Item { value, loc: floc.clone() };
    let resolution = grid.resolution.iter().map(|&n| at(Value::Integer(n as i64))).collect();
    let values = grid.values.iter().map(|&v| at(Value::Number(f64::from(v)))).collect();
    node.push(("type", text("sdfgrid", &loc)));
    node.push(("resolution", at(Value::Array(resolution))));
    node.push(("values", at(Value::Array(values))));
    if let Some((normals, nloc)) = p.string("normals")? {
        node.push(("normals", text(&normals, &nloc)));
    }
    // Whether the surface is closed: a hint for Mitsuba's own tracing, none here.
    let _ = p.boolean("watertight")?;
    Ok(())
}

/// The material of a shape: its BSDF's, with its area emitter's emission.
fn material<'a>(ctx: &mut Ctx<'a>, p: &Plugin<'a>) -> Result<String, ParamError> {
    let mut bsdf = None;
    let mut emitter = None;
    for &o in &p.objects {
        let target = ctx.deref(o)?;
        match target.tag.as_str() {
            "bsdf" => bsdf = Some(target),
            "emitter" => emitter = Some(target),
            _ => {}
        }
    }
    let name = match bsdf {
        Some(b) => bsdfs::material_name(ctx, b)?,
        None => bsdfs::default_material(ctx, emitter.is_some()),
    };
    let Some(e) = emitter else { return Ok(name) };
    let reads = ctx.attribute_reads.len();
    let (radiance, rloc) = emitters::area_radiance(ctx, e)?;
    let mut material = ctx.materials.iter().find(|m| m.key == name).map(|m| m.item.clone()).expect("made above");
    if let Value::Table(t) = &mut material.value {
        t.entries.retain(|en| en.key != "emission");
        t.entries.push(entry("emission", radiance));
    }
    let emitting = ctx.fresh(&format!("{name}_emitting"));
    let _ = rloc;
    ctx.materials.push(entry(&emitting, material));
    let mut used = ctx.material_attributes.get(&name).cloned().unwrap_or_default();
    used.extend(ctx.attribute_reads[reads..].iter().cloned());
    ctx.material_attributes.insert(emitting.clone(), used);
    Ok(emitting)
}

/// The mesh attribute the textures of `material` read, as the colour of the
/// PLY mesh entry `ply_mesh` (`[meshes] color`). A mesh has one colour, so a
/// shape whose textures read two attributes is an error, as are face
/// attributes on a mesh that is not a PLY file (only PLY files have them).
fn mesh_colour(ctx: &mut Ctx<'_>, p: &Plugin<'_>, material: &str, ply_mesh: Option<&str>) -> Result<(), ParamError> {
    let used = ctx.material_attributes.get(material).cloned().unwrap_or_default();
    let Some((first, first_loc)) = used.first() else { return Ok(()) };
    if let Some((other, l)) = used.iter().find(|(n, _)| n != first) {
        return Err(err(
            l,
            format!("{}: its textures read the mesh attributes \"{first}\" and \"{other}\"; lamplight reads one per shape", p.label),
        ));
    }
    match ply_mesh {
        Some(mesh) => {
            let e = ctx.meshes.iter_mut().find(|m| m.key == mesh).expect("pushed above");
            if let Value::Table(t) = &mut e.item.value {
                t.entries.push(entry("color", text(first, first_loc)));
            }
        }
        None if first.starts_with("face_") => {
            return Err(err(first_loc, format!("{}: mesh_attribute \"{first}\": face attributes are read from PLY files only", p.label)));
        }
        // A vertex colour elsewhere is the shape's own (an OBJ's none: white).
        None => {}
    }
    Ok(())
}

/// A mesh's `shading` from `face_normals`: `"flat"` when true; else Mitsuba
/// smooths a mesh without normals by the angle-weighted vertex normals, as
/// lamplight's `"smooth"` does.
fn shading(p: &mut Plugin<'_>) -> Result<Item, ParamError> {
    Ok(match p.boolean("face_normals")? {
        Some((true, l)) => text("flat", &l),
        Some((false, l)) => text("smooth", &l),
        None => text("smooth", &p.el.loc),
    })
}

fn mesh_name(ctx: &mut Ctx<'_>, el: &El) -> String {
    match el.get("id") {
        Some(id) if !ctx.meshes.iter().any(|m| m.key == id) => id.to_string(),
        _ => ctx.fresh("mesh"),
    }
}

/// `merge`: Mitsuba joins the meshes nested in it that share a BSDF into one
/// mesh, to save memory and time, and keeps its other shapes as they are; the
/// image is that of the nested shapes themselves, so each is read on its own.
fn merge<'a>(ctx: &mut Ctx<'a>, p: Plugin<'a>, out: &mut Vec<Item>) -> Result<(), ParamError> {
    for &o in &p.objects {
        let target = ctx.deref(o)?;
        if target.tag == "shape" {
            read(ctx, target, out)?;
        } else {
            ctx.warn(&o.loc, format!("shape \"merge\": nested <{}> is not supported, ignored", target.tag));
        }
    }
    ctx.finish(p);
    Ok(())
}

/// A `shapegroup`: its shapes as a definition named by its id.
fn shapegroup<'a>(ctx: &mut Ctx<'a>, el: &'a El, p: Plugin<'a>) -> Result<(), ParamError> {
    let id = el.require("id").map_err(|_| err(&el.loc, "shape \"shapegroup\": needs an id (instances refer to it)"))?;
    let mut children = Vec::new();
    for &o in &p.objects {
        if o.tag == "shape" {
            read(ctx, o, &mut children)?;
        } else {
            ctx.warn(&o.loc, format!("shape \"shapegroup\": nested <{}> is not supported, ignored", o.tag));
        }
    }
    let group = table_of(
        vec![("type", text("group", &el.loc)), ("children", Item { value: Value::Array(children), loc: el.loc.clone() })],
        &el.loc,
    );
    ctx.definitions.push(entry(&id.value, group));
    ctx.finish(p);
    let _ = table;
    Ok(())
}
