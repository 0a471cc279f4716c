//! The collision world: an external object evaluated once before every pass of the
//! plan. It reads each collision body's arguments (shape, placement, velocities,
//! contact parameters) from registers computed from states and parameters, runs the
//! broadphase and the narrowphase, and writes each body's contact force and torque and
//! the world's two gap functions, which the plan reads like any register.
//!
//! Events: the world keeps the set `C` of pairs in contact, changed only in event
//! mode. `gaps[0]` is the smallest distance over pairs outside `C` (it also turns
//! negative when a pair's linear sweep since the last accepted step hits, so a fast
//! body cannot pass through a thin one within a step); `gaps[1]` is `2 tol` minus the
//! largest distance over pairs in `C` (negative once a pair has separated). A pair
//! joins `C` at an event when its distance is at most `tol` and leaves it when it is
//! more than `1.5 tol`: both decisions sit well inside the hysteresis band, so a
//! crossing located to rounding always changes the set. Both are
//! zero crossings of the world's `when`, so onset and separation are located events.
//! With impulse impacts, the world applies Newton restitution impulses to the bodies'
//! velocity states in event mode (sequential impulses until no pair approaches).

use rustc_hash::FxHashMap as HashMap;
use unimo_codegen::model::CollisionModel;
use unimo_codegen::tape::Reg;
use unimo_dae::collision_args::{CollisionBodyArgs, LawCode, ShapeCode};
use unimo_geometry::laws::{self, Damping, Friction};
use unimo_geometry::{
    aabb, contacts, time_of_impact, AllPairs, Broadphase, ContactPoint, ContactQuery, Moving,
    Placement, Scratch, Shape, ShapeKind, SweepAndPrune,
};

/// Counters for reports.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CollisionStats {
    pub evaluations: u64,
    pub broadphase_tests: u64,
    pub narrowphase_pairs: u64,
    pub impulses: u64,
    pub contact_changes: u64,
}

/// The mutable side of the world (lives in the event state).
#[derive(Default)]
pub struct CollisionState {
    shapes: Vec<Shape>,
    dynamic: Vec<bool>,
    placements: Vec<Placement>,
    origin: Vec<Placement>,
    boxes: Vec<unimo_geometry::Aabb>,
    pairs: Vec<(u32, u32)>,
    /// Pairs in contact, with the approach speed when they touched.
    contact: HashMap<(u32, u32), f64>,
    /// Per penalty contact in `contact` that began with an approach: the time the
    /// approach takes to cross the thinner body's half thickness (for the step cap).
    duration: HashMap<(u32, u32), f64>,
    broadphase: Option<Box<dyn Broadphase + Send>>,
    scratch: Scratch,
    points: Vec<ContactPoint>,
    pub stats: CollisionStats,
}

impl Clone for CollisionState {
    fn clone(&self) -> Self {
        // Geometry is rebuilt from the arguments on first use.
        CollisionState {
            contact: self.contact.clone(),
            stats: self.stats.clone(),
            ..CollisionState::default()
        }
    }
}

impl std::fmt::Debug for CollisionState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CollisionState")
            .field("bodies", &self.shapes.len())
            .field("contact", &self.contact.len())
            .field("stats", &self.stats)
            .finish()
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add_to(a: &mut [f64], b: [f64; 3]) {
    a[0] += b[0];
    a[1] += b[1];
    a[2] += b[2];
}

/// Why the world cannot evaluate (reported like a failing block).
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionFailure {
    pub body: String,
    pub reason: String,
}

struct View<'a> {
    m: &'a CollisionModel,
    r: &'a [f64],
}

/// A field (or three) of a body's arguments.
type Field = fn(&CollisionBodyArgs<Reg>) -> Reg;
type Field3 = fn(&CollisionBodyArgs<Reg>) -> [Reg; 3];

impl View<'_> {
    fn arg(&self, b: usize, f: Field) -> f64 {
        self.r[f(&self.m.bodies[b].args) as usize]
    }
    fn v3(&self, b: usize, f: Field3) -> [f64; 3] {
        f(&self.m.bodies[b].args).map(|x| self.r[x as usize])
    }
    fn rotation(&self, b: usize) -> [[f64; 3]; 3] {
        let rot = self.m.bodies[b].args.rotation;
        std::array::from_fn(|i| std::array::from_fn(|j| self.r[rot[3 * i + j] as usize]))
    }
    fn velocity_at(&self, b: usize, p: [f64; 3], r: [f64; 3]) -> [f64; 3] {
        let v = self.v3(b, |a| a.velocity);
        let w = self.v3(b, |a| a.angular_velocity);
        let c = cross(w, sub(p, r));
        [v[0] + c[0], v[1] + c[1], v[2] + c[2]]
    }
    fn mean(&self, a: usize, b: usize, f: Field) -> f64 {
        0.5 * (self.arg(a, f) + self.arg(b, f))
    }
}

fn shape_of(v: &View<'_>, b: usize) -> Result<Shape, String> {
    let d = v.v3(b, |a| a.dims);
    let code = v.arg(b, |a| a.shape);
    let Some(code) = ShapeCode::from_value(code) else {
        return Err(format!("unknown shape code {code}"));
    };
    let kind = match code {
        ShapeCode::Sphere => ShapeKind::Sphere { radius: d[0] },
        ShapeCode::Box => ShapeKind::Box {
            half: [d[0] / 2.0, d[1] / 2.0, d[2] / 2.0],
        },
        ShapeCode::Capsule => ShapeKind::Capsule {
            half_height: d[1] / 2.0,
            radius: d[0],
        },
        ShapeCode::Cylinder => ShapeKind::Cylinder {
            half_height: d[1] / 2.0,
            radius: d[0],
        },
        ShapeCode::Cone => ShapeKind::Cone {
            half_height: d[1] / 2.0,
            radius: d[0],
        },
        ShapeCode::Ellipsoid => ShapeKind::Ellipsoid { semi_axes: d },
        ShapeCode::HalfSpace => ShapeKind::HalfSpace,
    };
    Shape::new(kind).map_err(|e| e.0)
}

impl CollisionState {
    fn build(&mut self, v: &View<'_>) -> Result<(), CollisionFailure> {
        let n = v.m.bodies.len();
        self.shapes.clear();
        self.dynamic.clear();
        for b in 0..n {
            let s = shape_of(v, b).map_err(|reason| CollisionFailure {
                body: v.m.bodies[b].name.clone(),
                reason,
            })?;
            self.shapes.push(s);
            self.dynamic.push(v.arg(b, |a| a.dynamic) != 0.0);
        }
        let choice = v.r[v.m.world_args.broadphase as usize].round() as i64;
        let bounded = self.shapes.iter().filter(|s| s.is_bounded()).count();
        // Two bodies (or fewer bounded ones) leave the broadphase nothing to save.
        self.broadphase = Some(if choice == 1 || (choice == 0 && n <= 2) || bounded <= 1 {
            Box::new(AllPairs::default())
        } else {
            Box::new(SweepAndPrune::default())
        });
        Ok(())
    }

    /// Evaluates the world: forces, torques and gaps into their registers; in event
    /// mode also the contact set and impulses.
    pub fn evaluate(
        &mut self,
        m: &CollisionModel,
        r: &mut [f64],
        event_mode: bool,
    ) -> Result<(), CollisionFailure> {
        self.stats.evaluations += 1;
        let n = m.bodies.len();
        if self.shapes.len() != n {
            self.build(&View { m, r })?;
        }
        let margin = r[m.world_args.margin as usize].max(0.0);
        let tol = r[m.world_args.tolerance as usize].max(0.0);
        let sweep = r[m.world_args.sweep as usize] != 0.0;
        self.place(m, r)?;
        if self.origin.len() != n {
            self.origin = self.placements.clone();
        }
        if event_mode && m.bodies.iter().any(|_| true) {
            self.impulses(m, r, tol)?;
        }
        let v = View { m, r };
        // Bounding boxes: current and at the start of the step, for the sweep.
        self.boxes.clear();
        for b in 0..n {
            let now = aabb(&self.shapes[b], &self.placements[b]);
            let then = aabb(&self.shapes[b], &self.origin[b]);
            self.boxes.push(now.merged(&then).loosened(margin));
        }
        let bp = self.broadphase.as_mut().expect("built above");
        let before = bp.tests();
        bp.pairs(&self.boxes, &mut self.pairs);
        self.stats.broadphase_tests += bp.tests() - before;

        let mut out = vec![0.0; 6 * n];
        let (mut g_new, mut g_sep) = (1.0f64, 1.0f64);
        let mut seen_contact = 0usize;
        let mut changes = 0u64;
        for p in 0..self.pairs.len() {
            let (i, j) = self.pairs[p];
            let (a, b) = (i as usize, j as usize);
            if !self.dynamic[a] && !self.dynamic[b] {
                continue;
            }
            let ga = v.arg(a, |a| a.group).round() as i64;
            if ga != 0 && ga == v.arg(b, |a| a.group).round() as i64 {
                continue;
            }
            self.stats.narrowphase_pairs += 1;
            self.pair_contacts(m, a, b, margin)?;
            let dist = self.points.iter().map(|c| c.dist).fold(margin, f64::min);
            let key = (i, j);
            if event_mode {
                changes += self.update_contact(&v, a, b, dist, tol);
            }
            match self.contact.get(&key) {
                Some(_) => {
                    seen_contact += 1;
                    g_sep = g_sep.min(2.0 * tol - dist);
                }
                None => {
                    let g = self.swept_gap(a, b, dist, sweep);
                    g_new = g_new.min(g);
                }
            }
            if v.arg(a, |a| a.impulses) != 0.0 || v.arg(b, |a| a.impulses) != 0.0 {
                continue;
            }
            self.penalty_forces(&v, a, b, &mut out)?;
        }
        // Pairs in contact that are no longer candidates have separated by more than
        // the margin.
        if seen_contact < self.contact.len() {
            if event_mode {
                let pairs = &self.pairs;
                let before = self.contact.len();
                self.contact.retain(|k, _| pairs.contains(k));
                self.duration.retain(|k, _| pairs.contains(k));
                changes += (before - self.contact.len()) as u64;
            } else {
                g_sep = g_sep.min(2.0 * tol - margin.max(3.0 * tol));
            }
        }
        self.stats.contact_changes += changes;
        for (b, body) in m.bodies.iter().enumerate() {
            for k in 0..6 {
                r[body.outputs[k] as usize] = out[6 * b + k];
            }
        }
        r[m.gaps[0] as usize] = g_new;
        r[m.gaps[1] as usize] = g_sep;
        Ok(())
    }

    /// The bodies' placements, checked to be finite and rotations.
    fn place(&mut self, m: &CollisionModel, r: &[f64]) -> Result<(), CollisionFailure> {
        let n = m.bodies.len();
        let v = View { m, r };
        self.placements.clear();
        for b in 0..n {
            let rot = v.rotation(b);
            let det = dot(rot[0], cross(rot[1], rot[2]));
            let a = &m.bodies[b].args;
            let finite = (a.position.iter())
                .chain(&a.rotation)
                .chain(&a.velocity)
                .chain(&a.angular_velocity)
                .all(|&x| r[x as usize].is_finite());
            if !finite || (det - 1.0).abs() > 0.1 {
                return Err(CollisionFailure {
                    body: m.bodies[b].name.clone(),
                    reason: format!(
                        "placement or velocity is not finite, or the rotation matrix is not \
                         a rotation (det = {det:.3})"
                    ),
                });
            }
            self.placements.push(Placement {
                r: v.v3(b, |a| a.position),
                rot,
            });
        }
        Ok(())
    }

    /// In event mode: the pair `(a, b)` joins the contact set at a distance of at most
    /// `tol` (with its approach speed, and for penalty contacts the time a thin body
    /// takes to pass) and leaves it beyond `1.5 tol`. Returns the changes (0 or 1).
    fn update_contact(&mut self, v: &View<'_>, a: usize, b: usize, dist: f64, tol: f64) -> u64 {
        let key = (a as u32, b as u32);
        let (ra, rb) = (self.placements[a].r, self.placements[b].r);
        let in_contact = self.contact.contains_key(&key);
        if !in_contact && dist <= tol {
            let approach = self
                .points
                .iter()
                .min_by(|x, y| x.dist.total_cmp(&y.dist))
                .map(|c| {
                    let p = mid(c);
                    let rel = sub(v.velocity_at(a, p, ra), v.velocity_at(b, p, rb));
                    dot(rel, c.normal).max(0.0)
                })
                .unwrap_or(0.0);
            self.contact.insert(key, approach);
            if v.arg(a, |a| a.impulses) == 0.0 && v.arg(b, |a| a.impulses) == 0.0 && approach > 0.0
            {
                let thin = self.shapes[a]
                    .half_thickness
                    .min(self.shapes[b].half_thickness);
                self.duration.insert(key, thin / approach);
            }
            1
        } else if in_contact && dist > 1.5 * tol {
            // The separation crossing is located where dist = 2 tol (to rounding):
            // deciding at 1.5 tol keeps the decision on the right side of it.
            self.contact.remove(&key);
            self.duration.remove(&key);
            1
        } else {
            0
        }
    }

    /// The gap of a pair outside the contact set: its distance, negative when its
    /// linear sweep since the last accepted step hits.
    fn swept_gap(&self, a: usize, b: usize, dist: f64, sweep: bool) -> f64 {
        let mut g = dist;
        if dist > 0.0 && sweep {
            // Did the pair pass through each other since the last step?
            let da = sub(self.placements[a].r, self.origin[a].r);
            let db = sub(self.placements[b].r, self.origin[b].r);
            let rel = sub(da, db);
            if dot(rel, rel) > 0.0 {
                let moving = |i: usize, velocity| Moving {
                    shape: &self.shapes[i],
                    placement: &self.origin[i],
                    velocity,
                };
                if let Some(s) = time_of_impact(moving(a, da), moving(b, db), 1.0) {
                    if s < 1.0 {
                        g = -(1.0 - s) * dot(rel, rel).sqrt();
                    }
                }
            }
        }
        g
    }

    /// Penalty forces and torques of the pair `(a, b)`, shared over its penetrating
    /// points, added to `out` (six values per body).
    fn penalty_forces(
        &self,
        v: &View<'_>,
        a: usize,
        b: usize,
        out: &mut [f64],
    ) -> Result<(), CollisionFailure> {
        let (ra, rb) = (self.placements[a].r, self.placements[b].r);
        let mass = |x: usize| {
            if self.dynamic[x] {
                v.arg(x, |a| a.mass)
            } else {
                f64::INFINITY
            }
        };
        let (ma, mb) = (mass(a), mass(b));
        let m_eff = if ma.is_infinite() {
            mb
        } else if mb.is_infinite() {
            ma
        } else {
            ma * mb / (ma + mb)
        };
        let k = v.mean(a, b, |a| a.stiffness);
        let nexp = v.mean(a, b, |a| a.exponent);
        let damping = damping_law(v, a, b)?;
        let friction = Friction {
            mu_static: v.mean(a, b, |a| a.mu_static),
            mu_sliding: v.mean(a, b, |a| a.mu_sliding),
            v_switch: v.mean(a, b, |a| a.v_switch).max(f64::MIN_POSITIVE),
            f_max: v.mean(a, b, |a| a.f_max),
        };
        // The pair's law acts at its deepest point: its spring part is `K δmax^n`
        // however many points the manifold has. Each penetrating point takes the share
        // `δᵢ^n / Σ δⱼ^n` of it, so a point that joins at depth 0 adds nothing at once,
        // and a flat face reported with 4 or 8 points at one depth (parry's cap of a
        // cylinder, whose square turns with the normal) pushes the same.
        let (deepest, sum) = self
            .points
            .iter()
            .filter(|c| c.dist < 0.0)
            .fold((0.0f64, 0.0f64), |(deepest, sum), c| {
                (deepest.max(-c.dist), sum + (-c.dist).powf(nexp))
            });
        if sum <= 0.0 {
            return Ok(());
        }
        let scale = deepest.powf(nexp) / sum;
        // The restitution laws divide by the impact speed. The speed at first touch is
        // wrong when other bodies push the contact harder later (a rack of balls:
        // over-damped rebound); the pair's current relative energy, kinetic along the
        // normal plus elastic, as a speed, equals the impact speed throughout an
        // undamped binary impact and follows such pushes.
        let elastic = 2.0 * k * deepest.powf(nexp + 1.0) / ((nexp + 1.0) * m_eff);
        for c in &self.points {
            if c.dist >= 0.0 {
                continue;
            }
            let p = mid(c);
            let rel = sub(v.velocity_at(a, p, ra), v.velocity_at(b, p, rb));
            let vn = dot(rel, c.normal);
            let v_ref = (vn * vn + elastic).sqrt().max(V_FLOOR);
            let fnorm = scale * laws::normal_force(k, nexp, damping, -c.dist, vn, v_ref);
            let mut fa = [
                -fnorm * c.normal[0],
                -fnorm * c.normal[1],
                -fnorm * c.normal[2],
            ];
            if !friction.is_zero() {
                let vt = [
                    rel[0] - vn * c.normal[0],
                    rel[1] - vn * c.normal[1],
                    rel[2] - vn * c.normal[2],
                ];
                let ff = laws::friction_force(&friction, vt, fnorm);
                fa = [fa[0] + ff[0], fa[1] + ff[1], fa[2] + ff[2]];
            }
            let fb = [-fa[0], -fa[1], -fa[2]];
            add_to(&mut out[6 * a..6 * a + 3], fa);
            add_to(&mut out[6 * a + 3..6 * a + 6], cross(sub(p, ra), fa));
            add_to(&mut out[6 * b..6 * b + 3], fb);
            add_to(&mut out[6 * b + 3..6 * b + 6], cross(sub(p, rb), fb));
        }
        Ok(())
    }

    /// Newton restitution impulses along the normal at the deepest point of every pair
    /// in contact that approaches, repeated until none does (sequential impulses: a
    /// row of touching balls passes the impulse on).
    fn impulses(
        &mut self,
        m: &CollisionModel,
        r: &mut [f64],
        tol: f64,
    ) -> Result<(), CollisionFailure> {
        let n = m.bodies.len();
        if !m.bodies.iter().any(|b| r[b.args.impulses as usize] != 0.0) {
            return Ok(());
        }
        // Candidate pairs from the current placements.
        self.boxes.clear();
        for b in 0..n {
            self.boxes
                .push(aabb(&self.shapes[b], &self.placements[b]).loosened(2.0 * tol));
        }
        let bp = self.broadphase.as_mut().expect("built");
        bp.pairs(&self.boxes, &mut self.pairs);
        let pairs = self.pairs.clone();
        for _sweep in 0..1000 {
            let mut any = false;
            for &(i, j) in &pairs {
                let (a, b) = (i as usize, j as usize);
                if !self.dynamic[a] && !self.dynamic[b] {
                    continue;
                }
                let v = View { m, r };
                if v.arg(a, |a| a.impulses) == 0.0 && v.arg(b, |a| a.impulses) == 0.0 {
                    continue;
                }
                let ga = v.arg(a, |a| a.group).round() as i64;
                if ga != 0 && ga == v.arg(b, |a| a.group).round() as i64 {
                    continue;
                }
                self.pair_contacts(m, a, b, 2.0 * tol)?;
                let Some(c) = self
                    .points
                    .iter()
                    .min_by(|x, y| x.dist.total_cmp(&y.dist))
                    .copied()
                else {
                    continue;
                };
                let p = mid(&c);
                let (ra, rb) = (self.placements[a].r, self.placements[b].r);
                let rel = sub(v.velocity_at(a, p, ra), v.velocity_at(b, p, rb));
                let vn = dot(rel, c.normal);
                if vn <= 1e-12 * (dot(rel, rel).sqrt() + 1.0) {
                    continue;
                }
                let e = v.mean(a, b, |a| a.restitution);
                let inv = |body: usize, arm: [f64; 3]| -> (f64, [f64; 3], [f64; 3]) {
                    if !self.dynamic[body] {
                        return (0.0, [0.0; 3], [0.0; 3]);
                    }
                    let im = 1.0 / v.arg(body, |a| a.mass);
                    let pl = &self.placements[body];
                    let ib = v.v3(body, |a| a.inertia);
                    // I^-1 (arm x n) in world coordinates.
                    let an = pl.unrotate(cross(arm, c.normal));
                    let x = pl.rotate([an[0] / ib[0], an[1] / ib[1], an[2] / ib[2]]);
                    (im, x, arm)
                };
                let (ima, xa, arma) = inv(a, sub(p, ra));
                let (imb, xb, armb) = inv(b, sub(p, rb));
                let kk =
                    ima + imb + dot(cross(xa, arma), c.normal) + dot(cross(xb, armb), c.normal);
                if kk <= 0.0 || !kk.is_finite() {
                    continue;
                }
                let j = (1.0 + e) * vn / kk;
                for (body, sign, im, x) in [(a, -1.0, ima, xa), (b, 1.0, imb, xb)] {
                    if !self.dynamic[body] {
                        continue;
                    }
                    let Some(regs) = m.bodies[body].velocity_states else {
                        return Err(CollisionFailure {
                            body: m.bodies[body].name.clone(),
                            reason: "impulse impacts need the body's velocity and angular \
                                     velocity to be state variables"
                                .into(),
                        });
                    };
                    for k in 0..3 {
                        r[regs[k] as usize] += sign * j * im * c.normal[k];
                        r[regs[3 + k] as usize] += sign * j * x[k];
                    }
                }
                self.stats.impulses += 1;
                any = true;
            }
            if !any {
                return Ok(());
            }
        }
        Err(CollisionFailure {
            body: "the collision world".into(),
            reason: "impulses did not settle after 1000 sweeps (a locked cluster of bodies)".into(),
        })
    }

    /// The contact points of bodies `a` and `b` closer than `prediction`, into
    /// `self.points`.
    fn pair_contacts(
        &mut self,
        m: &CollisionModel,
        a: usize,
        b: usize,
        prediction: f64,
    ) -> Result<(), CollisionFailure> {
        self.points.clear();
        let query = ContactQuery {
            a: &self.shapes[a],
            pa: &self.placements[a],
            b: &self.shapes[b],
            pb: &self.placements[b],
            prediction,
        };
        contacts(query, &mut self.scratch, &mut self.points).map_err(|e| CollisionFailure {
            body: format!("{} and {}", m.bodies[a].name, m.bodies[b].name),
            reason: e.0,
        })?;
        Ok(())
    }

    /// The current placements become the origin of the next sweep (after each accepted
    /// step and each event).
    pub fn commit(&mut self) {
        self.origin.clone_from(&self.placements);
    }

    /// The largest step the integrator may take while the current penalty impacts
    /// last: a quarter of the time the approach speed needs to cross the thinner body's
    /// half thickness. Without it a step that starts at the touching instant could put
    /// every stage on the far side of a thin body, where the contact force is zero, and
    /// pass through it with no error to notice; with it some stage always sees the force.
    pub fn step_cap(&self) -> f64 {
        self.duration
            .values()
            .fold(f64::INFINITY, |a, &d| a.min(d / 4.0))
    }

    pub fn pairs_in_contact(&self) -> usize {
        self.contact.len()
    }
}

/// Smallest reference speed of the restitution laws (a contact at rest).
/// The pair's damping law (the first body's `law`, the mean of the pair's parameters).
fn damping_law(v: &View<'_>, a: usize, b: usize) -> Result<Damping, CollisionFailure> {
    let law = v.arg(a, |a| a.law);
    Ok(match LawCode::from_value(law) {
        Some(LawCode::Clipped) => Damping::Clipped {
            d: v.mean(a, b, |a| a.damping),
        },
        Some(LawCode::HuntCrossley) => Damping::HuntCrossley {
            e: v.mean(a, b, |a| a.restitution),
        },
        Some(LawCode::Flores) => Damping::Flores {
            e: v.mean(a, b, |a| a.restitution),
        },
        None => {
            return Err(CollisionFailure {
                body: v.m.bodies[a].name.clone(),
                reason: format!(
                    "unknown damping law code {law} (1 clipped, 2 Hunt-Crossley, 3 Flores)"
                ),
            })
        }
    })
}

const V_FLOOR: f64 = 1e-6;

fn mid(c: &ContactPoint) -> [f64; 3] {
    [
        0.5 * (c.point_a[0] + c.point_b[0]),
        0.5 * (c.point_a[1] + c.point_b[1]),
        0.5 * (c.point_a[2] + c.point_b[2]),
    ]
}
