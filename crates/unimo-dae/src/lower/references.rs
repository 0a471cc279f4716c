//! Component references lowered: locals and `for` iterators, model variables and
//! package constants, subscripts (constant or computed) picking elements.

use super::{unsupported, Local, Lowerer};
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprId, RelOp, ScalarId};
use crate::tensor::Tensor;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// Whether subscripts pick a slice (`[:]`, `[1:3]`) of one dimension.
fn slice(subs: &[Subscript]) -> bool {
    match subs {
        [Subscript::Colon(_)] => true,
        [Subscript::Expr(e)] => matches!(e.kind, ExprKind::Range { .. }),
        _ => false,
    }
}

impl Lowerer<'_> {
    pub(super) fn local(&self, name: &str) -> Option<&Local> {
        self.locals.iter().rev().find(|l| l.name == name)
    }

    /// The value of a reference.
    pub(crate) fn reference(&mut self, r: &ComponentRef) -> DaeResult<Tensor> {
        if r.global {
            return self.global_ref(r);
        }
        if r.parts.len() == 1 {
            let name = r.parts[0].name.text.as_str();
            if name == "time" {
                let t = self.a().time();
                return Ok(Tensor::scalar(t));
            }
            if let Some(l) = self.local(name) {
                if l.record.is_some() && !r.parts[0].subscripts.is_empty() {
                    return Err(unsupported("subscripts on a record", r.span));
                }
                let Some(v) = l.value.clone() else {
                    return Err(DaeError::UsedBeforeAssigned {
                        name: name.to_string(),
                        span: r.span,
                    });
                };
                return self.subscript(v, &r.parts[0].subscripts, r.span);
            }
        }
        // A field of a function's record variable (`a.re`).
        if r.parts.len() > 1 && !r.global {
            if let Some(l) = self.local(r.parts[0].name.text.as_str()) {
                if let (Some(ty), Some(v)) = (l.record.clone(), l.value.clone()) {
                    return self.record_field(ty, v, &r.parts[1..], r.span);
                }
            }
        }
        // A slice of an array of components (`pin[1:3].i`): the elements' values.
        if r.parts[..r.parts.len() - 1]
            .iter()
            .any(|p| slice(&p.subscripts))
        {
            if let Some(t) = self.through_component_array(r)? {
                return Ok(t);
            }
        }
        // Subscripts of an inner part (`p[i].x` in a loop) must be known here: they
        // select the component, hence the variable.
        let folded = self.fold_inner_subscripts(r)?;
        let r = folded.as_ref().unwrap_or(r);
        let key = unimo_flat::eval::var_key(r);
        let builtin_enum = r.parts.len() == 2
            && matches!(
                r.parts[0].name.text.as_str(),
                "StateSelect" | "AssertionLevel"
            );
        if builtin_enum && !self.vars.contains_key(&key) {
            return self.global_ref(r);
        }
        let Some((first, dims)) = self.vars.get(&key).cloned() else {
            // A whole record instance (`z`, `c[2]`).
            let mut instance = key.clone();
            if let Some(last) = r.parts.last() {
                instance.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
            }
            if let Some(t) = self.record_instance(&instance, r.span)? {
                return Ok(t);
            }
            if let Some(t) = self.through_component_array(r)? {
                return Ok(t);
            }
            return Err(DaeError::NoSuchVariable {
                name: key.to_string(),
                span: r.span,
            });
        };
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        // One element picked by constant indices: no need to build the whole array.
        if !subs.is_empty() && subs.len() == dims.len() {
            if let Some(k) = self.constant_position(&dims, &subs)? {
                let s = ScalarId(first.0 + k as u32);
                let e = self.current_value(s);
                return Ok(Tensor::scalar(e));
            }
        }
        let n: usize = dims.iter().product();
        let data = (0..n)
            .map(|k| self.current_value(ScalarId(first.0 + k as u32)))
            .collect();
        let t = Tensor { dims, data };
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        self.subscript(t, &subs, r.span)
    }

    /// A reference through an array of components without subscripts (`port.T` of
    /// `port[1].T` ... `port[3].T`, spec 10.6.9): the array of the elements' values,
    /// the components' dimension first. `None`: no part of `r` is such an array.
    fn through_component_array(&mut self, r: &ComponentRef) -> DaeResult<Option<Tensor>> {
        let n = r.parts.len();
        for j in 0..n.saturating_sub(1) {
            // The indices picked: all (probed), or a range of constants.
            let range = match r.parts[j].subscripts.as_slice() {
                [] | [Subscript::Colon(_)] => None,
                [Subscript::Expr(e)] => match &e.kind {
                    ExprKind::Range { start, step, stop } => {
                        let a = self.constant_int(start)?;
                        let h = match step {
                            Some(h) => self.constant_int(h)?,
                            None => 1,
                        };
                        let b = self.constant_int(stop)?;
                        if h == 0 {
                            return Err(unsupported("a range with step 0", e.span));
                        }
                        Some((a, h, b))
                    }
                    _ => continue,
                },
                _ => continue,
            };
            let mut c = r.clone();
            let mut elements: Vec<Tensor> = Vec::new();
            let mut k = range.map_or(1, |(a, _, _)| a);
            loop {
                if let Some((_, h, b)) = range {
                    if (h > 0 && k > b) || (h < 0 && k < b) {
                        break;
                    }
                }
                c.parts[j].subscripts = vec![Subscript::Expr(Expr {
                    kind: ExprKind::Integer(k),
                    span: r.span,
                })];
                let mut path = unimo_flat::eval::var_key_parts(&c.parts[..=j]);
                path.push_str(&unimo_syntax::print::subscripts(&c.parts[j].subscripts));
                if !self.instance_exists(&path) {
                    if range.is_some() {
                        return Err(DaeError::NoSuchInstance {
                            name: path.to_string(),
                            span: r.span,
                        });
                    }
                    break;
                }
                elements.push(self.reference(&c)?);
                k += range.map_or(1, |(_, h, _)| h);
            }
            let Some(first) = elements.first() else {
                continue;
            };
            let inner = first.dims.clone();
            if elements.iter().any(|e| e.dims != inner) {
                return Err(unsupported(
                    "a reference through an array of components of different sizes",
                    r.span,
                ));
            }
            let mut dims = vec![elements.len()];
            dims.extend_from_slice(&inner);
            let data = elements.into_iter().flat_map(|e| e.data).collect();
            return Ok(Some(Tensor { dims, data }));
        }
        Ok(None)
    }

    /// Whether some variable of the flat model is inside the instance `path`.
    fn instance_exists(&mut self, path: &str) -> bool {
        let model = self.model;
        self.instances
            .get_or_insert_with(|| {
                let mut set = rustc_hash::FxHashSet::default();
                for v in &model.vars {
                    for (i, ch) in v.name.char_indices() {
                        if ch == '.' {
                            set.insert(v.name[..i].to_string());
                        }
                    }
                }
                set
            })
            .contains(path)
    }

    /// `r` with the subscripts of its inner parts folded to Integer literals, or `None`
    /// when only its last part has subscripts.
    fn fold_inner_subscripts(&mut self, r: &ComponentRef) -> DaeResult<Option<ComponentRef>> {
        if !r.parts[..r.parts.len().saturating_sub(1)]
            .iter()
            .any(|p| !p.subscripts.is_empty())
        {
            return Ok(None);
        }
        let mut c = r.clone();
        let n = c.parts.len();
        for part in &mut c.parts[..n - 1] {
            for sub in &mut part.subscripts {
                if let Subscript::Expr(e) = sub {
                    if matches!(e.kind, ExprKind::Integer(_)) {
                        continue;
                    }
                    let k = self.constant_int(e)?;
                    *e = Expr {
                        kind: ExprKind::Integer(k),
                        span: e.span,
                    };
                }
            }
        }
        Ok(Some(c))
    }

    /// The value of the model scalar `s`: what the algorithm being lowered assigned to
    /// it so far, else the variable.
    pub(crate) fn current_value(&mut self, s: ScalarId) -> ExprId {
        match self.assigned.as_ref().and_then(|m| m.get(&s)) {
            Some(&e) => e,
            None => self.var_value(s),
        }
    }

    /// The row-major position selected by scalar constant subscripts, if they are.
    fn constant_position(
        &mut self,
        dims: &[usize],
        subs: &[Subscript],
    ) -> DaeResult<Option<usize>> {
        let mut pos = 0usize;
        for (d, s) in dims.iter().zip(subs) {
            let Subscript::Expr(e) = s else {
                return Ok(None);
            };
            self.end_stack.push(*d);
            let t = self.expr(e);
            self.end_stack.pop();
            let t = t?;
            if !t.is_scalar() {
                return Ok(None);
            }
            let Some(k) = self.const_value(t.data[0]) else {
                return Ok(None);
            };
            let k = k as i64;
            if k < 1 || k as usize > *d {
                return Err(DaeError::IndexOutOfBounds {
                    index: k,
                    size: *d,
                    span: e.span,
                });
            }
            pos = pos * d + (k as usize - 1);
        }
        Ok(Some(pos))
    }

    fn global_ref(&mut self, r: &ComponentRef) -> DaeResult<Tensor> {
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        if let Some((literal, ty)) = names.split_last() {
            let ty = ty.join(".");
            let lits: Option<Vec<String>> = match ty.as_str() {
                "StateSelect" => Some(
                    ["never", "avoid", "default", "prefer", "always"]
                        .map(String::from)
                        .to_vec(),
                ),
                "AssertionLevel" => Some(["error", "warning"].map(String::from).to_vec()),
                _ => self
                    .dae
                    .enumerations
                    .iter()
                    .find(|(n, _)| *n == ty)
                    .map(|(_, l)| l.clone()),
            };
            if let Some(k) = lits.and_then(|l| l.iter().position(|x| x == literal)) {
                let c = self.a().constant(k as f64 + 1.0);
                return Ok(Tensor::scalar(c));
            }
        }
        Err(DaeError::NotVariableOrLiteral {
            name: names.join("."),
            span: r.span,
        })
    }

    /// Applies subscripts: scalar indices drop a dimension, `:` and vectors keep it.
    pub(crate) fn subscript(
        &mut self,
        t: Tensor,
        subs: &[Subscript],
        span: Span,
    ) -> DaeResult<Tensor> {
        if subs.is_empty() {
            return Ok(t);
        }
        if subs.len() > t.dims.len() {
            return Err(DaeError::TooManySubscripts {
                count: subs.len(),
                dims: t.dims.clone(),
                span,
            });
        }
        let first_dim = t.dims[0];
        let rows = t.rows();
        let rest = &subs[1..];
        match &subs[0] {
            Subscript::Colon(_) => {
                let items = rows
                    .into_iter()
                    .map(|r| self.subscript(r, rest, span))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)
            }
            Subscript::Expr(e) => {
                self.end_stack.push(first_dim);
                let idx = self.expr(e);
                self.end_stack.pop();
                let idx = idx?;
                if idx.is_scalar() {
                    let row = self.pick(&rows, idx.data[0], first_dim, e.span)?;
                    self.subscript(row, rest, span)
                } else {
                    let mut items = Vec::new();
                    for &i in &idx.data {
                        let row = self.pick(&rows, i, first_dim, e.span)?;
                        items.push(self.subscript(row, rest, span)?);
                    }
                    Tensor::stack(items, span)
                }
            }
        }
    }

    /// Row `i` (1-based) of `rows`; a non-constant index picks with an `if` chain.
    fn pick(&mut self, rows: &[Tensor], i: ExprId, n: usize, span: Span) -> DaeResult<Tensor> {
        if let Some(k) = self.const_value(i) {
            let k = k as i64;
            if k < 1 || k as usize > n {
                return Err(DaeError::IndexOutOfBounds {
                    index: k,
                    size: n,
                    span,
                });
            }
            return Ok(rows[k as usize - 1].clone());
        }
        // x[i] with a discrete i: if i == 1 then x[1] elseif ... else x[n].
        let mut acc = rows[n - 1].clone();
        for k in (0..n - 1).rev() {
            let kc = self.a().constant(k as f64 + 1.0);
            let c = self.a().rel(RelOp::Eq, i, kc);
            let data = rows[k]
                .data
                .iter()
                .zip(&acc.data)
                .map(|(&x, &y)| self.dae.arena.if_(c, x, y))
                .collect();
            acc = Tensor {
                dims: acc.dims.clone(),
                data,
            };
        }
        Ok(acc)
    }
}
