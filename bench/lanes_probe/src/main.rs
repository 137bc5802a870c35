//! A probe, not the renderer: the Cornell box path-traced (NEE with MIS, Russian
//! roulette after 4 segments, Lambertian surfaces, depth 8) by one kernel written
//! over `N` lanes, with `N` paths in lockstep (a finished lane takes the next
//! sample), to measure what lanes give over one path with the same arithmetic:
//! every lane count traces the same rays and computes the same sample values
//! (a pixel's sum may differ in its last bits: lanes finish its samples in
//! another order). Each object
//! is tested for every ray (no boxes), in `f64`. The random values come from a
//! cheap generator, then from one that costs what lamplight's sampler costs
//! (hashed per lane in scalar code). `N` lanes of `f64` are plain arrays whose
//! loops LLVM turns into AVX2 (build with `-C target-cpu=x86-64-v3`); masks are
//! all-ones bit patterns, which it selects with; `bool` masks stayed scalar
//! and were slower than one lane.
use glam::{DMat3, DMat4, DVec3};
use std::ops::{Add, Div, Mul, Sub};

#[derive(Clone, Copy)]
struct V<const N: usize>([f64; N]);
#[derive(Clone, Copy)]
struct M<const N: usize>([u64; N]);

impl<const N: usize> V<N> {
    #[inline(always)]
    fn s(x: f64) -> Self {
        V([x; N])
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut o = self.0;
        for i in 0..N {
            o[i] = f(self.0[i]);
        }
        V(o)
    }
    #[inline(always)]
    fn zip(self, b: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut o = self.0;
        for i in 0..N {
            o[i] = f(self.0[i], b.0[i]);
        }
        V(o)
    }
    #[inline(always)]
    fn cmp(self, b: Self, f: impl Fn(f64, f64) -> bool) -> M<N> {
        let mut o = [0u64; N];
        for i in 0..N {
            o[i] = if f(self.0[i], b.0[i]) { !0 } else { 0 };
        }
        M(o)
    }
    #[inline(always)]
    fn sel(m: M<N>, a: Self, b: Self) -> Self {
        let mut o = b.0;
        for i in 0..N {
            o[i] = f64::from_bits((a.0[i].to_bits() & m.0[i]) | (b.0[i].to_bits() & !m.0[i]));
        }
        V(o)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
}
impl<const N: usize> M<N> {
    #[inline(always)]
    fn and(self, b: Self) -> Self {
        let mut o = self.0;
        for i in 0..N {
            o[i] &= b.0[i];
        }
        M(o)
    }
    #[inline(always)]
    fn not(self) -> Self {
        let mut o = self.0;
        for i in 0..N {
            o[i] = !o[i];
        }
        M(o)
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().fold(0, |a, &b| a | b) != 0
    }
}
macro_rules! op {
    ($t:ident, $f:ident, $o:tt) => {
        impl<const N: usize> $t for V<N> {
            type Output = V<N>;
            #[inline(always)]
            fn $f(self, b: V<N>) -> V<N> {
                self.zip(b, |x, y| x $o y)
            }
        }
    };
}
op!(Add, add, +);
op!(Sub, sub, -);
op!(Mul, mul, *);
op!(Div, div, /);

#[derive(Clone, Copy)]
struct V3<const N: usize> {
    x: V<N>,
    y: V<N>,
    z: V<N>,
}
impl<const N: usize> V3<N> {
    #[inline(always)]
    fn s(v: DVec3) -> Self {
        V3 { x: V::s(v.x), y: V::s(v.y), z: V::s(v.z) }
    }
    #[inline(always)]
    fn dot(self, b: Self) -> V<N> {
        self.x * b.x + self.y * b.y + self.z * b.z
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        V3 { x: self.x + b.x, y: self.y + b.y, z: self.z + b.z }
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        V3 { x: self.x - b.x, y: self.y - b.y, z: self.z - b.z }
    }
    #[inline(always)]
    fn scale(self, k: V<N>) -> Self {
        V3 { x: self.x * k, y: self.y * k, z: self.z * k }
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        V3 { x: self.x * b.x, y: self.y * b.y, z: self.z * b.z }
    }
    #[inline(always)]
    fn sel(m: M<N>, a: Self, b: Self) -> Self {
        V3 { x: V::sel(m, a.x, b.x), y: V::sel(m, a.y, b.y), z: V::sel(m, a.z, b.z) }
    }
}

struct Rect {
    corner: DVec3,
    eu: DVec3,
    ev: DVec3,
    n: DVec3,
    du: DVec3,
    dv: DVec3,
    albedo: DVec3,
}
fn rect(m: DMat4, albedo: DVec3) -> Rect {
    let corner = m.transform_point3(DVec3::new(-1.0, -1.0, 0.0));
    let eu = m.transform_vector3(DVec3::new(2.0, 0.0, 0.0));
    let ev = m.transform_vector3(DVec3::new(0.0, 2.0, 0.0));
    let n = eu.cross(ev).normalize();
    let (uu, uv, vv) = (eu.dot(eu), eu.dot(ev), ev.dot(ev));
    let det = uu * vv - uv * uv;
    let du = (eu * vv - ev * uv) / det;
    let dv = (ev * uu - eu * uv) / det;
    Rect { corner, eu, ev, n, du, dv, albedo }
}
struct Cube {
    l: DMat3,
    lo: DVec3,
    hi: DVec3,
    normals: [DVec3; 6], // +x,-x,+y,-y,+z,-z world
    albedo: DVec3,
}
fn cube(m: DMat4, albedo: DVec3) -> Cube {
    let inv = m.inverse();
    let l = DMat3::from_mat4(inv);
    let shift = inv.w_axis.truncate();
    let lo = DVec3::NEG_ONE - shift;
    let hi = DVec3::ONE - shift;
    let nm = DMat3::from_mat4(inv).transpose();
    let ax = [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z];
    Cube { l, lo, hi, normals: ax.map(|a| (nm * a).normalize()), albedo }
}

struct Scene {
    rects: Vec<Rect>,
    cubes: Vec<Cube>,
    le: DVec3,
    light_area: f64,
}

/// Nearest hit: (t, normal, albedo index) per lane; t = inf for a miss. `obj` = -1 miss.
#[inline(always)]
fn closest<const N: usize>(s: &Scene, o: V3<N>, d: V3<N>) -> (V<N>, V3<N>, V3<N>, [i32; N]) {
    let zero = V::s(0.0);
    let one = V::s(1.0);
    let mut best = V::<N>::s(f64::INFINITY);
    let mut n = V3::s(DVec3::ZERO);
    let mut alb = V3::s(DVec3::ZERO);
    let mut obj = [-1i32; N];
    for (k, r) in s.rects.iter().enumerate() {
        let nn = V3::s(r.n);
        let c = V3::s(r.corner);
        let denom = d.dot(nn);
        let t = c.sub(o).dot(nn) / denom;
        let p = o.add(d.scale(t));
        let local = p.sub(c);
        let u = local.dot(V3::s(r.du));
        let v = local.dot(V3::s(r.dv));
        let ok = denom.cmp(zero, |a, b| a != b).and(t.cmp(zero, |a, b| a > b)).and(t.cmp(best, |a, b| a < b));
        let ok = ok
            .and(u.cmp(zero, |a, b| a >= b))
            .and(u.cmp(one, |a, b| a <= b))
            .and(v.cmp(zero, |a, b| a >= b))
            .and(v.cmp(one, |a, b| a <= b));
        best = V::sel(ok, t, best);
        n = V3::sel(ok, nn, n);
        alb = V3::sel(ok, V3::s(r.albedo), alb);
        for i in 0..N {
            if ok.0[i] != 0 {
                obj[i] = k as i32;
            }
        }
    }
    for (k, c) in s.cubes.iter().enumerate() {
        let mulv = |v: V3<N>| V3 {
            x: V::s(c.l.x_axis.x) * v.x + V::s(c.l.y_axis.x) * v.y + V::s(c.l.z_axis.x) * v.z,
            y: V::s(c.l.x_axis.y) * v.x + V::s(c.l.y_axis.y) * v.y + V::s(c.l.z_axis.y) * v.z,
            z: V::s(c.l.x_axis.z) * v.x + V::s(c.l.y_axis.z) * v.y + V::s(c.l.z_axis.z) * v.z,
        };
        let (lo, ld) = (mulv(o), mulv(d));
        let mut enter = V::<N>::s(f64::NEG_INFINITY);
        let mut exit = V::<N>::s(f64::INFINITY);
        let mut enter_face = V::<N>::s(0.0);
        let mut exit_face = V::<N>::s(0.0);
        for (a, (oo, dd, l, h)) in
            [(lo.x, ld.x, c.lo.x, c.hi.x), (lo.y, ld.y, c.lo.y, c.hi.y), (lo.z, ld.z, c.lo.z, c.hi.z)].into_iter().enumerate()
        {
            let inv = one / dd;
            let tl = (V::s(l) - oo) * inv;
            let th = (V::s(h) - oo) * inv;
            let up = inv.cmp(zero, |a, b| a >= b);
            let near = V::sel(up, tl, th);
            let far = V::sel(up, th, tl);
            // faces: 2a = +axis (max), 2a+1 = -axis (min). Entering going up: min face.
            let nf = V::sel(up, V::s((2 * a + 1) as f64), V::s((2 * a) as f64));
            let ff = V::sel(up, V::s((2 * a) as f64), V::s((2 * a + 1) as f64));
            let m1 = near.cmp(enter, |a, b| a > b);
            enter = V::sel(m1, near, enter);
            enter_face = V::sel(m1, nf, enter_face);
            let m2 = far.cmp(exit, |a, b| a < b);
            exit = V::sel(m2, far, exit);
            exit_face = V::sel(m2, ff, exit_face);
        }
        let entering = enter.cmp(zero, |a, b| a > b);
        let t = V::sel(entering, enter, exit);
        let face = V::sel(entering, enter_face, exit_face);
        let ok = enter.cmp(exit, |a, b| a <= b).and(t.cmp(zero, |a, b| a > b)).and(t.cmp(best, |a, b| a < b));
        best = V::sel(ok, t, best);
        let mut fnrm = n;
        for i in 0..N {
            if ok.0[i] != 0 {
                let f = c.normals[face.0[i] as usize];
                fnrm.x.0[i] = f.x;
                fnrm.y.0[i] = f.y;
                fnrm.z.0[i] = f.z;
                obj[i] = (s.rects.len() + k) as i32;
            }
        }
        n = fnrm;
        alb = V3::sel(ok, V3::s(c.albedo), alb);
    }
    (best, n, alb, obj)
}

/// True where something other than the light lies before `dist`.
#[inline(always)]
fn blocked<const N: usize>(s: &Scene, o: V3<N>, d: V3<N>, dist: V<N>) -> M<N> {
    let (t, _, _, obj) = closest(s, o, d);
    let mut m = t.cmp(dist * V::s(1.0 - 1e-9), |a, b| a < b);
    for i in 0..N {
        if obj[i] == 0 {
            m.0[i] = 0;
        }
    }
    m
}

/// Where a sample's random values come from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Values {
    /// A cheap LCG with a mixed output.
    Cheap,
    /// At the cost of lamplight's sampler, per value: two SplitMix64 mixes for
    /// the dimension's seeds (from the pixel and the dimension), two
    /// Laine-Karras permutations and two bit reversals (`PixelSampler::get_1d`),
    /// hashed per lane in scalar code.
    Sampler,
    /// As `Sampler` without the two mixes per lane: the cost if lanes that take
    /// the samples of one pixel computed each dimension's seeds once.
    SharedSeeds,
    /// `Sampler`'s values, hashed for all lanes at once ([`draw_lanes`]): loops
    /// over the lanes that LLVM vectorises (the 64-bit multiplies emulated from
    /// 32-bit ones, as AVX2 has none).
    SamplerInLanes,
}

/// One value for each lane from `Values::Sampler`'s hash, written over the
/// lanes (structure of arrays), for each lane's pixel seed, reversed index and
/// dimension.
#[inline(always)]
fn draw_lanes<const N: usize>(seed: &[u64; N], index_reversed: &[u32; N], dimension: &[u32; N]) -> [f64; N] {
    let mut h = [0u64; N];
    let mut h2 = [0u64; N];
    for i in 0..N {
        h[i] = mix(seed[i] ^ (dimension[i] as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    }
    for i in 0..N {
        h2[i] = mix(h[i] ^ 0x2545_F491_4F6C_DD1D);
    }
    let mut x = [0u32; N];
    for i in 0..N {
        x[i] = laine_karras(index_reversed[i], h2[i] as u32).reverse_bits();
    }
    for i in 0..N {
        x[i] = laine_karras(x[i], h[i] as u32).reverse_bits();
    }
    std::array::from_fn(|i| x[i] as f64 * (1.0 / 4_294_967_296.0))
}

/// A sample's random values ([`Values`]).
#[derive(Clone, Copy)]
struct Rng {
    /// The LCG's state, or the pixel's seed.
    state: u64,
    index_reversed: u32,
    dimension: u32,
    values: Values,
}

// `mix` and `laine_karras` are copies of `lamplight_core::sampling::sobol`'s
// private functions: the probe stands outside the workspace and needs the
// hashes inlined into its lane loops; a change there should be copied here.
#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[inline(always)]
fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

impl Rng {
    fn new(pixel: u64, index: u32, values: Values) -> Rng {
        let pixel_seed = mix(pixel.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x1234);
        let state = if values == Values::Cheap { pixel_seed ^ index as u64 } else { pixel_seed };
        Rng { state, index_reversed: index.reverse_bits(), dimension: 0, values }
    }

    #[inline(always)]
    fn next(&mut self) -> f64 {
        if self.values != Values::Cheap {
            let h = self.state ^ (self.dimension as u64).wrapping_mul(0xD1B5_4A32_D192_ED03);
            let (h, h2) = if matches!(self.values, Values::Sampler | Values::SamplerInLanes) {
                let h = mix(h);
                (h, mix(h ^ 0x2545_F491_4F6C_DD1D))
            } else {
                (h, h.rotate_left(29))
            };
            self.dimension += 1;
            let i = laine_karras(self.index_reversed, h2 as u32).reverse_bits();
            return laine_karras(i, h as u32).reverse_bits() as f64 * (1.0 / 4_294_967_296.0);
        }
        self.state = self.state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let x = self.state ^ (self.state >> 29);
        let x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        ((x ^ (x >> 32)) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

fn render<const N: usize>(s: &Scene, w: usize, spp: usize, values: Values) -> (Vec<DVec3>, u64) {
    let mut img = vec![DVec3::ZERO; w * w];
    let total = w * w * spp;
    let eye = DVec3::new(0.0, 0.0, 3.9);
    let tan = (39.3077f64.to_radians() * 0.5).tan();
    let mut next_sample = 0usize;
    // lane state
    let mut o = V3::<N>::s(DVec3::ZERO);
    let mut d = V3::<N>::s(DVec3::ZERO);
    let mut beta = V3::<N>::s(DVec3::ZERO);
    let mut l = V3::<N>::s(DVec3::ZERO);
    let mut depth = [0u32; N];
    let mut prev_pdf = V::<N>::s(0.0);
    let mut alive = M([0u64; N]);
    let mut pix = [0usize; N];
    let mut rng = [Rng::new(0, 0, values); N];
    let mut rays = 0u64;
    let light = &s.rects[0];
    loop {
        // refill
        for i in 0..N {
            if alive.0[i] == 0 {
                if depth[i] != u32::MAX && pix[i] != usize::MAX && (l.x.0[i] != 0.0 || l.y.0[i] != 0.0 || l.z.0[i] != 0.0) {
                    img[pix[i]] += DVec3::new(l.x.0[i], l.y.0[i], l.z.0[i]);
                }
                l.x.0[i] = 0.0;
                l.y.0[i] = 0.0;
                l.z.0[i] = 0.0;
                if next_sample >= total {
                    depth[i] = u32::MAX;
                    continue;
                }
                let sidx = next_sample;
                next_sample += 1;
                let p = sidx / spp;
                pix[i] = p;
                rng[i] = Rng::new(p as u64, (sidx % spp) as u32, values);
                let (px, py) = ((p % w) as f64 + rng[i].next(), (p / w) as f64 + rng[i].next());
                let (a, b) = ((2.0 * px / w as f64 - 1.0) * tan, (1.0 - 2.0 * py / w as f64) * tan);
                let dir = DVec3::new(a, b, -1.0).normalize();
                o.x.0[i] = eye.x;
                o.y.0[i] = eye.y;
                o.z.0[i] = eye.z;
                d.x.0[i] = dir.x;
                d.y.0[i] = dir.y;
                d.z.0[i] = dir.z;
                beta.x.0[i] = 1.0;
                beta.y.0[i] = 1.0;
                beta.z.0[i] = 1.0;
                depth[i] = 0;
                prev_pdf.0[i] = 0.0;
                alive.0[i] = !0;
            }
        }
        if !alive.any() {
            break;
        }
        rays += alive.0.iter().filter(|&&a| a != 0).count() as u64;
        let (t, n0, alb, obj) = closest(s, o, d);
        let hit = t.cmp(V::s(f64::INFINITY), |a, b| a < b).and(alive);
        let p = o.add(d.scale(t));
        // face the ray
        let facing = d.dot(n0).cmp(V::s(0.0), |a, b| a < b);
        let neg = V3 { x: V::s(0.0) - n0.x, y: V::s(0.0) - n0.y, z: V::s(0.0) - n0.z };
        let n = V3::sel(facing, n0, neg);
        // emitter hit: the light's front (normal -y, facing the ray)
        let mut u = [[0.0f64; 5]; N];
        if values == Values::SamplerInLanes {
            let seed = std::array::from_fn(|i| rng[i].state);
            let index_reversed = std::array::from_fn(|i| rng[i].index_reversed);
            for k in 0..5 {
                let dimension = std::array::from_fn(|i| rng[i].dimension + k as u32);
                let v = draw_lanes::<N>(&seed, &index_reversed, &dimension);
                for i in 0..N {
                    u[i][k] = v[i];
                }
            }
            for r in rng.iter_mut() {
                r.dimension += 5;
            }
        } else {
            for i in 0..N {
                for k in 0..5 {
                    u[i][k] = rng[i].next();
                }
            }
        }
        let col = |k: usize| V(std::array::from_fn(|i| u[i][k]));
        for i in 0..N {
            if hit.0[i] != 0 && obj[i] == 0 && facing.0[i] != 0 {
                let w = if depth[i] == 0 {
                    1.0
                } else {
                    let cos_l = -(d.x.0[i] * n0.x.0[i] + d.y.0[i] * n0.y.0[i] + d.z.0[i] * n0.z.0[i]);
                    let pl = t.0[i] * t.0[i] / (cos_l * s.light_area);
                    let pb = prev_pdf.0[i];
                    pb * pb / (pb * pb + pl * pl)
                };
                l.x.0[i] += beta.x.0[i] * s.le.x * w;
                l.y.0[i] += beta.y.0[i] * s.le.y * w;
                l.z.0[i] += beta.z.0[i] * s.le.z * w;
            }
        }
        let mut go = hit;
        for i in 0..N {
            if depth[i] + 1 >= 8 {
                go.0[i] = 0;
            }
        }
        // NEE
        let y = V3::s(light.corner).add(V3::s(light.eu).scale(col(0))).add(V3::s(light.ev).scale(col(1)));
        let to = y.sub(p);
        let d2 = to.dot(to);
        let dist = d2.sqrt();
        let wi = to.scale(V::s(1.0) / dist);
        let cos_l = V::s(0.0) - wi.dot(V3::s(light.n));
        let cos_s = wi.dot(n);
        let ok = go.and(cos_l.cmp(V::s(0.0), |a, b| a > b)).and(cos_s.cmp(V::s(0.0), |a, b| a > b));
        if ok.any() {
            let eps = V::s(1e-7);
            let so = p.add(n.scale(eps));
            rays += ok.0.iter().filter(|&&a| a != 0).count() as u64;
            let b = blocked(s, so, wi, dist);
            let vis = ok.and(b.not());
            let pl = d2 / (cos_l * V::s(s.light_area));
            let pb = cos_s * V::s(std::f64::consts::FRAC_1_PI);
            let wmis = pl * pl / (pl * pl + pb * pb);
            let k = cos_s * V::s(std::f64::consts::FRAC_1_PI) * wmis / pl;
            let c = beta.mul(alb).mul(V3::s(s.le)).scale(k);
            l = V3::sel(vis, l.add(c), l);
        }
        // BSDF sample (cosine)
        let (a, b) = (col(2) * V::s(2.0) - V::s(1.0), col(3) * V::s(2.0) - V::s(1.0));
        let r2 = a * a + b * b;
        let r2 = V::sel(r2.cmp(V::s(1.0), |x, y| x > y), V::s(0.999), r2);
        let z = (V::s(1.0) - r2).sqrt();
        // basis
        let sign = n.z.map(|v| 1f64.copysign(v));
        let aa = V::s(-1.0) / (sign + n.z);
        let bb = n.x * n.y * aa;
        let tx = V3 { x: V::s(1.0) + sign * n.x * n.x * aa, y: sign * bb, z: V::s(0.0) - sign * n.x };
        let ty = V3 { x: bb, y: sign + n.y * n.y * aa, z: V::s(0.0) - n.y };
        let nd = tx.scale(a).add(ty.scale(b)).add(n.scale(z));
        prev_pdf = z * V::s(std::f64::consts::FRAC_1_PI);
        beta = beta.mul(alb);
        // RR
        for i in 0..N {
            if go.0[i] != 0 {
                depth[i] += 1;
                if depth[i] >= 4 {
                    let m = beta.x.0[i].max(beta.y.0[i]).max(beta.z.0[i]).min(1.0);
                    if !(u[i][4] < m) {
                        go.0[i] = 0;
                    } else {
                        beta.x.0[i] /= m;
                        beta.y.0[i] /= m;
                        beta.z.0[i] /= m;
                    }
                }
            }
        }
        o = V3::sel(go, p.add(n.scale(V::s(1e-7))), o);
        d = V3::sel(go, nd, d);
        alive = go;
    }
    (img, rays)
}

fn main() {
    let t = |x: f64, y: f64, z: f64| DMat4::from_translation(DVec3::new(x, y, z));
    let rx = |deg: f64| DMat4::from_rotation_x(deg.to_radians());
    let ry = |deg: f64| DMat4::from_rotation_y(deg.to_radians());
    let white = DVec3::new(0.885809, 0.698859, 0.666422);
    let green = DVec3::new(0.105421, 0.37798, 0.076425);
    let red = DVec3::new(0.570068, 0.0430135, 0.0443706);
    let rects = vec![
        rect(t(0.0, 0.99, 0.01) * rx(90.0) * DMat4::from_scale(DVec3::new(0.23, 0.19, 0.19)), white),
        rect(t(0.0, -1.0, 0.0) * rx(-90.0), white),
        rect(t(0.0, 1.0, 0.0) * rx(90.0), white),
        rect(t(0.0, 0.0, -1.0), white),
        rect(t(1.0, 0.0, 0.0) * ry(-90.0), green),
        rect(t(-1.0, 0.0, 0.0) * ry(90.0), red),
    ];
    let light_area = rects[0].eu.cross(rects[0].ev).length();
    let cubes = vec![
        cube(t(0.335, -0.7, 0.38) * ry(-17.0) * DMat4::from_scale(DVec3::splat(0.3)), white),
        cube(t(-0.33, -0.4, -0.28) * ry(18.25) * DMat4::from_scale(DVec3::new(0.3, 0.61, 0.3)), white),
    ];
    let s = Scene { rects, cubes, le: DVec3::new(18.387, 13.9873, 6.75357), light_area };
    let (w, spp) = (256, 16);
    for values in [Values::Cheap, Values::Sampler, Values::SharedSeeds, Values::SamplerInLanes] {
        println!("random values: {values:?}");
        for round in 0..3 {
            let mut times = Vec::new();
            let mut means = Vec::new();
            let mut rays = Vec::new();
            for lanes in [1, 4, 8] {
                let t0 = std::time::Instant::now();
                let (img, r) = match lanes {
                    1 => render::<1>(&s, w, spp, values),
                    4 => render::<4>(&s, w, spp, values),
                    _ => render::<8>(&s, w, spp, values),
                };
                times.push(t0.elapsed().as_secs_f64());
                means.push(img.iter().fold(DVec3::ZERO, |a, b| a + *b) / (img.len() * spp) as f64);
                rays.push(r);
            }
            let same = rays.iter().all(|r| *r == rays[0]) && means.iter().all(|m| (*m - means[0]).abs().max_element() < 1e-12);
            println!(
                "  round {round}: 1 lane {:.3} s ({:.2} M samples/s), 4 lanes {:.3} s ({:.2}x), 8 lanes {:.3} s ({:.2}x); {} rays, image mean {:.5?}, the same for every lane count (up to the order a pixel's samples are summed in): {same}",
                times[0],
                (w * w * spp) as f64 / times[0] / 1e6,
                times[1],
                times[0] / times[1],
                times[2],
                times[0] / times[2],
                rays[0],
                means[0].to_array()
            );
        }
    }
}
