//! Shapes and poses at the crate boundary (plain `[f64; 3]` arrays) and their parry
//! counterparts; the ellipsoid, which parry lacks, as a support map of our own.

use parry3d_f64::math::{Matrix, Pose, Rotation, Vector};
use parry3d_f64::shape::{SharedShape, SupportMap};

pub type V3 = [f64; 3];

/// The shapes a collision body can have, in its body frame. Cylinder, cone and capsule
/// have their axis along the body's y axis (parry's convention); the half-space is
/// `z <= 0` of the body frame (outward normal +z, through the body origin).
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeKind {
    Sphere {
        radius: f64,
    },
    Box {
        half: V3,
    },
    Capsule {
        half_height: f64,
        radius: f64,
    },
    Cylinder {
        half_height: f64,
        radius: f64,
    },
    Cone {
        half_height: f64,
        radius: f64,
    },
    Ellipsoid {
        semi_axes: V3,
    },
    HalfSpace,
    ConvexHull {
        points: Vec<V3>,
    },
    TriMesh {
        vertices: Vec<V3>,
        triangles: Vec<[u32; 3]>,
    },
}

/// Why a shape could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct ShapeError(pub String);

/// A homogeneous ellipsoid `x²/a² + y²/b² + z²/c² <= 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipsoid {
    pub semi_axes: Vector,
}

impl SupportMap for Ellipsoid {
    /// The point of the surface whose outer normal is `dir`: `A² d / |A d|`.
    fn local_support_point(&self, dir: Vector) -> Vector {
        let a = self.semi_axes;
        let ad = a * dir;
        let n = ad.length();
        if n == 0.0 {
            return Vector::new(a.x, 0.0, 0.0);
        }
        a * ad / n
    }
}

/// A shape ready for queries.
#[derive(Clone)]
pub struct Shape {
    pub kind: ShapeKind,
    pub(crate) parry: Option<SharedShape>,
    pub(crate) ellipsoid: Option<Ellipsoid>,
    /// Radius of a sphere about the body origin that holds the shape (infinite for the
    /// half-space).
    pub bounding_radius: f64,
    /// Half the smallest extent of the shape (infinite for the half-space): how far a
    /// body may move into it before it could come out on the other side.
    pub half_thickness: f64,
}

impl std::fmt::Debug for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Shape").field("kind", &self.kind).finish()
    }
}

fn v(x: V3) -> Vector {
    Vector::new(x[0], x[1], x[2])
}

/// The largest length a collision shape or placement may have: the queries square
/// lengths and compare features of a body with its size, so beyond this (1e12 times a
/// unit-size feature) a body's own features drop below f64 resolution, and near 1e200
/// parry's manifolds overflow (and panic).
pub const MAX_LENGTH: f64 = 1e12;

fn positive(what: &str, x: f64) -> Result<f64, ShapeError> {
    if x > 0.0 && x <= MAX_LENGTH {
        Ok(x)
    } else {
        Err(ShapeError(format!(
            "{what} must be positive and at most {MAX_LENGTH:e}, got {x:e}"
        )))
    }
}

/// A hull's or mesh's points: finite and within [`MAX_LENGTH`] of the body origin.
fn bounded_points(what: &str, points: &[V3]) -> Result<(), ShapeError> {
    match points
        .iter()
        .find(|p| !p.iter().all(|c| c.is_finite() && c.abs() <= MAX_LENGTH))
    {
        Some(p) => Err(ShapeError(format!(
            "{what} point {p:?} is not finite or farther than {MAX_LENGTH:e} from the body origin"
        ))),
        None => Ok(()),
    }
}

/// The radius of the largest sphere a shape surely holds (0 where no cheap bound is
/// known).
fn half_thickness(kind: &ShapeKind) -> f64 {
    match kind {
        ShapeKind::Sphere { radius } => *radius,
        ShapeKind::Box { half } => half.iter().fold(f64::INFINITY, |m, &h| m.min(h)),
        ShapeKind::Capsule { radius, .. } => *radius,
        ShapeKind::Cylinder {
            half_height,
            radius,
        }
        | ShapeKind::Cone {
            half_height,
            radius,
        } => half_height.min(*radius),
        ShapeKind::Ellipsoid { semi_axes } => {
            semi_axes.iter().fold(f64::INFINITY, |m, &a| m.min(a))
        }
        ShapeKind::HalfSpace => f64::INFINITY,
        // Hulls and meshes: no cheap inradius; a mesh may be a single sheet.
        ShapeKind::ConvexHull { .. } | ShapeKind::TriMesh { .. } => 0.0,
    }
}

impl Shape {
    pub fn new(kind: ShapeKind) -> Result<Shape, ShapeError> {
        let (parry, ellipsoid, radius) = match &kind {
            ShapeKind::Sphere { radius } => {
                let r = positive("sphere radius", *radius)?;
                (Some(SharedShape::ball(r)), None, r)
            }
            ShapeKind::Box { half } => {
                for &h in half {
                    positive("box half extent", h)?;
                }
                (
                    Some(SharedShape::cuboid(half[0], half[1], half[2])),
                    None,
                    v(*half).length(),
                )
            }
            ShapeKind::Capsule {
                half_height,
                radius,
            } => {
                let h = positive("capsule half height", *half_height)?;
                let r = positive("capsule radius", *radius)?;
                (Some(SharedShape::capsule_y(h, r)), None, h + r)
            }
            ShapeKind::Cylinder {
                half_height,
                radius,
            } => {
                let h = positive("cylinder half height", *half_height)?;
                let r = positive("cylinder radius", *radius)?;
                (Some(SharedShape::cylinder(h, r)), None, h.hypot(r))
            }
            ShapeKind::Cone {
                half_height,
                radius,
            } => {
                let h = positive("cone half height", *half_height)?;
                let r = positive("cone radius", *radius)?;
                (Some(SharedShape::cone(h, r)), None, h.hypot(r))
            }
            ShapeKind::Ellipsoid { semi_axes } => {
                for &a in semi_axes {
                    positive("ellipsoid semi-axis", a)?;
                }
                let e = Ellipsoid {
                    semi_axes: v(*semi_axes),
                };
                (
                    None,
                    Some(e),
                    semi_axes.iter().fold(0.0f64, |m, &a| m.max(a)),
                )
            }
            ShapeKind::HalfSpace => (Some(SharedShape::halfspace(Vector::Z)), None, f64::INFINITY),
            ShapeKind::ConvexHull { points } => {
                bounded_points("convex hull", points)?;
                let pts: Vec<Vector> = points.iter().map(|&p| v(p)).collect();
                let s = SharedShape::convex_hull(&pts).ok_or_else(|| {
                    ShapeError("the convex hull of the points is degenerate".into())
                })?;
                let r = pts.iter().fold(0.0f64, |m, p| m.max(p.length()));
                (Some(s), None, r)
            }
            ShapeKind::TriMesh {
                vertices,
                triangles,
            } => {
                bounded_points("triangle mesh", vertices)?;
                let pts: Vec<Vector> = vertices.iter().map(|&p| v(p)).collect();
                for t in triangles {
                    if t.iter().any(|&i| i as usize >= pts.len()) {
                        return Err(ShapeError(format!(
                            "triangle {t:?} refers to a vertex past the {} given",
                            pts.len()
                        )));
                    }
                }
                let r = pts.iter().fold(0.0f64, |m, p| m.max(p.length()));
                let s = SharedShape::trimesh(pts, triangles.clone())
                    .map_err(|e| ShapeError(format!("invalid triangle mesh: {e}")))?;
                (Some(s), None, r)
            }
        };
        let half_thickness = half_thickness(&kind);
        Ok(Shape {
            kind,
            parry,
            ellipsoid,
            bounding_radius: radius,
            half_thickness,
        })
    }

    /// Whether the shape is bounded (everything except the half-space).
    pub fn is_bounded(&self) -> bool {
        self.bounding_radius.is_finite()
    }
}

/// A rigid placement: position of the body origin and rotation matrix (body to world,
/// row-major), as a model's frame connector carries them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub r: V3,
    pub rot: [V3; 3],
}

impl Placement {
    pub const IDENTITY: Placement = Placement {
        r: [0.0; 3],
        rot: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    };

    pub fn at(r: V3) -> Placement {
        Placement {
            r,
            ..Placement::IDENTITY
        }
    }

    /// The parry pose; the rotation matrix is orthonormalised through a quaternion.
    pub fn pose(&self) -> Pose {
        let m = Matrix::from_cols(
            Vector::new(self.rot[0][0], self.rot[1][0], self.rot[2][0]),
            Vector::new(self.rot[0][1], self.rot[1][1], self.rot[2][1]),
            Vector::new(self.rot[0][2], self.rot[1][2], self.rot[2][2]),
        );
        Pose::from_parts(v(self.r), Rotation::from_mat3(&m).normalize())
    }

    /// A body-frame vector in world coordinates.
    pub fn rotate(&self, x: V3) -> V3 {
        let m = &self.rot;
        [
            m[0][0] * x[0] + m[0][1] * x[1] + m[0][2] * x[2],
            m[1][0] * x[0] + m[1][1] * x[1] + m[1][2] * x[2],
            m[2][0] * x[0] + m[2][1] * x[1] + m[2][2] * x[2],
        ]
    }

    /// A world vector in body coordinates.
    pub fn unrotate(&self, x: V3) -> V3 {
        let m = &self.rot;
        [
            m[0][0] * x[0] + m[1][0] * x[1] + m[2][0] * x[2],
            m[0][1] * x[0] + m[1][1] * x[1] + m[2][1] * x[2],
            m[0][2] * x[0] + m[1][2] * x[1] + m[2][2] * x[2],
        ]
    }
}

pub(crate) fn to_v3(x: Vector) -> V3 {
    [x.x, x.y, x.z]
}

pub(crate) fn to_vector(x: V3) -> Vector {
    v(x)
}
