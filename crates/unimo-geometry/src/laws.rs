//! Contact force laws: paper B's penalty law (Hertz spring plus a damper clipped so the
//! contact never pulls), Hunt–Crossley and Flores damping stated by a coefficient of
//! restitution, and paper B's friction with static and sliding coefficients.

/// How the normal damping is stated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Damping {
    /// Paper B: `Fd = D * ddelta/dt`, clipped to `[-Fc, Fc]`.
    Clipped { d: f64 },
    /// Hunt–Crossley: `Fn = K delta^n (1 + 3(1-e)/2 * ddelta/dt / v_impact)`.
    HuntCrossley { e: f64 },
    /// Flores et al.: `Fn = K delta^n (1 + 8(1-e)/(5e) * ddelta/dt / v_impact)`.
    Flores { e: f64 },
}

/// Normal force magnitude (pushing the bodies apart, never negative) for penetration
/// `delta >= 0` growing at `delta_dot`; `v_impact` is the impact speed the restitution
/// laws divide by (the collision world passes the pair's current relative energy as a
/// speed, which equals the impact speed throughout an undamped binary impact).
pub fn normal_force(
    k: f64,
    n: f64,
    damping: Damping,
    delta: f64,
    delta_dot: f64,
    v_impact: f64,
) -> f64 {
    if delta <= 0.0 {
        return 0.0;
    }
    let fc = k * delta.powf(n);
    let f = match damping {
        Damping::Clipped { d } => fc + (d * delta_dot).clamp(-fc, fc),
        Damping::HuntCrossley { e } => {
            fc * (1.0 + 1.5 * (1.0 - e) * delta_dot / v_impact.max(f64::MIN_POSITIVE))
        }
        Damping::Flores { e } => {
            fc * (1.0
                + 8.0 * (1.0 - e) / (5.0 * e.max(1e-12)) * delta_dot
                    / v_impact.max(f64::MIN_POSITIVE))
        }
    };
    f.max(0.0)
}

/// Paper B's friction parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// Coefficient below the switching velocity (paper B's `mu_r`).
    pub mu_static: f64,
    /// Coefficient at or above it (`mu_s`).
    pub mu_sliding: f64,
    /// Switching velocity `v_c`.
    pub v_switch: f64,
    /// Cap `F_max` on the friction magnitude.
    pub f_max: f64,
}

impl Friction {
    pub fn is_zero(&self) -> bool {
        self.mu_static == 0.0 && self.mu_sliding == 0.0
    }
}

/// Friction force on A for tangential slip velocity `v_t` (of A relative to B) and
/// normal force `fn_`. Paper B's law, with one change: below the switching velocity the
/// direction `-v/|v|` is replaced by `-v/v_c`, so the force goes to zero with the slip
/// instead of jumping (the paper's law has no defined value at zero slip and makes a
/// resting contact chatter).
pub fn friction_force(f: &Friction, v_t: [f64; 3], fn_: f64) -> [f64; 3] {
    let s = (v_t[0] * v_t[0] + v_t[1] * v_t[1] + v_t[2] * v_t[2]).sqrt();
    if s == 0.0 || fn_ <= 0.0 {
        return [0.0; 3];
    }
    let (mu, scale) = if s < f.v_switch {
        (f.mu_static, 1.0 / f.v_switch)
    } else {
        (f.mu_sliding, 1.0 / s)
    };
    let mag = (mu * fn_).min(f.f_max);
    [
        -mag * v_t[0] * scale,
        -mag * v_t[1] * scale,
        -mag * v_t[2] * scale,
    ]
}

/// Paper B's tangent basis from a unit normal: `t1` has its two smaller components set
/// to 1 and the third solved from `n . t1 = 0`; `t2 = n x t1`; both normalised.
pub fn tangent_basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let big = (0..3)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(2);
    let mut t1 = [1.0; 3];
    let others: f64 = (0..3).filter(|&k| k != big).map(|k| n[k]).sum();
    t1[big] = -others / n[big];
    let l = (t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]).sqrt();
    let t1 = [t1[0] / l, t1[1] / l, t1[2] / l];
    let t2 = [
        n[1] * t1[2] - n[2] * t1[1],
        n[2] * t1[0] - n[0] * t1[2],
        n[0] * t1[1] - n[1] * t1[0],
    ];
    (t1, t2)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates a linear (n = 1) Hunt–Crossley impact of a unit mass and returns the
    /// coefficient of restitution it produces.
    fn restitution(damping: Damping, v0: f64) -> f64 {
        let (k, m) = (1e6, 1.0);
        let (mut x, mut v) = (0.0f64, v0);
        let h = 1e-8;
        loop {
            let a = -normal_force(k, 1.0, damping, x, v, v0) / m;
            // semi-implicit Euler, small step
            v += h * a;
            x += h * v;
            if x < 0.0 {
                return -v / v0;
            }
        }
    }

    #[test]
    fn restitution_laws_give_roughly_the_stated_coefficient() {
        // Hunt–Crossley is accurate for e near 1, Flores over the whole range.
        let e = restitution(Damping::HuntCrossley { e: 0.9 }, 1.0);
        assert!((e - 0.9).abs() < 0.02, "{e}");
        for target in [0.3, 0.6, 0.9] {
            let e = restitution(Damping::Flores { e: target }, 2.0);
            assert!((e - target).abs() < 0.06, "Flores {target}: {e}");
        }
    }

    #[test]
    fn clipped_damper_never_pulls() {
        for dd in [-1e9, -1.0, 0.0, 1.0, 1e9] {
            let f = normal_force(1e5, 1.5, Damping::Clipped { d: 1e4 }, 1e-3, dd, 0.0);
            let fc = 1e5 * 1e-3f64.powf(1.5);
            assert!((0.0..=2.0 * fc + 1e-12).contains(&f), "{dd}: {f}");
        }
        assert_eq!(
            normal_force(1e5, 1.5, Damping::Clipped { d: 1e4 }, -1e-3, 5.0, 0.0),
            0.0
        );
    }

    #[test]
    fn friction_opposes_slip_and_respects_the_cap() {
        let f = Friction {
            mu_static: 0.5,
            mu_sliding: 0.3,
            v_switch: 0.01,
            f_max: 2.0,
        };
        let ff = friction_force(&f, [1.0, 0.0, 0.0], 10.0);
        assert_eq!(ff, [-2.0, 0.0, 0.0]);
        let ff = friction_force(&f, [0.0, 1.0, 0.0], 1.0);
        assert!((ff[1] + 0.3).abs() < 1e-15);
        let ff = friction_force(&f, [0.0, 0.005, 0.0], 1.0);
        assert!((ff[1] + 0.25).abs() < 1e-15, "{ff:?}");
        assert_eq!(friction_force(&f, [0.0; 3], 1.0), [0.0; 3]);
    }

    #[test]
    fn tangent_basis_is_orthonormal() {
        for n in [[0.0, 0.0, 1.0], [0.6, 0.0, -0.8], [1.0 / 3f64.sqrt(); 3]] {
            let (t1, t2) = tangent_basis(n);
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            assert!(
                dot(n, t1).abs() < 1e-15 && dot(n, t2).abs() < 1e-15 && dot(t1, t2).abs() < 1e-15
            );
            assert!((dot(t1, t1) - 1.0).abs() < 1e-15 && (dot(t2, t2) - 1.0).abs() < 1e-15);
        }
    }
}
