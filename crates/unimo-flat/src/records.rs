//! Records as structured variables: the fields of a record class (for its constructor
//! and for the back end's layout), and record bindings split into field bindings
//! (`parameter Complex p = Complex(1, 2)` gives `p.re = 1`, `p.im = 2`).

use crate::error::FlatError;
use crate::instantiate::Instantiator;
use crate::lookup::Found;
use crate::modif::{Bound, Mod};
use crate::tree::ClassId;
use smol_str::SmolStr;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// A field of a record class, as the constructor takes it.
#[derive(Clone, Debug)]
pub(crate) struct Field {
    pub name: SmolStr,
    /// Constants and `final` fields with a binding are not constructor inputs.
    pub input: bool,
    /// The field's binding in its declaration (its default in the constructor).
    pub default: Option<Expr>,
    /// The class that declares the field (the scope of its default).
    pub owner: ClassId,
}

impl Instantiator<'_, '_> {
    /// Whether `class` is a record (also through a short class definition).
    pub(crate) fn is_record(&self, class: ClassId) -> bool {
        self.tree.get(class).def.kind == ClassKind::Record
    }

    /// The fields of record `class` in constructor order: inherited ones first
    /// (spec 12.6.1).
    pub(crate) fn record_fields(&mut self, class: ClassId) -> Vec<Field> {
        let mut out = Vec::new();
        self.collect_fields(class, &mut out, 0);
        out
    }

    fn collect_fields(&mut self, class: ClassId, out: &mut Vec<Field>, depth: usize) {
        if depth > 32 {
            return;
        }
        for b in self.tree.bases(class) {
            self.collect_fields(b, out, depth + 1);
        }
        let def = self.tree.get(class).def.clone();
        for (e, cc) in def.component_clauses() {
            for d in &cc.components {
                let bound = d.modification.as_ref().is_some_and(|m| m.binding.is_some());
                let constant = cc.prefix.variability == Some(Variability::Constant);
                let input = !(constant || (e.is_final && bound));
                out.push(Field {
                    name: d.name.text.clone(),
                    input,
                    default: d.modification.as_ref().and_then(|m| m.binding.clone()),
                    owner: class,
                });
            }
        }
    }

    /// The record class a call calls, when it is a record constructor.
    pub(crate) fn constructor_class(&mut self, func: &Name, scope: ClassId) -> Option<ClassId> {
        let parts: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
        let start = if func.global { None } else { Some(scope) };
        match self.tree.lookup_dotted(start, &parts, false) {
            Some(Found::Class(c)) if self.is_record(c) => Some(c),
            _ => None,
        }
    }

    /// Splits the binding of a record component into bindings of its fields when the
    /// bound value is a record constructor call or another record component; the
    /// result keeps the binding when it cannot be split (a function returning a
    /// record, a conditional expression): the caller makes it a record equation.
    pub(crate) fn split_record_binding(&mut self, record: ClassId, m: Mod) -> Mod {
        let Some(b) = m.binding.clone() else {
            return m;
        };
        let fields = self.record_fields(record);
        let values: Vec<(SmolStr, Expr)> = match &b.expr.kind {
            ExprKind::Call { func, args } if args.iterators.is_empty() => {
                let Some(rc) = self.constructor_class(func, b.scope.class) else {
                    return match self.evaluated_record(&b, &fields) {
                        Some(values) => self.bind_fields(m, &b, values),
                        None => m,
                    };
                };
                let fields = self.record_fields(rc);
                let inputs: Vec<&Field> = fields.iter().filter(|f| f.input).collect();
                let mut out = Vec::new();
                if args.positional.len() > inputs.len() {
                    self.diags.push(
                        FlatError::RecordConstructorArity {
                            record: func.to_dotted(),
                            expected: inputs.len(),
                            given: args.positional.len(),
                            span: args.span,
                        }
                        .into(),
                    );
                    return Mod { binding: None, ..m };
                }
                for (f, a) in inputs.iter().zip(&args.positional) {
                    out.push((f.name.clone(), a.clone()));
                }
                for a in &args.named {
                    if !inputs.iter().any(|f| f.name == a.name.text) {
                        self.diags.push(
                            FlatError::NoRecordField {
                                record: func.to_dotted(),
                                field: a.name.text.to_string(),
                                fields: inputs.iter().map(|f| f.name.to_string()).collect(),
                                span: a.name.span,
                            }
                            .into(),
                        );
                        continue;
                    }
                    out.push((a.name.text.clone(), a.value.clone()));
                }
                out
            }
            ExprKind::Ref(r) => fields
                .iter()
                .filter(|f| f.input)
                .map(|f| {
                    let mut r = r.clone();
                    r.parts.push(RefPart {
                        name: Ident {
                            text: f.name.clone(),
                            span: r.span,
                        },
                        subscripts: Vec::new(),
                    });
                    (
                        f.name.clone(),
                        Expr {
                            kind: ExprKind::Ref(r),
                            span: b.expr.span,
                        },
                    )
                })
                .collect(),
            _ => match self.evaluated_record(&b, &fields) {
                Some(values) => values,
                None => return m,
            },
        };
        self.bind_fields(m, &b, values)
    }

    /// The fields of a record binding that is not a constructor (a call of a function
    /// returning a record, a conditional expression), evaluated at translation when
    /// every value it reads is known: the input fields' values as literals.
    fn evaluated_record(&mut self, b: &Bound, fields: &[Field]) -> Option<Vec<(SmolStr, Expr)>> {
        let flat = self.flat_expr(&b.expr, &b.scope);
        let Ok(crate::eval::Value::Record(_, values)) =
            crate::eval::eval(&flat, self, &mut Vec::new())
        else {
            return None;
        };
        Some(
            values
                .into_iter()
                .filter(|(n, _)| fields.iter().any(|f| f.input && f.name == n.as_str()))
                .map(|(n, v)| (SmolStr::from(n), v.to_expr(b.expr.span)))
                .collect(),
        )
    }

    /// `m` without its binding, each of `values` bound to its field instead (a
    /// modifier of the field itself wins).
    fn bind_fields(&mut self, m: Mod, b: &Bound, values: Vec<(SmolStr, Expr)>) -> Mod {
        let mut out = Mod { binding: None, ..m };
        for (name, value) in values {
            let child = Mod {
                binding: Some(Bound {
                    expr: value,
                    scope: b.scope.clone(),
                }),
                ..Mod::default()
            };
            match out.children.iter_mut().find(|(n, _)| *n == name) {
                // A modifier of the field itself wins over the record's binding.
                Some((_, existing)) if existing.binding.is_some() => {}
                Some((_, existing)) => *existing = existing.over(&child),
                None => out.children.push((name, child)),
            }
        }
        out
    }

    /// A record parameter whose binding could not be split into field bindings.
    pub(crate) fn unsplit_record_parameter(&mut self, name: &str, span: Span) {
        self.diags.push(
            FlatError::UnsplitRecordParameter {
                name: name.to_owned(),
                span,
            }
            .into(),
        );
    }
}

impl Instantiator<'_, '_> {
    /// Notes that the model uses record `class` (its type goes into the flat model).
    pub(crate) fn note_record(&mut self, class: ClassId) {
        if !self.records_used.contains(&class) {
            self.records_used.push(class);
        }
    }

    /// A record instance at `key` of type `class`.
    pub(crate) fn note_record_instance(&mut self, key: &str, class: ClassId) {
        self.note_record(class);
        let name = self.tree.full_name(class);
        self.model.record_instances.push((key.to_owned(), name));
    }

    /// The binding left on a structured component after splitting becomes a record
    /// equation `path = value`; a parameter's cannot (E2003).
    pub(crate) fn record_binding_equation(
        &mut self,
        m: &Mod,
        path: &[RefPart],
        variability: Option<crate::flat::Variability>,
        key: &str,
        span: Span,
    ) {
        let Some(b) = &m.binding else {
            return;
        };
        if matches!(
            variability,
            Some(crate::flat::Variability::Parameter | crate::flat::Variability::Constant)
        ) {
            self.unsplit_record_parameter(key, b.expr.span);
            return;
        }
        let rhs = self.flat_expr(&b.expr, &b.scope);
        let lhs = Expr {
            kind: ExprKind::Ref(crate::flat::path_ref(path.to_vec(), span)),
            span,
        };
        self.model.equations.push(Equation {
            kind: EquationKind::Simple { lhs, rhs },
            comment: Comment::default(),
            span,
        });
    }
}
