//! Fuzz target: the scanner and the hand-written fast path on any bytes. Wherever the
//! fast path answers, the pest grammar must build the same tree and diagnostics.
#![no_main]

use libfuzzer_sys::fuzz_target;
use unimo_source::FileId;
use unimo_syntax::differential::{fast_only, pest_only};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Some(fast) = fast_only(FileId(0), &text) {
        let pest = pest_only(FileId(0), &text);
        assert_eq!(fast.ast, pest.ast);
        assert_eq!(fast.diagnostics, pest.diagnostics);
    }
});
