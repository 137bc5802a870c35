//! Tangents for normal maps where a mesh has texture coordinates but no
//! `TANGENT`: MikkTSpace (the `mikktspace` crate), as the glTF specification
//! asks, computed in lamplight's `v`-up coordinates so that `w (n x t)` points
//! up the image, where a normal map's `+y` points.
//!
//! MikkTSpace gives a tangent per face corner; a vertex shared by corners with
//! different tangents (a UV seam the file did not split) gets their normalized
//! sum, with the sign most of its corners have.

use super::MeshData;
use lamplight_core::math::Vec3;

struct Geometry<'a> {
    mesh: &'a MeshData,
    uvs: &'a [[f64; 2]],
    sums: Vec<([f64; 3], f64)>,
}

impl Geometry<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face][vert] as usize
    }
}

impl mikktspace::Geometry for Geometry<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].as_vec3().to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        let n = match &self.mesh.normals {
            Some(n) => n[self.vertex(face, vert)],
            None => {
                let [a, b, c] = self.mesh.indices[face].map(|i| self.mesh.positions[i as usize]);
                (b - a).cross(c - a).normalize_or_zero()
            }
        };
        n.as_vec3().to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, vert)].map(|x| x as f32)
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        let v = self.vertex(face, vert);
        let (sum, sign) = &mut self.sums[v];
        for k in 0..3 {
            sum[k] += f64::from(tangent[k]);
        }
        *sign += f64::from(tangent[3]);
    }
}

/// Fills `mesh.attributes.tangents` from its texture coordinates when it has
/// those and no tangents; false when MikkTSpace could not (no faces).
pub(super) fn generate(mesh: &mut MeshData) -> bool {
    if mesh.attributes.tangents.is_some() {
        return true;
    }
    let Some(uvs) = mesh.attributes.uvs.clone() else { return false };
    let mut g = Geometry { mesh, uvs: &uvs, sums: vec![([0.0; 3], 0.0); mesh.positions.len()] };
    if !mikktspace::generate_tangents(&mut g) {
        return false;
    }
    let tangents = g
        .sums
        .iter()
        .map(|(t, s)| {
            let t = Vec3::from_array(*t).normalize_or_zero();
            [t.x, t.y, t.z, if *s < 0.0 { -1.0 } else { 1.0 }]
        })
        .collect();
    mesh.attributes.tangents = Some(tangents);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quad_gets_the_direction_of_u_and_a_bitangent_up_v() {
        // (u, v) = (x, y) on the quad in z = 0, normals +z: t = +x, w (n x t) = +y.
        let mut mesh = MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            normals: Some(vec![Vec3::Z; 4]),
            ..MeshData::default()
        };
        mesh.attributes.uvs = Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert!(generate(&mut mesh));
        for t in mesh.attributes.tangents.as_ref().unwrap() {
            let (tangent, w) = (Vec3::new(t[0], t[1], t[2]), t[3]);
            assert!((tangent - Vec3::X).length() < 1e-6, "{tangent}");
            assert!(((Vec3::Z.cross(tangent) * w) - Vec3::Y).length() < 1e-6);
        }
        // Mirrored v: the bitangent follows it.
        mesh.attributes.tangents = None;
        mesh.attributes.uvs = Some(vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
        assert!(generate(&mut mesh));
        let t = mesh.attributes.tangents.as_ref().unwrap()[0];
        assert!((Vec3::Z.cross(Vec3::new(t[0], t[1], t[2])) * t[3] - -Vec3::Y).length() < 1e-6, "{t:?}");
    }
}
