//! `coded_errors!`: a stage's error enum declared as a table, one entry per variant.
//!
//! Each entry gives the variant's doc comment (starting with its code), its message (a
//! `thiserror` `#[error(...)]` over its typed fields), its fields, its code and how the
//! diagnostic is decorated (labels, notes, help) from the fields. The macro writes the
//! enum (deriving `thiserror::Error`, so the calling crate depends on `thiserror`),
//! `code()`, `From<Enum> for Diagnostic` (an error or a warning as the code says) and
//! `VARIANT_DOCS`, the variants' names and doc comments, and (in tests) `samples()`, one
//! error per variant with default fields, `check_codes` and `check_variants`, which the
//! stages' tests call.

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

            /// Checks, in the stage's tests, [`check_codes`](Self::check_codes) and that
            /// each variant's diagnostic has a primary label.
            #[cfg(test)]
            #[allow(dead_code)] // a stage calls this or `check_codes`
            pub(crate) fn check_variants(codes: &[$code_ty]) {
                Self::check_codes(codes);
                for (e, (variant, _)) in Self::samples().into_iter().zip(Self::VARIANT_DOCS) {
                    let d = $crate::Diagnostic::from(e);
                    assert!(d.primary_span().is_some(), "{variant} has no primary label");
                }
            }

            /// Checks, in the stage's tests, that every code of `codes` has a variant,
            /// every variant's doc comment names one of them, and each variant's
            /// diagnostic carries that code and its severity (the checks of a stage
            /// whose errors need not point into a file: the command line's).
            #[cfg(test)]
            pub(crate) fn check_codes(codes: &[$code_ty]) {
                let documented = $crate::documented_code;
                for (variant, doc) in Self::VARIANT_DOCS {
                    assert!(
                        codes.iter().any(|c| c.as_str() == documented(doc)),
                        "{variant}: its doc names no code of the stage: {doc}"
                    );
                }
                for code in codes {
                    assert!(
                        Self::VARIANT_DOCS
                            .iter()
                            .any(|(_, doc)| documented(doc) == code.as_str()),
                        "{} has no variant",
                        code.as_str()
                    );
                }
                let samples = Self::samples();
                assert_eq!(samples.len(), Self::VARIANT_DOCS.len());
                for (e, (variant, doc)) in samples.into_iter().zip(Self::VARIANT_DOCS) {
                    let code = e.code();
                    assert_eq!(code.as_str(), documented(doc), "{variant}");
                    let d = $crate::Diagnostic::from(e);
                    assert_eq!(d.code, $crate::Code(code.as_str()), "{variant}");
                    assert_eq!(d.is_error(), !code.is_warning(), "{variant}");
                }
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

/// The code a variant's doc comment starts with (`E2005: ...` gives `E2005`); what
/// `check_variants` compares, public for the macro's expansion in the stages' crates.
#[doc(hidden)]
pub fn documented_code(doc: &str) -> &str {
    doc.trim_start().split(':').next().unwrap_or_default()
}
