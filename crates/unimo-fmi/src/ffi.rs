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

/// A get of `n` values of type `want` into the C array `values` of `n_values`
/// elements, each converted by `convert` (FMI 2.0 passes `n` for `n_values`).
///
/// # Safety
/// `refs` holds `n` references and `values` `n_values` writable values (FMI contract).
#[allow(clippy::too_many_arguments)] // the C arguments, then what the type decides
pub unsafe fn get_typed<T>(
    ptr: *mut c_void,
    function: &'static str,
    refs: *const u32,
    n: usize,
    values: *mut T,
    n_values: usize,
    want: Type,
    convert: fn(f64) -> T,
) -> i32 {
    // SAFETY: the caller's contract; checked for null.
    let Ok(out) = (unsafe { slice_mut(values, n_values, function) }) else {
        return ERROR;
    };
    call(ptr, function, ANY, |i| {
        expect_size(function, "values", n_values, n)?;
        // SAFETY: `refs` holds `n` references (the caller's contract).
        let refs = unsafe { slice(refs, n, function)? };
        check_types(i, function, refs, want)?;
        for (k, v) in i.get(function, refs)?.into_iter().enumerate() {
            out[k] = convert(v);
        }
        Ok(OK)
    })
}

/// A set of `n` values of type `want` from the C array `values` of `n_values`
/// elements, each converted by `convert`.
///
/// # Safety
/// `refs` holds `n` references and `values` `n_values` values (FMI contract).
#[allow(clippy::too_many_arguments)] // as `get_typed`
pub unsafe fn set_typed<T: Copy>(
    ptr: *mut c_void,
    function: &'static str,
    refs: *const u32,
    n: usize,
    values: *const T,
    n_values: usize,
    want: Type,
    convert: fn(T) -> f64,
) -> i32 {
    // SAFETY: the caller's contract; checked for null.
    let Ok(given) = (unsafe { slice(values, n_values, function) }) else {
        return ERROR;
    };
    call(ptr, function, ANY, |i| {
        expect_size(function, "values", n_values, n)?;
        // SAFETY: as in `get_typed`.
        let refs = unsafe { slice(refs, n, function)? };
        check_types(i, function, refs, want)?;
        let values: Vec<f64> = given.iter().map(|&v| convert(v)).collect();
        i.set(function, refs, &values)?;
        Ok(OK)
    })
}

/// The exported typed get and set functions of both versions, one line each:
/// `typed_access!(get fmi2GetReal, f64, Type::Real, |v| v)`; an FMI 3.0 function
/// names its extra array length after the conversion: `..., |v| v, n_values)`.
macro_rules! typed_access {
    (get $name:ident, $t:ty, $want:expr, $convert:expr $(, $n_values:ident)?) => {
        $crate::ffi::typed_access!(@fn $name, *mut $t, get_typed, $want, $convert $(, $n_values)?);
    };
    (set $name:ident, $t:ty, $want:expr, $convert:expr $(, $n_values:ident)?) => {
        $crate::ffi::typed_access!(@fn $name, *const $t, set_typed, $want, $convert $(, $n_values)?);
    };
    (@fn $name:ident, $ptr:ty, $helper:ident, $want:expr, $convert:expr $(, $n_values:ident)?) => {
        /// # Safety
        /// `vr` holds `n` references, `values` `n` values (FMI 3.0: `n_values`).
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instance: *mut std::ffi::c_void,
            vr: *const u32,
            n: usize,
            values: $ptr,
            $($n_values: usize,)?
        ) -> i32 {
            let n_values = [n $(, $n_values)?].into_iter().last().unwrap_or(n);
            // SAFETY: the FMI contract, forwarded.
            unsafe {
                $crate::ffi::$helper(instance, stringify!($name), vr, n, values, n_values, $want, $convert)
            }
        }
    };
}
pub(crate) use typed_access;

/// `fmi2FreeInstance` / `fmi3FreeInstance`: drops an instance `Box::into_raw` made.
pub fn free_instance(ptr: *mut c_void) {
    if ptr.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: made by an instantiate function with `Box::into_raw`, freed once.
        drop(unsafe { Box::from_raw(ptr as *mut Instance) });
    }));
}

/// The instance state guard of the functions an FMU does not provide.
pub fn unsupported(ptr: *mut c_void, function: &'static str) -> i32 {
    call(ptr, function, ANY, |_| {
        Err(FmiError::Unsupported(format!(
            "{function} is not provided by unimo's FMUs"
        )))
    })
}
