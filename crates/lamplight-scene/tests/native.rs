//! Scene files end to end: each built-in scene's example file renders to the
//! built-in's image, and the format's features (hierarchy, instancing, meshes,
//! implicit surfaces) build what they say.

use std::path::{Path, PathBuf};

use lamplight_core::film::Image;
use lamplight_core::{render_image, RenderControl, RenderOptions, Scene};
use lamplight_scene::builtin;
use lamplight_scene::instantiate::SceneFile;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(format!("{name}.toml"))
}

fn image(scene: &Scene, width: u32, height: u32) -> Image {
    let options = RenderOptions { width, height, threads: 2, ..RenderOptions::default() };
    render_image(scene, &options, &RenderControl::default()).unwrap().0
}

/// The example's render and the built-in's, at `width x height`, 1 spp.
fn both(name: &str, width: u32, height: u32) -> (Vec<u8>, Vec<u8>) {
    let file = SceneFile::read(&example(name)).unwrap_or_else(|e| panic!("{e}"));
    let from_file = file.build().unwrap_or_else(|e| panic!("{e}"));
    let built_in = (builtin::find(name).unwrap().build)().unwrap();
    assert_eq!(from_file.objects.len(), built_in.objects.len(), "{name}: object count");
    assert_eq!(from_file.lights.len(), built_in.lights.len(), "{name}: light count");
    assert_eq!(from_file.settings.max_depth, built_in.settings.max_depth);
    (image(&from_file, width, height).to_srgb8(), image(&built_in, width, height).to_srgb8())
}

#[test]
fn spheres_file_renders_the_builtin_byte_for_byte() {
    let (file, built_in) = both("spheres", 64, 36);
    assert!(file == built_in, "spheres.toml differs from the built-in");
}

#[test]
fn cornell_box_file_renders_the_builtin_byte_for_byte_under_both_integrators() {
    let (file, built_in) = both("cornell-box", 32, 32);
    assert!(file == built_in, "cornell-box.toml differs from the built-in (whitted)");
    let read = SceneFile::read(&example("cornell-box")).unwrap();
    assert_eq!(read.settings().unwrap().integrator, lamplight_core::integrators::find("path").unwrap());
    let options = RenderOptions {
        width: 24,
        height: 24,
        spp: 4,
        integrator: lamplight_core::integrators::find("path").unwrap(),
        ..RenderOptions::default()
    };
    let path = |scene: &Scene| render_image(scene, &options, &RenderControl::default()).unwrap().0.to_srgb8();
    let from_file = read.build().unwrap();
    let built_in = (builtin::find("cornell-box").unwrap().build)().unwrap();
    // The boxes' group transforms compose the built-in's matrices bit for bit ({:?}
    // prints every f64 exactly, the sign of a zero included).
    let shapes = |scene: &Scene| scene.objects.iter().map(|o| format!("{:?}", o.shape)).collect::<Vec<_>>();
    assert_eq!(shapes(&from_file), shapes(&built_in));
    assert!(path(&from_file) == path(&built_in), "cornell-box.toml differs from the built-in (path)");
}

#[test]
fn business_card_file_renders_the_builtin_byte_for_byte() {
    for (w, h) in [(32, 32), (64, 36)] {
        let (file, built_in) = both("business-card", w, h);
        assert!(file == built_in, "business-card.toml differs from the built-in at {w}x{h}");
    }
}

#[test]
fn luxo_file_renders_the_builtin_byte_for_byte() {
    // The lamp's joints are a node hierarchy whose offsets are written to 12
    // decimals, so its geometry differs from the built-in's in the last bits
    // (about 1e-13); at these sizes no pixel's 8-bit value changes. A larger
    // image could in principle flip a pixel that a silhouette grazes.
    for (w, h) in [(64, 36), (160, 90)] {
        let (file, built_in) = both("luxo", w, h);
        assert!(file == built_in, "luxo.toml differs from the built-in at {w}x{h}");
    }
}

#[test]
fn example_settings_are_the_builtin_defaults() {
    for b in builtin::BUILTINS {
        let s = SceneFile::read(&example(b.name)).unwrap().settings().unwrap();
        assert_eq!((s.width, s.height), b.default_size, "{}", b.name);
        // No spp but the card's (one ray a pixel): the default render is the
        // request layer's (anti-aliased Whitted).
        assert_eq!((s.spp, s.seed), (b.spp, 0), "{}", b.name);
        assert_eq!(s.integrator.name, b.integrator, "{}: the built-in's default integrator is the file's", b.name);
        assert_eq!(s.transfer, b.transfer, "{}: the built-in's output transfer is the file's", b.name);
        let request = lamplight_scene::request::SceneRequest::builtin(b);
        let job = lamplight_scene::request::Request::default().resolve(&request.defaults, lamplight_scene::request::Naming::Flags).unwrap();
        assert_eq!(job.options.integrator.name, b.integrator, "{}: `lamplight render {}` uses it", b.name, b.name);
        let file = lamplight_scene::request::SceneRequest::resolve(example(b.name).to_str().unwrap()).unwrap();
        let from_file =
            lamplight_scene::request::Request::default().resolve(&file.defaults, lamplight_scene::request::Naming::Flags).unwrap();
        assert_eq!(from_file.options, job.options, "{}: the file and the built-in render alike", b.name);
    }
}

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";

fn scene(text: &str) -> Scene {
    let file = SceneFile::parse(Path::new("t.toml"), &format!("{CAMERA}{text}")).unwrap_or_else(|e| panic!("{e}"));
    file.build().unwrap_or_else(|e| panic!("{e}"))
}

fn centre(scene: &Scene, object: usize) -> lamplight_core::math::Vec3 {
    scene.objects[object].shape.bounds().centroid()
}

#[test]
fn joints_carry_what_hangs_off_them() {
    // A sphere one unit along +x from a joint at (1, 0, 0) turned 90 degrees about z ends up at (1, 1, 0).
    let s = scene(
        "[[objects]]\ntype = \"group\"\ntranslate = [1, 0, 0]\nrotate = { z = 90 }\nchildren = [\n  { type = \"sphere\", center = [1, 0, 0], radius = 0.5 },\n  { type = \"group\", translate = [1, 0, 0], scale = 2, children = [{ type = \"sphere\", center = [1, 0, 0], radius = 0.5 }] },\n]\n",
    );
    assert!((centre(&s, 0) - lamplight_core::math::Vec3::new(1.0, 1.0, 0.0)).length() < 1e-12, "{}", centre(&s, 0));
    // Nested: (1,0,0) scaled by 2 -> (2,0,0), + (1,0,0) -> (3,0,0), turned -> (0,3,0), + (1,0,0).
    assert!((centre(&s, 1) - lamplight_core::math::Vec3::new(1.0, 3.0, 0.0)).length() < 1e-12, "{}", centre(&s, 1));
    let b = s.objects[1].shape.bounds();
    assert!((b.extent().x - 2.0).abs() < 1e-12, "uniform scale doubles the radius");
}

#[test]
fn a_mesh_placed_many_times_is_stored_once() {
    let s = scene(
        "[meshes.tri]\npositions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nindices = [[0, 1, 2]]\n[definitions.t]\ntype = \"mesh\"\nmesh = \"tri\"\n\
         [[objects]]\ntype = \"instance\"\nof = \"t\"\n[[objects]]\ntype = \"instance\"\nof = \"t\"\n[[objects]]\ntype = \"instance\"\nof = \"t\"\ntranslate = [0, 0, -2]\n",
    );
    assert_eq!(s.objects.len(), 3);
    assert!(std::sync::Arc::ptr_eq(&s.objects[0].shape, &s.objects[1].shape), "same geometry, not a copy");
    assert!((s.objects[2].shape.bounds().min.z + 2.0).abs() < 1e-12, "the third is moved, by an instance");
}

#[test]
fn non_uniform_scale_turns_a_sphere_into_an_ellipsoid() {
    let s = scene("[[objects]]\ntype = \"group\"\nscale = [2, 1, 1]\nchildren = [{ type = \"sphere\", center = [0, 0, 0], radius = 1 }]\n");
    let b = s.objects[0].shape.bounds();
    assert!((b.max.x - 2.0).abs() < 1e-6 && (b.max.y - 1.0).abs() < 1e-6, "{b:?}");
}

#[test]
fn implicit_surfaces_and_tori_are_hit_where_they_are() {
    use lamplight_core::math::Vec3;
    use lamplight_core::ray::Ray;
    let s = scene(
        "[[objects]]\ntype = \"implicit\"\nexpression = \"x*x + y*y + z*z - 1\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\nlipschitz = 4\n\
         [[objects]]\ntype = \"group\"\ntranslate = [0, 10, 0]\nchildren = [{ type = \"torus\", center = [0, 0, 0], axis = [0, 0, 1], major_radius = 1, minor_radius = 0.25 }]\n",
    );
    let hit = s.first_intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z), f64::INFINITY).unwrap();
    assert!((hit.t - 4.0).abs() < 1e-5, "{}", hit.t);
    // Through the torus's tube at x = 1 (centre moved to y = 10): enters at z = 0.25.
    let hit = s.first_intersect(&Ray::new(Vec3::new(1.0, 10.0, 5.0), -Vec3::Z), f64::INFINITY).unwrap();
    assert!((hit.t - 4.75).abs() < 1e-6, "{}", hit.t);
    assert_eq!(hit.object, 1);
}

#[test]
fn the_documented_examples_load() {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md")).unwrap();
    let blocks: Vec<&str> = doc.split("```toml\n").skip(1).map(|b| b.split("```").next().unwrap()).collect();
    assert!(blocks.len() >= 2);
    for block in blocks {
        let text = if block.contains("[camera]") { block.to_string() } else { format!("{CAMERA}{block}") };
        let file = SceneFile::parse(Path::new("doc.toml"), &text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        let s = file.build().unwrap_or_else(|e| panic!("{e}\n{text}"));
        image(&s, 8, 8);
    }
}

#[test]
fn roughness_reaches_the_material() {
    let s = scene(
        "[materials.frosted]\nkd = 0\nreflection = { type = \"dielectric\", ior = 1.5 }\nrefraction = { type = \"fresnel\", ior = 1.5 }\nroughness = 0.3\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"frosted\"\n",
    );
    let m = &s.materials[s.objects[0].material];
    assert_eq!(m.roughness, 0.3);
    let bsdf = lamplight_core::materials::bsdf_for(m, lamplight_core::math::Vec3::ZERO, true);
    assert!(matches!(bsdf.lobes(), [lamplight_core::bsdfs::Lobe::RoughGlass(glass)] if glass.alpha == 0.3), "{:?}", bsdf.lobes());
}

#[test]
fn frosted_example_has_rough_lobes_and_a_mesh_light() {
    use lamplight_core::bsdfs::Lobe;
    use lamplight_core::materials::bsdf_for;
    let path = example("frosted");
    let file = SceneFile::parse(&path, &std::fs::read_to_string(&path).unwrap()).unwrap_or_else(|e| panic!("{e}"));
    let s = file.build().unwrap_or_else(|e| panic!("{e}"));
    let lights = s.light_set();
    assert_eq!(lights.area.len(), 1, "the lamp mesh");
    assert!((lights.area[0].area() - 1.0).abs() < 1e-12);
    let lobes: Vec<Lobe> = s
        .objects
        .iter()
        .flat_map(|o| bsdf_for(&s.materials[o.material], lamplight_core::math::Vec3::ZERO, true).lobes().to_vec())
        .collect();
    assert!(lobes.iter().any(|l| matches!(l, Lobe::RoughGlass(glass) if glass.alpha == 0.2)));
    assert!(lobes.iter().any(|l| matches!(l, Lobe::RoughConductor(metal) if metal.alpha == 0.3)));
    let options = RenderOptions {
        width: 24,
        height: 16,
        spp: 16,
        integrator: lamplight_core::integrators::find("path").unwrap(),
        ..RenderOptions::default()
    };
    let (image, stats) = render_image(&s, &options, &RenderControl::default()).unwrap();
    assert_eq!(stats.nonfinite_samples, 0);
    assert!(image.pixels.iter().any(|p| p[0] > 0.05), "the lamp lights the scene");
}

/// An octahedron as an inline mesh, `normals` (a TOML array, or empty) and
/// `shading` given, lit by a point light (the camera looks at a corner).
fn octahedron(normals: &str, shading: &str) -> Vec<u8> {
    let text = format!(
        "[materials.m]\ncolor = [0.8, 0.6, 0.4]\nkd = 0.8\nks = 0.3\nshininess = 20\n\
         [meshes.octahedron]\npositions = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]\n\
         indices = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]\n{normals}{shading}\n\
         [[objects]]\ntype = \"mesh\"\nmesh = \"octahedron\"\nmaterial = \"m\"\n\
         [[objects]]\ntype = \"point_light\"\nposition = [3, 4, 2]\nintensity = 10\n"
    );
    image(&scene(&text), 48, 48).to_srgb8()
}

#[test]
fn smooth_shading_gives_a_mesh_without_normals_its_angle_weighted_vertex_normals() {
    // By symmetry the angle-weighted normal of each vertex of the octahedron is its own direction.
    let axes = "normals = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]\n";
    let smooth = octahedron("", "shading = \"smooth\"\n");
    assert!(smooth == octahedron(axes, ""), "smooth shading is the octahedron with its axes as normals");
    assert!(smooth == octahedron(axes, "shading = \"smooth\"\n"), "a mesh's own normals win");
    let flat = octahedron("", "");
    assert!(flat != smooth, "the default keeps a mesh without normals flat");
    assert!(flat == octahedron(axes, "shading = \"flat\"\n"), "flat ignores the mesh's normals");
    assert!(flat == octahedron("", "shading = \"file\"\n"));
}

/// A square in z = 0 whose normal is `normal` (+z faces the camera at z = 5).
fn square(normal_towards_camera: bool, flip: bool, material: &str) -> String {
    let (u, v) = if normal_towards_camera { ("[2, 0, 0]", "[0, 2, 0]") } else { ("[0, 2, 0]", "[2, 0, 0]") };
    format!("[[objects]]\ntype = \"rectangle\"\ncorner = [-1, -1, 0]\nedge_u = {u}\nedge_v = {v}\nmaterial = \"{material}\"\nflip_normals = {flip}\n")
}

#[test]
fn flip_normals_turns_the_side_one_sided_materials_and_emitters_act_on() {
    let lit = |normal_towards_camera, flip| {
        let text = format!(
            "[materials.m]\ncolor = [0.8, 0.6, 0.4]\nkd = 0.9\nsided = \"front\"\n{}\
             [[objects]]\ntype = \"point_light\"\nposition = [1, 2, 4]\nintensity = 20\n",
            square(normal_towards_camera, flip, "m")
        );
        image(&scene(&text), 24, 24).to_srgb8()
    };
    let facing = lit(true, false);
    assert!(facing.iter().any(|&b| b > 50), "a one-sided square facing the camera and the light is lit");
    assert!(lit(false, false).iter().all(|&b| b == 0), "seen from its back it is black");
    assert!(lit(false, true) == facing, "turned away but flipped, it is the square that faces the camera");
    assert!(lit(true, true).iter().all(|&b| b == 0), "facing but flipped, it shows its back");
    // An emitter emits from its front (one-sided): flipping turns it towards the camera.
    let glow = |flip| {
        let text = format!("[materials.e]\ncolor = 0\nkd = 0\nka = 0\nemission = [2, 1, 0.5]\n{}", square(false, flip, "e"));
        image(&scene(&text), 8, 8)
    };
    assert_eq!(glow(false).get(4, 4), [0.0, 0.0, 0.0], "the back of an emitter is dark");
    assert_eq!(glow(true).get(4, 4), [2.0, 1.0, 0.5], "flipped, its emission faces the camera");
}

/// A dict's source (Python's scene dicts, `Source::for_dict`): its relative
/// mesh paths resolve against its folder, and its errors name the dict and
/// not a file, through the same build as a scene file's. (This description is
/// parsed from TOML text, so its values carry text spans, which a dict has no
/// text for: the error names the dict alone. A dict read from Python carries
/// key paths; `python/tests/test_hardening.py` checks those messages.)
#[test]
fn a_dict_resolves_against_its_folder_and_names_itself_in_errors() {
    use lamplight_scene::formats::native::Source;
    let dir = std::env::temp_dir().join(format!("lamplight-dict-source-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let as_dict = |text: &str| {
        let parsed = SceneFile::parse(Path::new("unused.toml"), &format!("{CAMERA}{text}")).unwrap_or_else(|e| panic!("{e}"));
        SceneFile { description: parsed.description, source: Source::for_dict(dir.clone()) }
    };
    let mesh = "[meshes.m]\nfile = \"tri.obj\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n";
    let built = as_dict(mesh).build().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(built.objects.len(), 1);
    let missing = as_dict(&mesh.replace("tri.obj", "none.obj")).build().unwrap_err().to_string();
    let expected = format!("scene dict: mesh \"m\": file \"none.obj\" not found (looked for {})", dir.join("none.obj").display());
    assert_eq!(missing, expected);
    let bad = as_dict("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n").build().unwrap_err().to_string();
    assert_eq!(bad, "scene dict: sphere: invalid radius: must be a positive number, got -1");
    std::fs::remove_dir_all(&dir).ok();
}
