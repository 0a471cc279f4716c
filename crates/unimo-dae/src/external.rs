//! External functions and objects that unimo implements itself: the Modelica Standard
//! Library's tables (`ModelicaStandardTables`, written in C by the MSL and in Rust by
//! us), its random number generators and string hash (`random.rs`), the impure
//! generator (`impure.rs`) and the real FFT (`fft.rs`, `external_fft.rs`). Lowering turns the MSL's `external "C"` calls into [`Node::Ext`] nodes and the
//! table constructors into [`ExternalObjectSite`]s; the runtime builds the objects
//! after the parameters and evaluates the nodes (`unimo_runtime::tables`). An external
//! function unimo does not provide is a coded error naming it.

use crate::error::DaeError;
use crate::expr::{ExprId, Node};
use crate::lower::Local;
use crate::lower::Lowerer;
use crate::tensor::Tensor;
use unimo_flat::functions::{ExternalCall, FlatFunction};
use unimo_source::Span;

/// A function unimo provides for external C code: a function of an external object,
/// evaluated by the runtime (`Ext(f, [object, a, b, _])`), or a pure function of its
/// operands (a random number generator's step, `Ext(f, [s1, s2, s3, s4])`).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum ExtFn {
    /// 1-D table: value of column `icol` at abscissa `u`: `(table, icol, u)`.
    Table1D,
    /// Its derivative with respect to `u`.
    Table1DSlope,
    /// Smallest and largest abscissa: `(table)`.
    Table1DMin,
    Table1DMax,
    /// Time table: value of column `icol` at time `t`: `(table, icol, t)`.
    TimeTable,
    /// Its derivative with respect to `t`.
    TimeTableSlope,
    /// First and last time of the table: `(table)`.
    TimeTableMin,
    TimeTableMax,
    /// The next time event after `t`: `(table, t)`.
    TimeTableNextEvent,
    /// Output `k` of one xorshift64* step of the state `(s1, s2)`: 0 the random number,
    /// 1 and 2 the new state.
    Xorshift64Star(u8),
    /// Output `k` of one xorshift128+ step of the state `(s1, .., s4)`: 0 the random
    /// number, 1 to 4 the new state.
    Xorshift128Plus(u8),
    /// Output `k` of one xorshift1024* step on the two words it reads, as Integer
    /// halves `(s0 lo, s0 hi, s1 lo, s1 hi)`: 0 the random number, 1 and 2 the halves
    /// of the new word (`impure.rs` keeps the rest of the state).
    Xorshift1024Star(u8),
    /// A call of `impureRandom` before `impure.rs` turns it into a step of the hidden
    /// state: operand 0 is the call's number. Never evaluated.
    ImpureRandom,
    /// Writes three input values of a real FFT, `(slot, a, b, c)`: `slot` is the site
    /// times [`crate::fft::SITE_STRIDE`] plus the position; the value is the site's
    /// base (`external_fft.rs`).
    FftPush,
    /// `(x, y)`: the value of `x`, once both are computed (ties the pushes together).
    FftJoin,
    /// Output of a real FFT, `(site, k, n)`: 0 amplitude `k`, 1 phase `k`, 2 `info`,
    /// of the `n` values pushed to the site.
    RealFft(u8),
    /// `delay`'s value, `(site, delayMax, at, d)`: the history the runtime records of
    /// site `site` read at time `at`; `d` the constant delay time, or NaN (`delay.rs`).
    Delay,
    /// Its derivative with respect to `at`.
    DelaySlope,
}

const XORSHIFT64: [&str; 3] = ["xorshift64star", "xorshift64star_s1", "xorshift64star_s2"];
const XORSHIFT1024: [&str; 3] = [
    "xorshift1024star",
    "xorshift1024star_lo",
    "xorshift1024star_hi",
];
const XORSHIFT128: [&str; 5] = [
    "xorshift128plus",
    "xorshift128plus_s1",
    "xorshift128plus_s2",
    "xorshift128plus_s3",
    "xorshift128plus_s4",
];

impl ExtFn {
    pub fn name(self) -> &'static str {
        match self {
            ExtFn::Table1D => "table1D",
            ExtFn::Table1DSlope => "table1DSlope",
            ExtFn::Table1DMin => "table1DMin",
            ExtFn::Table1DMax => "table1DMax",
            ExtFn::TimeTable => "timeTable",
            ExtFn::TimeTableSlope => "timeTableSlope",
            ExtFn::TimeTableMin => "timeTableMin",
            ExtFn::TimeTableMax => "timeTableMax",
            ExtFn::TimeTableNextEvent => "timeTableNextEvent",
            ExtFn::Xorshift64Star(k) => XORSHIFT64[usize::from(k).min(2)],
            ExtFn::Xorshift128Plus(k) => XORSHIFT128[usize::from(k).min(4)],
            ExtFn::Xorshift1024Star(k) => XORSHIFT1024[usize::from(k).min(2)],
            ExtFn::ImpureRandom => "impureRandom",
            ExtFn::FftPush => "fftPush",
            ExtFn::FftJoin => "fftJoin",
            ExtFn::RealFft(0) => "realFFTamplitude",
            ExtFn::RealFft(1) => "realFFTphase",
            ExtFn::RealFft(_) => "realFFTinfo",
            ExtFn::Delay => "delay",
            ExtFn::DelaySlope => "delaySlope",
        }
    }

    /// Whether the value is a function of the operands alone (no object, no state).
    pub fn is_pure(self) -> bool {
        matches!(
            self,
            ExtFn::Xorshift64Star(_) | ExtFn::Xorshift128Plus(_) | ExtFn::Xorshift1024Star(_)
        )
    }

    /// The value of a pure function at `ops`.
    pub fn apply_pure(self, ops: [f64; 4]) -> f64 {
        match self {
            ExtFn::Xorshift64Star(k) => {
                let (r, s) = crate::random::xorshift64star([ops[0], ops[1]]);
                if k == 0 {
                    r
                } else {
                    s[usize::from(k - 1).min(1)]
                }
            }
            ExtFn::Xorshift128Plus(k) => {
                let (r, s) = crate::random::xorshift128plus(ops);
                if k == 0 {
                    r
                } else {
                    s[usize::from(k - 1).min(3)]
                }
            }
            ExtFn::Xorshift1024Star(k) => crate::random::xorshift1024star(ops, k),
            _ => f64::NAN,
        }
    }

    /// The value of a pure function whose operands are all known constants.
    pub fn eval_pure(self, ops: [Option<f64>; 4]) -> Option<f64> {
        if !self.is_pure() {
            return None;
        }
        let mut known = [0.0; 4];
        for (k, v) in ops.iter().enumerate().take(1 + self.arity()) {
            known[k] = (*v)?;
        }
        Some(self.apply_pure(known))
    }

    /// How many operands it reads after the first (the object handle of a table).
    pub fn arity(self) -> usize {
        match self {
            ExtFn::Xorshift64Star(_) => 1,
            ExtFn::Xorshift128Plus(_) | ExtFn::Xorshift1024Star(_) => 3,
            ExtFn::ImpureRandom => 0,
            ExtFn::FftPush => 3,
            ExtFn::FftJoin => 1,
            ExtFn::Table1DMin | ExtFn::Table1DMax | ExtFn::TimeTableMin | ExtFn::TimeTableMax => 0,
            ExtFn::TimeTableNextEvent => 1,
            _ => 2,
        }
    }

    /// The derivative with respect to the last operand, where the value is smooth in
    /// it (`None`: piecewise constant, derivative zero).
    pub fn slope(self) -> Option<ExtFn> {
        match self {
            ExtFn::Table1D => Some(ExtFn::Table1DSlope),
            ExtFn::TimeTable => Some(ExtFn::TimeTableSlope),
            ExtFn::Delay => Some(ExtFn::DelaySlope),
            _ => None,
        }
    }
}

/// The kind of an external object.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ObjectKind {
    /// `ModelicaStandardTables_CombiTable1D_init*`: a table of functions of one input.
    Table1D,
    /// `ModelicaStandardTables_CombiTimeTable_init*`: a table of functions of time.
    TimeTable,
}

/// An external object made once, after the parameters: its kind and the expressions
/// of its constructor's arguments (parameters), scalarized.
#[derive(Clone, Debug)]
pub struct ExternalObjectSite {
    pub kind: ObjectKind,
    /// The table, row by row.
    pub table: Vec<ExprId>,
    pub rows: usize,
    pub cols: usize,
    /// The table columns the outputs read (1-based, column 1 is the abscissa).
    pub columns: Vec<ExprId>,
    /// `Modelica.Blocks.Types.Smoothness` and `Extrapolation` ordinals.
    pub smoothness: ExprId,
    pub extrapolation: ExprId,
    /// Time tables: start time, shift time and `TimeEvents` ordinal (zero otherwise).
    pub start_time: ExprId,
    pub shift_time: ExprId,
    pub time_events: ExprId,
    pub span: Span,
}

/// What an external C function is to unimo.
enum Foreign {
    /// Makes an object: the positions of (table, columns, smoothness, extrapolation)
    /// and, for time tables, (start time, shift time, time events) in its arguments.
    Constructor(ObjectKind, [usize; 4], Option<[usize; 3]>),
    /// Reads an object: the function and the positions of its operands.
    Getter(ExtFn, &'static [usize]),
    /// The derivative of a getter times the derivative of its input (last position).
    Derivative(ExtFn, &'static [usize], usize),
    /// Releases an object: nothing to do.
    Destructor,
    /// One step of a random number generator with `n` state entries: the call's
    /// arguments are (state in, state out, random number).
    Random(fn(u8) -> ExtFn, usize),
    /// The hash of its String argument, known at compile time.
    HashString,
    /// A seed from the clock and the process id (different in every run).
    AutomaticGlobalSeed,
    /// Sets the state of the impure xorshift1024* generator (`impure.rs`).
    SetImpureState,
    /// One number of the impure generator (`impure.rs`).
    ImpureRandom,
    /// `ModelicaFFT_kiss_fftr` (`external_fft.rs`).
    RealFft,
}

fn foreign(name: &str) -> Option<Foreign> {
    use Foreign::*;
    Some(match name {
        "ModelicaStandardTables_CombiTable1D_init2"
        | "ModelicaStandardTables_CombiTable1D_init3" => {
            Constructor(ObjectKind::Table1D, [2, 5, 7, 8], None)
        }
        "ModelicaStandardTables_CombiTimeTable_init2"
        | "ModelicaStandardTables_CombiTimeTable_init3" => {
            Constructor(ObjectKind::TimeTable, [2, 6, 8, 9], Some([5, 10, 11]))
        }
        "ModelicaStandardTables_CombiTable1D_getValue" => Getter(ExtFn::Table1D, &[0, 1, 2]),
        "ModelicaStandardTables_CombiTable1D_getDerValue" => {
            Derivative(ExtFn::Table1DSlope, &[0, 1, 2], 3)
        }
        "ModelicaStandardTables_CombiTable1D_minimumAbscissa" => Getter(ExtFn::Table1DMin, &[0]),
        "ModelicaStandardTables_CombiTable1D_maximumAbscissa" => Getter(ExtFn::Table1DMax, &[0]),
        "ModelicaStandardTables_CombiTimeTable_getValue" => Getter(ExtFn::TimeTable, &[0, 1, 2]),
        "ModelicaStandardTables_CombiTimeTable_getDerValue" => {
            Derivative(ExtFn::TimeTableSlope, &[0, 1, 2], 5)
        }
        "ModelicaStandardTables_CombiTimeTable_minimumTime" => Getter(ExtFn::TimeTableMin, &[0]),
        "ModelicaStandardTables_CombiTimeTable_maximumTime" => Getter(ExtFn::TimeTableMax, &[0]),
        "ModelicaStandardTables_CombiTimeTable_nextTimeEvent" => {
            Getter(ExtFn::TimeTableNextEvent, &[0, 1])
        }
        "ModelicaStandardTables_CombiTable1D_close"
        | "ModelicaStandardTables_CombiTimeTable_close" => Destructor,
        "ModelicaRandom_xorshift64star" => Random(ExtFn::Xorshift64Star, 2),
        "ModelicaRandom_xorshift128plus" => Random(ExtFn::Xorshift128Plus, 4),
        "ModelicaStrings_hashString" => HashString,
        "ModelicaRandom_automaticGlobalSeed" => AutomaticGlobalSeed,
        "ModelicaRandom_setInternalState_xorshift1024star" => SetImpureState,
        "ModelicaRandom_impureRandom_xorshift1024star" => ImpureRandom,
        "ModelicaFFT_kiss_fftr" => RealFft,
        _ => return None,
    })
}

impl Lowerer<'_> {
    /// The body of an external function: its inputs are bound as locals; the outputs
    /// are set here from unimo's implementation of the foreign function.
    pub(crate) fn external_body(
        &mut self,
        f: &FlatFunction,
        ext: &ExternalCall,
        span: Span,
    ) -> Result<(), DaeError> {
        let Some(kind) = foreign(&ext.function) else {
            return Err(DaeError::ExternalNotProvided {
                function: f.name.to_string(),
                foreign: ext.function.to_string(),
                span,
            });
        };
        let value = match kind {
            Foreign::Destructor => return Ok(()),
            Foreign::Getter(func, at) => {
                let args = self.scalar_args(ext, at, span)?;
                self.ext_node(func, &args)
            }
            Foreign::Derivative(func, at, der_at) => {
                let args = self.scalar_args(ext, at, span)?;
                let slope = self.ext_node(func, &args);
                let du = self.scalar_args(ext, &[der_at], span)?[0];
                self.dae.arena.mul(slope, du)
            }
            Foreign::Constructor(kind, at, time) => self.construct(kind, ext, at, time, span)?,
            Foreign::Random(func, n) => return self.random_step(f, ext, func, n, span),
            Foreign::HashString => {
                let text = ext.args.first().and_then(|a| self.text_value(a));
                let Some(text) = text else {
                    return Err(DaeError::ExternalStringNotKnown {
                        function: f.name.to_string(),
                        span,
                    });
                };
                let h = crate::random::hash_string(&text);
                self.dae.arena.constant(f64::from(h))
            }
            Foreign::SetImpureState => {
                let state = self.foreign_arg(ext, 0, span)?;
                return self.impure_seed(f, state.data, span);
            }
            Foreign::ImpureRandom => self.impure_call(span),
            Foreign::RealFft => return self.real_fft(f, ext, span),
            Foreign::AutomaticGlobalSeed => {
                let seed = automatic_global_seed();
                self.dae.arena.constant(f64::from(seed))
            }
        };
        let output = ext
            .output
            .clone()
            .or_else(|| f.outputs.first().map(|o| o.name.clone()))
            .unwrap_or_default();
        self.locals.push(Local {
            name: output,
            value: Some(Tensor::scalar(value)),
            record: None,
            text: None,
        });
        Ok(())
    }

    /// One step of a random number generator: the state in is the call's first
    /// argument; the random number and the new state are the outputs the call's other
    /// two arguments name, each entry one node of the generator's output.
    fn random_step(
        &mut self,
        f: &FlatFunction,
        ext: &ExternalCall,
        func: fn(u8) -> ExtFn,
        n: usize,
        span: Span,
    ) -> Result<(), DaeError> {
        let state = self.foreign_arg(ext, 0, span)?;
        if state.data.len() < n {
            return Err(DaeError::StateVectorSize {
                function: f.name.to_string(),
                needed: n,
                given: state.data.len(),
                span,
            });
        }
        let words = &state.data[..n];
        let number = self.ext_node(func(0), words);
        let next: Vec<ExprId> = (1..=n)
            .map(|k| self.ext_node(func(k as u8), words))
            .collect();
        let name = |k: usize| match ext.args.get(k).map(|a| &a.kind) {
            Some(unimo_syntax::ast::ExprKind::Ref(r)) if r.parts.len() == 1 => {
                Some(r.parts[0].name.text.to_string())
            }
            _ => None,
        };
        let (Some(state_out), Some(result)) = (name(1), name(2)) else {
            return Err(DaeError::ExternalOutputs {
                function: f.name.to_string(),
                foreign: ext.function.to_string(),
                span,
            });
        };
        self.assign_outputs([
            (state_out, Tensor::vector(next)),
            (result, Tensor::scalar(number)),
        ]);
        Ok(())
    }

    /// The outputs of an external call, as the caller's locals (name, value).
    pub(crate) fn assign_outputs(&mut self, outputs: impl IntoIterator<Item = (String, Tensor)>) {
        for (name, value) in outputs {
            self.locals.push(Local {
                name,
                value: Some(value),
                record: None,
                text: None,
            });
        }
    }

    pub(crate) fn ext_node(&mut self, func: ExtFn, args: &[ExprId]) -> ExprId {
        let zero = self.dae.arena.zero();
        let get = |k: usize| args.get(k).copied().unwrap_or(zero);
        let ops = [get(0), get(1), get(2), get(3)];
        self.dae.arena.rebuild(Node::Ext(func, ops), &ops)
    }

    /// The scalar arguments at positions `at` of the external call.
    fn scalar_args(
        &mut self,
        ext: &ExternalCall,
        at: &[usize],
        span: Span,
    ) -> Result<Vec<ExprId>, DaeError> {
        at.iter()
            .map(|&k| {
                let t = self.foreign_arg(ext, k, span)?;
                t.data
                    .first()
                    .copied()
                    .ok_or_else(|| DaeError::EmptyExternalArgument {
                        foreign: ext.function.to_string(),
                        span,
                    })
            })
            .collect()
    }

    /// Argument `k` of the foreign call, lowered.
    pub(crate) fn foreign_arg(
        &mut self,
        ext: &ExternalCall,
        k: usize,
        span: Span,
    ) -> Result<Tensor, DaeError> {
        let a = ext
            .args
            .get(k)
            .ok_or_else(|| DaeError::TooFewExternalArguments {
                foreign: ext.function.to_string(),
                span,
            })?;
        self.expr(a)
    }

    /// A table constructor: the object's site; its value is the site's index.
    fn construct(
        &mut self,
        kind: ObjectKind,
        ext: &ExternalCall,
        at: [usize; 4],
        time: Option<[usize; 3]>,
        span: Span,
    ) -> Result<ExprId, DaeError> {
        let arg = |me: &mut Self, k: usize| me.foreign_arg(ext, k, span);
        let table = arg(self, at[0])?;
        let (rows, cols) = match table.dims.as_slice() {
            [r, c] => (*r, *c),
            _ => (0, 0),
        };
        if rows == 0 || cols == 0 {
            return Err(DaeError::EmptyTable { span });
        }
        let columns = arg(self, at[1])?.data;
        let smoothness = arg(self, at[2])?.data[0];
        let extrapolation = arg(self, at[3])?.data[0];
        let zero = self.dae.arena.zero();
        let (start_time, shift_time, time_events) = match time {
            Some([s, h, e]) => (
                arg(self, s)?.data[0],
                arg(self, h)?.data[0],
                arg(self, e)?.data[0],
            ),
            None => (zero, zero, zero),
        };
        let index = self.dae.external_objects.len();
        self.dae.external_objects.push(ExternalObjectSite {
            kind,
            table: table.data,
            rows,
            cols,
            columns,
            smoothness,
            extrapolation,
            start_time,
            shift_time,
            time_events,
            span,
        });
        Ok(self.dae.arena.constant(index as f64))
    }
}

impl Lowerer<'_> {
    /// A call whose outputs are not used is dropped; when the function reaches (itself
    /// or through the functions it calls) an external function unimo does not provide,
    /// its effects (a file written, a message printed) are lost: warning `W3001`, never
    /// silently.
    pub(crate) fn warn_unexecuted(&mut self, func: &unimo_syntax::ast::Name, span: Span) {
        let name = func.to_dotted();
        let name = name.trim_start_matches('.');
        let Some(missing) = self.unprovided_external(name) else {
            return;
        };
        let warning = DaeError::CallNotExecuted {
            function: name.to_owned(),
            missing: missing.to_string(),
            span,
        };
        self.dae.warnings.push(warning.into());
    }

    /// The first external C function (depth first, in call order) that `name` or a
    /// function it calls is, and that unimo does not provide.
    fn unprovided_external(&self, name: &str) -> Option<String> {
        let mut stack = vec![name.to_owned()];
        let mut seen = std::collections::HashSet::new();
        while let Some(name) = stack.pop() {
            if !seen.insert(name.clone()) {
                continue;
            }
            let Some(f) = self.functions.get(name.as_str()) else {
                continue;
            };
            match &f.external_call {
                Some(ext) if f.external => {
                    if foreign(&ext.function).is_none() {
                        return Some(ext.function.clone());
                    }
                }
                _ if f.external => return Some(f.name.clone()),
                _ => {
                    let mut called = Vec::new();
                    for s in &f.algorithm {
                        unimo_flat::functions::statement_calls(s, &mut called);
                    }
                    stack.extend(called.into_iter().rev());
                }
            }
        }
        None
    }
}

/// Whether a call statement of the external C function `name` (no outputs used) must
/// be lowered for its effect: the impure generator's seeding.
pub(crate) fn has_effect(name: &str) -> bool {
    matches!(foreign(name), Some(Foreign::SetImpureState))
}

/// `ModelicaRandom_automaticGlobalSeed`: 1 + the time of day in milliseconds (UTC) +
/// 6007 times the process id, as the MSL's C code forms it: a different seed in every
/// run, which is what the function is for.
fn automatic_global_seed() -> i32 {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default();
    let ms = i64::from(now.subsec_millis());
    let secs = now.as_secs() as i64;
    let (sec, min, hour) = (secs % 60, (secs / 60) % 60, (secs / 3600) % 24);
    let pid = i64::from(std::process::id());
    let seed = 1 + ms + 1000 * sec + 60_000 * min + 3_600_000 * hour + 6007 * pid;
    seed as i32
}
