//! Records in lowering: a record value is its fields side by side (nested records
//! flattened, arrays row-major) in one vector `Tensor`; record equations are then
//! vector equations. Whole record instances of the model, record constructors, and
//! functions' record inputs, outputs and locals (with field access and field
//! assignment) lower through this layout.

use crate::error::{DaeError, DaeResult};
use crate::lower::{unsupported, Lowerer};
use crate::tensor::Tensor;
use unimo_flat::functions::{FlatRecord, FuncVar};
use unimo_source::Span;
use unimo_syntax::ast::*;

/// Where a field sits in its record's value.
pub(crate) struct Slot {
    pub offset: usize,
    pub len: usize,
    pub dims: Vec<usize>,
    /// The record type of a field that is a record (scalar).
    pub record: Option<String>,
}

impl<'m> Lowerer<'m> {
    fn record_type(&self, name: &str, span: Span) -> DaeResult<&'m FlatRecord> {
        let name = name.trim_start_matches('.');
        self.model
            .records
            .iter()
            .find(|r| r.name == name)
            .ok_or_else(|| DaeError::UnknownRecord {
                name: name.to_string(),
                span,
            })
    }

    /// Fixed dimensions of a record field.
    fn field_dims(f: &FuncVar, span: Span) -> DaeResult<Vec<usize>> {
        f.dims
            .iter()
            .map(|d| {
                d.ok_or_else(|| {
                    unsupported(
                        format!(
                            "record field `{}` of a size not known at compile time",
                            f.name
                        ),
                        span,
                    )
                })
            })
            .collect()
    }

    /// Number of scalars in a value of record `name`.
    pub(crate) fn record_size(&self, name: &str, span: Span) -> DaeResult<usize> {
        let r = self.record_type(name, span)?;
        let mut n = 0;
        for f in &r.fields {
            n += self.field_len(f, span)?;
        }
        Ok(n)
    }

    fn field_len(&self, f: &FuncVar, span: Span) -> DaeResult<usize> {
        let count: usize = Self::field_dims(f, span)?.iter().product();
        Ok(match &f.record {
            Some(r) => count * self.record_size(r, span)?,
            None => count,
        })
    }

    /// The slot of field `field` in record `name`.
    pub(crate) fn record_slot(&self, name: &str, field: &str, span: Span) -> DaeResult<Slot> {
        let r = self.record_type(name, span)?;
        let mut offset = 0;
        for f in &r.fields {
            let len = self.field_len(f, span)?;
            if f.name == field {
                let dims = Self::field_dims(f, span)?;
                if f.record.is_some() && !dims.is_empty() {
                    return Err(unsupported("arrays of records inside records", span));
                }
                return Ok(Slot {
                    offset,
                    len,
                    dims,
                    record: f.record.clone(),
                });
            }
            offset += len;
        }
        Err(DaeError::NoRecordField {
            record: r.name.to_string(),
            field: field.to_string(),
            span,
        })
    }

    /// Size of a function's record variable (a record, not an array of records).
    pub(crate) fn record_local_size(&self, v: &FuncVar, span: Span) -> DaeResult<usize> {
        if !v.dims.is_empty() {
            return Err(unsupported(format!("array of records `{}`", v.name), span));
        }
        self.record_size(v.record.as_deref().unwrap_or_default(), span)
    }

    /// The value of the model's record instance `key` (its fields side by side), if
    /// `key` is one.
    pub(crate) fn record_instance(&mut self, key: &str, span: Span) -> DaeResult<Option<Tensor>> {
        let Some(ty) = self
            .model
            .record_instances
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, t)| t.clone())
        else {
            return Ok(None);
        };
        let r = self.record_type(&ty, span)?;
        let mut data = Vec::new();
        for f in &r.fields {
            let path = format!("{key}.{}", f.name);
            let part = match &f.record {
                Some(_) if f.dims.is_empty() => self.record_instance(&path, span)?,
                _ => {
                    let r = ComponentRef {
                        global: false,
                        parts: vec![RefPart {
                            name: Ident {
                                text: path.as_str().into(),
                                span,
                            },
                            subscripts: Vec::new(),
                        }],
                        span,
                    };
                    Some(self.reference(&r)?)
                }
            };
            let Some(part) = part else {
                return Err(DaeError::NoSuchRecordPart {
                    name: path.to_string(),
                    span,
                });
            };
            data.extend(part.data);
        }
        Ok(Some(Tensor::vector(data)))
    }

    /// A record constructor call: the arguments (or the fields' defaults) side by side.
    pub(crate) fn constructor(
        &mut self,
        name: &str,
        args: &CallArgs,
        span: Span,
    ) -> DaeResult<Option<Tensor>> {
        let name = name.trim_start_matches('.');
        let Some(r) = self.model.records.iter().find(|r| r.name == name) else {
            return Ok(None);
        };
        let mut given: Vec<Option<&Expr>> = vec![None; r.fields.len()];
        if args.positional.len() > r.fields.len() {
            return Err(DaeError::RecordConstructorArity {
                record: name.to_string(),
                span,
            });
        }
        for (k, a) in args.positional.iter().enumerate() {
            given[k] = Some(a);
        }
        for a in &args.named {
            let Some(k) = r.fields.iter().position(|f| f.name == a.name.text.as_str()) else {
                return Err(DaeError::RecordConstructorField {
                    record: name.to_string(),
                    field: a.name.text.to_string(),
                    span: a.name.span,
                });
            };
            given[k] = Some(&a.value);
        }
        let mut data = Vec::new();
        for (f, g) in r.fields.iter().zip(given) {
            let Some(e) = g.or(f.default.as_ref()) else {
                return Err(DaeError::RecordFieldNotGiven {
                    field: f.name.to_string(),
                    record: name.to_string(),
                    span,
                });
            };
            let v = self.expr(e)?;
            let len = self.field_len(f, span)?;
            data.extend(as_vector(v, len, span)?.data);
        }
        Ok(Some(Tensor::vector(data)))
    }

    /// The part of a record value that `fields` (`.a.b`) select.
    pub(crate) fn record_field(
        &mut self,
        mut ty: String,
        mut value: Tensor,
        fields: &[RefPart],
        span: Span,
    ) -> DaeResult<Tensor> {
        for (i, p) in fields.iter().enumerate() {
            if !p.subscripts.is_empty() && i + 1 < fields.len() {
                return Err(unsupported("subscripted record fields", span));
            }
            let slot = self.record_slot(&ty, p.name.text.as_str(), span)?;
            let data = value.data[slot.offset..slot.offset + slot.len].to_vec();
            value = Tensor {
                dims: if slot.record.is_some() {
                    vec![slot.len]
                } else {
                    slot.dims
                },
                data,
            };
            match slot.record {
                Some(r) => ty = r,
                None if i + 1 < fields.len() => return Err(not_a_record(p, span)),
                None => {}
            }
        }
        match fields.last() {
            Some(p) if !p.subscripts.is_empty() => self.subscript(value, &p.subscripts, span),
            _ => Ok(value),
        }
    }

    /// Assigns `value` to field `fields` of the record local at `k`.
    pub(crate) fn assign_record_field(
        &mut self,
        k: usize,
        fields: &[RefPart],
        value: Tensor,
        span: Span,
    ) -> DaeResult<()> {
        let mut ty = self.locals[k].record.clone().unwrap_or_default();
        let mut offset = 0;
        let mut slot = None;
        for (i, p) in fields.iter().enumerate() {
            if !p.subscripts.is_empty() && i + 1 < fields.len() {
                return Err(unsupported("assignment to subscripted record fields", span));
            }
            let s = self.record_slot(&ty, p.name.text.as_str(), span)?;
            offset += s.offset;
            match &s.record {
                Some(r) => ty = r.clone(),
                None if i + 1 < fields.len() => return Err(not_a_record(p, span)),
                None => {}
            }
            slot = Some(s);
        }
        let Some(slot) = slot else {
            return Ok(());
        };
        let subs = fields
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        if !subs.is_empty() {
            // Elements of an array field (`g.axis[1] := ...`).
            if slot.record.is_some() {
                return Err(unsupported("subscripts on a record", span));
            }
            let positions = self.positions(&slot.dims, &subs)?;
            let v = as_vector(value, positions.len(), span)?;
            let Some(cur) = self.locals[k].value.as_mut() else {
                return Err(DaeError::UsedBeforeAssigned {
                    name: self.locals[k].name.to_string(),
                    span,
                });
            };
            for (p, e) in positions.into_iter().zip(v.data) {
                cur.data[offset + p] = e;
            }
            return Ok(());
        }
        let v = as_vector(value, slot.len, span)?;
        let Some(cur) = self.locals[k].value.as_mut() else {
            return Err(DaeError::UsedBeforeAssigned {
                name: self.locals[k].name.to_string(),
                span,
            });
        };
        cur.data[offset..offset + slot.len].copy_from_slice(&v.data);
        Ok(())
    }
}

/// `v` as a vector of `len` scalars (its elements in row-major order, or a scalar
/// repeated).
fn as_vector(v: Tensor, len: usize, span: Span) -> DaeResult<Tensor> {
    if v.data.len() == len {
        return Ok(Tensor {
            dims: vec![len],
            data: v.data,
        });
    }
    crate::lower::broadcast(v, &[len], span)
}

/// A field access through something that is not a record (`a.re.x`).
fn not_a_record(p: &RefPart, span: Span) -> DaeError {
    DaeError::NotARecord {
        name: p.name.text.to_string(),
        span,
    }
}
