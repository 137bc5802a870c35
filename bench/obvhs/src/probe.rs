//! Watertightness probe: a rotated, triangulated 64 x 64 grid (a continuous sheet)
//! and rays aimed exactly at its interior vertices and at points on its interior
//! edges. Every such ray crosses the sheet, so a miss is a leak through a crack
//! between neighbouring triangles.

use glam::{Mat3, Vec3};

/// The sheet: positions and triangles.
pub fn sheet() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let n = 64u32;
    let rot = Mat3::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.1);
    let shift = Vec3::new(0.3, -1.7, 2.1);
    let positions = (0..=n)
        .flat_map(|y| (0..=n).map(move |x| (x, y)))
        .map(|(x, y)| (rot * Vec3::new(x as f32 / 8.0, y as f32 / 8.0, 0.0) + shift).to_array())
        .collect();
    let id = |x: u32, y: u32| y * (n + 1) + x;
    let indices = (0..n)
        .flat_map(|y| (0..n).flat_map(move |x| [[id(x, y), id(x + 1, y), id(x + 1, y + 1)], [id(x, y), id(x + 1, y + 1), id(x, y + 1)]]))
        .collect();
    (positions, indices)
}

/// `count` rays from both sides of the sheet at its interior vertices and edge
/// points (deterministic pseudo-random choice).
pub fn rays(positions: &[[f32; 3]], count: usize) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let n = 64usize;
    let p = |x: usize, y: usize| Vec3::from_array(positions[y * (n + 1) + x]);
    let normal = (p(1, 0) - p(0, 0)).cross(p(0, 1) - p(0, 0)).normalize();
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut origins, mut dirs) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for i in 0..count {
        let (x, y) = (1 + (next() * (n - 2) as f64) as usize, 1 + (next() * (n - 2) as f64) as usize);
        let a = p(x, y);
        // Vertex, or a point on the edge to the right, above, or along the diagonal.
        let target = match i % 4 {
            0 => a,
            k => {
                let b = [p(x + 1, y), p(x, y + 1), p(x + 1, y + 1)][k - 1];
                a + (b - a) * next() as f32
            }
        };
        let side = if i % 8 < 4 { 1.0 } else { -1.0 };
        let lateral = Vec3::new(next() as f32 - 0.5, next() as f32 - 0.5, next() as f32 - 0.5) * 2.0;
        let origin = target + normal * side * (0.5 + 2.0 * next() as f32) + lateral;
        origins.push(origin.to_array());
        dirs.push((target - origin).to_array());
    }
    (origins, dirs)
}
