//! Arrays of scalar expressions during lowering (row-major), and the array operators
//! of Modelica (spec 10.6) on them: elementwise arithmetic, products, slicing.

use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprArena, ExprId};
use unimo_source::Span;

/// A scalar (no dims) or an array of scalar expressions, row-major.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tensor {
    pub dims: Vec<usize>,
    pub data: Vec<ExprId>,
}

impl Tensor {
    pub fn scalar(e: ExprId) -> Tensor {
        Tensor {
            dims: Vec::new(),
            data: vec![e],
        }
    }

    pub fn vector(data: Vec<ExprId>) -> Tensor {
        Tensor {
            dims: vec![data.len()],
            data,
        }
    }

    pub fn is_scalar(&self) -> bool {
        self.dims.is_empty()
    }

    /// The single element of a scalar (or of a one-element array).
    pub fn as_scalar(&self, span: Span) -> DaeResult<ExprId> {
        if self.data.len() == 1 && self.dims.iter().all(|&d| d == 1) {
            Ok(self.data[0])
        } else {
            Err(DaeError::ScalarNeeded {
                dims: self.dims.clone(),
                span,
            })
        }
    }

    pub fn map(&self, mut f: impl FnMut(ExprId) -> ExprId) -> Tensor {
        Tensor {
            dims: self.dims.clone(),
            data: self.data.iter().map(|&x| f(x)).collect(),
        }
    }

    /// Sub-arrays along the first dimension.
    pub fn rows(&self) -> Vec<Tensor> {
        let Some((&n, rest)) = self.dims.split_first() else {
            return vec![self.clone()];
        };
        let size: usize = rest.iter().product();
        (0..n)
            .map(|i| Tensor {
                dims: rest.to_vec(),
                data: self.data[i * size..(i + 1) * size].to_vec(),
            })
            .collect()
    }

    /// Stacks equally sized tensors along a new first dimension.
    pub fn stack(items: Vec<Tensor>, span: Span) -> DaeResult<Tensor> {
        let inner = items.first().map(|t| t.dims.clone()).unwrap_or_default();
        let mut dims = vec![items.len()];
        dims.extend(&inner);
        let mut data = Vec::new();
        for t in items {
            if t.dims != inner {
                return Err(size_error(&inner, &t.dims, span));
            }
            data.extend(t.data);
        }
        Ok(Tensor { dims, data })
    }
}

pub use unimo_flat::flat::fmt_dims;

pub fn size_error(a: &[usize], b: &[usize], span: Span) -> DaeError {
    DaeError::SizesDiffer {
        left: a.to_vec(),
        right: b.to_vec(),
        equation: false,
        span,
    }
}

/// Elementwise `f(a, b)`, with a scalar broadcast against an array when `broadcast`.
pub fn elementwise(
    arena: &mut ExprArena,
    a: &Tensor,
    b: &Tensor,
    broadcast: bool,
    span: Span,
    f: impl Fn(&mut ExprArena, ExprId, ExprId) -> ExprId,
) -> DaeResult<Tensor> {
    if a.dims == b.dims {
        let data = a
            .data
            .iter()
            .zip(&b.data)
            .map(|(&x, &y)| f(arena, x, y))
            .collect();
        return Ok(Tensor {
            dims: a.dims.clone(),
            data,
        });
    }
    if broadcast && a.is_scalar() {
        let x = a.data[0];
        return Ok(b.map(|y| f(arena, x, y)));
    }
    if broadcast && b.is_scalar() {
        let y = b.data[0];
        return Ok(a.map(|x| f(arena, x, y)));
    }
    Err(size_error(&a.dims, &b.dims, span))
}

/// Modelica's `*`: scalar products, dot product, matrix-vector and matrix-matrix.
pub fn multiply(arena: &mut ExprArena, a: &Tensor, b: &Tensor, span: Span) -> DaeResult<Tensor> {
    if a.is_scalar() || b.is_scalar() {
        return elementwise(arena, a, b, true, span, ExprArena::mul);
    }
    let dot = |arena: &mut ExprArena, xs: &mut dyn Iterator<Item = (ExprId, ExprId)>| {
        let mut acc = arena.zero();
        for (x, y) in xs {
            let p = arena.mul(x, y);
            acc = arena.add(acc, p);
        }
        acc
    };
    match (a.dims.as_slice(), b.dims.as_slice()) {
        ([n], [m]) if n == m => {
            let e = dot(
                arena,
                &mut a.data.iter().copied().zip(b.data.iter().copied()),
            );
            Ok(Tensor::scalar(e))
        }
        ([r, c], [m]) if c == m => {
            let data = (0..*r)
                .map(|i| {
                    let mut it = (0..*c).map(|k| (a.data[i * c + k], b.data[k]));
                    dot(arena, &mut it)
                })
                .collect();
            Ok(Tensor::vector(data))
        }
        ([m], [r, c]) if m == r => {
            let data = (0..*c)
                .map(|j| {
                    let mut it = (0..*r).map(|k| (a.data[k], b.data[k * c + j]));
                    dot(arena, &mut it)
                })
                .collect();
            Ok(Tensor::vector(data))
        }
        ([r, k1], [k2, c]) if k1 == k2 => {
            let mut data = Vec::with_capacity(r * c);
            for i in 0..*r {
                for j in 0..*c {
                    let mut it = (0..*k1).map(|k| (a.data[i * k1 + k], b.data[k * c + j]));
                    data.push(dot(arena, &mut it));
                }
            }
            Ok(Tensor {
                dims: vec![*r, *c],
                data,
            })
        }
        _ => Err(size_error(&a.dims, &b.dims, span)),
    }
}

/// `transpose(a)` of a matrix.
pub fn transpose(a: &Tensor, span: Span) -> DaeResult<Tensor> {
    let [r, c] = a.dims[..] else {
        return Err(DaeError::TransposeNeedsMatrix {
            dims: a.dims.clone(),
            span,
        });
    };
    let mut data = Vec::with_capacity(r * c);
    for j in 0..c {
        for i in 0..r {
            data.push(a.data[i * c + j]);
        }
    }
    Ok(Tensor {
        dims: vec![c, r],
        data,
    })
}

/// Concatenation along dimension `k` (0-based) of arrays with equal other dims.
pub fn concatenate(items: &[Tensor], k: usize, span: Span) -> DaeResult<Tensor> {
    let Some(first) = items.first() else {
        return Ok(Tensor::vector(Vec::new()));
    };
    let nd = first.dims.len();
    if k >= nd {
        return Err(DaeError::ConcatenationDimension {
            dimension: k + 1,
            dims: first.dims.clone(),
            span,
        });
    }
    for t in items {
        let same = t.dims.len() == nd && (0..nd).all(|d| d == k || t.dims[d] == first.dims[d]);
        if !same {
            return Err(size_error(&first.dims, &t.dims, span));
        }
    }
    let outer: usize = first.dims[..k].iter().product();
    let mut dims = first.dims.clone();
    dims[k] = items.iter().map(|t| t.dims[k]).sum();
    let mut data = Vec::new();
    for o in 0..outer {
        for t in items {
            let chunk: usize = t.dims[k..].iter().product();
            data.extend_from_slice(&t.data[o * chunk..(o + 1) * chunk]);
        }
    }
    Ok(Tensor { dims, data })
}
