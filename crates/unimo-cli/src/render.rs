//! Renders [`unimo_source::Diagnostic`]s as text with the source line, a caret and
//! `file:line:col` (codespan-reporting). The only place diagnostics become text.

use codespan_reporting::diagnostic::{
    Diagnostic as CsDiagnostic, Label as CsLabel, LabelStyle, Severity as CsSeverity,
};
use codespan_reporting::files::{Error as FilesError, Files};
use codespan_reporting::term::{self, termcolor};
use std::ops::Range;
use unimo_source::{Diagnostic, FileId, Severity, SourceMap};

/// Adapts a [`SourceMap`] to codespan's file database.
struct MapFiles<'m>(&'m SourceMap);

impl<'m> Files<'m> for MapFiles<'m> {
    type FileId = FileId;
    type Name = String;
    type Source = &'m str;

    fn name(&'m self, id: FileId) -> Result<String, FilesError> {
        self.check(id)?;
        Ok(self.0.get(id).path().display().to_string())
    }

    fn source(&'m self, id: FileId) -> Result<&'m str, FilesError> {
        self.check(id)?;
        Ok(self.0.get(id).text())
    }

    fn line_index(&'m self, id: FileId, byte_index: usize) -> Result<usize, FilesError> {
        self.check(id)?;
        let starts = self.0.get(id).line_starts();
        Ok(starts
            .partition_point(|&s| s as usize <= byte_index)
            .saturating_sub(1))
    }

    fn line_range(&'m self, id: FileId, line_index: usize) -> Result<Range<usize>, FilesError> {
        self.check(id)?;
        let file = self.0.get(id);
        let starts = file.line_starts();
        let start = *starts.get(line_index).ok_or(FilesError::LineTooLarge {
            given: line_index,
            max: starts.len() - 1,
        })? as usize;
        let end = starts
            .get(line_index + 1)
            .map_or(file.text().len(), |&s| s as usize);
        Ok(start..end)
    }
}

impl MapFiles<'_> {
    fn check(&self, id: FileId) -> Result<(), FilesError> {
        if id.index() < self.0.len() {
            Ok(())
        } else {
            Err(FilesError::FileMissing)
        }
    }
}

fn convert(d: &Diagnostic, map: &SourceMap) -> CsDiagnostic<FileId> {
    let severity = match d.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
        Severity::Note => CsSeverity::Note,
    };
    let labels = d
        .labels
        .iter()
        .filter(|l| l.span.file.index() < map.len())
        .map(|l| {
            let style = if l.primary {
                LabelStyle::Primary
            } else {
                LabelStyle::Secondary
            };
            let len = map.get(l.span.file).text().len();
            let range = (l.span.start as usize).min(len)..(l.span.end as usize).min(len);
            CsLabel::new(style, l.span.file, range).with_message(l.message.clone())
        })
        .collect();
    let mut notes: Vec<String> = d.notes.clone();
    if let Some(h) = &d.help {
        notes.push(format!("help: {h}"));
    }
    CsDiagnostic::new(severity)
        .with_code(d.code.0)
        .with_message(d.message.clone())
        .with_labels(labels)
        .with_notes(notes)
}

fn config() -> term::Config {
    term::Config::default()
}

/// Renders one diagnostic without colour (for files, pipes and snapshot tests).
pub fn render_plain(d: &Diagnostic, map: &SourceMap) -> String {
    let files = MapFiles(map);
    term::emit_into_string(&config(), &files, &convert(d, map)).unwrap_or_else(|e| {
        format!(
            "{}[{}]: {} (could not show source: {e})\n",
            severity_word(d.severity),
            d.code,
            d.message
        )
    })
}

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

/// Writes diagnostics to stderr, in colour when stderr is a terminal.
pub fn emit_stderr(diags: &[Diagnostic], map: &SourceMap, color: bool) {
    let choice = if color {
        termcolor::ColorChoice::Auto
    } else {
        termcolor::ColorChoice::Never
    };
    let stream = termcolor::StandardStream::stderr(choice);
    let mut lock = stream.lock();
    let files = MapFiles(map);
    for d in diags {
        let _ = term::emit_to_write_style(&mut lock, &config(), &files, &convert(d, map));
    }
}
