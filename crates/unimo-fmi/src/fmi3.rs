//! The FMI 3.0 C functions (Model Exchange and Co-Simulation) over [`Instance`], as
//! `fmi2.rs` does for FMI 2.0. The functions of features our FMUs do not declare
//! (other integer widths, binaries, clocks, FMU states, derivatives of outputs) exist,
//! as every importer looks them all up, and return `fmi3Error` with a message.

use crate::description::{Kind, Version};
use crate::error::FmiError;
use crate::ffi::{self, call, slice, slice_mut, text, typed_access, Type, ANY, ERROR, OK};
use crate::instance::{resource_folder, Instance, State};
use std::ffi::{c_char, c_int, c_void, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

type Inst = *mut c_void;
type Status = c_int;
type Vr = u32;

/// `fmi3LogMessageCallback`.
type LogFn = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

const ME_STATES: &[State] = &[State::Event, State::ContinuousTime];

#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

fn make_logger(environment: *mut c_void, log: Option<LogFn>) -> crate::instance::Logger {
    let environment = environment as usize;
    Box::new(move |error: bool, message: &str| {
        let Some(log) = log else { return };
        let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
        let (status, category) = if error {
            (ERROR, c"logStatusError")
        } else {
            (OK, c"logEvents")
        };
        // SAFETY: the importer's callback with valid NUL-terminated strings.
        unsafe {
            log(
                environment as *mut c_void,
                status,
                category.as_ptr(),
                message.as_ptr(),
            )
        };
    })
}

/// Both instantiate functions.
///
/// # Safety
/// Strings NUL-terminated or null.
unsafe fn instantiate(
    kind: Kind,
    name: *const c_char,
    token: *const c_char,
    resource_path: *const c_char,
    environment: *mut c_void,
    log: Option<LogFn>,
) -> Inst {
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the FMI contract on the arguments.
        let (name, token, path) = unsafe { (text(name), text(token), text(resource_path)) };
        let name = name.unwrap_or_default();
        let logger = make_logger(environment, log);
        let (Some(token), Some(path)) = (token, path) else {
            logger(true, "error[E4705]: instantiate: the instantiation token or the resource path is missing");
            return None;
        };
        let folder = resource_folder(&path);
        match Instance::new(&name, kind, Version::Fmi3, &token, &folder, logger) {
            Ok(instance) => Some(Box::into_raw(Box::new(instance)) as Inst),
            Err(e) => {
                make_logger(environment, log)(true, &format!("error[{}]: {e}", e.code()));
                None
            }
        }
    }));
    outcome.ok().flatten().unwrap_or(std::ptr::null_mut())
}

/// # Safety
/// FMI 3.0: strings NUL-terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    name: *const c_char,
    token: *const c_char,
    path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    env: *mut c_void,
    log: Option<LogFn>,
) -> Inst {
    // SAFETY: forwarded contract.
    unsafe { instantiate(Kind::ModelExchange, name, token, path, env, log) }
}

/// # Safety
/// FMI 3.0: strings NUL-terminated.
#[no_mangle]
#[allow(clippy::too_many_arguments)] // the FMI 3.0 signature
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    name: *const c_char,
    token: *const c_char,
    path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    _event_mode_used: bool,
    _early_return_allowed: bool,
    _required_intermediate: *const Vr,
    _n_required_intermediate: usize,
    env: *mut c_void,
    log: Option<LogFn>,
    _intermediate_update: *const c_void,
) -> Inst {
    // SAFETY: forwarded contract.
    unsafe { instantiate(Kind::CoSimulation, name, token, path, env, log) }
}

#[no_mangle]
pub extern "C" fn fmi3InstantiateScheduledExecution() -> Inst {
    std::ptr::null_mut()
}

#[no_mangle]
pub extern "C" fn fmi3FreeInstance(instance: Inst) {
    ffi::free_instance(instance);
}

#[no_mangle]
pub extern "C" fn fmi3SetDebugLogging(
    instance: Inst,
    _on: bool,
    _n: usize,
    _categories: *const *const c_char,
) -> Status {
    call(instance, "fmi3SetDebugLogging", ANY, |_| Ok(OK))
}

#[no_mangle]
pub extern "C" fn fmi3EnterInitializationMode(
    instance: Inst,
    tolerance_defined: bool,
    tolerance: f64,
    start: f64,
    stop_defined: bool,
    stop: f64,
) -> Status {
    call(
        instance,
        "fmi3EnterInitializationMode",
        &[State::Instantiated],
        |i| {
            i.setup(
                tolerance_defined.then_some(tolerance),
                start,
                stop_defined.then_some(stop),
            );
            i.set_time(start);
            i.state = State::Initialization;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi3ExitInitializationMode(instance: Inst) -> Status {
    call(
        instance,
        "fmi3ExitInitializationMode",
        &[State::Initialization],
        |i| {
            i.exit_initialization()?;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi3Terminate(instance: Inst) -> Status {
    call(
        instance,
        "fmi3Terminate",
        &[State::Event, State::ContinuousTime, State::Step],
        |i| {
            i.terminate()?;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi3Reset(instance: Inst) -> Status {
    call(instance, "fmi3Reset", ANY, |i| {
        i.reset()?;
        Ok(OK)
    })
}

typed_access!(get fmi3GetFloat64, f64, Type::Real, |v| v, n_values);
typed_access!(get fmi3GetInt32, i32, Type::Integer, |v| v as i32, n_values);
typed_access!(get fmi3GetBoolean, bool, Type::Boolean, |v| v != 0.0, n_values);
typed_access!(set fmi3SetFloat64, f64, Type::Real, |v| v, n_values);
typed_access!(set fmi3SetInt32, i32, Type::Integer, f64::from, n_values);
typed_access!(set fmi3SetBoolean, bool, Type::Boolean, |v| f64::from(u8::from(v)), n_values);

#[no_mangle]
pub extern "C" fn fmi3EnterEventMode(instance: Inst) -> Status {
    call(
        instance,
        "fmi3EnterEventMode",
        &[State::ContinuousTime, State::Step],
        |i| {
            i.enter_event_mode();
            Ok(OK)
        },
    )
}

/// Writes `value` through a pointer checked for null.
fn put<T>(p: *mut T, value: T, function: &'static str) -> Result<(), FmiError> {
    // SAFETY: FMI contract (a writable value or null, refused).
    let out = unsafe { slice_mut(p, 1, function)? };
    out[0] = value;
    Ok(())
}

/// # Safety
/// Every pointer writable.
#[no_mangle]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    instance: Inst,
    need_update: *mut bool,
    terminate: *mut bool,
    nominals_changed: *mut bool,
    values_changed: *mut bool,
    next_time_defined: *mut bool,
    next_time: *mut f64,
) -> Status {
    let f = "fmi3UpdateDiscreteStates";
    call(instance, f, &[State::Event], |i| {
        let outcome = i.update_discrete_states()?;
        put(need_update, false, f)?;
        put(terminate, outcome.terminated.is_some(), f)?;
        put(nominals_changed, false, f)?;
        put(values_changed, outcome.states_changed, f)?;
        put(next_time_defined, outcome.next_time.is_some(), f)?;
        put(next_time, outcome.next_time.unwrap_or(0.0), f)?;
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi3EnterContinuousTimeMode(instance: Inst) -> Status {
    call(
        instance,
        "fmi3EnterContinuousTimeMode",
        &[State::Event],
        |i| {
            i.state = State::ContinuousTime;
            Ok(OK)
        },
    )
}

#[no_mangle]
pub extern "C" fn fmi3EnterStepMode(instance: Inst) -> Status {
    call(
        instance,
        "fmi3EnterStepMode",
        &[State::Event, State::Step],
        |i| {
            i.state = State::Step;
            Ok(OK)
        },
    )
}

/// # Safety
/// The two flags writable.
#[no_mangle]
pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
    instance: Inst,
    _no_set_prior: bool,
    enter_event_mode: *mut bool,
    terminate: *mut bool,
) -> Status {
    let f = "fmi3CompletedIntegratorStep";
    call(instance, f, &[State::ContinuousTime], |i| {
        put(enter_event_mode, false, f)?;
        put(terminate, false, f)?;
        i.completed_step()?;
        Ok(OK)
    })
}

#[no_mangle]
pub extern "C" fn fmi3SetTime(instance: Inst, time: f64) -> Status {
    call(instance, "fmi3SetTime", ME_STATES, |i| {
        i.set_time(time);
        Ok(OK)
    })
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetContinuousStates(
    instance: Inst,
    x: *const f64,
    n: usize,
) -> Status {
    let f = "fmi3SetContinuousStates";
    call(instance, f, &[State::ContinuousTime], |i| {
        ffi::expect_size(f, "states", n, i.n_states())?;
        // SAFETY: FMI contract; checked for null.
        let x = unsafe { slice(x, n, f)? };
        i.set_states(x);
        Ok(OK)
    })
}

/// The array getters of Model Exchange: `what` fills `n` values.
fn get_array(
    instance: Inst,
    f: &'static str,
    allowed: &[State],
    p: *mut f64,
    n: usize,
    expected: fn(&Instance) -> usize,
    what: fn(&mut Instance, &mut [f64]) -> Result<(), FmiError>,
) -> Status {
    call(instance, f, allowed, |i| {
        ffi::expect_size(f, "values", n, expected(i))?;
        // SAFETY: FMI contract; checked for null.
        let out = unsafe { slice_mut(p, n, f)? };
        what(i, out)?;
        Ok(OK)
    })
}

/// # Safety
/// `dx` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
    instance: Inst,
    dx: *mut f64,
    n: usize,
) -> Status {
    get_array(
        instance,
        "fmi3GetContinuousStateDerivatives",
        ME_STATES,
        dx,
        n,
        Instance::n_states,
        Instance::derivatives,
    )
}

/// # Safety
/// `z` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetEventIndicators(instance: Inst, z: *mut f64, n: usize) -> Status {
    get_array(
        instance,
        "fmi3GetEventIndicators",
        ME_STATES,
        z,
        n,
        Instance::n_indicators,
        Instance::event_indicators,
    )
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStates(instance: Inst, x: *mut f64, n: usize) -> Status {
    get_array(
        instance,
        "fmi3GetContinuousStates",
        ANY,
        x,
        n,
        Instance::n_states,
        |i, out| {
            out.copy_from_slice(&i.states());
            Ok(())
        },
    )
}

/// # Safety
/// `x` holds `n` values.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
    instance: Inst,
    x: *mut f64,
    n: usize,
) -> Status {
    get_array(
        instance,
        "fmi3GetNominalsOfContinuousStates",
        ANY,
        x,
        n,
        Instance::n_states,
        |i, out| {
            out.copy_from_slice(&i.nominals());
            Ok(())
        },
    )
}

/// # Safety
/// `n` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(instance: Inst, n: *mut usize) -> Status {
    let f = "fmi3GetNumberOfEventIndicators";
    call(instance, f, ANY, |i| {
        put(n, i.n_indicators(), f).map(|_| OK)
    })
}

/// # Safety
/// `n` writable.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(instance: Inst, n: *mut usize) -> Status {
    let f = "fmi3GetNumberOfContinuousStates";
    call(instance, f, ANY, |i| put(n, i.n_states(), f).map(|_| OK))
}

/// # Safety
/// Every pointer writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)] // the FMI 3.0 signature
pub unsafe extern "C" fn fmi3DoStep(
    instance: Inst,
    t: f64,
    h: f64,
    _no_set_prior: bool,
    event_handling_needed: *mut bool,
    terminate: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    let f = "fmi3DoStep";
    call(instance, f, &[State::Step], |i| {
        if i.kind != Kind::CoSimulation {
            return Err(FmiError::WrongState {
                function: f,
                state: "Model Exchange",
            });
        }
        let going = i.do_step(t, h)?;
        put(event_handling_needed, false, f)?;
        put(terminate, !going, f)?;
        put(early_return, false, f)?;
        put(last_successful_time, i.time(), f)?;
        // FMI 3.0: a model that terminated ends its step with `terminateSimulation`.
        Ok(OK)
    })
}

/// Functions for what our FMUs do not declare: each returns `fmi3Error` with a
/// message. They are declared with the instance argument only: with the C calling
/// convention the caller passes and removes any further arguments, which are unused.
macro_rules! not_provided {
    ($($name:ident),* $(,)?) => {
        $(
            #[no_mangle]
            pub extern "C" fn $name(instance: Inst) -> Status {
                ffi::unsupported(instance, stringify!($name))
            }
        )*
    };
}

not_provided!(
    fmi3ActivateModelPartition,
    fmi3DeserializeFMUState,
    fmi3EnterConfigurationMode,
    fmi3EvaluateDiscreteStates,
    fmi3ExitConfigurationMode,
    fmi3FreeFMUState,
    fmi3GetAdjointDerivative,
    fmi3GetBinary,
    fmi3GetClock,
    fmi3GetDirectionalDerivative,
    fmi3GetFMUState,
    fmi3GetFloat32,
    fmi3GetInt16,
    fmi3GetInt64,
    fmi3GetInt8,
    fmi3GetIntervalDecimal,
    fmi3GetIntervalFraction,
    fmi3GetNumberOfVariableDependencies,
    fmi3GetOutputDerivatives,
    fmi3GetShiftDecimal,
    fmi3GetShiftFraction,
    fmi3GetString,
    fmi3GetUInt16,
    fmi3GetUInt32,
    fmi3GetUInt64,
    fmi3GetUInt8,
    fmi3GetVariableDependencies,
    fmi3SerializeFMUState,
    fmi3SerializedFMUStateSize,
    fmi3SetBinary,
    fmi3SetClock,
    fmi3SetFMUState,
    fmi3SetFloat32,
    fmi3SetInt16,
    fmi3SetInt64,
    fmi3SetInt8,
    fmi3SetIntervalDecimal,
    fmi3SetIntervalFraction,
    fmi3SetShiftDecimal,
    fmi3SetShiftFraction,
    fmi3SetString,
    fmi3SetUInt16,
    fmi3SetUInt32,
    fmi3SetUInt64,
    fmi3SetUInt8,
);
