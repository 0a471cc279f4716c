//! Parameter folding: the parameters whose values are fixed when the model is compiled.
//! Equations read them as constants, so that the arena's folding removes what they
//! switch off: terms multiplied by zero, branches of `if`-expressions that cannot be
//! taken, and relations whose value cannot change (no zero crossing, no event).
//!
//! By default every parameter is folded except those the user keeps tunable
//! ([`FoldOptions::tunable`]), the parameters computed by initial equations
//! (`fixed = false`) and every parameter whose binding reads one of those.

use crate::dae::ScalarKind;
use crate::expr::ScalarId;
use crate::lower::Lowerer;
use rustc_hash::FxHashSet as HashSet;
use unimo_flat::flat::Variability;
use unimo_flat::FlatModel;

/// Which parameters the compiled model keeps tunable (changeable without compiling
/// again); the others are folded into the code.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FoldOptions {
    /// Keep every parameter tunable: fold only the parameters declared with
    /// `annotation(Evaluate = true)` and the parameters bound to them (and constants)
    /// alone.
    pub tunable_all: bool,
    /// Parameters kept tunable, by their flat names (`k`, `ball.e`); the name of a
    /// record or array covers its fields and elements. Parameters whose bindings read
    /// a tunable parameter stay tunable with it.
    pub tunable: Vec<String>,
}

/// Whether the flat variable `var` is covered by the name `name` (itself, or a field
/// or element of it).
fn covers(name: &str, var: &str) -> bool {
    let var = var.trim_matches('\'');
    var == name
        || var
            .strip_prefix(name)
            .is_some_and(|rest| rest.starts_with('.') || rest.starts_with('['))
}

/// The names of `options.tunable` that cover no parameter of `model` (a command-line
/// error for the caller to report).
pub fn unknown_tunable<'o>(model: &FlatModel, options: &'o FoldOptions) -> Vec<&'o str> {
    options
        .tunable
        .iter()
        .filter(|n| {
            !model
                .vars
                .iter()
                .any(|v| v.variability == Variability::Parameter && covers(n, &v.name))
        })
        .map(String::as_str)
        .collect()
}

impl Lowerer<'_> {
    /// Decides which parameters are fixed at translation (see the module's doc) and
    /// records their values in `evaluated`.
    pub(crate) fn evaluate_parameters(&mut self, options: &FoldOptions) {
        let mut evaluate: Vec<ScalarId> = Vec::new();
        let mut tunable: HashSet<ScalarId> = HashSet::default();
        for v in &self.model.vars {
            if v.variability != Variability::Parameter {
                continue;
            }
            let Some(&(first, ref dims)) = self.vars.get(&v.name) else {
                continue;
            };
            let scalars = (0..dims.iter().product::<usize>()).map(|k| ScalarId(first.0 + k as u32));
            if v.evaluate {
                evaluate.extend(scalars);
            } else if options.tunable_all
                || (!v.is_final && options.tunable.iter().any(|n| covers(n, &v.name)))
            {
                // A `final` parameter cannot be set: it is tunable only through what
                // it is bound to.
                tunable.extend(scalars);
            }
        }
        // Constants never change: every one with a value is folded, in either mode
        // (`constant Real eps` of a block decides its `if` branches).
        for k in 0..self.dae.scalars.len() {
            let s = ScalarId(k as u32);
            if self.dae.scalars[k].kind == ScalarKind::Constant {
                if let Some(x) = self.parameter_value(s) {
                    let c = self.dae.arena.constant(x);
                    self.evaluated.insert(s, c);
                }
            }
        }
        for s in evaluate {
            tunable.remove(&s);
            if let Some(x) = self.parameter_value(s) {
                let c = self.dae.arena.constant(x);
                self.evaluated.insert(s, c);
            }
        }
        if options.tunable_all {
            self.fold_readers_of_evaluated();
        } else {
            self.fold_all_but(tunable);
        }
        let mut folded: Vec<ScalarId> = self
            .evaluated
            .keys()
            .copied()
            .filter(|s| self.dae.scalars[s.index()].kind == ScalarKind::Parameter)
            .collect();
        folded.sort();
        self.dae.folded_parameters = folded;
    }

    /// Every parameter not in `tunable`, not computed by initial equations and not
    /// reading (through its binding, transitively) a parameter that is either.
    fn fold_all_but(&mut self, mut tunable: HashSet<ScalarId>) {
        let n = self.dae.scalars.len();
        for k in 0..n {
            let sc = &self.dae.scalars[k];
            if sc.kind == ScalarKind::Parameter && sc.fixed == Some(false) {
                tunable.insert(ScalarId(k as u32));
            }
        }
        // Parameters following a tunable one through their bindings stay tunable.
        loop {
            let mut grew = false;
            for k in 0..n {
                let s = ScalarId(k as u32);
                let sc = &self.dae.scalars[k];
                if sc.kind != ScalarKind::Parameter
                    || tunable.contains(&s)
                    || self.evaluated.contains_key(&s)
                {
                    continue;
                }
                let Some(b) = sc.binding.or(sc.start) else {
                    continue;
                };
                if self.dae.arena.vars(b).iter().any(|v| tunable.contains(v)) {
                    tunable.insert(s);
                    grew = true;
                }
            }
            if !grew {
                break;
            }
        }
        for k in 0..n {
            let s = ScalarId(k as u32);
            if self.dae.scalars[k].kind != ScalarKind::Parameter
                || tunable.contains(&s)
                || self.evaluated.contains_key(&s)
            {
                continue;
            }
            if let Some(x) = self.parameter_value(s) {
                let c = self.dae.arena.constant(x);
                self.evaluated.insert(s, c);
            }
        }
    }

    /// With every parameter tunable: the parameters whose binding reads evaluated
    /// parameters and constants alone (a capacitor's `final C = CapVal`), so that
    /// `0 * der(v)` leaves the equations as the tool that wrote the model meant.
    fn fold_readers_of_evaluated(&mut self) {
        if self.evaluated.is_empty() {
            return;
        }
        loop {
            let mut grew = false;
            for k in 0..self.dae.scalars.len() {
                let s = ScalarId(k as u32);
                let sc = &self.dae.scalars[k];
                if sc.kind != ScalarKind::Parameter
                    || sc.fixed == Some(false)
                    || self.evaluated.contains_key(&s)
                {
                    continue;
                }
                let Some(b) = sc.binding else { continue };
                let vars = self.dae.arena.vars(b);
                let reads_evaluated = vars.iter().any(|v| self.evaluated.contains_key(v));
                let only_fixed = vars.iter().all(|v| {
                    self.evaluated.contains_key(v)
                        || self.dae.scalars[v.index()].kind == ScalarKind::Constant
                });
                if reads_evaluated && only_fixed {
                    if let Some(x) = self.parameter_value(s) {
                        let c = self.dae.arena.constant(x);
                        self.evaluated.insert(s, c);
                        grew = true;
                    }
                }
            }
            if !grew {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::covers;

    #[test]
    fn a_name_covers_itself_its_fields_and_elements() {
        assert!(covers("k", "k"));
        assert!(covers("ball", "ball.e"));
        assert!(covers("a", "a[2]"));
        assert!(covers("ball.e", "'ball.e'"));
        assert!(!covers("k", "k2"));
        assert!(!covers("ball.e", "ball"));
    }
}
