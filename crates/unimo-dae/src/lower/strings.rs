//! String comparisons decided at translation: Strings have no numeric value, but a
//! comparison of String literals, String parameters and constants (and substrings of
//! them) is a Boolean constant (`if C1 == "D" then 1 else sqrt(3)`).

use super::Lowerer;
use crate::error::DaeResult;
use crate::tensor::Tensor;
use unimo_flat::flat::FlatType;
use unimo_syntax::ast::*;

/// How deep String bindings may refer to other String bindings.
const MAX_DEPTH: u32 = 16;

impl Lowerer<'_> {
    /// `a == b`, `a <> b` (and the orderings) of two Strings known at translation:
    /// the Boolean constant. `None`: not a comparison of Strings known here.
    pub(super) fn string_comparison(
        &mut self,
        op: BinaryOp,
        lhs: &Expr,
        rhs: &Expr,
    ) -> DaeResult<Option<Tensor>> {
        let BinaryOp::Rel(relation) = op else {
            return Ok(None);
        };
        if !self.is_string(lhs) && !self.is_string(rhs) {
            return Ok(None);
        }
        let (Some(a), Some(b)) = (self.string_value(lhs, 0), self.string_value(rhs, 0)) else {
            return Ok(None);
        };
        let v = relation.apply(a, b);
        Ok(Some(Tensor::scalar(self.a().boolean(v))))
    }

    /// Whether `e` is a String literal or a reference to a String variable.
    fn is_string(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::String(_) => true,
            ExprKind::Ref(r) => self.string_var(r).is_some(),
            _ => false,
        }
    }

    /// The binding of the String variable `r` refers to (`None`: not one).
    fn string_var(&self, r: &ComponentRef) -> Option<&Expr> {
        if r.parts.iter().any(|p| !p.subscripts.is_empty()) {
            return None;
        }
        let key = unimo_flat::eval::var_key(r);
        self.model
            .vars
            .iter()
            .find(|v| v.name == key && v.ty == FlatType::String && v.dims.is_empty())
            .and_then(|v| v.binding.as_deref())
    }

    /// The value of a String expression known at translation: a literal, a String
    /// parameter or constant with such a binding, a concatenation, or a substring of
    /// one (`Modelica.Utilities.Strings.substring`, the external `ModelicaStrings_substring`).
    fn string_value(&mut self, e: &Expr, depth: u32) -> Option<String> {
        if depth > MAX_DEPTH {
            return None;
        }
        match &e.kind {
            ExprKind::String(s) => Some(s.clone()),
            ExprKind::Ref(r) => {
                let b = self.string_var(r)?.clone();
                self.string_value(&b, depth + 1)
            }
            ExprKind::Binary {
                op: BinaryOp::Add,
                lhs,
                rhs,
            } => {
                let a = self.string_value(lhs, depth + 1)?;
                let b = self.string_value(rhs, depth + 1)?;
                Some(a + &b)
            }
            ExprKind::Call { func, args } => {
                let name = func.to_dotted();
                let f = self.functions.get(name.trim_start_matches('.'))?;
                let c = f.external_call.as_ref()?;
                // The arguments in the order of the inputs (the MSL's declaration).
                let in_order = c.args.len() == f.inputs.len()
                    && c.args.iter().zip(&f.inputs).all(|(a, i)| {
                        matches!(&a.kind, ExprKind::Ref(r) if r.parts.len() == 1
                            && r.parts[0].name.text == i.name)
                    });
                if c.function != "ModelicaStrings_substring"
                    || !in_order
                    || args.positional.len() != 3
                {
                    return None;
                }
                let s = self.string_value(&args.positional[0], depth + 1)?;
                let start = self.constant_int(&args.positional[1]).ok()?;
                let stop = self.constant_int(&args.positional[2]).ok()?;
                substring(&s, start, stop)
            }
            _ => None,
        }
    }
}

/// `ModelicaStrings_substring`: characters `start` to `stop` (1-based, inclusive) of
/// `s`; `None` when they are not inside it.
fn substring(s: &str, start: i64, stop: i64) -> Option<String> {
    let chars: Vec<char> = s.chars().collect();
    let n = chars.len() as i64;
    if start < 1 || stop < start || stop > n {
        return None;
    }
    Some(chars[(start - 1) as usize..stop as usize].iter().collect())
}

#[cfg(test)]
mod tests {
    #[test]
    fn substring_picks_characters() {
        assert_eq!(super::substring("Dy01", 1, 1).as_deref(), Some("D"));
        assert_eq!(super::substring("Dy01", 2, 4).as_deref(), Some("y01"));
        assert_eq!(super::substring("Dy01", 3, 5), None);
        assert_eq!(super::substring("Dy01", 0, 1), None);
    }
}
