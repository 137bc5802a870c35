//! Indexed triangle mesh with its own BVH.
//!
//! A mesh is a list of vertex positions and a list of faces, each three indices
//! into it (counter-clockwise seen from outside is the front, as for
//! [`super::Triangle`]), with optional per-vertex normals. Every face is
//! intersected with the watertight kernel [`super::intersect_triangle`], so a
//! closed mesh has no cracks along its shared edges and vertices.
//!
//! Normals: the geometric normal of a hit is the face's
//! `normalize((p1 - p0) x (p2 - p0))`. With vertex normals, the shading normal is
//! the barycentric interpolation `b0 n0 + b1 n1 + b2 n2`, normalized, and negated
//! if it points to the other side of the face than the geometric normal (the
//! renderer keeps both outward); where the interpolation vanishes it is the
//! geometric normal.
//!
//! Faces with zero area are kept, so that face `i` is still face `i` of the file
//! (for the ids that [`TriangleMesh::intersect_triangle_index`] reports), but left
//! out of the BVH: no ray ever hits them.
//!
//! Vertex attributes ([`VertexAttributes`]: texture coordinates, colours,
//! tangents) are interpolated barycentrically at shading time, the weights
//! recomputed from the hit point ([`super::surface::barycentric`]), so a hit
//! carries nothing more than before. Without texture coordinates a face's
//! corners are at `(0, 0)`, `(1, 0)`, `(1, 1)` (pbrt-v4's default); `dp/du`,
//! `dp/dv` are the face's ([`super::surface::triangle_tangents`]).
//!
//! The mesh is one object of the scene; its BVH over its own faces (one box per
//! triangle) makes the scene a two-level hierarchy, so a mesh placed twice is
//! stored once.

use super::surface::{barycentric, triangle_tangents};
use super::triangle::{face_normal, intersect_triangle, TriangleHit, WatertightRay, DEFAULT_UV};
use super::{Shape, SurfaceCoords, SurfaceHit};
use crate::accel::{Aabb, Bvh};
use crate::math::{Rgb, Vec3};
use crate::ray::Ray;
use crate::Error;

/// An indexed triangle mesh.
#[derive(Clone, Debug)]
pub struct TriangleMesh {
    positions: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    normals: Option<Vec<Vec3>>,
    bvh: Bvh,
    /// BVH primitive -> face index, when some faces are degenerate (`None`: identity).
    faces_in_bvh: Option<Vec<u32>>,
    bounds: Aabb,
    attributes: VertexAttributes,
}

/// Per-vertex data a mesh interpolates for shading, each list one entry per
/// vertex when present.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VertexAttributes {
    /// Texture coordinates (glTF `TEXCOORD_0`, OBJ `vt`, PLY `u v`).
    pub uvs: Option<Vec<[f64; 2]>>,
    /// A second set of texture coordinates (glTF `TEXCOORD_1`).
    pub uvs1: Option<Vec<[f64; 2]>>,
    /// Linear RGB colours (glTF `COLOR_0`, PLY `red green blue`).
    pub colors: Option<Vec<Rgb>>,
    /// Colours constant over each face, one per triangle (a PLY face attribute
    /// that a Mitsuba `mesh_attribute` reads): where present, the mesh's colour
    /// is its face's, not the interpolated `colors`.
    pub face_colors: Option<Vec<Rgb>>,
    /// Tangents `(x, y, z, w)`, `w = +-1` the bitangent's sign (glTF `TANGENT`, or MikkTSpace).
    pub tangents: Option<Vec<[f64; 4]>>,
}

/// The coordinates at `p` of the face `v` with corner texture coordinates `uv`,
/// its weights from the point.
pub(super) fn interpolated_coords(p: Vec3, v: [Vec3; 3], uv: [[f64; 2]; 3], normal: Vec3) -> SurfaceCoords {
    let b = barycentric(p, v[0], v[1], v[2]);
    let at = |k: usize| uv[0][k] * b[0] + uv[1][k] * b[1] + uv[2][k] * b[2];
    let (dpdu, dpdv) = triangle_tangents(v, uv, normal);
    SurfaceCoords::new([at(0), at(1)], dpdu, dpdv)
}

impl TriangleMesh {
    /// A mesh from vertex `positions`, faces `indices` (three vertex indices each)
    /// and optional per-vertex `normals` (one per position; normalized here).
    ///
    /// Errors: no faces, a non-finite coordinate, an index out of range (the message
    /// names the face and the index), a normals list of the wrong length or with a
    /// non-finite component, or every face degenerate. Degenerate faces among good
    /// ones are accepted and never hit (see the module docs).
    pub fn new(positions: Vec<Vec3>, indices: Vec<[u32; 3]>, normals: Option<Vec<Vec3>>) -> Result<TriangleMesh, Error> {
        if indices.is_empty() {
            return Err(Error::invalid("indices", "a mesh needs at least one face"));
        }
        if positions.len() > u32::MAX as usize {
            return Err(Error::invalid("positions", "more vertices than 32-bit indices can address"));
        }
        // A hit names its face by a u32 below `SurfaceHit::NO_PRIMITIVE`.
        if indices.len() >= SurfaceHit::NO_PRIMITIVE as usize {
            return Err(Error::invalid("indices", "more faces than 32-bit face indices can address"));
        }
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(Error::invalid("positions", format!("vertex {i} is not finite: {}", positions[i])));
        }
        for (face, idx) in indices.iter().enumerate() {
            if let Some(&bad) = idx.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(Error::invalid(
                    "indices",
                    format!("face {face} refers to vertex {bad}, but there are only {} vertices", positions.len()),
                ));
            }
        }
        let normals = match normals {
            None => None,
            Some(n) if n.len() != positions.len() => {
                return Err(Error::invalid("normals", format!("{} normals for {} vertices", n.len(), positions.len())));
            }
            Some(n) => {
                if let Some(i) = n.iter().position(|v| !v.is_finite()) {
                    return Err(Error::invalid("normals", format!("normal {i} is not finite: {}", n[i])));
                }
                // A zero normal stays zero; the hit then falls back to the face normal.
                Some(n.into_iter().map(|v| v.normalize_or_zero()).collect())
            }
        };

        let mut boxes = Vec::with_capacity(indices.len());
        let mut live = Vec::with_capacity(indices.len());
        for (face, idx) in indices.iter().enumerate() {
            let [p0, p1, p2] = idx.map(|i| positions[i as usize]);
            if face_normal(p0, p1, p2).is_some() {
                boxes.push(Aabb::from_points([p0, p1, p2]));
                live.push(face as u32);
            }
        }
        if boxes.is_empty() {
            return Err(Error::DegenerateGeometry(format!("all {} faces of the mesh have zero area", indices.len())));
        }
        let faces_in_bvh = (live.len() != indices.len()).then_some(live);
        let bvh = Bvh::build(&boxes);
        let bounds = bvh.bounds();
        Ok(TriangleMesh { positions, indices, normals, bvh, faces_in_bvh, bounds, attributes: VertexAttributes::default() })
    }

    /// This mesh with per-vertex `attributes`. Errors: a list whose length is
    /// not the vertex count, or a value that is not finite (named with its vertex).
    pub fn with_attributes(mut self, attributes: VertexAttributes) -> Result<TriangleMesh, Error> {
        let n = self.positions.len();
        fn check<T>(name: &str, list: &Option<Vec<T>>, n: usize, finite: impl Fn(&T) -> bool) -> Result<(), Error> {
            let Some(list) = list else { return Ok(()) };
            if list.len() != n {
                return Err(Error::invalid(name, format!("{} values for {n} vertices", list.len())));
            }
            match list.iter().position(|x| !finite(x)) {
                Some(i) => Err(Error::invalid(name, format!("the value of vertex {i} is not finite"))),
                None => Ok(()),
            }
        }
        check("texture coordinates", &attributes.uvs, n, |uv| uv.iter().all(|x| x.is_finite()))?;
        check("second texture coordinates", &attributes.uvs1, n, |uv| uv.iter().all(|x| x.is_finite()))?;
        check("colors", &attributes.colors, n, |c| c.is_finite())?;
        if let Some(faces) = &attributes.face_colors {
            if faces.len() != self.indices.len() {
                return Err(Error::invalid("face colors", format!("{} values for {} faces", faces.len(), self.indices.len())));
            }
            if let Some(i) = faces.iter().position(|c| !c.is_finite()) {
                return Err(Error::invalid("face colors", format!("the value of face {i} is not finite")));
            }
        }
        check("tangents", &attributes.tangents, n, |t| t.iter().all(|x| x.is_finite()))?;
        self.attributes = attributes;
        Ok(self)
    }

    /// The per-vertex attributes.
    pub fn attributes(&self) -> &VertexAttributes {
        &self.attributes
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Faces, three vertex indices each, in file order.
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }

    /// Unit per-vertex normals (zero where the input normal was zero), if given.
    pub fn normals(&self) -> Option<&[Vec3]> {
        self.normals.as_deref()
    }

    /// Number of faces, degenerate ones included.
    pub fn face_count(&self) -> usize {
        self.indices.len()
    }

    /// Number of zero-area faces, which are never hit.
    pub fn degenerate_face_count(&self) -> usize {
        self.faces_in_bvh.as_ref().map_or(0, |live| self.indices.len() - live.len())
    }

    /// The mesh's own BVH (statistics).
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The three vertices of face `face`.
    #[inline]
    pub fn face_vertices(&self, face: u32) -> [Vec3; 3] {
        self.indices[face as usize].map(|i| self.positions[i as usize])
    }

    #[inline]
    fn face_of(&self, prim: u32) -> u32 {
        match &self.faces_in_bvh {
            Some(live) => live[prim as usize],
            None => prim,
        }
    }

    /// The nearest hit in `(t_min, t_max)` and the index of the face hit (its
    /// position in `indices`).
    pub fn intersect_triangle_index(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(SurfaceHit, u32)> {
        let w = WatertightRay::new(ray);
        let mut best: Option<(TriangleHit, u32)> = None;
        self.bvh.traverse(ray.origin, ray.dir, t_min, t_max, |prim, t_max| {
            let face = self.face_of(prim);
            let [p0, p1, p2] = self.face_vertices(face);
            let hit = intersect_triangle(&w, p0, p1, p2, t_min, t_max)?;
            best = Some((hit, face));
            Some(hit.t)
        });
        let (hit, face) = best?;
        Some((self.surface_hit(face, &hit), face))
    }

    /// Normals of a hit on `face`: the face normal, and the interpolated vertex
    /// normal turned to the same side.
    fn surface_hit(&self, face: u32, hit: &TriangleHit) -> SurfaceHit {
        let [p0, p1, p2] = self.face_vertices(face);
        // Faces in the BVH have non-zero area, so this is `Some`; the fallback only keeps NaN out.
        let normal = face_normal(p0, p1, p2).unwrap_or(Vec3::Z);
        let shading_normal = match &self.normals {
            None => normal,
            Some(n) => {
                let [i0, i1, i2] = self.indices[face as usize];
                let interpolated = n[i0 as usize] * hit.b0 + n[i1 as usize] * hit.b1 + n[i2 as usize] * hit.b2;
                match interpolated.try_normalize() {
                    Some(s) if s.dot(normal) < 0.0 => -s,
                    Some(s) => s,
                    None => normal,
                }
            }
        };
        SurfaceHit { t: hit.t, normal, shading_normal, error: 0.0, primitive_index: face }
    }
}

impl Shape for TriangleMesh {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        self.intersect_triangle_index(ray, t_min, t_max).map(|(hit, _)| hit)
    }

    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let w = WatertightRay::new(ray);
        self.bvh.any(ray.origin, ray.dir, t_min, t_max, |prim| {
            let [p0, p1, p2] = self.face_vertices(self.face_of(prim));
            intersect_triangle(&w, p0, p1, p2, t_min, t_max).is_some()
        })
    }

    fn primitive_count(&self) -> usize {
        self.indices.len()
    }

    fn triangles(&self) -> Option<Vec<[Vec3; 3]>> {
        Some((0..self.indices.len() as u32).map(|f| self.face_vertices(f)).collect())
    }

    fn surface_coords(&self, p: Vec3, n: Vec3, primitive: Option<u32>) -> SurfaceCoords {
        let Some(face) = primitive.filter(|&f| (f as usize) < self.indices.len()) else {
            return SurfaceCoords::unparametrized(n);
        };
        let idx = self.indices[face as usize].map(|i| i as usize);
        let v = idx.map(|i| self.positions[i]);
        let a = &self.attributes;
        let uv = a.uvs.as_ref().map_or(DEFAULT_UV, |uvs| idx.map(|i| uvs[i]));
        let normal = face_normal(v[0], v[1], v[2]).unwrap_or(n);
        let mut coords = interpolated_coords(p, v, uv, normal);
        coords.uv1 = a.uvs1.as_ref().map(|uvs| {
            let c = interpolated_coords(p, v, idx.map(|i| uvs[i]), normal);
            super::surface::SecondUv { uv: c.uv, dpdu: c.dpdu, dpdv: c.dpdv }
        });
        let b = barycentric(p, v[0], v[1], v[2]);
        coords.color = match &a.face_colors {
            Some(f) => Some(f[face as usize]),
            None => a.colors.as_ref().map(|c| c[idx[0]] * b[0] + c[idx[1]] * b[1] + c[idx[2]] * b[2]),
        };
        coords.tangent = a.tangents.as_ref().and_then(|t| {
            let [t0, t1, t2] = idx.map(|i| t[i]);
            let xyz = |t: [f64; 4]| Vec3::new(t[0], t[1], t[2]);
            // The sign is per vertex (a mirrored UV island): the nearest corner's.
            let nearest = if b[0] >= b[1] && b[0] >= b[2] {
                t0
            } else if b[1] >= b[2] {
                t1
            } else {
                t2
            };
            let w = if nearest[3] < 0.0 { -1.0 } else { 1.0 };
            (xyz(t0) * b[0] + xyz(t1) * b[1] + xyz(t2) * b[2]).try_normalize().map(|t| (t, w))
        });
        coords
    }
}

mod vertex_normals;

#[cfg(test)]
mod tests;
