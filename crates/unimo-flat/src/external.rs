//! External functions and objects: a function whose body is `external "builtin"` is
//! the built-in of that name (`Modelica.Math.sin` is `sin`), so calls to it become
//! built-in calls; a class that `extends ExternalObject` (spec 12.9.7) is the type of
//! opaque handles made by its `constructor` function (the MSL's tables).

use unimo_syntax::ast::{Causality, ClassBody, ClassDef, ElementKind, ExprKind};

/// Whether `def` is an external object class: a class extending `ExternalObject`.
pub(crate) fn is_external_object(def: &ClassDef) -> bool {
    let ClassBody::Long { composition, .. } = &def.body else {
        return false;
    };
    composition.elements.iter().any(|e| {
        matches!(&e.kind, ElementKind::Extends(x)
            if x.base.parts.len() == 1 && x.base.parts[0].text == "ExternalObject")
    })
}

/// The built-in function a function stands for: its external clause says
/// `external "builtin"`, and its call (if written) passes the inputs in their declared
/// order and assigns the only output. `None` for any other function.
pub(crate) fn builtin_alias(def: &ClassDef) -> Option<&'static str> {
    let ClassBody::Long { composition, .. } = &def.body else {
        return None;
    };
    let ext = composition.external.as_ref()?;
    if ext.language.as_deref() != Some("builtin") {
        return None;
    }
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    for e in &composition.elements {
        if let ElementKind::Component(cc) = &e.kind {
            for d in &cc.components {
                match cc.prefix.causality {
                    Some(Causality::Input) => inputs.push(d.name.text.as_str()),
                    Some(Causality::Output) => outputs.push(d.name.text.as_str()),
                    None => {}
                }
            }
        }
    }
    let name = match &ext.call {
        None => def.name.text.as_str(),
        Some(call) => {
            let args_are_inputs = call.args.len() == inputs.len()
                && call.args.iter().zip(&inputs).all(|(a, i)| {
                    matches!(&a.kind, ExprKind::Ref(r)
                        if r.parts.len() == 1 && r.parts[0].subscripts.is_empty()
                            && r.parts[0].name.text == *i)
                });
            let output_ok = match &call.output {
                Some(r) => {
                    outputs.len() == 1 && r.parts.len() == 1 && r.parts[0].name.text == outputs[0]
                }
                None => outputs.is_empty(),
            };
            if !(args_are_inputs && output_ok) {
                return None;
            }
            call.function.text.as_str()
        }
    };
    unimo_builtins::find(name)
        .filter(|b| b.kind != unimo_builtins::Kind::Unsupported)
        .map(|b| b.name)
}
