//! Smooth vertex normals for a mesh whose file has none, weighted by the angle
//! each face makes at the vertex (Thürmer and Wüthrich, "Computing Vertex
//! Normals from Polygonal Facets", JGT 1998), the weighting Mitsuba 3 uses for
//! meshes without normals and the one that does not depend on how a surface
//! happens to be cut into triangles.
//!
//! `n_v = normalize(sum over faces f at v of alpha_f(v) n_f)`, with `n_f` the
//! face's unit normal and `alpha_f(v)` its interior angle at `v`. Faces of zero
//! area add nothing; a vertex whose sum vanishes (no face with area, or faces
//! that cancel) gets a zero normal, which the mesh reads as "use the face's".

use super::face_normal;
use crate::math::Vec3;

impl super::TriangleMesh {
    /// The angle-weighted vertex normals of `positions` and `indices` (see the
    /// module documentation); indices must be in range.
    pub fn angle_weighted_normals(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
        let mut sums = vec![Vec3::ZERO; positions.len()];
        for face in indices {
            let p = face.map(|i| positions[i as usize]);
            let Some(n) = face_normal(p[0], p[1], p[2]) else { continue };
            for corner in 0..3 {
                let (a, b) = (p[(corner + 1) % 3] - p[corner], p[(corner + 2) % 3] - p[corner]);
                let angle = a.angle_between(b);
                if angle.is_finite() {
                    sums[face[corner] as usize] += n * angle;
                }
            }
        }
        sums.into_iter().map(Vec3::normalize_or_zero).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::TriangleMesh;
    use crate::math::Vec3;

    #[test]
    fn a_cube_corner_gets_the_diagonal_however_its_faces_are_cut() {
        // The corner at the origin of the unit cube's three faces x = 0, y = 0,
        // z = 0 (outward -x, -y, -z): one face cut into two triangles at the
        // corner, one cut along its diagonal, the third fanned into three.
        let positions = vec![
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
        ];
        let indices = vec![
            [0, 2, 1], // x = 0, two triangles meeting at the corner (angles 45 + 45)
            [0, 3, 2],
            [0, 4, 5], // y = 0, one half (45 degrees at the corner) and the other half not at it
            [0, 5, 3],
            [0, 1, 7], // z = 0, fanned into three (26.6 + 18.4 + 45 degrees)
            [0, 7, 6],
            [0, 6, 4],
        ];
        let n = TriangleMesh::angle_weighted_normals(&positions, &indices);
        let diagonal = -Vec3::ONE.normalize();
        assert!((n[0] - diagonal).length() < 1e-12, "{}", n[0]);
        // A vertex on one face only takes that face's normal.
        assert!((n[2] - -Vec3::X).length() < 1e-12, "{}", n[2]);
    }

    #[test]
    fn degenerate_faces_and_lone_vertices_give_zero() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0), Vec3::Y];
        let n = TriangleMesh::angle_weighted_normals(&positions, &[[0, 1, 2]]);
        assert!(n.iter().all(|v| *v == Vec3::ZERO), "{n:?}");
    }
}
