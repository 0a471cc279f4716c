//! The FMI 2.0 C functions (Model Exchange and Co-Simulation) over [`Instance`]:
//! argument conversion only, every body inside [`ffi::call`] (no panic crosses the
//! C boundary, wrong calls are `fmi2Error` with a message to the logger).

use crate::description::{Kind, Version};
use crate::ffi::{self, call, slice, slice_mut, text, typed_access, Type, ANY, DISCARD, ERROR, OK};
use crate::instance::{resource_folder, Instance, State};
use std::ffi::{c_char, c_int, c_uint, c_void, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

type Component = *mut c_void;
type Status = c_int;
type Bool = c_int;
type Vr = c_uint;

/// `fmi2CallbackLogger` (variadic: the message is a format string).
type LoggerFn =
    unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct CallbackFunctions {
    logger: Option<LoggerFn>,
    allocate_memory: *const c_void,
    free_memory: *const c_void,
    step_finished: *const c_void,
    component_environment: *mut c_void,
}

/// `fmi2EventInfo`.
#[repr(C)]
pub struct EventInfo {
    new_discrete_states_needed: Bool,
    terminate_simulation: Bool,
    nominals_of_continuous_states_changed: Bool,
    values_of_continuous_states_changed: Bool,
    next_event_time_defined: Bool,
    next_event_time: f64,
}

const ME_STATES: &[State] = &[State::Event, State::ContinuousTime];

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

fn make_logger(name: &str, callbacks: &CallbackFunctions) -> crate::instance::Logger {
    let logger = callbacks.logger;
    let environment = callbacks.component_environment as usize;
    let name = CString::new(name.replace('\0', " ")).unwrap_or_default();
    Box::new(move |error: bool, message: &str| {
        let Some(logger) = logger else { return };
        // The message is a printf format: `%` doubled.
        let message =
            CString::new(message.replace('\0', " ").replace('%', "%%")).unwrap_or_default();
        let (status, category) = if error {
            (ERROR, c"logStatusError")
        } else {
            (OK, c"logEvents")
        };
        // SAFETY: the importer's logger, called with valid NUL-terminated strings.
        unsafe {
            logger(
                environment as *mut c_void,
                name.as_ptr(),
                status,
                category.as_ptr(),
                message.as_ptr(),
            )
        };
    })
}

/// # Safety
/// FMI 2.0: strings NUL-terminated, `functions` a valid callback structure.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const CallbackFunctions,
    _visible: Bool,
    _logging_on: Bool,
) -> Component {
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the FMI contract on the arguments.
        let (name, guid, location) =
            unsafe { (text(instance_name), text(guid), text(resource_location)) };
        let callbacks = unsafe { functions.as_ref() }?;
        let name = name.unwrap_or_default();
        let logger = make_logger(&name, callbacks);
        let kind = match fmu_type {
            0 => Kind::ModelExchange,
            1 => Kind::CoSimulation,
            _ => {
                logger(
                    true,
                    &format!("error[E4705]: fmi2Instantiate: unknown fmuType {fmu_type}"),
                );
                return None;
            }
        };
        let (Some(guid), Some(location)) = (guid, location) else {
            logger(
                true,
                "error[E4705]: fmi2Instantiate: the GUID or the resource location is missing",
            );
            return None;
        };
        let folder = resource_folder(&location);
        match Instance::new(&name, kind, Version::Fmi2, &guid, &folder, logger) {
            Ok(instance) => Some(Box::into_raw(Box::new(instance)) as Component),
            Err(e) => {
                let logger = make_logger(&name, callbacks);
                logger(true, &format!("error[{}]: {e}", e.code()));
                None
            }
        }
    }));
    outcome.ok().flatten().unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub extern "C" fn fmi2FreeInstance(c: Component) {
    ffi::free_instance(c);
}

#[no_mangle]
pub extern "C" fn fmi2SetDebugLogging(
    c: Component,
    _on: Bool,
    _n: usize,
    _categories: *const *const c_char,
) -> Status {
    call(c, "fmi2SetDebugLogging", ANY, |_| Ok(OK))
}

#[no_mangle]
pub extern "C" fn fmi2SetupExperiment(
    c: Component,
    tolerance_defined: Bool,
    tolerance: f64,
    start: f64,
    stop_defined: Bool,
    stop: f64,
) -> Status {
    call(c, "fmi2SetupExperiment", &[State::Instantiated], |i| {
        let tolerance = (tolerance_defined != 0).then_some(tolerance);
        i.setup(tolerance, start, (stop_defined != 0).then_some(stop));
        i.set_time(start);
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi2EnterInitializationMode(c: Component) -> Status {
    call(
        c,
        "fmi2EnterInitializationMode",
        &[State::Instantiated],
        |i| {
            i.state = State::Initialization;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi2ExitInitializationMode(c: Component) -> Status {
    call(
        c,
        "fmi2ExitInitializationMode",
        &[State::Initialization],
        |i| {
            i.exit_initialization()?;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi2Terminate(c: Component) -> Status {
    call(
        c,
        "fmi2Terminate",
        &[State::Event, State::ContinuousTime, State::Step],
        |i| {
            i.terminate()?;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi2Reset(c: Component) -> Status {
    call(c, "fmi2Reset", ANY, |i| {
        i.reset()?;
        Ok(OK)
    })
}

typed_access!(get fmi2GetReal, f64, Type::Real, |v| v);
typed_access!(get fmi2GetInteger, c_int, Type::Integer, |v| v as c_int);
typed_access!(get fmi2GetBoolean, Bool, Type::Boolean, |v| Bool::from(v != 0.0));
typed_access!(set fmi2SetReal, f64, Type::Real, |v| v);
typed_access!(set fmi2SetInteger, c_int, Type::Integer, f64::from);
typed_access!(set fmi2SetBoolean, Bool, Type::Boolean, |v| f64::from(u8::from(v != 0)));

#[no_mangle]
pub extern "C" fn fmi2GetString(
    c: Component,
    _vr: *const Vr,
    _n: usize,
    _value: *mut *const c_char,
) -> Status {
    ffi::unsupported(c, "fmi2GetString")
}

#[no_mangle]
pub extern "C" fn fmi2SetString(
    c: Component,
    _vr: *const Vr,
    _n: usize,
    _value: *const *const c_char,
) -> Status {
    ffi::unsupported(c, "fmi2SetString")
}

#[no_mangle]
pub extern "C" fn fmi2GetFMUstate(c: Component, _state: *mut *mut c_void) -> Status {
    ffi::unsupported(c, "fmi2GetFMUstate")
}

#[no_mangle]
pub extern "C" fn fmi2SetFMUstate(c: Component, _state: *mut c_void) -> Status {
    ffi::unsupported(c, "fmi2SetFMUstate")
}

#[no_mangle]
pub extern "C" fn fmi2FreeFMUstate(c: Component, _state: *mut *mut c_void) -> Status {
    ffi::unsupported(c, "fmi2FreeFMUstate")
}

#[no_mangle]
pub extern "C" fn fmi2SerializedFMUstateSize(
    c: Component,
    _state: *mut c_void,
    _size: *mut usize,
) -> Status {
    ffi::unsupported(c, "fmi2SerializedFMUstateSize")
}

#[no_mangle]
pub extern "C" fn fmi2SerializeFMUstate(
    c: Component,
    _state: *mut c_void,
    _bytes: *mut c_char,
    _size: usize,
) -> Status {
    ffi::unsupported(c, "fmi2SerializeFMUstate")
}

#[no_mangle]
pub extern "C" fn fmi2DeSerializeFMUstate(
    c: Component,
    _bytes: *const c_char,
    _size: usize,
    _state: *mut *mut c_void,
) -> Status {
    ffi::unsupported(c, "fmi2DeSerializeFMUstate")
}

#[no_mangle]
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: Component,
    _unknowns: *const Vr,
    _n_unknowns: usize,
    _knowns: *const Vr,
    _n_knowns: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> Status {
    ffi::unsupported(c, "fmi2GetDirectionalDerivative")
}

#[no_mangle]
pub extern "C" fn fmi2EnterEventMode(c: Component) -> Status {
    call(c, "fmi2EnterEventMode", ME_STATES, |i| {
        i.enter_event_mode();
        Ok(OK)
    })
}

/// # Safety
/// `info` points to an `fmi2EventInfo`.
#[no_mangle]
pub unsafe extern "C" fn fmi2NewDiscreteStates(c: Component, info: *mut EventInfo) -> Status {
    call(c, "fmi2NewDiscreteStates", &[State::Event], |i| {
        // SAFETY: FMI contract; checked for null.
        let info = unsafe { slice_mut(info, 1, "fmi2NewDiscreteStates")? };
        let outcome = i.update_discrete_states()?;
        info[0] = EventInfo {
            new_discrete_states_needed: 0,
            terminate_simulation: Bool::from(outcome.terminated.is_some()),
            nominals_of_continuous_states_changed: 0,
            values_of_continuous_states_changed: Bool::from(outcome.states_changed),
            next_event_time_defined: Bool::from(outcome.next_time.is_some()),
            next_event_time: outcome.next_time.unwrap_or(0.0),
        };
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi2EnterContinuousTimeMode(c: Component) -> Status {
    call(c, "fmi2EnterContinuousTimeMode", &[State::Event], |i| {
        i.state = State::ContinuousTime;
        Ok(OK)
    })
}

/// # Safety
/// The two flags point to writable booleans.
#[no_mangle]
pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
    c: Component,
    _no_set_prior: Bool,
    enter_event_mode: *mut Bool,
    terminate: *mut Bool,
) -> Status {
    call(
        c,
        "fmi2CompletedIntegratorStep",
        &[State::ContinuousTime],
        |i| {
            // SAFETY: FMI contract; checked for null.
            let (enter, stop) = unsafe {
                (
                    slice_mut(enter_event_mode, 1, "fmi2CompletedIntegratorStep")?,
                    slice_mut(terminate, 1, "fmi2CompletedIntegratorStep")?,
                )
            };
            i.completed_step()?;
            enter[0] = 0;
            stop[0] = 0;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi2SetTime(c: Component, time: f64) -> Status {
    call(
        c,
        "fmi2SetTime",
        &[
            State::Event,
            State::ContinuousTime,
            State::Instantiated,
            State::Initialization,
        ],
        |i| {
            i.set_time(time);
            Ok(OK)
        },
    )
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetContinuousStates(c: Component, x: *const f64, n: usize) -> Status {
    call(
        c,
        "fmi2SetContinuousStates",
        &[State::ContinuousTime],
        |i| {
            ffi::expect_size("fmi2SetContinuousStates", "states", n, i.n_states())?;
            // SAFETY: FMI contract; checked for null.
            let x = unsafe { slice(x, n, "fmi2SetContinuousStates")? };
            i.set_states(x);
            Ok(OK)
        },
    )
}

/// # Safety
/// `dx` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDerivatives(c: Component, dx: *mut f64, n: usize) -> Status {
    call(c, "fmi2GetDerivatives", ME_STATES, |i| {
        ffi::expect_size("fmi2GetDerivatives", "derivatives", n, i.n_states())?;
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(dx, n, "fmi2GetDerivatives")? };
        i.derivatives(out)?;
        Ok(OK)
    })
}

/// # Safety
/// `z` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetEventIndicators(c: Component, z: *mut f64, n: usize) -> Status {
    call(c, "fmi2GetEventIndicators", ME_STATES, |i| {
        ffi::expect_size(
            "fmi2GetEventIndicators",
            "event indicators",
            n,
            i.n_indicators(),
        )?;
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(z, n, "fmi2GetEventIndicators")? };
        i.event_indicators(out)?;
        Ok(OK)
    })
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetContinuousStates(c: Component, x: *mut f64, n: usize) -> Status {
    call(c, "fmi2GetContinuousStates", ANY, |i| {
        ffi::expect_size("fmi2GetContinuousStates", "states", n, i.n_states())?;
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(x, n, "fmi2GetContinuousStates")? };
        out.copy_from_slice(&i.states());
        Ok(OK)
    })
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
    c: Component,
    x: *mut f64,
    n: usize,
) -> Status {
    call(c, "fmi2GetNominalsOfContinuousStates", ANY, |i| {
        ffi::expect_size(
            "fmi2GetNominalsOfContinuousStates",
            "states",
            n,
            i.n_states(),
        )?;
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(x, n, "fmi2GetNominalsOfContinuousStates")? };
        out.copy_from_slice(&i.nominals());
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetRealInputDerivatives(
    c: Component,
    _vr: *const Vr,
    _n: usize,
    _order: *const c_int,
    _value: *const f64,
) -> Status {
    ffi::unsupported(c, "fmi2SetRealInputDerivatives")
}

#[no_mangle]
pub extern "C" fn fmi2GetRealOutputDerivatives(
    c: Component,
    _vr: *const Vr,
    _n: usize,
    _order: *const c_int,
    _value: *mut f64,
) -> Status {
    ffi::unsupported(c, "fmi2GetRealOutputDerivatives")
}

#[no_mangle]
pub extern "C" fn fmi2DoStep(c: Component, t: f64, h: f64, _no_set_prior: Bool) -> Status {
    call(c, "fmi2DoStep", &[State::Step], |i| {
        if i.kind != Kind::CoSimulation {
            return Err(crate::error::FmiError::WrongState {
                function: "fmi2DoStep",
                state: "Model Exchange",
            });
        }
        Ok(if i.do_step(t, h)? { OK } else { DISCARD })
    })
}

#[no_mangle]
pub extern "C" fn fmi2CancelStep(c: Component) -> Status {
    ffi::unsupported(c, "fmi2CancelStep")
}

#[no_mangle]
pub extern "C" fn fmi2GetStatus(c: Component, _kind: c_int, _value: *mut c_int) -> Status {
    ffi::unsupported(c, "fmi2GetStatus")
}

/// # Safety
/// `value` points to a writable real.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: c_int, value: *mut f64) -> Status {
    call(c, "fmi2GetRealStatus", ANY, |i| {
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(value, 1, "fmi2GetRealStatus")? };
        // fmi2LastSuccessfulTime = 2.
        if kind != 2 {
            return Err(crate::error::FmiError::Unsupported(format!(
                "fmi2GetRealStatus of kind {kind}"
            )));
        }
        out[0] = i.time();
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi2GetIntegerStatus(c: Component, _kind: c_int, _value: *mut c_int) -> Status {
    ffi::unsupported(c, "fmi2GetIntegerStatus")
}

/// # Safety
/// `value` points to a writable boolean.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: Component,
    kind: c_int,
    value: *mut Bool,
) -> Status {
    call(c, "fmi2GetBooleanStatus", ANY, |i| {
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(value, 1, "fmi2GetBooleanStatus")? };
        // fmi2Terminated = 3.
        if kind != 3 {
            return Err(crate::error::FmiError::Unsupported(format!(
                "fmi2GetBooleanStatus of kind {kind}"
            )));
        }
        out[0] = Bool::from(i.terminated);
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi2GetStringStatus(
    c: Component,
    _kind: c_int,
    _value: *mut *const c_char,
) -> Status {
    ffi::unsupported(c, "fmi2GetStringStatus")
}
