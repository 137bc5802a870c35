// scratch: render a builtin to PNG (not committed)
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = &args[1];
    let (w, h): (u32, u32) = (args[2].parse().unwrap(), args[3].parse().unwrap());
    let b = lamplight_scene::builtin::find(name).unwrap();
    let t = std::time::Instant::now();
    let scene = (b.build)(w as f64 / h as f64).unwrap();
    if std::env::var_os("BOUNDS").is_some() {
        for (i, o) in scene.objects.iter().enumerate() {
            eprintln!("{i} {:?} {:?}", o.shape.bounds(), std::any::type_name_of_val(&*o.shape));
        }
    }
    let opts = lamplight_core::RenderOptions {
        width: w,
        height: h,
        spp: args.get(5).map(|s| s.parse().unwrap()).unwrap_or(1),
        ..Default::default()
    };
    let (img, stats) = lamplight_core::render(&scene, &opts, &Default::default()).unwrap();
    eprintln!("{:?} build+render {:?} rays {}", stats.elapsed, t.elapsed(), stats.rays.total());
    image::save_buffer(&args[4], &img.to_srgb8(), w, h, image::ExtendedColorType::Rgb8).unwrap();
    if let Some(p) = args.get(6) {
        let f: Vec<f32> = img.pixels.iter().flat_map(|p| *p).collect();
        std::fs::write(p, f.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>()).unwrap();
    }
}
#[allow(dead_code)]
fn _x() {}
