//! The Modelica libraries shipped with unimo, embedded at build time from `stdlib/`.
//!
//! Invariant: data only. Paths use `/` and are relative to `stdlib/`
//! (`UnilateralMBS/Bodies/RigidBody.mo`).

include!(concat!(env!("OUT_DIR"), "/files.rs"));

/// The text of one embedded file.
pub fn file(path: &str) -> Option<&'static str> {
    FILES.iter().find(|(p, _)| *p == path).map(|(_, t)| *t)
}

#[cfg(test)]
mod tests {
    #[test]
    fn embeds_the_unilateral_library() {
        assert!(super::file("UnilateralMBS/package.mo").is_some());
        assert!(super::FILES.len() >= 10);
    }
}
