//! From the flat model's drawn components (`__unimo_visual` annotations, recorded by
//! flattening) to bodies: shape, dimensions, and where each position and rotation
//! entry comes from (a column of the result, or a constant of the model).

use super::table::ResultTable;
use crate::api::ApiError;
use crate::error::CliError;
use std::collections::HashMap;
use unimo_flat::flat::FlatType;
use unimo_flat::{FlatModel, FlatVisual};
use unimo_syntax::ast::{Argument, Expr, ExprKind, UnaryOp};

/// The shapes the page draws. Dimensions as `Unimo.Collision.ShapeType` states them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    Sphere,
    Box,
    Capsule,
    Cylinder,
    Cone,
    Ellipsoid,
    Plane,
}

impl Shape {
    /// The shape a name denotes (case-insensitive; `HalfSpace` is the plane).
    pub fn from_name(name: &str) -> Option<Shape> {
        Some(match name.to_ascii_lowercase().as_str() {
            "sphere" => Shape::Sphere,
            "box" => Shape::Box,
            "capsule" => Shape::Capsule,
            "cylinder" => Shape::Cylinder,
            "cone" => Shape::Cone,
            "ellipsoid" => Shape::Ellipsoid,
            "plane" | "halfspace" => Shape::Plane,
            _ => return None,
        })
    }

    /// The shape of an Integer code, in `Unimo.Collision.ShapeType`'s order (1: sphere).
    fn from_code(code: f64) -> Option<Shape> {
        const ORDER: [Shape; 7] = [
            Shape::Sphere,
            Shape::Box,
            Shape::Capsule,
            Shape::Cylinder,
            Shape::Cone,
            Shape::Ellipsoid,
            Shape::Plane,
        ];
        if (1.0..=7.0).contains(&code) && code.fract() == 0.0 {
            Some(ORDER[code as usize - 1])
        } else {
            None
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Shape::Sphere => "sphere",
            Shape::Box => "box",
            Shape::Capsule => "capsule",
            Shape::Cylinder => "cylinder",
            Shape::Cone => "cone",
            Shape::Ellipsoid => "ellipsoid",
            Shape::Plane => "plane",
        }
    }
}

/// Where a number comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Series {
    Column(usize),
    Constant(f64),
}

/// A body's orientation: body frame to world.
#[derive(Clone, Debug, PartialEq)]
pub enum Rotation {
    Identity,
    /// Row-major 3x3 matrix.
    Matrix(Vec<Series>),
    /// Unit quaternion (w, x, y, z).
    Quaternion(Vec<Series>),
}

/// One drawn body.
#[derive(Clone, Debug)]
pub struct Body {
    /// The instance path.
    pub name: String,
    pub class: String,
    pub shape: Shape,
    pub size: [f64; 3],
    /// A plane's normal in the body frame.
    pub normal: [f64; 3],
    pub color: Option<String>,
    pub position: Vec<Series>,
    pub rotation: Rotation,
}

/// The keys an annotation may set.
const KEYS: [&str; 7] = [
    "shape",
    "size",
    "position",
    "rotation",
    "quaternion",
    "normal",
    "color",
];

/// What the model knows: its flat variables and its constant values by scalar name.
pub struct ModelValues<'a> {
    pub flat: &'a FlatModel,
    pub constants: &'a HashMap<String, f64>,
}

/// The bodies of the model's drawn components, their series in `table`.
pub fn bodies(model: &ModelValues<'_>, table: &ResultTable) -> Result<Vec<Body>, ApiError> {
    model
        .flat
        .visuals
        .iter()
        .map(|v| body(model, table, v))
        .collect()
}

fn body(model: &ModelValues<'_>, table: &ResultTable, v: &FlatVisual) -> Result<Body, ApiError> {
    let at = Resolver { model, table, v };
    for arg in &v.spec.args {
        let Argument::Modify { name, .. } = arg else {
            return Err(at.malformed("only `key = value` arguments".into()));
        };
        let key = name.to_dotted();
        if !KEYS.contains(&key.as_str()) {
            return Err(at.malformed(format!("unknown key `{key}` (keys: {})", KEYS.join(", "))));
        }
    }
    let shape = at.shape()?;
    let position = match at.get("position") {
        Some(e) => at.series(e, 3, "position")?,
        None => return Err(at.malformed("`position` is missing".into())),
    };
    let rotation = match (at.get("rotation"), at.get("quaternion")) {
        (Some(_), Some(_)) => {
            return Err(at.malformed("give `rotation` or `quaternion`, not both".into()))
        }
        (Some(e), None) => Rotation::Matrix(at.series(e, 9, "rotation")?),
        (None, Some(e)) => Rotation::Quaternion(at.series(e, 4, "quaternion")?),
        (None, None) => Rotation::Identity,
    };
    let size = match at.get("size") {
        Some(e) => at.numbers(e)?,
        None if shape == Shape::Plane => Vec::new(),
        None => return Err(at.malformed("`size` is missing".into())),
    };
    let needed = match shape {
        Shape::Sphere => 1,
        Shape::Capsule | Shape::Cylinder | Shape::Cone => 2,
        Shape::Box | Shape::Ellipsoid => 3,
        Shape::Plane => 0,
    };
    if size.len() < needed || size.iter().take(needed).any(|x| x.is_nan() || *x <= 0.0) {
        return Err(at.malformed(format!(
            "a {} needs {needed} positive dimension(s) in `size`, got {size:?}",
            shape.name()
        )));
    }
    let mut dims = [0.0; 3];
    for (d, x) in dims.iter_mut().zip(&size) {
        *d = *x;
    }
    let normal = match at.get("normal") {
        Some(e) => {
            let n = at.numbers(e)?;
            let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n.len() != 3 || len.is_nan() || len <= 0.0 {
                return Err(at.malformed("`normal` must be a nonzero 3-vector".into()));
            }
            [n[0] / len, n[1] / len, n[2] / len]
        }
        None => [0.0, 0.0, 1.0],
    };
    let color = match at.get("color").map(|e| &e.kind) {
        None => None,
        Some(ExprKind::String(c)) if is_color(c) => Some(c.clone()),
        Some(_) => return Err(at.malformed("`color` must be a string \"#rrggbb\"".into())),
    };
    Ok(Body {
        name: v.path.clone(),
        class: v.class.clone(),
        shape,
        size: dims,
        normal,
        color,
        position,
        rotation,
    })
}

fn is_color(c: &str) -> bool {
    c.len() == 7 && c.starts_with('#') && c[1..].chars().all(|x| x.is_ascii_hexdigit())
}

/// Reads one annotation's arguments for the instance it belongs to.
struct Resolver<'m, 'a> {
    model: &'m ModelValues<'a>,
    table: &'m ResultTable,
    v: &'m FlatVisual,
}

/// One entry of an annotation value: a number, or a scalar of the model by full name.
enum Item {
    Number(f64),
    Name(String),
}

impl Resolver<'_, '_> {
    fn get(&self, key: &str) -> Option<&Expr> {
        self.v.spec.args.iter().find_map(|arg| match arg {
            Argument::Modify {
                name,
                modification: Some(m),
                ..
            } if name.to_dotted() == key => m.binding.as_ref(),
            _ => None,
        })
    }

    /// `E0071`: the annotation is malformed.
    fn malformed(&self, what: String) -> ApiError {
        CliError::MalformedVisual {
            path: self.v.path.clone(),
            class: self.v.class.clone(),
            what,
        }
        .into()
    }

    fn shape(&self) -> Result<Shape, ApiError> {
        let Some(e) = self.get("shape") else {
            return Err(self.malformed("`shape` is missing".into()));
        };
        let found = match &e.kind {
            ExprKind::String(s) => Shape::from_name(s),
            ExprKind::Ref(_) => {
                let full = self.full_name(e);
                let var = self.model.flat.vars.iter().find(|v| v.name == full);
                let Some(var) = var.filter(|v| v.dims.is_empty()) else {
                    return Err(self.not_a_variable(&full));
                };
                let value = self.constant(&full)?;
                match &var.ty {
                    FlatType::Enumeration { literals, .. } => {
                        let k = value.round() as usize;
                        literals
                            .get(k.wrapping_sub(1))
                            .and_then(|l| Shape::from_name(l))
                    }
                    _ => Shape::from_code(value),
                }
            }
            _ => None,
        };
        found.ok_or_else(|| {
            self.malformed(format!(
                "`shape = {}` is not a shape (sphere, box, capsule, cylinder, cone, \
                 ellipsoid, plane; or a parameter of type Unimo.Collision.ShapeType)",
                unimo_syntax::print::expr(e)
            ))
        })
    }

    /// The instance path joined with a reference as written (`r`, `InPortA.r`, `dims[1]`).
    fn full_name(&self, e: &Expr) -> String {
        format!("{}.{}", self.v.path, unimo_syntax::print::expr(e))
    }

    /// `E0072`: a name that is no variable of the instance.
    fn not_a_variable(&self, full: &str) -> ApiError {
        let name = full.strip_prefix(&format!("{}.", self.v.path));
        CliError::VisualNotVariable {
            path: self.v.path.clone(),
            class: self.v.class.clone(),
            name: name.unwrap_or(full).to_owned(),
        }
        .into()
    }

    /// The scalar entries of an annotation value: numbers, `{...}` of them, references
    /// (arrays expanded row-major).
    fn items(&self, e: &Expr, out: &mut Vec<Item>) -> Result<(), ApiError> {
        match &e.kind {
            ExprKind::Integer(i) => out.push(Item::Number(*i as f64)),
            ExprKind::Real(x) => out.push(Item::Number(*x)),
            ExprKind::Unary {
                op: UnaryOp::Neg,
                operand,
            } => match operand.kind {
                ExprKind::Integer(i) => out.push(Item::Number(-(i as f64))),
                ExprKind::Real(x) => out.push(Item::Number(-x)),
                _ => return Err(self.unsupported(e)),
            },
            ExprKind::Array(entries) => {
                for x in entries {
                    self.items(x, out)?;
                }
            }
            ExprKind::Ref(r) => {
                let full = self.full_name(e);
                let subscripted = r.parts.last().is_some_and(|p| !p.subscripts.is_empty());
                let flat = &self.model.flat.vars;
                if let Some(var) = flat.iter().find(|v| v.name == full) {
                    out.extend(scalar_names(&full, &var.dims).into_iter().map(Item::Name));
                } else if subscripted {
                    out.push(Item::Name(full));
                } else {
                    return Err(self.not_a_variable(&full));
                }
            }
            _ => return Err(self.unsupported(e)),
        }
        Ok(())
    }

    fn unsupported(&self, e: &Expr) -> ApiError {
        self.malformed(format!(
            "`{}`: a value is a number, a name of the instance or `{{...}}` of them",
            unimo_syntax::print::expr(e)
        ))
    }

    /// `count` entries, each a column of the result or a constant.
    fn series(&self, e: &Expr, count: usize, key: &str) -> Result<Vec<Series>, ApiError> {
        let mut items = Vec::new();
        self.items(e, &mut items)?;
        if items.len() != count {
            return Err(self.malformed(format!(
                "`{key}` has {} entries, {count} needed",
                items.len()
            )));
        }
        items
            .into_iter()
            .map(|item| match item {
                Item::Number(x) => Ok(Series::Constant(x)),
                Item::Name(n) => match self.table.column(&n) {
                    Some(k) => Ok(Series::Column(k)),
                    None => self.constant(&n).map(Series::Constant),
                },
            })
            .collect()
    }

    /// Numbers known before the run (dimensions, a normal).
    fn numbers(&self, e: &Expr) -> Result<Vec<f64>, ApiError> {
        let mut items = Vec::new();
        self.items(e, &mut items)?;
        items
            .into_iter()
            .map(|item| match item {
                Item::Number(x) => Ok(x),
                Item::Name(n) => match self.model.constants.get(&n) {
                    Some(x) => Ok(*x),
                    None => match self.table.column(&n) {
                        Some(k) => Ok(self.table.rows[0][k]),
                        None => Err(self.missing(&n)),
                    },
                },
            })
            .collect()
    }

    fn constant(&self, name: &str) -> Result<f64, ApiError> {
        self.model
            .constants
            .get(name)
            .copied()
            .ok_or_else(|| self.missing(name))
    }

    /// `E0073`: a variable the scene needs is neither a column nor a constant.
    fn missing(&self, name: &str) -> ApiError {
        CliError::MissingColumn {
            name: name.to_owned(),
            path: self.v.path.clone(),
        }
        .into()
    }
}

/// The scalar names of a variable: `x`, `x[1]`.., `x[1,1]`, `x[1,2]`.. (row-major).
fn scalar_names(name: &str, dims: &[usize]) -> Vec<String> {
    unimo_dae::lower::index_tuples(dims)
        .into_iter()
        .map(|t| {
            if t.is_empty() {
                name.to_owned()
            } else {
                let parts: Vec<String> = t.iter().map(|i| i.to_string()).collect();
                format!("{name}[{}]", parts.join(","))
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_expand_row_major() {
        assert_eq!(
            scalar_names("b.R", &[2, 2]),
            ["b.R[1,1]", "b.R[1,2]", "b.R[2,1]", "b.R[2,2]"]
        );
        assert_eq!(scalar_names("b.r", &[]), ["b.r"]);
    }

    #[test]
    fn shapes_by_name_and_code() {
        assert_eq!(Shape::from_name("HalfSpace"), Some(Shape::Plane));
        assert_eq!(Shape::from_name("Ellipsoid"), Some(Shape::Ellipsoid));
        assert_eq!(Shape::from_name("torus"), None);
        assert_eq!(Shape::from_code(4.0), Some(Shape::Cylinder));
        assert_eq!(Shape::from_code(8.0), None);
        assert_eq!(Shape::from_code(1.5), None);
    }
}
