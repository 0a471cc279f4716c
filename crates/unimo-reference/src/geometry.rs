//! Closed-form kinematics of a homogeneous ellipsoid over the fixed plane y = 0: the
//! attitude matrix from the quaternion, the support point (the point of the ellipsoid
//! whose outer normal is -n, n = +y), the gap, the velocity of the material point there
//! and the part of the gap's second derivative that does not depend on the forces.

/// A vector or point resolved in a frame.
pub type Vec3 = [f64; 3];
/// A 3x3 matrix, rows first.
pub type Mat3 = [[f64; 3]; 3];

/// The plane's unit outer normal, `+y` of the absolute frame.
pub const NORMAL: Vec3 = [0.0, 1.0, 0.0];

pub fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn scale(s: f64, a: Vec3) -> Vec3 {
    [s * a[0], s * a[1], s * a[2]]
}

pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// `m * v`.
pub fn mat_vec(m: &Mat3, v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// `m' * v`.
pub fn mat_t_vec(m: &Mat3, v: Vec3) -> Vec3 {
    [
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    ]
}

/// Rotation body frame -> absolute frame of the quaternion `{q0, q1, q2, q3}`
/// (`x_AF = q x_body q*`), divided by `q.q` so that it stays orthogonal when `q` drifts
/// off unit length.
pub fn rotation(q: &[f64]) -> Mat3 {
    let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
    let s = 1.0 / (w * w + x * x + y * y + z * z);
    [
        [
            s * (w * w + x * x - y * y - z * z),
            s * 2.0 * (x * y - w * z),
            s * 2.0 * (x * z + w * y),
        ],
        [
            s * 2.0 * (x * y + w * z),
            s * (w * w - x * x + y * y - z * z),
            s * 2.0 * (y * z - w * x),
        ],
        [
            s * 2.0 * (x * z - w * y),
            s * 2.0 * (y * z + w * x),
            s * (w * w - x * x - y * y + z * z),
        ],
    ]
}

/// A homogeneous ellipsoid: semi-axes along its body axes, mass, principal inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    pub semi_axes: Vec3,
    pub mass: f64,
}

impl Ellipsoid {
    /// Principal moments of inertia `m/5 (b^2 + c^2, a^2 + c^2, a^2 + b^2)`.
    pub fn inertia(&self) -> Vec3 {
        let [a, b, c] = self.semi_axes;
        let k = self.mass / 5.0;
        [
            k * (b * b + c * c),
            k * (a * a + c * c),
            k * (a * a + b * b),
        ]
    }
}

/// The body's state vector: `r` (0..3), `v` (3..6), `q` (6..10), body-frame `omega`
/// (10..13).
pub const STATE_LEN: usize = 13;

/// What the contact laws need at one state, all in the absolute frame.
#[derive(Debug, Clone, Copy)]
pub struct Kinematics {
    /// Body -> absolute rotation.
    pub rotation: Mat3,
    /// Angular velocity, absolute frame.
    pub omega: Vec3,
    /// From the centre to the support point.
    pub rho: Vec3,
    /// Height of the support point above the plane (negative: penetration).
    pub gap: f64,
    /// Velocity of the material point of the body at the support point.
    pub point_velocity: Vec3,
    /// `d gap / dt` (the normal part of `point_velocity`).
    pub gap_rate: f64,
    /// Tangential part of `point_velocity` (the slip velocity).
    pub slip: Vec3,
    /// `n . (omega x (omega x rho) + omega x u)`, `u` the rate of the support point over
    /// the body surface: the part of `d2 gap/dt2` not due to the accelerations.
    pub bias: f64,
}

/// The kinematics of the support point at state `x`.
pub fn kinematics(body: &Ellipsoid, x: &[f64]) -> Kinematics {
    let rotation = rotation(&x[6..10]);
    let omega_body = [x[10], x[11], x[12]];
    let omega = mat_vec(&rotation, omega_body);
    let a2 = body.semi_axes.map(|s| s * s);
    let n_body = mat_t_vec(&rotation, NORMAL);
    let a2n = [a2[0] * n_body[0], a2[1] * n_body[1], a2[2] * n_body[2]];
    let support = dot(n_body, a2n).sqrt();
    let rho_body = scale(-1.0 / support, a2n);
    let rho = mat_vec(&rotation, rho_body);
    let gap = x[1] - support;
    let point_velocity = add([x[3], x[4], x[5]], cross(omega, rho));
    let gap_rate = dot(point_velocity, NORMAL);
    let slip = sub(point_velocity, scale(gap_rate, NORMAL));
    // the support point's motion over the body: n_body' = -omega_body x n_body
    let n_rate = scale(-1.0, cross(omega_body, n_body));
    let a2n_rate = [a2[0] * n_rate[0], a2[1] * n_rate[1], a2[2] * n_rate[2]];
    let support_rate = dot(n_body, a2n_rate) / support;
    let rho_body_rate = sub(
        scale(-1.0 / support, a2n_rate),
        scale(-support_rate / (support * support), a2n),
    );
    let u = mat_vec(&rotation, rho_body_rate);
    let bias = dot(
        NORMAL,
        add(cross(omega, cross(omega, rho)), cross(omega, u)),
    );
    Kinematics {
        rotation,
        omega,
        rho,
        gap,
        point_velocity,
        gap_rate,
        slip,
        bias,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_state() -> Vec<f64> {
        let q = [0.9, 0.2, -0.3, 0.25];
        let l = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut x = vec![0.1, 1.3, -0.2, 0.05, -0.3, 0.02];
        x.extend(q.iter().map(|v| v / l));
        x.extend([0.7, -10.0, 2.0]);
        x
    }

    #[test]
    fn the_support_point_is_the_lowest_point_of_the_surface() {
        let body = Ellipsoid {
            semi_axes: [1.0, 0.8, 1.2],
            mass: 1.0,
        };
        let x = sample_state();
        let k = kinematics(&body, &x);
        let t = rotation(&x[6..10]);
        let mut lowest = f64::INFINITY;
        let n = 400;
        for i in 0..=n {
            let theta = std::f64::consts::PI * i as f64 / n as f64;
            for j in 0..2 * n {
                let phi = std::f64::consts::PI * j as f64 / n as f64;
                let p = [
                    body.semi_axes[0] * theta.sin() * phi.cos(),
                    body.semi_axes[1] * theta.sin() * phi.sin(),
                    body.semi_axes[2] * theta.cos(),
                ];
                lowest = lowest.min(x[1] + mat_vec(&t, p)[1]);
            }
        }
        // the grid's lowest point is above the exact minimum, by less than its spacing^2
        assert!(k.gap <= lowest + 1e-15, "{} vs {lowest}", k.gap);
        assert!(lowest - k.gap < 1e-4, "{} vs {lowest}", k.gap);
        // the point lies on the surface
        let p = mat_t_vec(&t, k.rho);
        let f: f64 = (0..3).map(|i| (p[i] / body.semi_axes[i]).powi(2)).sum();
        assert!((f - 1.0).abs() < 1e-14);
    }

    #[test]
    fn gap_rate_and_bias_match_finite_differences() {
        let body = Ellipsoid {
            semi_axes: [1.0, 0.8, 1.2],
            mass: 1.0,
        };
        let x = sample_state();
        let k = kinematics(&body, &x);
        // move the body with constant v and omega for +-h (exact quaternion rotation)
        let at = |h: f64| {
            let mut y = x.clone();
            for i in 0..3 {
                y[i] += h * x[3 + i];
            }
            let w = [x[10], x[11], x[12]];
            let angle = norm(w) * h;
            let axis = scale(1.0 / norm(w), w);
            let dq = [
                (angle / 2.0).cos(),
                axis[0] * (angle / 2.0).sin(),
                axis[1] * (angle / 2.0).sin(),
                axis[2] * (angle / 2.0).sin(),
            ];
            let q = [x[6], x[7], x[8], x[9]];
            let prod = [
                q[0] * dq[0] - q[1] * dq[1] - q[2] * dq[2] - q[3] * dq[3],
                q[0] * dq[1] + q[1] * dq[0] + q[2] * dq[3] - q[3] * dq[2],
                q[0] * dq[2] - q[1] * dq[3] + q[2] * dq[0] + q[3] * dq[1],
                q[0] * dq[3] + q[1] * dq[2] - q[2] * dq[1] + q[3] * dq[0],
            ];
            y[6..10].copy_from_slice(&prod);
            kinematics(&body, &y).gap
        };
        // central differences with one Richardson extrapolation (error O(h^4))
        let first = |h: f64| (at(h) - at(-h)) / (2.0 * h);
        let second = |h: f64| (at(h) - 2.0 * k.gap + at(-h)) / (h * h);
        let h = 1e-3;
        let rate = (4.0 * first(h / 2.0) - first(h)) / 3.0;
        let second = (4.0 * second(h / 2.0) - second(h)) / 3.0;
        assert!((rate - k.gap_rate).abs() < 1e-7, "{rate} vs {}", k.gap_rate);
        // with constant v and omega the second derivative is the bias alone
        assert!((second - k.bias).abs() < 1e-5, "{second} vs {}", k.bias);
    }
}
