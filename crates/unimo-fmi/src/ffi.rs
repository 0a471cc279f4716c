//! What the C functions of both FMI versions share: the status codes, the guard every
//! exported function runs its body in (null instance, state check, errors to the
//! logger, panics caught), and checked conversions of C arrays and strings.

use crate::error::FmiError;
use crate::instance::{Instance, State};
use std::ffi::{c_char, c_void, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use unimo_dae::dae::ScalarType;

/// `fmi2OK` / `fmi3OK`.
pub const OK: i32 = 0;
/// `fmi2Discard` / `fmi3Discard`.
pub const DISCARD: i32 = 2;
/// `fmi2Error` / `fmi3Error`.
pub const ERROR: i32 = 3;

/// Every state but `Terminated`'s neighbours: the states a get may be called in.
pub const ANY: &[State] = &[
    State::Instantiated,
    State::Initialization,
    State::Event,
    State::ContinuousTime,
    State::Step,
    State::Terminated,
];

/// A panic's message.
pub fn panic_text(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".into())
}

/// Runs `body` on the instance behind `ptr` when it is in one of `allowed`: errors go
/// to the logger and become `Error`; a panic is caught and reported the same way.
pub fn call(
    ptr: *mut c_void,
    function: &'static str,
    allowed: &[State],
    body: impl FnOnce(&mut Instance) -> Result<i32, FmiError>,
) -> i32 {
    if ptr.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null instance pointer is one our instantiate function returned
    // (the FMI contract); the importer does not use it from two threads at once.
    let instance = unsafe { &mut *(ptr as *mut Instance) };
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        instance.expect(function, allowed)?;
        body(instance)
    }));
    let error = match outcome {
        Ok(Ok(status)) => return status,
        Ok(Err(e)) => e,
        Err(panic) => FmiError::Internal(format!("{function}: {}", panic_text(&*panic))),
    };
    let report = catch_unwind(AssertUnwindSafe(|| {
        instance.log(true, &format!("error[{}]: {error}", error.code()));
    }));
    drop(report);
    ERROR
}

/// A C array as a slice (`n == 0` allows a null pointer).
///
/// # Safety
/// `p` must point to `n` valid values when it is not null.
pub unsafe fn slice<'a, T>(
    p: *const T,
    n: usize,
    function: &'static str,
) -> Result<&'a [T], FmiError> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(null(function));
    }
    // SAFETY: non-null and `n` values long (the caller's contract).
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// A writable C array as a slice.
///
/// # Safety
/// `p` must point to `n` writable values when it is not null.
pub unsafe fn slice_mut<'a, T>(
    p: *mut T,
    n: usize,
    function: &'static str,
) -> Result<&'a mut [T], FmiError> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(null(function));
    }
    // SAFETY: as in `slice`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

fn null(function: &'static str) -> FmiError {
    FmiError::BadArgument {
        function,
        message: "a null pointer where an array was expected".into(),
    }
}

/// A C string, `None` when null.
///
/// # Safety
/// `p` must be null or a NUL-terminated string.
pub unsafe fn text(p: *const c_char) -> Option<String> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-null and NUL-terminated (the caller's contract).
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
}

/// The type class of a get or set function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    Real,
    Integer,
    Boolean,
}

/// Refuses value references of another type than the function's (FMI 3's `time`
/// and event indicators are Float64).
pub fn check_types(
    instance: &Instance,
    function: &'static str,
    refs: &[u32],
    want: Type,
) -> Result<(), FmiError> {
    let variables = &instance.compiled().variables;
    for &vr in refs {
        let ty = match variables.get(vr as usize).map(|v| v.ty) {
            None | Some(ScalarType::Real) => Type::Real,
            Some(ScalarType::Boolean) => Type::Boolean,
            Some(ScalarType::Integer | ScalarType::Enumeration(_)) => Type::Integer,
        };
        if ty != want {
            return Err(FmiError::BadArgument {
                function,
                message: format!("the value reference {vr} is a {ty:?}, not a {want:?}"),
            });
        }
    }
    Ok(())
}

/// `n` checked to be the size the model has.
pub fn expect_size(
    function: &'static str,
    what: &str,
    n: usize,
    expected: usize,
) -> Result<(), FmiError> {
    if n == expected {
        Ok(())
    } else {
        Err(FmiError::BadArgument {
            function,
            message: format!("{n} {what} given, the model has {expected}"),
        })
    }
}

/// The instance state guard of the functions an FMU does not provide.
pub fn unsupported(ptr: *mut c_void, function: &'static str) -> i32 {
    call(ptr, function, ANY, |_| {
        Err(FmiError::Unsupported(format!(
            "{function} is not provided by unimo's FMUs"
        )))
    })
}
