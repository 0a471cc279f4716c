//! Running tapes: the event state all tapes of a model share (relations, samples,
//! held roundings, and the external objects: tables, FFT scratch, the collision world,
//! `delay` histories)
//! and the interpreter of the instructions `unimo-codegen` compiles. A tape runs its
//! native code when it has code compiled from its instructions, else the interpreter
//! (the oracle of the native code).

use crate::native::TapeCall;
use unimo_codegen::model::CompiledModel;
use unimo_codegen::tape::{Op, Reg, Tape};
use unimo_dae::external::ExtFn;

/// Relation and sample state shared by all tapes of a model.
#[derive(Clone, Debug, Default)]
pub struct EventState {
    /// In event mode relations are computed and stored; otherwise they are read.
    pub event_mode: bool,
    pub relations: Vec<f64>,
    /// Forced outcome of a relation whose crossing was just located (1.0/0.0), used in
    /// event mode instead of the literal comparison (which may be on the wrong side of
    /// the root by rounding).
    pub forced: Vec<Option<f64>>,
    /// At events after initialization: a relation whose operands agree to rounding
    /// noise keeps its outcome (from before the event, or as forced by the located
    /// crossing), so that event iteration does not flip it on the last bits of a
    /// Newton solution.
    pub sticky: bool,
    pub samples: Vec<f64>,
    /// Values of the event-generating roundings (`Op::Held`).
    pub held: Vec<f64>,
    /// Outcome of a rounding whose bound was just crossed: `(before, after)`; used in
    /// event mode when the literal rounding still gives `before` (the argument sits on
    /// the bound up to rounding). Kept through every pass of the event.
    pub held_forced: Vec<Option<(f64, f64)>>,
    /// The collision world's mutable side (contact set, sweep origin, broadphase).
    pub collision: Option<Box<crate::collision::CollisionState>>,
    /// External objects (tables), built after the parameters; handle `k` is object `k`.
    pub objects: Vec<crate::tables::TableObject>,
    /// The real FFT sites' scratch areas and transforms.
    pub fft: crate::fft::FftScratch,
    /// The histories of the `delay` sites.
    pub delays: crate::delay::Delays,
}

/// Relative size below which the operands of a relation count as equal at an event
/// (blocks converge to about 1e-13; the root functions use the same floor).
pub const RELATION_NOISE: f64 = 1e-14;

/// Running a tape on a register file and event state.
pub trait Run {
    /// Runs the tape: its native code when it has code compiled from these
    /// instructions (`unimo-codegen`), else the interpreter.
    fn run(&self, r: &mut [f64], ev: &mut EventState);
    /// Runs the tape with the interpreter (the oracle of the native code).
    fn interpret(&self, r: &mut [f64], ev: &mut EventState);
}

impl Run for Tape {
    #[inline]
    fn run(&self, r: &mut [f64], ev: &mut EventState) {
        match &self.native {
            Some(native) if native.fits(self.ops.len(), r, ev) => native.call(r, ev),
            _ => self.interpret(r, ev),
        }
    }

    #[inline]
    fn interpret(&self, r: &mut [f64], ev: &mut EventState) {
        for &op in &self.ops {
            execute(op, r, ev);
        }
    }
}

/// Executes one instruction on the register file.
#[inline(always)]
pub fn execute(op: Op, r: &mut [f64], ev: &mut EventState) {
    match op {
        Op::Const(d, x) => r[d as usize] = x,
        Op::Copy(d, a) => r[d as usize] = r[a as usize],
        Op::Add(d, a, b) => r[d as usize] = r[a as usize] + r[b as usize],
        Op::Sub(d, a, b) => r[d as usize] = r[a as usize] - r[b as usize],
        Op::Mul(d, a, b) => r[d as usize] = r[a as usize] * r[b as usize],
        Op::Div(d, a, b) => r[d as usize] = r[a as usize] / r[b as usize],
        Op::Pow(d, a, b) => r[d as usize] = r[a as usize].powf(r[b as usize]),
        Op::Powi(d, a, n) => r[d as usize] = r[a as usize].powi(n),
        Op::Neg(d, a) => r[d as usize] = -r[a as usize],
        Op::Fn1(f, d, a) => r[d as usize] = f.apply(r[a as usize]),
        Op::Fn2(f, d, a, b) => r[d as usize] = f.apply(r[a as usize], r[b as usize]),
        Op::Rel(op, d, a, b) => r[d as usize] = f64::from(op.apply(r[a as usize], r[b as usize])),
        Op::RelEvent(op, d, a, b, k) => {
            let k = k as usize;
            if ev.event_mode {
                let (x, y) = (r[a as usize], r[b as usize]);
                let v = match ev.forced[k] {
                    Some(v) => v,
                    None if ev.sticky
                        && (x - y).abs() <= RELATION_NOISE * x.abs().max(y.abs()).max(1.0) =>
                    {
                        ev.relations[k]
                    }
                    None => f64::from(op.apply(x, y)),
                };
                ev.relations[k] = v;
            }
            r[d as usize] = ev.relations[k];
        }
        Op::And(d, a, b) => r[d as usize] = f64::from(r[a as usize] != 0.0 && r[b as usize] != 0.0),
        Op::Or(d, a, b) => r[d as usize] = f64::from(r[a as usize] != 0.0 || r[b as usize] != 0.0),
        Op::Not(d, a) => r[d as usize] = f64::from(r[a as usize] == 0.0),
        Op::Select(d, c, a, b) => {
            r[d as usize] = if r[c as usize] != 0.0 {
                r[a as usize]
            } else {
                r[b as usize]
            }
        }
        Op::Sample(d, k) => r[d as usize] = ev.samples[k as usize],
        Op::Ext(f, d, ops) if f.is_pure() => {
            r[d as usize] = f.apply_pure(ops.map(|k| r[k as usize]));
        }
        Op::Ext(ExtFn::FftPush, d, [slot, a, b, c]) => {
            let values = [r[a as usize], r[b as usize], r[c as usize]];
            r[d as usize] = ev.fft.push(r[slot as usize], values);
        }
        Op::Ext(ExtFn::FftJoin, d, [a, ..]) => r[d as usize] = r[a as usize],
        Op::Ext(ExtFn::RealFft(kind), d, [base, k, n, _]) => {
            let (base, k, n) = (r[base as usize], r[k as usize], r[n as usize]);
            r[d as usize] = ev.fft.output(base, kind, k, n);
        }
        Op::Ext(f @ (ExtFn::Delay | ExtFn::DelaySlope), d, [site, dmax, at, fixed]) => {
            let (site, at) = (r[site as usize], r[at as usize]);
            let bounds = [r[dmax as usize], r[fixed as usize]];
            r[d as usize] = ev.delays.read(site, bounds, at, f == ExtFn::DelaySlope);
        }
        Op::Ext(f, d, [o, a, b, _]) => {
            let object = r[o as usize];
            r[d as usize] = match ev.objects.get(object as usize) {
                Some(t) if object >= 0.0 => t.eval(f, r[a as usize], r[b as usize]),
                _ => f64::NAN,
            };
        }
        Op::Held(kind, d, a, k) => {
            let k = k as usize;
            if ev.event_mode {
                let literal = kind.apply(r[a as usize]);
                ev.held[k] = match ev.held_forced[k] {
                    Some((before, after)) if literal == before => after,
                    _ => literal,
                };
            }
            r[d as usize] = ev.held[k];
        }
        Op::HeldBounds(kind, lo, hi, k) => {
            let (l, h) = kind.bounds(ev.held[k as usize]);
            r[lo as usize] = l;
            r[hi as usize] = h;
        }
    }
}

/// Setting up a compiled model's run: its event state and its parameters (with the
/// external objects built from them).
pub trait Instance {
    /// An event state sized for the model (no external objects yet).
    fn new_event_state(&self) -> EventState;
    /// Runs the parameters' tape; with external objects, builds them from the
    /// parameters and runs it again (parameters may read the objects: a friction
    /// table's value at zero speed).
    fn run_parameters(&self, regs: &mut [f64], ev: &mut EventState) -> Result<(), String>;
}

impl Instance for CompiledModel {
    fn new_event_state(&self) -> EventState {
        EventState {
            event_mode: false,
            relations: vec![0.0; self.root_ops.len()],
            forced: vec![None; self.root_ops.len()],
            held: vec![0.0; self.n_held],
            held_forced: vec![None; self.n_held],
            sticky: false,
            samples: vec![0.0; self.samples.len()],
            collision: self.collision.as_ref().map(|_| Box::default()),
            objects: Vec::new(),
            fft: Default::default(),
            delays: crate::delay::Delays::new(self.delay_inputs.len()),
        }
    }

    fn run_parameters(&self, regs: &mut [f64], ev: &mut EventState) -> Result<(), String> {
        self.parameters.run(regs, ev);
        if self.objects.is_empty() {
            return Ok(());
        }
        self.objects_tape.run(regs, ev);
        let values = |rs: &[Reg]| -> Vec<f64> { rs.iter().map(|&r| regs[r as usize]).collect() };
        let mut objects = Vec::with_capacity(self.objects.len());
        for site in &self.objects {
            let data = values(&site.table);
            let columns = values(&site.columns);
            let s = values(&site.settings);
            let object = crate::tables::TableObject::new(&crate::tables::TableArgs {
                kind: site.kind,
                data: &data,
                rows: site.rows,
                cols: site.cols,
                columns: &columns,
                smoothness: s[0],
                extrapolation: s[1],
                start_time: s[2],
                shift_time: s[3],
                time_events: s[4],
            })?;
            objects.push(object);
        }
        ev.objects = objects;
        self.parameters.run(regs, ev);
        Ok(())
    }
}
