//! The array built-ins lowered: reductions and `size`, `ndims`, constructors (`zeros`,
//! `fill`, `identity`, `linspace`, ...), `transpose`, `cross`, `skew`, `outerProduct`,
//! `array`, `vector`, `matrix`, `cat`; the built-ins unimo does not support refused.

use super::{unsupported, Lowerer};
use crate::error::{DaeError, DaeResult};
use crate::expr::ExprArena;
use crate::tensor::{self, Tensor};
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Lowerer<'_> {
    pub(super) fn array_builtin(
        &mut self,
        name: &str,
        args: &CallArgs,
        span: Span,
    ) -> DaeResult<Option<Tensor>> {
        let t = match name {
            "sum" | "product" | "min" | "max" => {
                let x = self.positional(args, 0, span)?;
                self.reduce(name, &x, span)?
            }
            "size" => {
                let x = self.positional(args, 0, span)?;
                if args.positional.len() > 1 {
                    let k = self.constant_int(&args.positional[1])?;
                    let n = x
                        .dims
                        .get((k - 1).max(0) as usize)
                        .copied()
                        .ok_or(DaeError::NoSuchDimension { dimension: k, span })?;
                    Tensor::scalar(self.a().constant(n as f64))
                } else {
                    let data = x
                        .dims
                        .iter()
                        .map(|&n| self.dae.arena.constant(n as f64))
                        .collect();
                    Tensor::vector(data)
                }
            }
            "ndims" => {
                let x = self.positional(args, 0, span)?;
                Tensor::scalar(self.a().constant(x.dims.len() as f64))
            }
            "transpose" => {
                let x = self.positional(args, 0, span)?;
                tensor::transpose(&x, span)?
            }
            "cross" => self.cross_product(args, span)?,
            "skew" => self.skew_matrix(args, span)?,
            "outerProduct" => {
                let x = self.positional(args, 0, span)?;
                let y = self.positional(args, 1, span)?;
                let mut data = Vec::new();
                for &a in &x.data {
                    for &b in &y.data {
                        data.push(self.dae.arena.mul(a, b));
                    }
                }
                Tensor {
                    dims: vec![x.data.len(), y.data.len()],
                    data,
                }
            }
            "scalar" => {
                let x = self.positional(args, 0, span)?;
                Tensor::scalar(x.as_scalar(span)?)
            }
            // `array(a, b, c)` is `{a, b, c}` (spec 10.4).
            "array" => {
                let items = args
                    .positional
                    .iter()
                    .map(|a| self.expr(a))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)?
            }
            "vector" => {
                let x = self.positional(args, 0, span)?;
                Tensor::vector(x.data)
            }
            "matrix" => {
                let x = self.positional(args, 0, span)?;
                as_matrix(x)
            }
            "cat" => {
                let k = self.constant_int(&args.positional[0])?;
                let items = args.positional[1..]
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<DaeResult<Vec<_>>>()?;
                tensor::concatenate(&items, (k - 1).max(0) as usize, span)?
            }
            "String" => return Err(unsupported("`String` outside an assert message", span)),
            "delay" => self.delay_call(args, span)?,
            "spatialDistribution" | "cardinality" | "getInstanceName" => {
                return Err(unsupported(format!("`{name}`"), span))
            }
            _ => return self.new_array(name, args, span),
        };
        Ok(Some(t))
    }

    /// `skew(x)`: the 3x3 matrix of the cross product with the 3-vector `x`.
    fn skew_matrix(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let x = self.positional(args, 0, span)?;
        if x.dims != [3] {
            return Err(tensor::size_error(&x.dims, &[3], span));
        }
        let ar = self.a();
        let z = ar.zero();
        let n = |ar: &mut ExprArena, k: usize| ar.neg(x.data[k]);
        let data = vec![
            z,
            n(ar, 2),
            x.data[1],
            x.data[2],
            z,
            n(ar, 0),
            n(ar, 1),
            x.data[0],
            z,
        ];
        Ok(Tensor {
            dims: vec![3, 3],
            data,
        })
    }

    /// `cross(x, y)` of two 3-vectors.
    fn cross_product(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let x = self.positional(args, 0, span)?;
        let y = self.positional(args, 1, span)?;
        if x.dims != [3] || y.dims != [3] {
            return Err(tensor::size_error(&x.dims, &y.dims, span));
        }
        let ar = self.a();
        let c = |ar: &mut ExprArena, i: usize, j: usize| {
            let p = ar.mul(x.data[i], y.data[j]);
            let q = ar.mul(x.data[j], y.data[i]);
            ar.sub(p, q)
        };
        let data = vec![c(ar, 1, 2), c(ar, 2, 0), c(ar, 0, 1)];
        Ok(Tensor::vector(data))
    }

    /// The array constructors `zeros`, `ones`, `fill`, `identity`, `diagonal` and
    /// `linspace`; `Ok(None)` when `name` is none of them.
    fn new_array(&mut self, name: &str, args: &CallArgs, span: Span) -> DaeResult<Option<Tensor>> {
        let t = match name {
            "zeros" | "ones" => {
                let dims = self.dims_args(args, 0)?;
                let v = self.a().constant(if name == "ones" { 1.0 } else { 0.0 });
                Tensor {
                    data: vec![v; dims.iter().product()],
                    dims,
                }
            }
            "fill" => {
                let x = self.positional(args, 0, span)?;
                let dims = self.dims_args(args, 1)?;
                let n: usize = dims.iter().product();
                let mut all = dims.clone();
                all.extend(&x.dims);
                let data = (0..n).flat_map(|_| x.data.iter().copied()).collect();
                Tensor { dims: all, data }
            }
            "identity" => {
                let n = self.constant_int(&args.positional[0])?.max(0) as usize;
                let (z, o) = (self.a().zero(), self.a().one());
                let data = (0..n * n)
                    .map(|k| if k / n == k % n { o } else { z })
                    .collect();
                Tensor {
                    dims: vec![n, n],
                    data,
                }
            }
            "diagonal" => {
                let x = self.positional(args, 0, span)?;
                let n = x.data.len();
                let z = self.a().zero();
                let data = (0..n * n)
                    .map(|k| if k / n == k % n { x.data[k / n] } else { z })
                    .collect();
                Tensor {
                    dims: vec![n, n],
                    data,
                }
            }
            "linspace" => {
                let a = self.positional(args, 0, span)?.as_scalar(span)?;
                let b = self.positional(args, 1, span)?.as_scalar(span)?;
                let n = self.constant_int(&args.positional[2])?.max(0) as usize;
                let mut data = Vec::new();
                for k in 0..n {
                    let f = if n > 1 {
                        k as f64 / (n - 1) as f64
                    } else {
                        0.0
                    };
                    let ar = self.a();
                    let fc = ar.constant(f);
                    let d = ar.sub(b, a);
                    let m = ar.mul(fc, d);
                    data.push(ar.add(a, m));
                }
                Tensor::vector(data)
            }
            _ => return Ok(None),
        };
        Ok(Some(t))
    }
}

/// A tensor as a matrix: scalars become 1x1, vectors columns.
pub(super) fn as_matrix(t: Tensor) -> Tensor {
    match t.dims.len() {
        0 => Tensor {
            dims: vec![1, 1],
            data: t.data,
        },
        1 => Tensor {
            dims: vec![t.dims[0], 1],
            data: t.data,
        },
        _ => t,
    }
}
