//! Fuzz target: any bytes through the parser and the AST dump must not panic, and every
//! diagnostic span must lie inside the input.
#![no_main]

use libfuzzer_sys::fuzz_target;
use unimo_source::{FileId, SourceFile};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let parsed = unimo_syntax::parse(FileId(0), &text);
    for d in &parsed.diagnostics {
        for l in &d.labels {
            assert!(l.span.start <= l.span.end && l.span.end as usize <= text.len());
        }
    }
    let source = SourceFile::new("fuzz.mo", text.as_ref());
    let _ = unimo_syntax::dump::dump(&parsed.ast, &source);
});
