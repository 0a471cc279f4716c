//! `coded_errors!`: a stage's error enum declared as a table, one entry per variant.
//!
//! Each entry gives the variant's doc comment (starting with its code), its message (a
//! `thiserror` `#[error(...)]` over its typed fields), its fields, its code and how the
//! diagnostic is decorated (labels, notes, help) from the fields. The macro writes the
//! enum (deriving `thiserror::Error`, so the calling crate depends on `thiserror`),
//! `code()`, `From<Enum> for Diagnostic` (an error or a warning as the code says) and
//! `VARIANT_DOCS`, the variants' names and doc comments, and (in tests) `samples()`, one
//! error per variant with default fields, which the stages' tests read.

/// Declares a coded error enum: see the module's documentation. The code type must have
/// `as_str()` and `is_warning()`.
#[macro_export]
macro_rules! coded_errors {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident : $code_ty:ty {
            $(
                $(#[doc = $doc:literal])*
                #[error $msg:tt]
                $variant:ident { $($field:ident : $fty:ty),* $(,)? } = $code:expr,
                |$d:ident| $diag:expr
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Debug, PartialEq, thiserror::Error)]
        $vis enum $name {
            $(
                $(#[doc = $doc])*
                #[error $msg]
                $variant { $($field: $fty),* },
            )*
        }

        impl $name {
            /// The variants' names and doc comments (each starts with its code).
            pub const VARIANT_DOCS: &'static [(&'static str, &'static str)] =
                &[$((stringify!($variant), concat!($($doc, "\n"),*))),*];

            /// One error of each variant, in `VARIANT_DOCS`'s order, with default
            /// fields (for the tests that check each variant's code).
            #[cfg(test)]
            pub(crate) fn samples() -> Vec<$name> {
                vec![$($name::$variant { $($field: Default::default()),* }),*]
            }

            /// The code of this error.
            #[allow(unused_variables)]
            pub fn code(&self) -> $code_ty {
                match self {
                    $($name::$variant { $($field),* } => $code,)*
                }
            }
        }

        impl From<$name> for $crate::Diagnostic {
            fn from(e: $name) -> $crate::Diagnostic {
                let code = e.code();
                let base = $crate::Diagnostic::new(
                    if code.is_warning() {
                        $crate::Severity::Warning
                    } else {
                        $crate::Severity::Error
                    },
                    code.as_str(),
                    e.to_string(),
                );
                match e {
                    $(
                        #[allow(unused_variables)]
                        $name::$variant { $($field),* } => {
                            let $d = base;
                            $diag
                        }
                    )*
                }
            }
        }
    };
}
