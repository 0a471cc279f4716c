//! Narrowphase queries in world coordinates: contact manifolds (several points per
//! pair), signed distance with witness points and normal, bounding boxes and time of
//! impact under linear motion.

use crate::shape::{to_v3, to_vector, Placement, Shape, ShapeKind, V3};
use parry3d_f64::bounding_volume::Aabb as ParryAabb;
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{
    self, ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher, ShapeCastOptions,
};
use parry3d_f64::shape::SupportMap;

/// One contact point between bodies A and B, in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint {
    /// Witness point on A's surface.
    pub point_a: V3,
    /// Witness point on B's surface.
    pub point_b: V3,
    /// Unit normal from A towards B.
    pub normal: V3,
    /// Signed distance along the normal (negative: penetration depth).
    pub dist: f64,
}

/// A query the geometry cannot answer for this pair of shapes.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct Unsupported(pub String);

fn name(s: &Shape) -> &'static str {
    match s.kind {
        ShapeKind::Sphere { .. } => "sphere",
        ShapeKind::Box { .. } => "box",
        ShapeKind::Capsule { .. } => "capsule",
        ShapeKind::Cylinder { .. } => "cylinder",
        ShapeKind::Cone { .. } => "cone",
        ShapeKind::Ellipsoid { .. } => "ellipsoid",
        ShapeKind::HalfSpace => "half-space",
        ShapeKind::ConvexHull { .. } => "convex hull",
        ShapeKind::TriMesh { .. } => "triangle mesh",
    }
}

fn unsupported(a: &Shape, b: &Shape) -> Unsupported {
    Unsupported(format!(
        "no contact query between a {} and a {}",
        name(a),
        name(b)
    ))
}

/// A placement the queries can work with: finite, its position within
/// [`MAX_LENGTH`](crate::shape::MAX_LENGTH) of the origin.
fn check_placement(p: &Placement) -> Result<(), Unsupported> {
    let limit = crate::shape::MAX_LENGTH;
    let position_ok = p.r.iter().all(|c| c.is_finite() && c.abs() <= limit);
    let rotation_ok = p.rot.iter().flatten().all(|c| c.is_finite());
    if position_ok && rotation_ok {
        Ok(())
    } else {
        Err(Unsupported(format!(
            "a body placed at {:?} (rotation {:?}): positions must be finite and within {limit:e}",
            p.r, p.rot
        )))
    }
}

/// Reusable memory for [`contacts`].
#[derive(Default)]
pub struct Scratch {
    manifolds: Vec<ContactManifold<(), ()>>,
}

/// The distance below which the closest points of two placed shapes A and B are
/// contact points, and the shapes.
#[derive(Clone, Copy)]
pub struct ContactQuery<'a> {
    pub prediction: f64,
    pub a: &'a Shape,
    pub pa: &'a Placement,
    pub b: &'a Shape,
    pub pb: &'a Placement,
}

/// Appends to `out` the contact points of A and B closer than `prediction` (every
/// point of every manifold: a box on a box gets its face, a cylinder lying on a box its
/// line). Returns how many were added.
pub fn contacts(
    query: ContactQuery<'_>,
    scratch: &mut Scratch,
    out: &mut Vec<ContactPoint>,
) -> Result<usize, Unsupported> {
    let Some(c) = sphere_contact(&query) else {
        return contacts_general(query, scratch, out);
    };
    // Spheres against spheres and planes in closed form: no general convex query.
    check_placement(query.pa)?;
    check_placement(query.pb)?;
    if c.dist > query.prediction {
        return Ok(0);
    }
    out.push(c);
    Ok(1)
}

/// The closed-form contact of a sphere with a sphere or a half-space (either order),
/// `None` for any other pair. The sphere's centre is its body origin.
fn sphere_contact(query: &ContactQuery<'_>) -> Option<ContactPoint> {
    let ContactQuery { a, pa, b, pb, .. } = *query;
    match (&a.kind, &b.kind) {
        (ShapeKind::Sphere { radius: ra }, ShapeKind::Sphere { radius: rb }) => {
            Some(sphere_sphere(pa.r, *ra, pb.r, *rb))
        }
        (ShapeKind::Sphere { radius }, ShapeKind::HalfSpace) => {
            Some(sphere_plane(pa.r, *radius, pb))
        }
        (ShapeKind::HalfSpace, ShapeKind::Sphere { radius }) => {
            Some(flip(sphere_plane(pb.r, *radius, pa)))
        }
        _ => None,
    }
}

/// Two spheres: the normal along the line of centres, from A to B (`+z` for
/// coincident centres).
pub fn sphere_sphere(ca: V3, ra: f64, cb: V3, rb: f64) -> ContactPoint {
    let d = [cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let n = if len > 0.0 {
        [d[0] / len, d[1] / len, d[2] / len]
    } else {
        [0.0, 0.0, 1.0]
    };
    ContactPoint {
        point_a: [ca[0] + ra * n[0], ca[1] + ra * n[1], ca[2] + ra * n[2]],
        point_b: [cb[0] - rb * n[0], cb[1] - rb * n[1], cb[2] - rb * n[2]],
        normal: n,
        dist: len - ra - rb,
    }
}

/// A sphere (A) against the half-space `z <= 0` of `plane`'s frame: the normal from A
/// into the half-space is `-n`, `n` the plane's outward normal.
pub fn sphere_plane(c: V3, radius: f64, plane: &Placement) -> ContactPoint {
    let n = plane.rotate([0.0, 0.0, 1.0]);
    let height =
        (c[0] - plane.r[0]) * n[0] + (c[1] - plane.r[1]) * n[1] + (c[2] - plane.r[2]) * n[2];
    ContactPoint {
        point_a: [
            c[0] - radius * n[0],
            c[1] - radius * n[1],
            c[2] - radius * n[2],
        ],
        point_b: [
            c[0] - height * n[0],
            c[1] - height * n[1],
            c[2] - height * n[2],
        ],
        normal: [-n[0], -n[1], -n[2]],
        dist: height - radius,
    }
}

/// [`contacts`] by parry's general queries (and the ellipsoid's closed form or support
/// map), for every pair, spheres included: the path a pair takes without the closed
/// forms (benchmarks compare the two).
pub fn contacts_general(
    query: ContactQuery<'_>,
    scratch: &mut Scratch,
    out: &mut Vec<ContactPoint>,
) -> Result<usize, Unsupported> {
    let ContactQuery {
        a,
        pa,
        b,
        pb,
        prediction,
    } = query;
    check_placement(pa)?;
    check_placement(pb)?;
    let before = out.len();
    match (a.ellipsoid.as_ref(), b.ellipsoid.as_ref()) {
        (None, None) => {
            let (ga, gb) = (a.parry.as_ref().unwrap(), b.parry.as_ref().unwrap());
            let (posa, posb) = (pa.pose(), pb.pose());
            let pos12 = posa.inv_mul(&posb);
            scratch.manifolds.clear();
            let mut ws = None;
            DefaultQueryDispatcher
                .contact_manifolds(
                    &pos12,
                    &*ga.0,
                    &*gb.0,
                    prediction,
                    &mut scratch.manifolds,
                    &mut ws,
                )
                .map_err(|_| unsupported(a, b))?;
            for m in &scratch.manifolds {
                let (sa, sb) = match &m.subshape_poses {
                    Some(p) => (
                        posa * p.pos1.unwrap_or(Pose::IDENTITY),
                        posb * p.pos2.unwrap_or(Pose::IDENTITY),
                    ),
                    None => (posa, posb),
                };
                let n = sa.rotation * m.local_n1;
                let first = out.len();
                for c in &m.points {
                    if c.dist > prediction {
                        continue;
                    }
                    out.push(ContactPoint {
                        point_a: to_v3(sa * c.local_p1),
                        point_b: to_v3(sb * c.local_p2),
                        normal: to_v3(n),
                        dist: c.dist,
                    });
                }
                keep_hull(out, first, a.bounding_radius.min(b.bounding_radius));
                snap_to_cap_axis([(a, pa, posa), (b, pb, posb)], &mut out[first..]);
            }
        }
        (Some(e), None) if b.kind == ShapeKind::HalfSpace => {
            if let Some(c) = ellipsoid_plane(e.semi_axes, pa, pb) {
                if c.dist <= prediction {
                    out.push(c);
                }
            }
        }
        (None, Some(e)) if a.kind == ShapeKind::HalfSpace => {
            if let Some(c) = ellipsoid_plane(e.semi_axes, pb, pa) {
                if c.dist <= prediction {
                    out.push(flip(c));
                }
            }
        }
        _ => {
            let sa: &dyn SupportMap = match (&a.ellipsoid, &a.parry) {
                (Some(e), _) => e,
                (None, Some(p)) => p.as_support_map().ok_or_else(|| unsupported(a, b))?,
                _ => return Err(unsupported(a, b)),
            };
            let sb: &dyn SupportMap = match (&b.ellipsoid, &b.parry) {
                (Some(e), _) => e,
                (None, Some(p)) => p.as_support_map().ok_or_else(|| unsupported(a, b))?,
                _ => return Err(unsupported(a, b)),
            };
            let (posa, posb) = (pa.pose(), pb.pose());
            let pos12 = posa.inv_mul(&posb);
            if let Some(c) =
                query::details::contact_support_map_support_map(&pos12, sa, sb, prediction)
            {
                out.push(ContactPoint {
                    point_a: to_v3(posa * c.point1),
                    point_b: to_v3(posa * c.point2),
                    normal: to_v3(posa.rotation * c.normal1),
                    dist: c.dist,
                });
            }
        }
    }
    Ok(out.len() - before)
}

/// The axis of a shape's flat round cap in world coordinates (cylinders and cones:
/// body y), `None` for other shapes.
fn cap_axis(s: &Shape, p: &Placement) -> Option<V3> {
    match s.kind {
        ShapeKind::Cylinder { .. } | ShapeKind::Cone { .. } => Some(p.rotate([0.0, 1.0, 0.0])),
        _ => None,
    }
}

/// How far A and B overlap along the unit direction `n` (from A to B), by their exact
/// support maps: `max a·n - min b·n` (negative: separated along `n`).
fn overlap_along(a: &Shape, pa: &Pose, b: &Shape, pb: &Pose, n: V3) -> Option<f64> {
    let sa = a.parry.as_ref()?.as_support_map()?;
    let sb = b.parry.as_ref()?.as_support_map()?;
    let d = to_vector(n);
    Some(sa.support_point(pa, d).dot(d) - sb.support_point(pb, -d).dot(d))
}

/// Puts the normal of one manifold (`points`) on a round cap's axis where that is the
/// better normal. parry approximates the flat cap of a cylinder or cone by a square
/// turned to the contact's azimuth; when two caps lie parallel, that azimuth is noise,
/// and the manifold alternates between 4 and 8 points and can come out with a normal
/// several degrees off the common axis (an edge of one square against an edge of the
/// other): a sideways force whose sign flips with the last digit of a position. A cap's
/// axis within 60° of the normal along which the shapes overlap less (exact support
/// maps) is the normal instead: the points keep their places and their distances are
/// measured along it.
fn snap_to_cap_axis(shapes: [(&Shape, &Placement, Pose); 2], points: &mut [ContactPoint]) {
    let Some(first) = points.first() else {
        return;
    };
    // Only round caps turn with the azimuth: other pairs keep parry's normal unexamined.
    if shapes.iter().all(|(s, p, _)| cap_axis(s, p).is_none()) {
        return;
    }
    let n = first.normal;
    let [(a, _, posa), (b, _, posb)] = &shapes;
    let overlap = |c: V3| overlap_along(a, posa, b, posb, c);
    let Some(mut best) = overlap(n) else {
        return;
    };
    let mut normal = None;
    for (s, p, _) in &shapes {
        let Some(u) = cap_axis(s, p) else {
            continue;
        };
        let along = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
        if along.abs() < 0.5 {
            continue;
        }
        let c = u.map(|x| x * along.signum());
        if let Some(o) = overlap(c) {
            if o < best {
                best = o;
                normal = Some(c);
            }
        }
    }
    let Some(c) = normal else {
        return;
    };
    for q in points {
        let d = [
            q.point_b[0] - q.point_a[0],
            q.point_b[1] - q.point_a[1],
            q.point_b[2] - q.point_a[2],
        ];
        q.normal = c;
        q.dist = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
    }
}

/// Reduces the points `out[first..]` of one manifold to the corners of their convex
/// hull in the contact plane (duplicates and interior or collinear points dropped).
/// parry adds the deepest point to the clipped features, which sits in the middle of a
/// flat contact or doubles a corner once the contact tilts by a hair: the force
/// distribution would jump with the sign of the tilt and make a resting body rock.
fn keep_hull(out: &mut Vec<ContactPoint>, first: usize, size: f64) {
    if out.len() - first <= 1 {
        return;
    }
    let n = out[first].normal;
    let (t1, t2) = crate::laws::tangent_basis(n);
    let eps = 1e-9 * size.max(f64::MIN_POSITIVE);
    let uv = |c: &ContactPoint| {
        let p = c.point_a;
        (
            p[0] * t1[0] + p[1] * t1[1] + p[2] * t1[2],
            p[0] * t2[0] + p[1] * t2[1] + p[2] * t2[2],
        )
    };
    let mut pts: Vec<(f64, f64, ContactPoint)> = out[first..]
        .iter()
        .map(|c| {
            let (u, v) = uv(c);
            (u, v, *c)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // Near-duplicates: keep the deeper one.
    let mut uniq: Vec<(f64, f64, ContactPoint)> = Vec::with_capacity(pts.len());
    for p in pts {
        match uniq
            .iter_mut()
            .find(|q| (q.0 - p.0).hypot(q.1 - p.1) <= eps)
        {
            Some(q) => {
                if p.2.dist < q.2.dist {
                    *q = p;
                }
            }
            None => uniq.push(p),
        }
    }
    uniq.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let hull = if uniq.len() <= 2 {
        uniq
    } else {
        // Andrew's monotone chain; collinear points are dropped.
        let cross = |o: &(f64, f64, ContactPoint),
                     a: &(f64, f64, ContactPoint),
                     b: &(f64, f64, ContactPoint)| {
            (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
        };
        let tol = eps * size.max(f64::MIN_POSITIVE);
        let mut lower: Vec<(f64, f64, ContactPoint)> = Vec::new();
        for p in &uniq {
            while lower.len() >= 2
                && cross(&lower[lower.len() - 2], &lower[lower.len() - 1], p) <= tol
            {
                lower.pop();
            }
            lower.push(*p);
        }
        let mut upper: Vec<(f64, f64, ContactPoint)> = Vec::new();
        for p in uniq.iter().rev() {
            while upper.len() >= 2
                && cross(&upper[upper.len() - 2], &upper[upper.len() - 1], p) <= tol
            {
                upper.pop();
            }
            upper.push(*p);
        }
        lower.pop();
        upper.pop();
        lower.extend(upper);
        lower
    };
    out.truncate(first);
    out.extend(hull.into_iter().map(|p| p.2));
}

fn flip(c: ContactPoint) -> ContactPoint {
    ContactPoint {
        point_a: c.point_b,
        point_b: c.point_a,
        normal: [-c.normal[0], -c.normal[1], -c.normal[2]],
        dist: c.dist,
    }
}

/// Ellipsoid (A) against the half-space `z <= 0` of B's frame, in closed form: the
/// point of the ellipsoid whose outer normal is `-n` is `r_A - T A² Tᵀ n /
/// sqrt(nᵀ T A² Tᵀ n)`.
pub fn ellipsoid_plane(
    semi_axes: Vector,
    pa: &Placement,
    plane: &Placement,
) -> Option<ContactPoint> {
    let n = plane.rotate([0.0, 0.0, 1.0]);
    let nb = pa.unrotate(n);
    let a2 = [
        semi_axes.x * semi_axes.x,
        semi_axes.y * semi_axes.y,
        semi_axes.z * semi_axes.z,
    ];
    let q = a2[0] * nb[0] * nb[0] + a2[1] * nb[1] * nb[1] + a2[2] * nb[2] * nb[2];
    let s = q.sqrt();
    if s == 0.0 {
        return None;
    }
    let local = [-a2[0] * nb[0] / s, -a2[1] * nb[1] / s, -a2[2] * nb[2] / s];
    let w = pa.rotate(local);
    let p = [pa.r[0] + w[0], pa.r[1] + w[1], pa.r[2] + w[2]];
    let dist = (p[0] - plane.r[0]) * n[0] + (p[1] - plane.r[1]) * n[1] + (p[2] - plane.r[2]) * n[2];
    Some(ContactPoint {
        point_a: p,
        point_b: [p[0] - dist * n[0], p[1] - dist * n[1], p[2] - dist * n[2]],
        normal: [-n[0], -n[1], -n[2]],
        dist,
    })
}

/// The deepest (or closest) point between A and B within `prediction`: signed distance,
/// witness points and normal.
pub fn closest(
    a: &Shape,
    pa: &Placement,
    b: &Shape,
    pb: &Placement,
    prediction: f64,
) -> Result<Option<ContactPoint>, Unsupported> {
    let mut out = Vec::new();
    let query = ContactQuery {
        a,
        pa,
        b,
        pb,
        prediction,
    };
    contacts(query, &mut Scratch::default(), &mut out)?;
    Ok(out.into_iter().min_by(|x, y| x.dist.total_cmp(&y.dist)))
}

/// Axis-aligned bounding box in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: V3,
    pub max: V3,
}

impl Aabb {
    pub fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.min[k] <= o.max[k] && o.min[k] <= self.max[k])
    }

    pub fn merged(&self, o: &Aabb) -> Aabb {
        let mut m = *self;
        for k in 0..3 {
            m.min[k] = m.min[k].min(o.min[k]);
            m.max[k] = m.max[k].max(o.max[k]);
        }
        m
    }

    pub fn loosened(&self, margin: f64) -> Aabb {
        let mut m = *self;
        for k in 0..3 {
            m.min[k] -= margin;
            m.max[k] += margin;
        }
        m
    }
}

/// The world bounding box of a placed shape (unbounded for the half-space).
pub fn aabb(s: &Shape, p: &Placement) -> Aabb {
    match (&s.ellipsoid, &s.parry) {
        (Some(e), _) => {
            let a = [e.semi_axes.x, e.semi_axes.y, e.semi_axes.z];
            let mut h = [0.0; 3];
            for (i, hi) in h.iter_mut().enumerate() {
                *hi = (0..3)
                    .map(|j| (p.rot[i][j] * a[j]).powi(2))
                    .sum::<f64>()
                    .sqrt();
            }
            Aabb {
                min: [p.r[0] - h[0], p.r[1] - h[1], p.r[2] - h[2]],
                max: [p.r[0] + h[0], p.r[1] + h[1], p.r[2] + h[2]],
            }
        }
        (None, Some(g)) if s.is_bounded() => {
            let b: ParryAabb = g.compute_aabb(&p.pose());
            Aabb {
                min: to_v3(b.mins),
                max: to_v3(b.maxs),
            }
        }
        _ => Aabb {
            min: [f64::NEG_INFINITY; 3],
            max: [f64::INFINITY; 3],
        },
    }
}

/// A body in a sweep: its shape, its placement at the sweep's start and its velocity
/// (translation only).
#[derive(Clone, Copy)]
pub struct Moving<'a> {
    pub shape: &'a Shape,
    pub placement: &'a Placement,
    pub velocity: V3,
}

/// First time in `[0, max_time]` at which A and B, each moving with its velocity,
/// touch: `Some(0)` when they already overlap. `None` when they do not meet or the pair
/// has no shape cast (ellipsoids).
pub fn time_of_impact(a: Moving<'_>, b: Moving<'_>, max_time: f64) -> Option<f64> {
    check_placement(a.placement).ok()?;
    check_placement(b.placement).ok()?;
    let (pa, va, pb, vb) = (a.placement, a.velocity, b.placement, b.velocity);
    match (&a.shape.kind, &b.shape.kind) {
        (ShapeKind::Sphere { radius: ra }, ShapeKind::Sphere { radius: rb }) => {
            let rel = sub3(pb.r, pa.r);
            return sphere_sweep(rel, sub3(vb, va), ra + rb, max_time);
        }
        (ShapeKind::Sphere { radius }, ShapeKind::HalfSpace) => {
            return plane_sweep(pa.r, va, *radius, pb, vb, max_time);
        }
        (ShapeKind::HalfSpace, ShapeKind::Sphere { radius }) => {
            return plane_sweep(pb.r, vb, *radius, pa, va, max_time);
        }
        _ => {}
    }
    time_of_impact_general(a, b, max_time)
}

fn sub3(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The first time in `[0, max_time]` at which `|rel + s w| = reach` (0 when already
/// within reach).
fn sphere_sweep(rel: V3, w: V3, reach: f64, max_time: f64) -> Option<f64> {
    let c = dot3(rel, rel) - reach * reach;
    if c <= 0.0 {
        return Some(0.0);
    }
    let (a, b) = (dot3(w, w), dot3(rel, w));
    let disc = b * b - a * c;
    if a == 0.0 || b >= 0.0 || disc < 0.0 {
        return None;
    }
    // The smaller root, written to avoid cancellation: c / (-b + sqrt(disc)).
    let s = c / (-b + disc.sqrt());
    (s <= max_time).then_some(s)
}

/// A sphere (centre `c`, velocity `v`) moving toward a half-space moving with `vp`.
fn plane_sweep(c: V3, v: V3, radius: f64, plane: &Placement, vp: V3, max_time: f64) -> Option<f64> {
    let n = plane.rotate([0.0, 0.0, 1.0]);
    let height = dot3(sub3(c, plane.r), n) - radius;
    if height <= 0.0 {
        return Some(0.0);
    }
    let rate = dot3(sub3(v, vp), n);
    if rate >= 0.0 {
        return None;
    }
    let s = -height / rate;
    (s <= max_time).then_some(s)
}

/// [`time_of_impact`] by parry's shape cast for every pair (the path spheres take
/// without their closed forms).
pub fn time_of_impact_general(a: Moving<'_>, b: Moving<'_>, max_time: f64) -> Option<f64> {
    check_placement(a.placement).ok()?;
    check_placement(b.placement).ok()?;
    let (ga, gb) = (a.shape.parry.as_ref()?, b.shape.parry.as_ref()?);
    let hit = query::cast_shapes(
        &a.placement.pose(),
        to_vector(a.velocity),
        &*ga.0,
        &b.placement.pose(),
        to_vector(b.velocity),
        &*gb.0,
        ShapeCastOptions::with_max_time_of_impact(max_time),
    )
    .ok()??;
    Some(hit.time_of_impact)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::ShapeKind as K;

    fn sh(k: K) -> Shape {
        Shape::new(k).unwrap()
    }

    fn moving<'a>(shape: &'a Shape, placement: &'a Placement, velocity: V3) -> Moving<'a> {
        Moving {
            shape,
            placement,
            velocity,
        }
    }

    #[test]
    fn sphere_above_plane_has_the_analytic_distance() {
        let ball = sh(K::Sphere { radius: 0.5 });
        let ground = sh(K::HalfSpace);
        let c = closest(
            &ball,
            &Placement::at([0.3, -2.0, 1.25]),
            &ground,
            &Placement::IDENTITY,
            10.0,
        )
        .unwrap()
        .unwrap();
        assert!((c.dist - 0.75).abs() < 1e-14, "{c:?}");
        assert!((c.normal[2] + 1.0).abs() < 1e-14);
        assert!((c.point_a[2] - 0.75).abs() < 1e-14 && c.point_b[2].abs() < 1e-14);
        let c = closest(
            &ball,
            &Placement::at([0.0, 0.0, 0.4]),
            &ground,
            &Placement::IDENTITY,
            0.0,
        )
        .unwrap()
        .unwrap();
        assert!((c.dist + 0.1).abs() < 1e-14, "penetration: {c:?}");
    }

    #[test]
    fn ellipsoid_support_map_agrees_with_the_closed_form_against_a_plane() {
        let e = sh(K::Ellipsoid {
            semi_axes: [0.3, 0.2, 0.1],
        });
        // A rotated ellipsoid above a plane; the GJK answer against a thin box that
        // stands for the plane must match the closed form.
        let (s, c) = (0.4f64.sin(), 0.4f64.cos());
        let pa = Placement {
            r: [0.0, 0.0, 0.35],
            rot: [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        };
        let exact = closest(&e, &pa, &sh(K::HalfSpace), &Placement::IDENTITY, 1.0)
            .unwrap()
            .unwrap();
        let a2 = [0.09 * s * s, 0.0, 0.01 * c * c];
        let expected = 0.35 - (a2[0] + a2[2]).sqrt();
        assert!(
            (exact.dist - expected).abs() < 1e-14,
            "{exact:?} vs {expected}"
        );
        let slab = sh(K::Box {
            half: [10.0, 10.0, 1.0],
        });
        let gjk = closest(&e, &pa, &slab, &Placement::at([0.0, 0.0, -1.0]), 1.0)
            .unwrap()
            .unwrap();
        assert!((gjk.dist - exact.dist).abs() < 1e-9, "{gjk:?} vs {exact:?}");
    }

    #[test]
    fn a_cylinder_lying_on_a_box_gets_several_contact_points() {
        // Axis along world x: rotate the body y axis onto x.
        let cyl = sh(K::Cylinder {
            half_height: 0.5,
            radius: 0.1,
        });
        let rot = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let pc = Placement {
            r: [0.0, 0.0, 0.1 - 1e-4],
            rot,
        };
        let table = sh(K::Box {
            half: [1.0, 1.0, 0.05],
        });
        let mut out = Vec::new();
        let query = ContactQuery {
            a: &cyl,
            pa: &pc,
            b: &table,
            pb: &Placement::at([0.0, 0.0, -0.05]),
            prediction: 0.0,
        };
        contacts(query, &mut Scratch::default(), &mut out).unwrap();
        assert!(
            out.len() >= 2,
            "line contact needs two points or more: {out:?}"
        );
        let xs: Vec<f64> = out.iter().map(|c| c.point_a[0]).collect();
        let spread = xs.iter().cloned().fold(f64::MIN, f64::max)
            - xs.iter().cloned().fold(f64::MAX, f64::min);
        assert!(
            spread > 0.9,
            "points should span the cylinder's length: {xs:?}"
        );
        for c in &out {
            assert!((c.dist + 1e-4).abs() < 1e-9, "{c:?}");
        }
    }

    #[test]
    fn time_of_impact_catches_a_fast_ball_before_a_thin_plate() {
        let ball = sh(K::Sphere { radius: 0.025 });
        let plate = sh(K::Box {
            half: [0.5, 0.5, 0.005],
        });
        // 100 m/s downwards from 1 m above: touches after (1 - 0.03)/100 s.
        let start = Placement::at([0.0, 0.0, 1.0]);
        let t = time_of_impact(
            moving(&ball, &start, [0.0, 0.0, -100.0]),
            moving(&plate, &Placement::IDENTITY, [0.0; 3]),
            1.0,
        )
        .unwrap();
        assert!((t - 0.97 / 100.0).abs() < 1e-9, "{t}");
        // Endpoints on both sides are clear of each other.
        assert!(closest(
            &ball,
            &Placement::at([0.0, 0.0, 1.0]),
            &plate,
            &Placement::IDENTITY,
            0.0
        )
        .unwrap()
        .is_none());
        assert!(closest(
            &ball,
            &Placement::at([0.0, 0.0, -1.0]),
            &plate,
            &Placement::IDENTITY,
            0.0
        )
        .unwrap()
        .is_none());
    }

    #[test]
    fn bad_dimensions_are_errors() {
        assert!(Shape::new(K::Sphere { radius: 0.0 }).is_err());
        assert!(Shape::new(K::Box {
            half: [1.0, f64::NAN, 1.0]
        })
        .is_err());
        let e = Shape::new(K::TriMesh {
            vertices: vec![[0.0; 3]],
            triangles: vec![[0, 1, 2]],
        });
        assert!(e.is_err());
    }

    /// A body 1e300 long is refused when it is built (parry's capsule-box manifold
    /// panicked on it), and a placement out of range makes the query an error.
    #[test]
    fn huge_shapes_and_placements_are_errors_not_panics() {
        for kind in [
            K::Capsule {
                half_height: 1e300,
                radius: 1.0,
            },
            K::Box {
                half: [1e300, 1.0, 1.0],
            },
            K::Sphere {
                radius: f64::INFINITY,
            },
            K::ConvexHull {
                points: vec![
                    [0.0; 3],
                    [1e300, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                ],
            },
        ] {
            let e = Shape::new(kind.clone()).expect_err("too large");
            assert!(e.0.contains("1e12"), "{kind:?}: {e}");
        }
        let capsule = sh(K::Capsule {
            half_height: 1e12,
            radius: 1.0,
        });
        let block = sh(K::Box { half: [1.0; 3] });
        // The largest allowed capsule lying on the box: touching at distance 0.5.
        let c = closest(
            &capsule,
            &Placement::at([0.0, 0.0, 2.5]),
            &block,
            &Placement::IDENTITY,
            1.0,
        )
        .unwrap()
        .unwrap();
        assert!((c.dist - 0.5).abs() < 1e-3, "{c:?}");
        let far = Placement::at([1e300, 0.0, 0.0]);
        let err = closest(&block, &far, &block, &Placement::IDENTITY, 1.0).unwrap_err();
        assert!(err.0.contains("finite and within"), "{err}");
        let nan = Placement::at([f64::NAN, 0.0, 0.0]);
        assert!(closest(&block, &nan, &block, &Placement::IDENTITY, 1.0).is_err());
        assert_eq!(
            time_of_impact(
                moving(&block, &far, [0.0; 3]),
                moving(&block, &Placement::IDENTITY, [0.0; 3]),
                1.0
            ),
            None
        );
    }
    /// A deterministic stream of numbers in [-1, 1).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        fn v3(&mut self, scale: f64) -> V3 {
            [
                self.next() * scale,
                self.next() * scale,
                self.next() * scale,
            ]
        }
        /// A rotation: Rodrigues' formula about a random axis.
        fn placement(&mut self, scale: f64) -> Placement {
            let (k, angle) = (self.v3(1.0), self.next() * 3.0);
            let len = dot3(k, k).sqrt().max(1e-9);
            let k = [k[0] / len, k[1] / len, k[2] / len];
            let (s, c) = angle.sin_cos();
            let mut rot = [[0.0; 3]; 3];
            for (i, row) in rot.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    let cross = match (i, j) {
                        (0, 1) => -k[2],
                        (0, 2) => k[1],
                        (1, 0) => k[2],
                        (1, 2) => -k[0],
                        (2, 0) => -k[1],
                        (2, 1) => k[0],
                        _ => 0.0,
                    };
                    let id = if i == j { 1.0 } else { 0.0 };
                    *x = c * id + s * cross + (1.0 - c) * k[i] * k[j];
                }
            }
            Placement {
                r: self.v3(scale),
                rot,
            }
        }
    }

    fn close3(a: V3, b: V3, tol: f64) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
    }

    /// The closed forms of spheres against spheres and planes give parry's general
    /// queries' answers: 2,000 random pairs (both orders), distances and points to
    /// 1e-12, normals to 1e-9 (parry's are unit vectors of its own rounding).
    #[test]
    fn sphere_closed_forms_agree_with_the_general_queries() {
        let mut rng = Lcg(7);
        let (mut fast, mut general) = (Vec::new(), Vec::new());
        let mut scratch = Scratch::default();
        for case in 0..2000 {
            let ra = 0.1 + rng.next().abs();
            let a = sh(K::Sphere { radius: ra });
            let b = if case % 2 == 0 {
                sh(K::Sphere {
                    radius: 0.1 + rng.next().abs(),
                })
            } else {
                sh(K::HalfSpace)
            };
            let (pa, pb) = (rng.placement(2.0), rng.placement(2.0));
            for (x, px, y, py) in [(&a, &pa, &b, &pb), (&b, &pb, &a, &pa)] {
                fast.clear();
                general.clear();
                let query = ContactQuery {
                    a: x,
                    pa: px,
                    b: y,
                    pb: py,
                    prediction: 10.0,
                };
                contacts(query, &mut scratch, &mut fast).unwrap();
                contacts_general(query, &mut scratch, &mut general).unwrap();
                assert_eq!(fast.len(), general.len(), "case {case}");
                for (f, g) in fast.iter().zip(&general) {
                    assert!((f.dist - g.dist).abs() <= 1e-12, "case {case}: {f:?} {g:?}");
                    assert!(
                        close3(f.point_a, g.point_a, 1e-12),
                        "case {case}: {f:?} {g:?}"
                    );
                    assert!(
                        close3(f.point_b, g.point_b, 1e-12),
                        "case {case}: {f:?} {g:?}"
                    );
                    assert!(close3(f.normal, g.normal, 1e-9), "case {case}: {f:?} {g:?}");
                }
            }
        }
    }

    /// Sweeps of spheres against spheres and planes: the closed form's first contact
    /// time equals parry's shape cast's to 1e-9 (its tolerance), hits and misses alike.
    #[test]
    fn sphere_sweeps_agree_with_the_shape_cast() {
        let mut rng = Lcg(11);
        let mut hits = 0;
        for case in 0..2000 {
            let a = sh(K::Sphere {
                radius: 0.1 + 0.3 * rng.next().abs(),
            });
            let b = if case % 2 == 0 {
                sh(K::Sphere {
                    radius: 0.1 + 0.3 * rng.next().abs(),
                })
            } else {
                sh(K::HalfSpace)
            };
            let (pa, pb) = (rng.placement(2.0), rng.placement(2.0));
            let (va, vb) = (rng.v3(3.0), rng.v3(3.0));
            for (x, px, vx, y, py, vy) in [(&a, &pa, va, &b, &pb, vb), (&b, &pb, vb, &a, &pa, va)] {
                let (x, y) = (moving(x, px, vx), moving(y, py, vy));
                let fast = time_of_impact(x, y, 1.0);
                let general = time_of_impact_general(x, y, 1.0);
                match (fast, general) {
                    (Some(f), Some(g)) => {
                        hits += 1;
                        assert!((f - g).abs() <= 1e-9, "case {case}: {f} {g}");
                    }
                    (None, None) => {}
                    other => panic!("case {case}: {other:?}"),
                }
            }
        }
        assert!(hits > 500, "{hits} hits");
    }
}
