//! The MSL's impure random number generator (`Modelica.Math.Random.Utilities`:
//! `initializeImpureRandom`, `impureRandom`, `impureRandomInteger`), made pure. In C
//! (`ModelicaRandom.c`) it is a process-global xorshift1024* state that every call
//! advances; here the state is 32 hidden discrete Integers of the model (sixteen 64-bit
//! words as Integer halves), so that each simulation run has its own and a call happens
//! exactly where its `when` branch fires, once per firing:
//!
//! * `setInternalState(rngState, id)` (inside `initializeImpureRandom`) records the
//!   seeded state: its words are the hidden variables' start values;
//! * each `impureRandom(id)` lowers to a placeholder ([`ExtFn::ImpureRandom`]);
//! * after lowering, [`Lowerer::expand_impure_random`] replaces the placeholders of the
//!   one `when` branch that holds them by steps of the generator from `pre` of the
//!   hidden state, in call order, and makes the branch assign the state after its
//!   last call.
//!
//! The state is kept rotated so that no step needs a run-time index: word 0 is `s[p]`,
//! word `k` is `s[(p + k) mod 16]`. A step reads words 0 and 1, and the state after it
//! is `(new, word 2, .., word 15, word 0)` (`s[p + 1]` replaced by the new word, `p`
//! advanced). Not supported (a coded error naming the function): calls outside `when`,
//! or in more than one `when` branch (their order at a shared instant is not defined
//! by the model's equations).

use crate::dae::{Scalar, ScalarKind, ScalarType, WhenAction};
use crate::error::DaeError;
use crate::expr::{ExprId, Node, RelOp, ScalarId};
use crate::external::ExtFn;
use crate::lower::Lowerer;
use rustc_hash::FxHashMap as HashMap;
use unimo_flat::functions::FlatFunction;
use unimo_source::Span;

/// Words of xorshift1024*'s state, and Integer entries of the MSL's state vector (two
/// per word, then the index `p`).
const WORDS: usize = 16;
const ENTRIES: usize = 2 * WORDS + 1;

/// What lowering saw of the impure generator.
#[derive(Default, Debug)]
pub(crate) struct ImpureCalls {
    /// The state vector given to `setInternalState` (33 Integer expressions).
    seed: Option<Vec<ExprId>>,
    /// The placeholders of the `impureRandom` calls, in call order.
    calls: Vec<(ExprId, Span)>,
}

impl Lowerer<'_> {
    /// `ModelicaRandom_setInternalState_xorshift1024star(state, ..)`: remembers the
    /// state the hidden variables start from.
    pub(crate) fn impure_seed(
        &mut self,
        f: &FlatFunction,
        state: Vec<ExprId>,
        span: Span,
    ) -> Result<(), DaeError> {
        if state.len() < ENTRIES {
            return Err(DaeError::StateVectorSize {
                function: f.name.to_string(),
                needed: ENTRIES,
                given: state.len(),
                span,
            });
        }
        self.impure.seed = Some(state);
        Ok(())
    }

    /// `ModelicaRandom_impureRandom_xorshift1024star(id)`: a placeholder numbered by
    /// the call.
    pub(crate) fn impure_call(&mut self, span: Span) -> ExprId {
        let k = self.dae.arena.constant(self.impure.calls.len() as f64);
        let zero = self.dae.arena.zero();
        let id = self
            .dae
            .arena
            .intern(Node::Ext(ExtFn::ImpureRandom, [k, zero, zero, zero]));
        self.impure.calls.push((id, span));
        id
    }

    /// Replaces the placeholders of `impureRandom` calls by steps of the hidden state
    /// (see the module comment). Errors are pushed to the lowering's errors.
    pub(crate) fn expand_impure_random(&mut self) {
        if self.impure.calls.is_empty() {
            return;
        }
        if let Err(e) = self.expand_impure() {
            self.errors.push(e);
        }
    }

    fn expand_impure(&mut self) -> Result<(), DaeError> {
        let span = self.impure.calls[0].1;
        let unsupported = |what: &'static str| DaeError::ImpureRandom { what, span };
        let placeholders: Vec<ExprId> = self.impure.calls.iter().map(|c| c.0).collect();
        let in_equations: Vec<ExprId> = (self.dae.equations.iter())
            .chain(&self.dae.initial_equations)
            .flat_map(|e| [e.lhs, e.rhs])
            .collect();
        if !self.reached(&in_equations, &placeholders).is_empty() {
            return Err(unsupported(
                "is only provided in `when` clauses by unimo (it is impure: each call draws the next number)",
            ));
        }
        let mut site = None;
        for (w, clause) in self.dae.whens.iter().enumerate() {
            for (b, branch) in clause.branches.iter().enumerate() {
                let roots: Vec<ExprId> = branch.actions.iter().filter_map(action_value).collect();
                let found = self.reached(&roots, &placeholders);
                if found.is_empty() {
                    continue;
                }
                if site.is_some() {
                    return Err(unsupported(
                        "is called in more than one `when` branch: not supported by unimo",
                    ));
                }
                site = Some((w, b, found));
            }
        }
        let Some((w, b, found)) = site else {
            return Ok(());
        };
        let Some(seed) = self.impure.seed.clone() else {
            return Err(unsupported(
                "is called without `initializeImpureRandom` (the generator has no state)",
            ));
        };
        let seed = self.solved_parameters(&seed);
        let state = self.hidden_state(&seed, span);
        self.step_branch(w, b, &found, &state);
        Ok(())
    }

    /// `exprs` with each parameter that an initial equation `p = e` defines (`fixed =
    /// false`, as `GlobalSeed.seed`) replaced by `e`: a start value is evaluated before
    /// the initial equations are solved.
    fn solved_parameters(&mut self, exprs: &[ExprId]) -> Vec<ExprId> {
        let mut defined = HashMap::default();
        for eq in &self.dae.initial_equations {
            if let Node::Var(s) = self.dae.arena.node(eq.lhs) {
                let sc = &self.dae.scalars[s.index()];
                let own = self.dae.arena.vars(eq.rhs).contains(&s);
                if sc.kind == ScalarKind::Parameter && sc.fixed == Some(false) && !own {
                    defined.insert(s, eq.rhs);
                }
            }
        }
        let mut memo = HashMap::default();
        exprs
            .iter()
            .map(|&e| (self.dae.arena).substitute(e, &|s| defined.get(&s).copied(), &mut memo))
            .collect()
    }

    /// The placeholders among `targets` that the expressions `roots` read, in call
    /// order.
    fn reached(&self, roots: &[ExprId], targets: &[ExprId]) -> Vec<ExprId> {
        let arena = &self.dae.arena;
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack: Vec<ExprId> = roots.to_vec();
        let mut found = rustc_hash::FxHashSet::default();
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            if matches!(arena.node(id), Node::Ext(ExtFn::ImpureRandom, _)) {
                found.insert(id);
            }
            stack.extend(arena.children(id));
        }
        targets
            .iter()
            .copied()
            .filter(|t| found.contains(t))
            .collect()
    }

    /// The 32 hidden discrete Integers of the rotated state, starting from the seeded
    /// state rotated by its index `p` (`state[33] mod 16`).
    fn hidden_state(&mut self, seed: &[ExprId], span: Span) -> Vec<ScalarId> {
        let arena = &mut self.dae.arena;
        let sixteen = arena.constant(WORDS as f64);
        let p = arena.fn2(crate::expr::Fn2::Mod, seed[2 * WORDS], sixteen);
        let mut out = Vec::with_capacity(2 * WORDS);
        for k in 0..2 * WORDS {
            let (word, half) = (k / 2, k % 2);
            let entry = |j: usize| seed[2 * ((j + word) % WORDS) + half];
            let start = match arena.as_const(p) {
                Some(p0) => entry(p0 as usize),
                None => {
                    let mut acc = entry(WORDS - 1);
                    for j in (0..WORDS - 1).rev() {
                        let jc = arena.constant(j as f64);
                        let is_j = arena.rel(RelOp::Eq, p, jc);
                        acc = arena.if_(is_j, entry(j), acc);
                    }
                    acc
                }
            };
            let mut s = Scalar::new(
                format!("impureRandom.state[{}]", k + 1),
                ScalarKind::Discrete,
                ScalarType::Integer,
                span,
            );
            s.start = Some(start);
            s.fixed = Some(true);
            s.description = Some("hidden state of the impure xorshift1024* generator".into());
            out.push(ScalarId(self.dae.scalars.len() as u32));
            self.dae.scalars.push(s);
        }
        out
    }

    /// Branch `b` of clause `w`: the placeholders `calls` become steps from `pre` of
    /// the hidden `state`, and the branch assigns the state after the last step.
    fn step_branch(&mut self, w: usize, b: usize, calls: &[ExprId], state: &[ScalarId]) {
        let arena = &mut self.dae.arena;
        let mut words: Vec<ExprId> = state.iter().map(|&s| arena.pre(s)).collect();
        let mut map = HashMap::default();
        for &call in calls {
            let ops = [words[0], words[1], words[2], words[3]];
            let step = |arena: &mut crate::expr::ExprArena, k: u8| {
                arena.rebuild(Node::Ext(ExtFn::Xorshift1024Star(k), ops), &ops)
            };
            map.insert(call, step(arena, 0));
            let (lo, hi) = (step(arena, 1), step(arena, 2));
            let mut next = vec![lo, hi];
            next.extend_from_slice(&words[4..]);
            next.extend_from_slice(&words[..2]);
            words = next;
        }
        let mut memo = HashMap::default();
        let span = self.dae.whens[w].origin;
        let branch = &mut self.dae.whens[w].branches[b];
        for (action, _) in &mut branch.actions {
            match action {
                WhenAction::Assign { value, .. } | WhenAction::Reinit { value, .. } => {
                    *value = replace(arena, *value, &map, &mut memo);
                }
                WhenAction::Assert { condition, .. } => {
                    *condition = replace(arena, *condition, &map, &mut memo);
                }
                WhenAction::Terminate { .. } => {}
            }
        }
        for (&target, &value) in state.iter().zip(&words) {
            branch
                .actions
                .push((WhenAction::Assign { target, value }, span));
        }
    }
}

/// The expression an action reads.
fn action_value(action: &(WhenAction, Span)) -> Option<ExprId> {
    match &action.0 {
        WhenAction::Assign { value, .. } | WhenAction::Reinit { value, .. } => Some(*value),
        WhenAction::Assert { condition, .. } => Some(*condition),
        WhenAction::Terminate { .. } => None,
    }
}

/// `id` with the nodes of `map` replaced (memoized over the shared graph).
fn replace(
    arena: &mut crate::expr::ExprArena,
    id: ExprId,
    map: &HashMap<ExprId, ExprId>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> ExprId {
    if let Some(&r) = map.get(&id).or_else(|| memo.get(&id)) {
        return r;
    }
    let kids: Vec<ExprId> = arena.children(id).collect();
    let new: Vec<ExprId> = kids.iter().map(|&k| replace(arena, k, map, memo)).collect();
    let r = if new == kids {
        id
    } else {
        let node = arena.node(id);
        arena.rebuild(node, &new)
    };
    memo.insert(id, r);
    r
}

#[cfg(test)]
mod tests {
    use crate::random::xorshift1024star;

    // The expected numbers come from this independent Python transcription of
    // `ModelicaRandom_xorshift1024star_internal` (index `p`, Python's unbounded
    // integers masked to 64 bits), first 20 numbers, of which a sample is kept:
    //
    //     M = (1 << 64) - 1
    //     def step(s, p):
    //         p &= 15; s0 = s[p]; p = (p + 1) & 15; s1 = s[p]
    //         s1 ^= (s1 << 31) & M; s1 ^= s1 >> 11; s0 ^= s0 >> 30
    //         s[p] = s0 ^ s1
    //         x = (s[p] * 1181783497276652981) & M
    //         xs = x - (1 << 64) if x >= (1 << 63) else x
    //         return p, xs * 5.42101086242752217004e-20 + 0.5
    //     s = [((0x0123456789ABCDEF * (i + 1)) ^ (i << 40)) & M for i in range(16)]
    //     p = 13
    //     for _ in range(20): p, y = step(s, p); print(repr(y))

    /// The rotated state of the module comment gives the numbers of MSL's indexed one.
    #[test]
    fn rotated_xorshift1024star_matches_an_independent_transcription() {
        let expected: [(usize, f64); 6] = [
            (0, 0.6472332157455604),
            (1, 0.9442639750300819),
            (2, 0.21599701717303554),
            (9, 0.7999177336619807),
            (16, 0.6551822875976339),
            (19, 0.7742259895200553),
        ];
        let s: Vec<u64> = (0..16u64)
            .map(|i| 0x0123_4567_89AB_CDEFu64.wrapping_mul(i + 1) ^ (i << 40))
            .collect();
        let halves = |x: u64| {
            [
                f64::from(x as u32 as i32),
                f64::from((x >> 32) as u32 as i32),
            ]
        };
        // Word k of the rotated state is s[(13 + k) mod 16].
        let mut words: Vec<[f64; 2]> = (0..16).map(|k| halves(s[(13 + k) % 16])).collect();
        let mut numbers = Vec::new();
        for _ in 0..20 {
            let ops = [words[0][0], words[0][1], words[1][0], words[1][1]];
            numbers.push(xorshift1024star(ops, 0));
            let new = [xorshift1024star(ops, 1), xorshift1024star(ops, 2)];
            let mut next = vec![new];
            next.extend_from_slice(&words[2..]);
            next.push(words[0]);
            words = next;
        }
        for (k, y) in expected {
            assert_eq!(numbers[k], y, "number {k}");
        }
    }
}
