use super::*;
use crate::sampling::Rng;
use std::collections::HashMap;

fn unit_vector(rng: &mut Rng) -> Vec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// Orders each face counter-clockwise seen from outside a mesh that is star-shaped
/// around the origin.
fn orient_outward(positions: &[Vec3], indices: &mut [[u32; 3]]) {
    for f in indices.iter_mut() {
        let [a, b, c] = f.map(|i| positions[i as usize]);
        if (b - a).cross(c - a).dot(a + b + c) < 0.0 {
            f.swap(1, 2);
        }
    }
}

/// The octahedron with vertices at +-1 on every axis, optionally with vertex normals.
fn octahedron(normals: bool) -> TriangleMesh {
    let positions = vec![Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let mut indices = Vec::new();
    for x in [0u32, 1] {
        for y in [2u32, 3] {
            for z in [4u32, 5] {
                indices.push([x, y, z]);
            }
        }
    }
    orient_outward(&positions, &mut indices);
    let n = normals.then(|| positions.clone());
    TriangleMesh::new(positions, indices, n).unwrap()
}

/// The cube `[-1, 1]^3` with every face cut into `n x n` squares of two triangles,
/// vertices shared: a closed mesh whose triangles have flat (zero-thickness) boxes.
fn subdivided_cube(n: i32) -> TriangleMesh {
    let mut positions = Vec::new();
    let mut ids: HashMap<[i32; 3], u32> = HashMap::new();
    let mut vertex = |g: [i32; 3]| {
        *ids.entry(g).or_insert_with(|| {
            positions.push(Vec3::new(g[0] as f64, g[1] as f64, g[2] as f64) * (2.0 / n as f64) - Vec3::ONE);
            (positions.len() - 1) as u32
        })
    };
    let mut indices = Vec::new();
    for axis in 0..3 {
        for side in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let corner = |di: i32, dj: i32| {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[(axis + 1) % 3] = i + di;
                        g[(axis + 2) % 3] = j + dj;
                        g
                    };
                    let [a, b, c, d] = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)].map(&mut vertex);
                    indices.push([a, b, c]);
                    indices.push([a, c, d]);
                }
            }
        }
    }
    orient_outward(&positions, &mut indices);
    TriangleMesh::new(positions, indices, None).unwrap()
}

/// Nearest hit over every face, without the BVH.
fn brute_force(mesh: &TriangleMesh, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let w = WatertightRay::new(ray);
    (0..mesh.face_count() as u32)
        .filter_map(|f| {
            let [p0, p1, p2] = mesh.face_vertices(f);
            intersect_triangle(&w, p0, p1, p2, t_min, t_max).map(|h| h.t)
        })
        .min_by(f64::total_cmp)
}

/// Edges of the mesh, each once.
fn edges(mesh: &TriangleMesh) -> Vec<(Vec3, Vec3)> {
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for f in mesh.indices() {
        for k in 0..3 {
            let (a, b) = (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3]));
            if seen.insert((a, b)) {
                out.push((mesh.positions()[a as usize], mesh.positions()[b as usize]));
            }
        }
    }
    out
}

/// Points exactly at vertices and (up to rounding) on edges.
fn edge_and_vertex_targets(mesh: &TriangleMesh, rng: &mut Rng, per_edge: usize) -> Vec<Vec3> {
    let mut targets = mesh.positions().to_vec();
    for (a, b) in edges(mesh) {
        targets.push((a + b) * 0.5);
        for _ in 0..per_edge {
            targets.push(a + (b - a) * rng.uniform());
        }
    }
    targets
}

#[test]
fn rays_through_edges_and_vertices_never_leak() {
    let mut rng = Rng::for_sample(3, 0, 0);
    for mesh in [octahedron(false), subdivided_cube(4)] {
        let targets = edge_and_vertex_targets(&mesh, &mut rng, 20);
        assert!(targets.len() > 100);
        for target in targets {
            // From inside (the centre and random interior points) out through the target.
            for origin in [Vec3::ZERO, unit_vector(&mut rng) * 0.3 * rng.uniform()] {
                let dist = (target - origin).length();
                let ray = Ray::new(origin, target - origin);
                let hit = mesh.intersect(&ray, 0.0, f64::INFINITY);
                assert!(hit.is_some_and(|h| (h.t - dist).abs() <= 1e-12 * dist), "leak from {origin} through {target}: {hit:?}");
                assert!(mesh.intersect_p(&ray, 0.0, f64::INFINITY));
            }
            // From outside along the line from the centre, entering through the target.
            let origin = target * (2.0 + 3.0 * rng.uniform());
            let ray = Ray::new(origin, -origin);
            let dist = (target - origin).length();
            let hit = mesh.intersect(&ray, 0.0, f64::INFINITY);
            assert!(hit.is_some_and(|h| (h.t - dist).abs() <= 1e-12 * dist), "leak from {origin} through {target}: {hit:?}");
        }
    }
}

#[test]
fn rays_crossing_a_closed_mesh_hit_it_an_even_number_of_times() {
    let mut rng = Rng::for_sample(5, 0, 0);
    let mesh = subdivided_cube(3);
    let mut crossings = 0;
    for _ in 0..3000 {
        let origin = unit_vector(&mut rng) * 4.0;
        let ray = Ray::new(origin, unit_vector(&mut rng) * 1.2 - origin);
        let mut t = 0.0;
        let mut count = 0;
        while let Some(hit) = mesh.intersect(&ray, t, f64::INFINITY) {
            t = hit.t;
            count += 1;
            assert!(count < 10, "runaway");
        }
        assert!(count == 0 || count == 2, "convex mesh crossed {count} times by {ray:?}");
        crossings += usize::from(count == 2);
    }
    assert!(crossings > 1000, "{crossings}");
}

#[test]
fn bvh_answers_equal_brute_force() {
    let mut rng = Rng::for_sample(9, 0, 0);
    for mesh in [octahedron(false), subdivided_cube(5)] {
        let mut targets = edge_and_vertex_targets(&mesh, &mut rng, 3);
        targets.extend((0..2000).map(|_| unit_vector(&mut rng) * 1.5 * rng.uniform()));
        for target in targets {
            let origin = unit_vector(&mut rng) * (1.0 + 4.0 * rng.uniform());
            let ray = Ray::new(origin, target - origin);
            let t_max = if rng.uniform() < 0.2 { 3.0 * rng.uniform() } else { f64::INFINITY };
            let expected = brute_force(&mesh, &ray, 0.0, t_max);
            let got = mesh.intersect_triangle_index(&ray, 0.0, t_max);
            assert_eq!(got.is_some(), expected.is_some(), "{ray:?}");
            assert_eq!(mesh.intersect_p(&ray, 0.0, t_max), expected.is_some());
            if let (Some((hit, face)), Some(t)) = (got, expected) {
                assert!((hit.t - t).abs() <= 1e-12 * t, "{} vs {t}", hit.t);
                let [p0, p1, p2] = mesh.face_vertices(face);
                let on_face = intersect_triangle(&WatertightRay::new(&ray), p0, p1, p2, 0.0, t_max).unwrap();
                assert_eq!(on_face.t, hit.t, "reported face is the one hit");
            }
        }
    }
}

#[test]
fn normals_interpolate_and_face_outward() {
    let mesh = octahedron(true);
    // At a vertex the interpolated normal is that vertex's normal.
    for (i, p) in mesh.positions().iter().enumerate() {
        let hit = mesh.intersect(&Ray::new(p * 3.0, -*p), 0.0, f64::INFINITY).unwrap();
        assert!((hit.shading_normal - mesh.normals().unwrap()[i]).length() < 1e-12);
        assert!((hit.t - 2.0).abs() < 1e-12);
    }
    // At a face centre it is the normalized mean of the three, here the face normal.
    let centre = Vec3::new(1.0, 1.0, 1.0) / 3.0;
    let hit = mesh.intersect(&Ray::new(Vec3::ZERO, centre), 0.0, f64::INFINITY).unwrap();
    let expected = Vec3::ONE.normalize();
    assert!((hit.normal - expected).length() < 1e-12 && (hit.shading_normal - expected).length() < 1e-12);
    // Elsewhere interpolation bends it; inward vertex normals are turned outward.
    let inward: Vec<Vec3> = mesh.positions().iter().map(|p| -*p).collect();
    let flipped = TriangleMesh::new(mesh.positions().to_vec(), mesh.indices().to_vec(), Some(inward)).unwrap();
    let target = Vec3::new(0.6, 0.3, 0.1);
    let a = mesh.intersect(&Ray::new(Vec3::ZERO, target), 0.0, f64::INFINITY).unwrap();
    let b = flipped.intersect(&Ray::new(Vec3::ZERO, target), 0.0, f64::INFINITY).unwrap();
    let bent = (Vec3::X * 0.6 + Vec3::Y * 0.3 + Vec3::Z * 0.1).normalize();
    assert!((a.shading_normal - bent).length() < 1e-12, "{}", a.shading_normal);
    assert!((b.shading_normal - bent).length() < 1e-12, "flipped to the face's side: {}", b.shading_normal);
    assert!(b.shading_normal.dot(b.normal) > 0.0);
}

#[test]
fn degenerate_faces_keep_their_numbers_and_are_never_hit() {
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 2.0, Vec3::new(0.0, 0.0, 1.0)];
    // Face 0 is collinear, face 1 is repeated-vertex, face 2 is real.
    let mesh = TriangleMesh::new(positions, vec![[0, 1, 3], [1, 1, 2], [0, 1, 2]], None).unwrap();
    assert_eq!(mesh.face_count(), 3);
    assert_eq!(mesh.primitive_count(), 3);
    assert_eq!(mesh.degenerate_face_count(), 2);
    let (hit, face) = mesh.intersect_triangle_index(&Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z), 0.0, f64::INFINITY).unwrap();
    assert_eq!(face, 2);
    assert_eq!(hit.normal, Vec3::Z);
    assert!(mesh.intersect(&Ray::new(Vec3::new(1.5, 0.0, 1.0), -Vec3::Z), 0.0, f64::INFINITY).is_none());
    assert_eq!(mesh.bounds(), Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)), "bounds of the faces that can be hit");
}

#[test]
fn invalid_meshes_are_rejected_with_the_place_named() {
    let tri = || vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let err = TriangleMesh::new(tri(), vec![[0, 1, 2], [0, 7, 2]], None).unwrap_err().to_string();
    assert!(err.contains("face 1") && err.contains("vertex 7"), "{err}");
    let mut bad = tri();
    bad[1].y = f64::NAN;
    let err = TriangleMesh::new(bad, vec![[0, 1, 2]], None).unwrap_err().to_string();
    assert!(err.contains("vertex 1"), "{err}");
    let err = TriangleMesh::new(tri(), vec![[0, 1, 2]], Some(vec![Vec3::Z; 2])).unwrap_err().to_string();
    assert!(err.contains("2 normals for 3 vertices"), "{err}");
    assert!(TriangleMesh::new(tri(), vec![[0, 1, 2]], Some(vec![Vec3::Z, Vec3::Z, Vec3::INFINITY])).is_err());
    assert!(TriangleMesh::new(tri(), vec![], None).is_err());
    assert!(matches!(TriangleMesh::new(tri(), vec![[0, 0, 1]], None), Err(Error::DegenerateGeometry(_))));
}

#[test]
fn attributes_are_interpolated_at_the_hit() {
    // A quad in z = 0 from (0, 0) to (2, 1) with (u, v) = (x / 2, y) and a colour ramp in x.
    let positions = vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let uvs = positions.iter().map(|p| [p.x / 2.0, p.y]).collect();
    let colors = positions.iter().map(|p| Rgb::new(p.x / 2.0, 0.0, 1.0)).collect();
    let tangents = vec![[1.0, 0.0, 0.0, 1.0]; 4];
    let mesh = TriangleMesh::new(positions, vec![[0, 1, 2], [0, 2, 3]], None)
        .unwrap()
        .with_attributes(VertexAttributes { uvs: Some(uvs), colors: Some(colors), tangents: Some(tangents), ..Default::default() })
        .unwrap();
    for (x, y) in [(1.5, 0.25), (0.5, 0.75)] {
        let hit = mesh.intersect(&Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z), 0.0, f64::INFINITY).unwrap();
        let c = mesh.surface_coords(Vec3::new(x, y, 0.0), hit.normal, hit.primitive());
        assert!((c.uv[0] - x / 2.0).abs() < 1e-12 && (c.uv[1] - y).abs() < 1e-12, "{:?}", c.uv);
        assert!((c.dpdu - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-12 && (c.dpdv - Vec3::Y).length() < 1e-12);
        assert!((c.color.unwrap() - Rgb::new(x / 2.0, 0.0, 1.0)).length() < 1e-12);
        assert_eq!(c.tangent, Some((Vec3::X, 1.0)));
    }
    let bad = TriangleMesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]], None).unwrap();
    let err = bad.with_attributes(VertexAttributes { uvs: Some(vec![[0.0, 0.0]]), ..Default::default() }).unwrap_err();
    assert_eq!(err.to_string(), "invalid texture coordinates: 1 values for 3 vertices");
}

#[test]
fn face_colours_are_constant_over_each_face_and_win_over_vertex_colours() {
    // The quad of the test above, its two triangles coloured 0.25 and 0.75 grey.
    let positions = vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let attributes = VertexAttributes {
        colors: Some(vec![Rgb::ONE; 4]),
        face_colors: Some(vec![Rgb::splat(0.25), Rgb::splat(0.75)]),
        ..Default::default()
    };
    let mesh = TriangleMesh::new(positions, vec![[0, 1, 2], [0, 2, 3]], None).unwrap().with_attributes(attributes).unwrap();
    // Below the diagonal (face 0) and above it (face 1), near and far from the corners.
    for (x, y, grey) in [(1.9, 0.05, 0.25), (1.0, 0.4, 0.25), (0.1, 0.9, 0.75), (0.9, 0.6, 0.75)] {
        let hit = mesh.intersect(&Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z), 0.0, f64::INFINITY).unwrap();
        let c = mesh.surface_coords(Vec3::new(x, y, 0.0), hit.normal, hit.primitive());
        assert_eq!(c.color, Some(Rgb::splat(grey)), "({x}, {y})");
    }
    let one = TriangleMesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]], None).unwrap();
    let err = one.clone().with_attributes(VertexAttributes { face_colors: Some(vec![Rgb::ONE; 2]), ..Default::default() }).unwrap_err();
    assert_eq!(err.to_string(), "invalid face colors: 2 values for 1 faces");
    let nan = VertexAttributes { face_colors: Some(vec![Rgb::splat(f64::NAN)]), ..Default::default() };
    assert!(one.with_attributes(nan).unwrap_err().to_string().contains("face 0"));
}
