//! One FMU instance, independent of the FMI version: the model read from the FMU's
//! `resources/`, the state machine of the calls (wrong order is `WrongState`), values
//! by value reference, and Model Exchange and Co-Simulation on our runtime's
//! [`Stepper`]. The C functions (`fmi2.rs`, `fmi3.rs`) only convert arguments.

use crate::description::{self, Kind, Version};
use crate::error::FmiError;
use crate::model::{Causality, Compiled, FlatSource};
use std::mem::ManuallyDrop;
use std::path::Path;
use unimo_dae::dae::ScalarType;
use unimo_runtime::sim::stepper::{EventOutcome, Stepper};
use unimo_runtime::sim::SimOptions;
use unimo_solve::Method;

/// Where the instance is in the FMI state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    Instantiated,
    Initialization,
    Event,
    ContinuousTime,
    Step,
    Terminated,
}

impl State {
    fn name(self) -> &'static str {
        match self {
            State::Instantiated => "Instantiated",
            State::Initialization => "InitializationMode",
            State::Event => "EventMode",
            State::ContinuousTime => "ContinuousTimeMode",
            State::Step => "StepMode",
            State::Terminated => "Terminated",
        }
    }
}

/// A compiled model and the stepper that borrows it (freed in that order).
struct Running {
    stepper: ManuallyDrop<Stepper<'static>>,
    compiled: *mut Compiled,
}

impl Running {
    fn new(compiled: Compiled, options: SimOptions) -> Running {
        let compiled = Box::into_raw(Box::new(compiled));
        // SAFETY: `compiled` is a leaked box that lives until `drop` below, which drops
        // the stepper (the only borrower) first and then frees the box.
        let model = unsafe { &(*compiled).model };
        Running {
            stepper: ManuallyDrop::new(Stepper::new(model, options)),
            compiled,
        }
    }

    fn compiled(&self) -> &Compiled {
        // SAFETY: valid until `drop` (see `new`).
        unsafe { &*self.compiled }
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        // SAFETY: the stepper borrows `*compiled`; it is dropped first, once, and the
        // box made by `Box::into_raw` in `new` is freed once.
        unsafe {
            ManuallyDrop::drop(&mut self.stepper);
            drop(Box::from_raw(self.compiled));
        }
    }
}

/// Messages to the importer's logger: (is an error, text).
pub type Logger = Box<dyn Fn(bool, &str)>;

pub struct Instance {
    pub name: String,
    pub kind: Kind,
    pub version: Version,
    pub state: State,
    pub logger: Logger,
    source: FlatSource,
    running: Running,
    /// Parameter values the importer set, applied by recompiling at the end of
    /// initialization.
    parameters: Vec<(String, ScalarType, f64)>,
    /// Start values of states the importer set (`initial = "exact"`), applied with the
    /// parameters.
    starts: Vec<(String, f64)>,
    options: SimOptions,
    /// The initialization ran; the first event update reports it.
    initial_event: bool,
    /// The event update of the current event mode ran.
    event_done: bool,
    pub terminated: bool,
}

/// The path of the folder a `file:` URI (FMI 2) or a path (FMI 3) names.
pub fn resource_folder(location: &str) -> std::path::PathBuf {
    let Some(rest) = location.strip_prefix("file:") else {
        return std::path::PathBuf::from(location);
    };
    let rest = rest.strip_prefix("//localhost").unwrap_or(rest);
    let rest = rest.trim_start_matches('/');
    let mut bytes = Vec::new();
    let raw = rest.as_bytes();
    let mut k = 0;
    while k < raw.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match (
            raw[k],
            raw.get(k + 1).and_then(|&b| hex(b)),
            raw.get(k + 2).and_then(|&b| hex(b)),
        ) {
            (b'%', Some(h), Some(l)) => {
                bytes.push((h * 16 + l) as u8);
                k += 3;
            }
            (b, _, _) => {
                bytes.push(b);
                k += 1;
            }
        }
    }
    std::path::PathBuf::from(format!("/{}", String::from_utf8_lossy(&bytes)))
}

impl Instance {
    /// Reads `resources/model.mo`, compiles it and checks it against `token`.
    pub fn new(
        name: &str,
        kind: Kind,
        version: Version,
        token: &str,
        resources: &Path,
        logger: Logger,
    ) -> Result<Instance, FmiError> {
        let path = resources.join("model.mo");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| FmiError::Resources(format!("cannot read {}: {e}", path.display())))?;
        let source = FlatSource::new(&text)?;
        let compiled = source.compile(&[], &[])?;
        let expected = description::token(&text, &compiled.variables);
        if expected != token {
            return Err(FmiError::Resources(format!(
                "the instantiation token {token} is not the model's {expected}"
            )));
        }
        let ex = &compiled.dae.experiment;
        let options = SimOptions::resolve(ex, &Default::default(), Method::Auto, false)
            .map_err(FmiError::Resources)?;
        let mut running = Running::new(compiled, options.clone());
        // Initial values to answer gets before initialization; a failure shows at the
        // end of initialization.
        let _ = running.stepper.initialize();
        Ok(Instance {
            name: name.to_owned(),
            kind,
            version,
            state: State::Instantiated,
            logger,
            source,
            running,
            parameters: Vec::new(),
            starts: Vec::new(),
            options,
            initial_event: false,
            event_done: false,
            terminated: false,
        })
    }

    pub fn compiled(&self) -> &Compiled {
        self.running.compiled()
    }

    pub fn log(&self, error: bool, message: &str) {
        (self.logger)(error, message);
    }

    /// Refuses the call unless the instance is in one of `allowed`.
    pub fn expect(&self, function: &'static str, allowed: &[State]) -> Result<(), FmiError> {
        if allowed.contains(&self.state) {
            Ok(())
        } else {
            Err(FmiError::WrongState {
                function,
                state: self.state.name(),
            })
        }
    }

    /// The experiment's start and stop time and tolerance (setupExperiment /
    /// enterInitializationMode).
    pub fn setup(&mut self, tolerance: Option<f64>, start: f64, stop: Option<f64>) {
        if let Some(tol) = tolerance.filter(|t| t.is_finite() && *t > 0.0) {
            self.options.rtol = tol;
            self.options.atol = tol / 100.0;
        }
        self.options.start = start;
        if let Some(stop) = stop.filter(|s| s.is_finite() && *s > start) {
            self.options.stop = stop;
        } else if self.options.stop <= start {
            self.options.stop = start + 1.0;
        }
    }

    /// The end of initialization: compiled again with the parameters set, initialized
    /// at the start time (the initial event included).
    pub fn exit_initialization(&mut self) -> Result<(), FmiError> {
        let compiled = self.source.compile(&self.parameters, &self.starts)?;
        self.running = Running::new(compiled, self.options.clone());
        self.running.stepper.set_time(self.options.start);
        self.running
            .stepper
            .initialize()
            .map_err(|e| FmiError::simulation(&e))?;
        self.initial_event = true;
        self.state = match self.kind {
            Kind::ModelExchange => State::Event,
            Kind::CoSimulation => State::Step,
        };
        Ok(())
    }

    fn check_reference(&self, function: &'static str, vr: u32) -> Result<(), FmiError> {
        let n = self.compiled().variables.len() as u32;
        let extra = match self.version {
            Version::Fmi2 => 0,
            Version::Fmi3 => 1 + self.compiled().model.roots.len() as u32,
        };
        if vr < n + extra {
            Ok(())
        } else {
            Err(FmiError::BadArgument {
                function,
                message: format!("no variable has the value reference {vr}"),
            })
        }
    }

    /// The values of `refs` (FMI 3: `time` and the event indicators too).
    pub fn get(&mut self, function: &'static str, refs: &[u32]) -> Result<Vec<f64>, FmiError> {
        for &vr in refs {
            self.check_reference(function, vr)?;
        }
        let evaluating = matches!(
            self.state,
            State::Event | State::ContinuousTime | State::Step
        );
        if evaluating {
            self.running
                .stepper
                .evaluate()
                .map_err(|e| FmiError::simulation(&e))?;
        }
        let n = self.compiled().variables.len() as u32;
        let mut indicators = Vec::new();
        if refs.iter().any(|&vr| vr > n) {
            indicators = vec![0.0; self.compiled().model.roots.len()];
            self.event_indicators(&mut indicators)?;
        }
        let stepper = &self.running.stepper;
        Ok(refs
            .iter()
            .map(|&vr| match vr.cmp(&n) {
                std::cmp::Ordering::Less => self
                    .overridden(vr)
                    .unwrap_or_else(|| stepper.registers()[vr as usize]),
                std::cmp::Ordering::Equal => stepper.time(),
                std::cmp::Ordering::Greater => indicators[(vr - n - 1) as usize],
            })
            .collect())
    }

    /// A parameter's value set but not yet compiled in.
    fn overridden(&self, vr: u32) -> Option<f64> {
        if !matches!(self.state, State::Instantiated | State::Initialization) {
            return None;
        }
        let name = &self.compiled().variables[vr as usize].name;
        self.parameters
            .iter()
            .find(|(n, _, _)| n == name)
            .map(|p| p.2)
            .or_else(|| self.starts.iter().find(|(n, _)| n == name).map(|p| p.1))
    }

    /// Sets parameters (before the end of initialization) and inputs.
    pub fn set(
        &mut self,
        function: &'static str,
        refs: &[u32],
        values: &[f64],
    ) -> Result<(), FmiError> {
        for (&vr, &value) in refs.iter().zip(values) {
            self.check_reference(function, vr)?;
            let Some(v) = self.compiled().variables.get(vr as usize) else {
                return Err(FmiError::BadArgument {
                    function,
                    message: format!("the variable {vr} cannot be set"),
                });
            };
            let (name, ty, causality, start_exact) =
                (v.name.clone(), v.ty, v.causality, v.start_exact);
            let before_init = matches!(self.state, State::Instantiated | State::Initialization);
            match causality {
                Causality::Parameter if before_init => {
                    if !value.is_finite() {
                        return Err(FmiError::BadArgument {
                            function,
                            message: format!("`{name}` = {value} is not a finite number"),
                        });
                    }
                    self.parameters.retain(|(n, _, _)| *n != name);
                    self.parameters.push((name, ty, value));
                }
                Causality::Input => self.running.stepper.set_register(vr, value),
                Causality::Local if start_exact && before_init => {
                    if !value.is_finite() {
                        return Err(FmiError::BadArgument {
                            function,
                            message: format!("the start value {value} of `{name}` is not finite"),
                        });
                    }
                    self.starts.retain(|(n, _)| *n != name);
                    self.starts.push((name, value));
                }
                _ => {
                    return Err(FmiError::BadArgument {
                        function,
                        message: format!(
                            "`{name}` cannot be set in {}: only parameters and states whose start is a literal with `fixed = true` (both before the end of initialization) and inputs can",
                            self.state.name()
                        ),
                    })
                }
            }
        }
        Ok(())
    }

    pub fn set_time(&mut self, t: f64) {
        self.running.stepper.set_time(t);
    }

    pub fn n_states(&self) -> usize {
        self.compiled().states.len()
    }

    pub fn n_indicators(&self) -> usize {
        self.compiled().model.roots.len()
    }

    pub fn states(&self) -> Vec<f64> {
        self.running.stepper.states()
    }

    pub fn set_states(&mut self, x: &[f64]) {
        self.running.stepper.set_states(x);
    }

    pub fn nominals(&self) -> Vec<f64> {
        self.compiled().model.nominals.clone()
    }

    pub fn derivatives(&mut self, out: &mut [f64]) -> Result<(), FmiError> {
        self.running
            .stepper
            .derivatives(out)
            .map_err(|e| FmiError::simulation(&e))
    }

    pub fn event_indicators(&mut self, out: &mut [f64]) -> Result<(), FmiError> {
        self.running
            .stepper
            .event_indicators(out)
            .map_err(|e| FmiError::simulation(&e))
    }

    /// The importer accepted an integrator step (Model Exchange): the collision
    /// world, if any, starts its next sweep here.
    pub fn completed_step(&mut self) -> Result<(), FmiError> {
        self.running
            .stepper
            .completed_step()
            .map_err(|e| FmiError::simulation(&e))
    }

    pub fn enter_event_mode(&mut self) {
        self.state = State::Event;
        self.event_done = false;
    }

    /// The event update (the initial event's outcome right after initialization).
    pub fn update_discrete_states(&mut self) -> Result<EventOutcome, FmiError> {
        // A sample instant at the start time is this event's (FMPy cannot integrate
        // to a `nextEventTime` equal to the current time).
        let stepper = &self.running.stepper;
        let sample_due = stepper
            .next_time_event()
            .is_some_and(|s| s <= stepper.time() * (1.0 + 1e-15) + 1e-300);
        if std::mem::take(&mut self.initial_event) && !sample_due {
            self.event_done = true;
            return Ok(EventOutcome {
                next_time: self.running.stepper.next_time_event(),
                ..EventOutcome::default()
            });
        }
        if self.event_done {
            return Ok(EventOutcome {
                next_time: self.running.stepper.next_time_event(),
                ..EventOutcome::default()
            });
        }
        self.event_done = true;
        let outcome = self
            .running
            .stepper
            .event_update()
            .map_err(|e| FmiError::simulation(&e))?;
        if let Some(message) = &outcome.terminated {
            self.terminated = true;
            self.log(false, &format!("the model terminated: {message}"));
        }
        Ok(outcome)
    }

    /// Co-Simulation: one communication step from `t` to `t + h`. Ok(false): the
    /// model terminated inside it.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<bool, FmiError> {
        let now = self.running.stepper.time();
        if (t - now).abs() > 1e-9 * now.abs().max(1.0) || h.is_nan() || h < 0.0 {
            return Err(FmiError::BadArgument {
                function: "doStep",
                message: format!(
                    "the step starts at {t} with size {h}, but the instance is at time {now}"
                ),
            });
        }
        let terminated = self
            .running
            .stepper
            .do_step(t + h)
            .map_err(|e| FmiError::simulation(&e))?;
        if let Some(message) = terminated {
            self.terminated = true;
            self.log(false, &format!("the model terminated: {message}"));
            return Ok(false);
        }
        Ok(true)
    }

    pub fn time(&self) -> f64 {
        self.running.stepper.time()
    }

    /// The end of the run: the terminal event (`when terminal()`).
    pub fn terminate(&mut self) -> Result<(), FmiError> {
        let result = if matches!(
            self.state,
            State::Event | State::ContinuousTime | State::Step
        ) {
            self.running
                .stepper
                .terminal()
                .map_err(|e| FmiError::simulation(&e))
        } else {
            Ok(())
        };
        self.state = State::Terminated;
        result
    }

    /// Back to the state after instantiation, with the default parameter values.
    pub fn reset(&mut self) -> Result<(), FmiError> {
        let compiled = self.source.compile(&[], &[])?;
        self.running = Running::new(compiled, self.options.clone());
        let _ = self.running.stepper.initialize();
        self.parameters.clear();
        self.starts.clear();
        self.state = State::Instantiated;
        self.terminated = false;
        self.initial_event = false;
        self.event_done = false;
        Ok(())
    }
}
