//! Values the instantiator resolves while it builds the flat model: enumeration
//! literals by path, parameters of an instance read while its bases are instantiated
//! (before it declares them), and the shape of a binding whose value is not constant.

use crate::eval::{self, EvalError, Value};
use crate::instantiate::Instantiator;
use crate::lookup::Found;
use unimo_source::Span;
use unimo_syntax::ast::{ClassBody, ClassDef, ElementKind, Expr, ExprKind};

/// Whether a long class inherits (an `extends` clause or a class extension).
pub(crate) fn def_has_bases(def: &ClassDef) -> bool {
    match &def.body {
        ClassBody::Long {
            composition,
            extends,
            ..
        } => {
            extends.is_some()
                || composition
                    .elements
                    .iter()
                    .any(|e| matches!(e.kind, ElementKind::Extends(_)))
        }
        _ => false,
    }
}

impl Instantiator<'_, '_> {
    /// The sizes of a flattened expression from its structure (array constructors,
    /// references to variables of known size, element-wise operations), for bindings
    /// whose values are not known at compile time.
    pub(crate) fn shape_of(&mut self, e: &Expr) -> Option<Vec<usize>> {
        match &e.kind {
            ExprKind::Array(items) => {
                // The outer size is certain; inner sizes only as far as known (a
                // reference to a component declared further down is not yet).
                let mut d = vec![items.len()];
                if let Some(first) = items.first() {
                    d.extend(self.shape_of(first).unwrap_or_default());
                }
                Some(d)
            }
            ExprKind::Ref(r) if r.parts.last().is_some_and(|p| p.subscripts.is_empty()) => {
                let key = eval::var_key(r);
                let id = self.var_id(&key)?;
                Some(self.model.vars[id.0 as usize].dims.clone())
            }
            ExprKind::Unary { operand, .. } => self.shape_of(operand),
            ExprKind::Binary { lhs, rhs, .. } => {
                let (a, b) = (self.shape_of(lhs)?, self.shape_of(rhs)?);
                Some(if a.len() >= b.len() { a } else { b })
            }
            ExprKind::If { otherwise, .. } => self.shape_of(otherwise),
            // `[a; b]`: rows add up down the blocks, columns across the first block
            // row; a scalar or vector block is promoted to a matrix (spec 10.4.2).
            ExprKind::Matrix(rows) => {
                let mut height = 0;
                let mut width = None;
                for row in rows {
                    let mut h = None;
                    let mut w = 0;
                    for item in row {
                        let mut d = self.shape_of(item)?;
                        d.resize(2.max(d.len()), 1);
                        h.get_or_insert(d[0]);
                        w += d[1];
                    }
                    height += h?;
                    width.get_or_insert(w);
                }
                Some(vec![height, width?])
            }
            // `vector(x)`: all of x's elements in one dimension.
            ExprKind::Call { func, args }
                if !func.global
                    && func.parts.len() == 1
                    && func.parts[0].text == "vector"
                    && args.positional.len() == 1 =>
            {
                let d = self.shape_of(&args.positional[0])?;
                Some(vec![d.iter().product()])
            }
            ExprKind::Call { func, args } if func.global => self
                .call_shape(func, args)
                .or_else(|| eval::eval(e, self, &mut Vec::new()).ok().map(|v| v.dims())),
            ExprKind::Integer(_) | ExprKind::Real(_) | ExprKind::Bool(_) | ExprKind::String(_) => {
                Some(Vec::new())
            }
            _ => eval::eval(e, self, &mut Vec::new()).ok().map(|v| v.dims()),
        }
    }

    /// The sizes of the first output of a user function called with `args`, from its
    /// declared sizes: constants, inputs (`output Real table[nTable, 2]` with `nTable`
    /// given as a constant argument or by its default) and `size(u, k)` of an input.
    fn call_shape(
        &mut self,
        func: &unimo_syntax::ast::Name,
        args: &unimo_syntax::ast::CallArgs,
    ) -> Option<Vec<usize>> {
        let name = func.to_dotted().trim_start_matches('.').to_owned();
        let parts: Vec<&str> = crate::flat::split_name(&name);
        let Some(crate::lookup::Found::Class(c)) = self.tree.lookup_dotted(None, &parts, false)
        else {
            return None;
        };
        if self.tree.get(c).def.kind != unimo_syntax::ast::ClassKind::Function {
            return None;
        }
        let f = self.flat_function(c, &name)?;
        let out = f.outputs.first()?;
        // The argument bound to input `k` (flattened: in the caller's terms).
        let argument = |k: usize| -> Option<Expr> {
            let input = f.inputs.get(k)?;
            args.named
                .iter()
                .find(|a| a.name.text.as_str() == input.name)
                .map(|a| a.value.clone())
                .or_else(|| args.positional.get(k).cloned())
        };
        let input_index = |n: &str| f.inputs.iter().position(|i| i.name == n);
        let mut dims = Vec::with_capacity(out.dims.len());
        for (k, d) in out.dims.iter().enumerate() {
            if let Some(n) = d {
                dims.push(*n);
                continue;
            }
            let e = out.dim_exprs.get(k)?.as_ref()?;
            let n = match &e.kind {
                ExprKind::Integer(n) => usize::try_from(*n).ok()?,
                ExprKind::Ref(r) if r.parts.len() == 1 && r.parts[0].subscripts.is_empty() => {
                    let k = input_index(r.parts[0].name.text.as_str())?;
                    match argument(k) {
                        Some(a) => eval::eval(&a, self, &mut Vec::new()).ok()?.as_int()?,
                        // The input's default is in the function's scope: only a
                        // constant is used here.
                        None => match f.inputs[k].default.as_ref()?.kind {
                            ExprKind::Integer(n) => n,
                            _ => return None,
                        },
                    }
                    .try_into()
                    .ok()?
                }
                ExprKind::Call { func, args: a } if func.to_dotted() == "size" => {
                    let (u, j) = (a.positional.first()?, a.positional.get(1)?);
                    let ExprKind::Ref(r) = &u.kind else {
                        return None;
                    };
                    let k = input_index(r.parts.first()?.name.text.as_str())?;
                    let ExprKind::Integer(j) = j.kind else {
                        return None;
                    };
                    let shape = self.shape_of(&argument(k)?)?;
                    *shape.get(usize::try_from(j).ok()?.checked_sub(1)?)?
                }
                _ => return None,
            };
            dims.push(n);
        }
        Some(dims)
    }

    /// The value of a parameter or constant of an instance whose bases are being
    /// instantiated, before the instance declares it: its modifier's binding, else its
    /// declaration's (evaluated in their scopes).
    pub(crate) fn pending_own_value(
        &mut self,
        key: &str,
        span: Span,
    ) -> Option<Result<Value, EvalError>> {
        let frame = self.pending_own.iter().rposition(|(p, ..)| {
            key.len() > p.len()
                && key.starts_with(p.as_str())
                && (p.is_empty() || key.as_bytes()[p.len()] == b'.')
        })?;
        let (prefix_key, class, m, scope) = self.pending_own[frame].clone();
        let name = key[prefix_key.len()..].trim_start_matches('.');
        if name.contains(['.', '[']) {
            return None;
        }
        let def = self.tree.get(class).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return None;
        };
        let (cc, d) = composition.elements.iter().find_map(|e| match &e.kind {
            ElementKind::Component(cc) => cc
                .components
                .iter()
                .find(|d| d.name.text == name)
                .map(|d| (cc, d)),
            _ => None,
        })?;
        if !matches!(
            cc.prefix.variability,
            Some(
                unimo_syntax::ast::Variability::Parameter
                    | unimo_syntax::ast::Variability::Constant
            )
        ) {
            return None;
        }
        let (expr, expr_scope) = match m.child(name).and_then(|c| c.binding.as_ref()) {
            Some(b) => (b.expr.clone(), b.scope.clone()),
            None => (d.modification.as_ref()?.binding.clone()?, scope.clone()),
        };
        if !self.evaluating.insert(key.to_owned()) {
            return Some(Err(EvalError::Cycle {
                span,
                name: key.to_owned(),
            }));
        }
        let flat = self.expr(&expr, &expr_scope, &mut Vec::new(), &mut Vec::new());
        let r = eval::eval(&flat, self, &mut Vec::new());
        self.evaluating.remove(key);
        Some(r)
    }

    /// The value of an enumeration literal named by its full path
    /// (`Modelica.Blocks.Types.FilterType.LowPass`), following short classes.
    pub(crate) fn enum_literal(&mut self, key: &str) -> Option<Value> {
        let parts = crate::flat::split_name(key);
        let (literal, path) = parts.split_last()?;
        let mut class = match self.tree.lookup_dotted(None, path, false)? {
            Found::Class(c) => c,
            _ => return None,
        };
        for _ in 0..32 {
            match &self.tree.get(class).def.body {
                ClassBody::Enumeration { literals, .. } => {
                    let k = literals.iter().position(|l| l.name.text == *literal)?;
                    let name = format!("{}.{literal}", self.tree.full_name(class));
                    return Some(Value::Enum(k as i64 + 1, name));
                }
                ClassBody::Short { .. } => class = *self.tree.bases(class).first()?,
                _ => return None,
            }
        }
        None
    }
}
