//! The arguments of the collision world's two external calls by name:
//! `collisionBody(...)` (one per `Unimo.Collision.CollisionBody`) and
//! `collisionGaps(...)` (the `CollisionWorld`). Lowering builds them from the call's
//! flattened scalar arguments with `T = ExprId`; the runtime maps them to registers
//! (`T = Reg`). The order is the one of the library's call, listed in
//! [`COLLISION_BODY_PARAMS`] (a test checks it against `stdlib/Unimo/Collision`).

/// The parameters of `collisionBody`, in call order: the name the library passes and the
/// number of scalars.
pub const COLLISION_BODY_PARAMS: [(&str, usize); 20] = [
    ("shape", 1),
    ("dims", 3),
    ("r", 3),
    ("R", 9),
    ("v", 3),
    ("w", 3),
    ("dynamic", 1),
    ("K", 1),
    ("n", 1),
    ("law", 1),
    ("D", 1),
    ("e", 1),
    ("muStatic", 1),
    ("muSliding", 1),
    ("vSwitch", 1),
    ("fMax", 1),
    ("impulses", 1),
    ("m", 1),
    ("I", 3),
    ("group", 1),
];

/// The number of scalar arguments of `collisionBody`.
pub const COLLISION_BODY_ARGS: usize = {
    let mut n = 0;
    let mut k = 0;
    while k < COLLISION_BODY_PARAMS.len() {
        n += COLLISION_BODY_PARAMS[k].1;
        k += 1;
    }
    n
};

/// The parameters of `collisionGaps`, in call order.
pub const COLLISION_WORLD_PARAMS: [&str; 4] = ["margin", "tolerance", "broadphase", "sweep"];

/// The number of scalar arguments of `collisionGaps`.
pub const COLLISION_WORLD_ARGS: usize = COLLISION_WORLD_PARAMS.len();

/// Shape codes of `Unimo.Collision.ShapeType` (the enumeration's literals in order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeCode {
    Sphere = 1,
    Box,
    Capsule,
    Cylinder,
    Cone,
    Ellipsoid,
    HalfSpace,
}

impl ShapeCode {
    pub const ALL: [ShapeCode; 7] = [
        ShapeCode::Sphere,
        ShapeCode::Box,
        ShapeCode::Capsule,
        ShapeCode::Cylinder,
        ShapeCode::Cone,
        ShapeCode::Ellipsoid,
        ShapeCode::HalfSpace,
    ];

    /// The shape of an argument's value; `None` for a value that is no code.
    pub fn from_value(x: f64) -> Option<ShapeCode> {
        Self::ALL.into_iter().find(|&c| c as i64 as f64 == x)
    }
}

/// Damping-law codes of `Unimo.Collision.DampingLaw`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawCode {
    Clipped = 1,
    HuntCrossley,
    Flores,
}

impl LawCode {
    pub const ALL: [LawCode; 3] = [LawCode::Clipped, LawCode::HuntCrossley, LawCode::Flores];

    /// The law of an argument's value; `None` for a value that is no code.
    pub fn from_value(x: f64) -> Option<LawCode> {
        Self::ALL.into_iter().find(|&c| c as i64 as f64 == x)
    }
}

/// One collision body's arguments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CollisionBodyArgs<T> {
    /// A [`ShapeCode`].
    pub shape: T,
    /// Dimensions (meaning by shape: radius, height, semi-axes, box edges).
    pub dims: [T; 3],
    /// Position of the body origin.
    pub position: [T; 3],
    /// Rotation matrix body to world, row-major.
    pub rotation: [T; 9],
    pub velocity: [T; 3],
    /// Angular velocity in world coordinates.
    pub angular_velocity: [T; 3],
    /// Nonzero for a moving body, 0 for an obstacle fixed to the ground.
    pub dynamic: T,
    /// Contact stiffness `K` and its exponent `n`.
    pub stiffness: T,
    pub exponent: T,
    /// A [`LawCode`].
    pub law: T,
    /// Damping coefficient `D` and restitution `e`.
    pub damping: T,
    pub restitution: T,
    pub mu_static: T,
    pub mu_sliding: T,
    pub v_switch: T,
    pub f_max: T,
    /// Nonzero for impulse impacts.
    pub impulses: T,
    pub mass: T,
    /// Principal moments of inertia in the body frame.
    pub inertia: [T; 3],
    /// Bodies of the same nonzero group do not collide.
    pub group: T,
}

impl<T: Copy> CollisionBodyArgs<T> {
    /// From the call's scalar arguments in order; `None` unless there are exactly
    /// [`COLLISION_BODY_ARGS`].
    pub fn from_flat(a: &[T]) -> Option<Self> {
        if a.len() != COLLISION_BODY_ARGS {
            return None;
        }
        let mut at = 0;
        let mut take = |n: usize| {
            at += n;
            &a[at - n..at]
        };
        let one = |s: &[T]| s[0];
        let three = |s: &[T]| [s[0], s[1], s[2]];
        Some(CollisionBodyArgs {
            shape: one(take(1)),
            dims: three(take(3)),
            position: three(take(3)),
            rotation: std::array::from_fn({
                let s = take(9);
                move |i| s[i]
            }),
            velocity: three(take(3)),
            angular_velocity: three(take(3)),
            dynamic: one(take(1)),
            stiffness: one(take(1)),
            exponent: one(take(1)),
            law: one(take(1)),
            damping: one(take(1)),
            restitution: one(take(1)),
            mu_static: one(take(1)),
            mu_sliding: one(take(1)),
            v_switch: one(take(1)),
            f_max: one(take(1)),
            impulses: one(take(1)),
            mass: one(take(1)),
            inertia: three(take(3)),
            group: one(take(1)),
        })
    }

    /// The scalar arguments in call order (the inverse of [`Self::from_flat`]).
    pub fn to_flat(&self) -> Vec<T> {
        let mut v = Vec::with_capacity(COLLISION_BODY_ARGS);
        v.push(self.shape);
        v.extend(self.dims);
        v.extend(self.position);
        v.extend(self.rotation);
        v.extend(self.velocity);
        v.extend(self.angular_velocity);
        v.extend([
            self.dynamic,
            self.stiffness,
            self.exponent,
            self.law,
            self.damping,
            self.restitution,
            self.mu_static,
            self.mu_sliding,
            self.v_switch,
            self.f_max,
            self.impulses,
            self.mass,
        ]);
        v.extend(self.inertia);
        v.push(self.group);
        v
    }

    /// Each argument through `f`.
    pub fn map<U: Copy>(&self, mut f: impl FnMut(T) -> U) -> CollisionBodyArgs<U> {
        let flat: Vec<U> = self.to_flat().into_iter().map(&mut f).collect();
        CollisionBodyArgs::from_flat(&flat).expect("same layout")
    }
}

/// The collision world's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CollisionWorldArgs<T> {
    /// Distance within which pairs are looked at in the narrowphase.
    pub margin: T,
    /// Contact tolerance: a pair within it is in contact.
    pub tolerance: T,
    /// 0 automatic, 1 all pairs, 2 sweep and prune.
    pub broadphase: T,
    /// Nonzero: the linear sweep test against tunnelling.
    pub sweep: T,
}

impl<T: Copy> CollisionWorldArgs<T> {
    /// From the call's scalar arguments in order.
    pub fn from_flat(a: &[T]) -> Option<Self> {
        match *a {
            [margin, tolerance, broadphase, sweep] => Some(CollisionWorldArgs {
                margin,
                tolerance,
                broadphase,
                sweep,
            }),
            _ => None,
        }
    }

    pub fn to_flat(&self) -> [T; 4] {
        [self.margin, self.tolerance, self.broadphase, self.sweep]
    }

    pub fn map<U>(&self, mut f: impl FnMut(T) -> U) -> CollisionWorldArgs<U> {
        CollisionWorldArgs {
            margin: f(self.margin),
            tolerance: f(self.tolerance),
            broadphase: f(self.broadphase),
            sweep: f(self.sweep),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_and_named_agree() {
        let flat: Vec<u32> = (0..COLLISION_BODY_ARGS as u32).collect();
        let a = CollisionBodyArgs::from_flat(&flat).unwrap();
        assert_eq!(a.to_flat(), flat);
        assert_eq!(COLLISION_BODY_ARGS, 38);
        // Spot checks against the parameter list.
        let offset = |name: &str| {
            let k = COLLISION_BODY_PARAMS
                .iter()
                .position(|(n, _)| *n == name)
                .unwrap();
            COLLISION_BODY_PARAMS[..k]
                .iter()
                .map(|p| p.1)
                .sum::<usize>() as u32
        };
        assert_eq!(a.rotation[0], offset("R"));
        assert_eq!(a.law, offset("law"));
        assert_eq!(a.mass, offset("m"));
        assert_eq!(a.inertia, [offset("I"), offset("I") + 1, offset("I") + 2]);
        assert_eq!(a.group, 37);
        assert_eq!(a.map(|x| x * 2).to_flat()[5], 10);
        assert!(CollisionBodyArgs::from_flat(&flat[1..]).is_none());
        let w = CollisionWorldArgs::from_flat(&[1, 2, 3, 4]).unwrap();
        assert_eq!((w.margin, w.sweep), (1, 4));
    }

    #[test]
    fn codes() {
        assert_eq!(ShapeCode::from_value(7.0), Some(ShapeCode::HalfSpace));
        assert_eq!(ShapeCode::from_value(0.0), None);
        assert_eq!(ShapeCode::from_value(1.5), None);
        assert_eq!(LawCode::from_value(2.0), Some(LawCode::HuntCrossley));
        assert_eq!(LawCode::from_value(4.0), None);
    }
}
