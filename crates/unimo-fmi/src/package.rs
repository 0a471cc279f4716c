//! The FMU archive: the model description, the shared library under
//! `binaries/linux64/` (FMI 2.0) or `binaries/x86_64-linux/` (FMI 3.0) and the flat model under `resources/`, in a zip file
//! (stored entries, written here: no compression library needed).

use crate::description::{self, Header, Kind, Version};
use crate::error::FmiError;
use crate::model::{Causality, FlatSource};
use std::path::Path;
use unimo_dae::dae::ScalarKind;
use unimo_runtime::sim::stepper::Stepper;
use unimo_runtime::sim::SimOptions;
use unimo_solve::Method;

/// What `unimo fmu` asks for.
pub struct Request<'a> {
    /// The flat model (`unimo flatten`'s text).
    pub flat_text: &'a str,
    pub version: Version,
    pub kind: Kind,
    /// The prebuilt `libunimo_fmi.so`.
    pub library: &'a Path,
}

/// What was written: counts for the command line's summary.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    pub identifier: String,
    pub variables: usize,
    pub states: usize,
    pub event_indicators: usize,
    pub bytes: usize,
    /// The library was packaged without its debug information and symbol table
    /// (`strip` or `objcopy` found); false: as built.
    pub stripped: bool,
}

/// The FMU's files and the archive bytes.
pub fn build(r: &Request<'_>) -> Result<(Vec<u8>, Summary), FmiError> {
    let source = FlatSource::new(r.flat_text)?;
    let mut compiled = source.compile(&[], &[])?;
    let options = SimOptions::resolve(
        &compiled.dae.experiment,
        &Default::default(),
        Method::Auto,
        false,
    )
    .map_err(FmiError::Model)?;
    let starts = {
        let mut stepper = Stepper::new(&compiled.model, options.clone());
        stepper.initialize().map_err(|e| FmiError::simulation(&e))?;
        stepper.registers().to_vec()
    };
    for v in &mut compiled.variables {
        let wants_start = matches!(v.causality, Causality::Parameter | Causality::Input)
            || v.kind == ScalarKind::Constant
            || v.start_exact;
        if wants_start {
            v.start = starts.get(v.scalar as usize).copied();
        }
    }
    let flat = source.flat();
    let name = flat.name.trim_matches('\'').to_owned();
    let identifier = description::identifier(&name);
    let token = description::token(r.flat_text, &compiled.variables);
    let header = Header {
        model_name: &name,
        description: "",
        identifier: &identifier,
        token: &token,
        version: r.version,
        kind: r.kind,
        experiment: (options.start, options.stop, options.rtol, options.interval),
    };
    let xml = description::write(&header, &compiled);
    let (library, stripped) = library_bytes(r.library)?;
    // FMI 2.0 names the platform `linux64`, FMI 3.0 by its tuple.
    let platform = match r.version {
        Version::Fmi2 => "linux64",
        Version::Fmi3 => "x86_64-linux",
    };
    let files: Vec<(String, &[u8])> = vec![
        ("modelDescription.xml".into(), xml.as_bytes()),
        (format!("binaries/{platform}/{identifier}.so"), &library),
        ("resources/model.mo".into(), r.flat_text.as_bytes()),
    ];
    let bytes = zip(&files);
    let summary = Summary {
        identifier,
        variables: compiled.variables.len(),
        states: compiled.states.len(),
        event_indicators: compiled.model.roots.len(),
        bytes: bytes.len(),
        stripped,
    };
    Ok((bytes, summary))
}

/// The library's bytes as the FMU ships them: without debug information and the
/// symbols no one links against (the FMI functions stay in the dynamic symbol table),
/// when `strip` or `objcopy` (binutils) is there to remove them (a release build with
/// the release profile's debug information: 56 MB as built, a few MB stripped); as
/// built otherwise. The library itself is never changed: a copy is stripped.
fn library_bytes(path: &Path) -> Result<(Vec<u8>, bool), FmiError> {
    let read = |p: &Path| {
        std::fs::read(p)
            .map_err(|e| FmiError::LibraryMissing(format!("cannot read {}: {e}", p.display())))
    };
    let original = read(path)?;
    let copy = std::env::temp_dir().join(format!(
        "unimo-fmu-{}-{}.so",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos())
    ));
    if std::fs::write(&copy, &original).is_err() {
        return Ok((original, false));
    }
    let tools: [(&str, &[&str]); 2] = [
        ("strip", &["--strip-unneeded"]),
        ("objcopy", &["--strip-unneeded"]),
    ];
    let stripped = tools.iter().any(|(tool, args)| {
        std::process::Command::new(tool)
            .args(*args)
            .arg(&copy)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    });
    let result = match stripped {
        true => read(&copy).map(|b| (b, true)),
        false => Ok((original, false)),
    };
    let _ = std::fs::remove_file(&copy);
    result
}

/// CRC-32 (IEEE), as zip files use.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A zip archive of `files` (stored, no compression).
pub fn zip(files: &[(String, &[u8])]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    let le16 = |v: &mut Vec<u8>, x: u16| v.extend_from_slice(&x.to_le_bytes());
    let le32 = |v: &mut Vec<u8>, x: u32| v.extend_from_slice(&x.to_le_bytes());
    for (name, data) in files {
        let offset = out.len() as u32;
        let (crc, size) = (crc32(data), data.len() as u32);
        // Local file header: version 2.0, no flags, stored, time and date 1980-01-01.
        le32(&mut out, 0x0403_4b50);
        for x in [20, 0, 0, 0, 0x21] {
            le16(&mut out, x);
        }
        for x in [crc, size, size] {
            le32(&mut out, x);
        }
        le16(&mut out, name.len() as u16);
        le16(&mut out, 0);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        // Central directory entry.
        le32(&mut central, 0x0201_4b50);
        for x in [20, 20, 0, 0, 0, 0x21] {
            le16(&mut central, x);
        }
        for x in [crc, size, size] {
            le32(&mut central, x);
        }
        for x in [name.len() as u16, 0, 0, 0, 0] {
            le16(&mut central, x);
        }
        le32(&mut central, 0);
        le32(&mut central, offset);
        central.extend_from_slice(name.as_bytes());
    }
    let central_offset = out.len() as u32;
    out.extend_from_slice(&central);
    le32(&mut out, 0x0605_4b50);
    for x in [0, 0, files.len() as u16, files.len() as u16] {
        le16(&mut out, x);
    }
    le32(&mut out, central.len() as u32);
    le32(&mut out, central_offset);
    le16(&mut out, 0);
    out
}

/// Writes the archive to `path`.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), FmiError> {
    std::fs::write(path, bytes).map_err(|e| FmiError::Write(format!("{}: {e}", path.display())))
}

#[cfg(test)]
mod tests {
    #[test]
    fn crc32_of_the_standard_check_string() {
        assert_eq!(super::crc32(b"123456789"), 0xcbf4_3926);
    }
}
