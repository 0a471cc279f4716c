//! The scene's laws: free flight under gravity, the contact force of the regularised
//! Coulomb law (spec A.5) with the normal force that keeps the support point on the plane
//! (`d2 gap/dt2 = 0`), and Newton's impact law with the regularised friction impulse
//! (spec A.6), all for the ellipsoid of `geometry` on the plane y = 0.

use crate::geometry::{
    add, cross, dot, kinematics, mat_t_vec, mat_vec, norm, scale, Ellipsoid, Kinematics, Vec3,
    NORMAL, STATE_LEN,
};

/// Parameters of one scene (paper A, section 4; spec A.9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    pub body: Ellipsoid,
    /// Gravity acceleration along -y.
    pub gravity: f64,
    /// Newton's coefficient of restitution `k`.
    pub restitution: f64,
    /// Coulomb friction coefficient `f`.
    pub friction: f64,
    /// Regularising slip velocity `delta`.
    pub delta: f64,
    /// Predicted jump height below which the body lands.
    pub clearance_tolerance: f64,
}

/// The constraint's state (the library's `State`: 0, 1, 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    Flight,
    Sliding,
    Rolling,
}

impl Phase {
    /// The library's integer code.
    pub fn code(self) -> i32 {
        match self {
            Phase::Flight => 0,
            Phase::Sliding => 1,
            Phase::Rolling => 2,
        }
    }
}

/// Accelerations of the body under gravity and a force `force` at the support point:
/// centre acceleration (absolute frame) and body-frame angular acceleration.
fn accelerations(scene: &Scene, k: &Kinematics, x: &[f64], force: Vec3) -> (Vec3, Vec3) {
    let m = scene.body.mass;
    let inertia = scene.body.inertia();
    let w = [x[10], x[11], x[12]];
    let iw = [inertia[0] * w[0], inertia[1] * w[1], inertia[2] * w[2]];
    let torque = mat_t_vec(&k.rotation, cross(k.rho, force));
    let gyro = cross(w, iw);
    let eps = [0, 1, 2].map(|i| (torque[i] - gyro[i]) / inertia[i]);
    let a = add(scale(1.0 / m, force), [0.0, -scene.gravity, 0.0]);
    (a, eps)
}

/// `d2 gap/dt2` for given accelerations.
fn gap_acceleration(k: &Kinematics, a: Vec3, eps_body: Vec3) -> f64 {
    let eps = mat_vec(&k.rotation, eps_body);
    dot(NORMAL, add(a, cross(eps, k.rho))) + k.bias
}

/// The direction factor `w` of the friction force `N (n + w)`: `-f v_t/|v_t|` sliding,
/// `-f v_t/delta` rolling (the regularised law).
pub fn friction_factor(scene: &Scene, k: &Kinematics, phase: Phase) -> Vec3 {
    let speed = norm(k.slip);
    let divisor = match phase {
        Phase::Rolling => scene.delta,
        _ => speed,
    };
    if scene.friction == 0.0 || divisor == 0.0 {
        return [0.0; 3];
    }
    scale(-scene.friction / divisor, k.slip)
}

/// The contact state the slip selects: Rolling at `|v_t| <= delta`, else Sliding (with
/// friction; without it the contact always slides, as in the library).
pub fn slip_phase(scene: &Scene, k: &Kinematics) -> Phase {
    if scene.friction > 0.0 && norm(k.slip) <= scene.delta {
        Phase::Rolling
    } else {
        Phase::Sliding
    }
}

/// `d2 gap/dt2` in free flight (the library's `-relan`).
pub fn free_gap_acceleration(scene: &Scene, k: &Kinematics, x: &[f64]) -> f64 {
    let (a, eps) = accelerations(scene, k, x, [0.0; 3]);
    gap_acceleration(k, a, eps)
}

/// The normal force `N` (> 0 pushes the body up) that keeps `d2 gap/dt2 = 0` with the
/// friction of `phase`, and the contact force `N (n + w)`.
pub fn contact_force(scene: &Scene, k: &Kinematics, x: &[f64], phase: Phase) -> (f64, Vec3) {
    let direction = add(NORMAL, friction_factor(scene, k, phase));
    let free = free_gap_acceleration(scene, k, x);
    let (a1, eps1) = accelerations(scene, k, x, direction);
    let per_newton = gap_acceleration(k, a1, eps1) - free;
    let n = -free / per_newton;
    (n, scale(n, direction))
}

/// `x' = rhs(x)` in `phase`.
pub fn rhs(scene: &Scene, phase: Phase, x: &[f64], out: &mut [f64]) {
    let k = kinematics(&scene.body, x);
    let force = match phase {
        Phase::Flight => [0.0; 3],
        _ => contact_force(scene, &k, x, phase).1,
    };
    let (a, eps) = accelerations(scene, &k, x, force);
    out[..3].copy_from_slice(&x[3..6]);
    out[3..6].copy_from_slice(&a);
    let (q, w) = (&x[6..10], [x[10], x[11], x[12]]);
    out[6] = 0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]);
    out[7] = 0.5 * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]);
    out[8] = 0.5 * (q[0] * w[1] - q[1] * w[2] + q[3] * w[0]);
    out[9] = 0.5 * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]);
    out[10..13].copy_from_slice(&eps);
}

/// Kinetic plus potential energy.
pub fn energy(scene: &Scene, x: &[f64]) -> f64 {
    let inertia = scene.body.inertia();
    let m = scene.body.mass;
    let v2 = x[3] * x[3] + x[4] * x[4] + x[5] * x[5];
    let rot: f64 = (0..3).map(|i| inertia[i] * x[10 + i] * x[10 + i]).sum();
    0.5 * m * v2 + 0.5 * rot + m * scene.gravity * x[1]
}

/// Why an impact has no solution.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImpactError {
    #[error("E4901 no impulse: the normal impulse per unit would be {0:e} (the friction impulse turns the body into the plane)")]
    NoImpulse(f64),
}

/// Applies Newton's impact law with the regularised friction impulse to `x` (left limit)
/// and returns the impulse magnitude `s` (the impulse on the body is `s (n + w)`, `w` from
/// the slip just before the impact).
pub fn apply_impact(scene: &Scene, x: &mut [f64]) -> Result<f64, ImpactError> {
    debug_assert_eq!(x.len(), STATE_LEN);
    let k = kinematics(&scene.body, x);
    let direction = add(NORMAL, friction_factor(scene, &k, slip_phase(scene, &k)));
    let inertia = scene.body.inertia();
    let m = scene.body.mass;
    // angular velocity increment per unit impulse (body frame), and point velocity change
    let dw_body = {
        let t = mat_t_vec(&k.rotation, cross(k.rho, direction));
        [0, 1, 2].map(|i| t[i] / inertia[i])
    };
    let dw = mat_vec(&k.rotation, dw_body);
    let dv_point = add(scale(1.0 / m, direction), cross(dw, k.rho));
    let per_unit = dot(NORMAL, dv_point);
    if per_unit <= 0.0 {
        return Err(ImpactError::NoImpulse(per_unit));
    }
    let s = -(1.0 + scene.restitution) * k.gap_rate / per_unit;
    for i in 0..3 {
        x[3 + i] += s * direction[i] / m;
        x[10 + i] += s * dw_body[i];
    }
    Ok(s)
}
