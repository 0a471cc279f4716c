//! MAT v4 result files in the layout of Dymola and OpenModelica (`dsres`): `Aclass`,
//! `name`, `description`, `dataInfo`, `data_1` (time-invariant values) and `data_2`
//! (trajectories), written and read back by our own code.
//!
//! A MAT v4 matrix is a header of five little-endian `i32`s — type, rows, columns,
//! imaginary flag, length of the name with its NUL — then the name, then the data in
//! column-major order. Types used here: `0` double, `20` int32, `51` text (one byte per
//! character). The `binTrans` layout stores `name` and `description` with one column
//! per variable (so each name is contiguous), `dataInfo` as 4 x n, `data_1` as
//! n1 x 2 (values at the start and stop time) and `data_2` as n2 x points (one column
//! per output point, time in the first row).

use super::{ResultVariable, Storage};
use std::collections::HashMap;
use std::io::{self, Write};

const TYPE_DOUBLE: i32 = 0;
const TYPE_INT32: i32 = 20;
const TYPE_TEXT: i32 = 51;

/// The name and description of the time column, as OpenModelica writes them.
const TIME_NAME: &str = "time";
const TIME_DESCRIPTION: &str = "Simulation time [s]";

fn header(out: &mut dyn Write, name: &str, ty: i32, rows: usize, cols: usize) -> io::Result<()> {
    let too_big = |n: usize| {
        i32::try_from(n).map_err(|_| io::Error::other(format!("matrix `{name}` too large")))
    };
    for v in [
        ty,
        too_big(rows)?,
        too_big(cols)?,
        0,
        too_big(name.len() + 1)?,
    ] {
        out.write_all(&v.to_le_bytes())?;
    }
    out.write_all(name.as_bytes())?;
    out.write_all(&[0])
}

/// A text matrix with one column per string, padded with NULs to the longest.
fn text_columns(out: &mut dyn Write, name: &str, strings: &[&str]) -> io::Result<()> {
    let width = strings.iter().map(|s| s.len()).max().unwrap_or(0).max(1);
    header(out, name, TYPE_TEXT, width, strings.len())?;
    let mut padded = Vec::with_capacity(width * strings.len());
    for s in strings {
        padded.extend_from_slice(s.as_bytes());
        padded.resize(padded.len() + width - s.len(), 0);
    }
    out.write_all(&padded)
}

/// A text matrix with one row per string (`Aclass`), padded with spaces.
fn text_rows(out: &mut dyn Write, name: &str, strings: &[&str]) -> io::Result<()> {
    let width = strings.iter().map(|s| s.len()).max().unwrap_or(0);
    header(out, name, TYPE_TEXT, strings.len(), width)?;
    for k in 0..width {
        for s in strings {
            out.write_all(&[*s.as_bytes().get(k).unwrap_or(&b' ')])?;
        }
    }
    Ok(())
}

fn doubles(out: &mut dyn Write, values: impl Iterator<Item = f64>) -> io::Result<()> {
    for v in values {
        out.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}

/// Where each variable's values are: `(matrix, signed 1-based row)`, time first.
/// Returns the data_1 and data_2 row counts with it (time is a row of both).
fn data_info(vars: &[ResultVariable]) -> (Vec<(i32, i32)>, usize, usize) {
    let (mut n1, mut n2) = (1i32, 1i32);
    let mut info: Vec<(i32, i32)> = vars
        .iter()
        .map(|v| match v.storage {
            Storage::Constant(_) => {
                n1 += 1;
                (1, n1)
            }
            Storage::Column(_) => {
                n2 += 1;
                (2, n2)
            }
            Storage::Alias { .. } => (0, 0),
        })
        .collect();
    for (k, v) in vars.iter().enumerate() {
        if let Storage::Alias { target, negated } = v.storage {
            let (matrix, row) = info[target];
            info[k] = (matrix, if negated { -row } else { row });
        }
    }
    (info, n1 as usize, n2 as usize)
}

/// Writes a result file. `times` and `rows` are the run's output points; a
/// `Storage::Column(c)` variable is `rows[..][c]`. Aliases must point at a variable
/// that is not itself an alias.
pub fn write(
    out: &mut dyn Write,
    vars: &[ResultVariable],
    times: &[f64],
    rows: &[Vec<f64>],
    (start, stop): (f64, f64),
) -> io::Result<()> {
    text_rows(out, "Aclass", &["Atrajectory", "1.1", "", "binTrans"])?;
    let names: Vec<&str> = std::iter::once(TIME_NAME)
        .chain(vars.iter().map(|v| v.name.as_str()))
        .collect();
    text_columns(out, "name", &names)?;
    let descriptions: Vec<&str> = std::iter::once(TIME_DESCRIPTION)
        .chain(vars.iter().map(|v| v.description.as_str()))
        .collect();
    text_columns(out, "description", &descriptions)?;
    let (info, n1, n2) = data_info(vars);
    header(out, "dataInfo", TYPE_INT32, 4, names.len())?;
    for [a, b, c, d] in
        std::iter::once([0, 1, 0, -1]).chain(info.iter().map(|&(matrix, row)| [matrix, row, 0, 0]))
    {
        for v in [a, b, c, d] {
            out.write_all(&v.to_le_bytes())?;
        }
    }
    let constants: Vec<f64> = vars
        .iter()
        .filter_map(|v| match v.storage {
            Storage::Constant(x) => Some(x),
            _ => None,
        })
        .collect();
    header(out, "data_1", TYPE_DOUBLE, n1, 2)?;
    for bound in [start, stop] {
        doubles(out, std::iter::once(bound).chain(constants.iter().copied()))?;
    }
    let columns: Vec<usize> = vars
        .iter()
        .filter_map(|v| match v.storage {
            Storage::Column(c) => Some(c),
            _ => None,
        })
        .collect();
    header(out, "data_2", TYPE_DOUBLE, n2, times.len())?;
    for (t, row) in times.iter().zip(rows) {
        doubles(
            out,
            std::iter::once(*t).chain(columns.iter().map(|&c| row[c])),
        )?;
    }
    Ok(())
}

/// The values of a matrix read back.
#[derive(Clone, Debug, PartialEq)]
pub enum MatData {
    Double(Vec<f64>),
    Int32(Vec<i32>),
    Text(Vec<u8>),
}

/// One matrix of a MAT v4 file: column-major data.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix {
    pub rows: usize,
    pub cols: usize,
    pub data: MatData,
}

impl Matrix {
    /// Column `k` of a text matrix, without its padding.
    pub fn text_column(&self, k: usize) -> String {
        let MatData::Text(bytes) = &self.data else {
            return String::new();
        };
        let column = &bytes[k * self.rows..(k + 1) * self.rows];
        String::from_utf8_lossy(column)
            .trim_end_matches(['\0', ' '])
            .to_owned()
    }

    fn number(&self, row: usize, col: usize) -> f64 {
        let k = col * self.rows + row;
        match &self.data {
            MatData::Double(v) => v[k],
            MatData::Int32(v) => v[k] as f64,
            MatData::Text(v) => v[k] as f64,
        }
    }
}

fn read_i32(bytes: &[u8], at: &mut usize) -> Result<i32, String> {
    let chunk = bytes
        .get(*at..*at + 4)
        .ok_or("the file ends inside a matrix header")?;
    *at += 4;
    Ok(i32::from_le_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]))
}

/// The matrices of a file, by name.
pub type MatFile = HashMap<String, Matrix>;

/// Reads every matrix of a little-endian MAT v4 file (double, int32 and text types).
pub fn read(bytes: &[u8]) -> Result<MatFile, String> {
    let mut at = 0;
    let mut out = HashMap::new();
    while at < bytes.len() {
        let ty = read_i32(bytes, &mut at)?;
        let rows = usize::try_from(read_i32(bytes, &mut at)?).map_err(|e| e.to_string())?;
        let cols = usize::try_from(read_i32(bytes, &mut at)?).map_err(|e| e.to_string())?;
        let _imaginary = read_i32(bytes, &mut at)?;
        let name_len = usize::try_from(read_i32(bytes, &mut at)?).map_err(|e| e.to_string())?;
        let name = bytes
            .get(at..at + name_len)
            .ok_or("the file ends in a name")?;
        let name = String::from_utf8_lossy(name)
            .trim_end_matches('\0')
            .to_owned();
        at += name_len;
        let n = rows * cols;
        let width = match ty {
            TYPE_DOUBLE => 8,
            TYPE_INT32 => 4,
            TYPE_TEXT => 1,
            _ => return Err(format!("matrix `{name}`: unsupported type {ty}")),
        };
        let raw = bytes
            .get(at..at + n * width)
            .ok_or(format!("matrix `{name}`: the file ends in its data"))?;
        at += n * width;
        let data = match ty {
            TYPE_DOUBLE => MatData::Double(
                raw.chunks_exact(8)
                    .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
                    .collect(),
            ),
            TYPE_INT32 => MatData::Int32(
                raw.chunks_exact(4)
                    .map(|c| i32::from_le_bytes(c.try_into().unwrap_or([0; 4])))
                    .collect(),
            ),
            _ => MatData::Text(raw.to_vec()),
        };
        out.insert(name, Matrix { rows, cols, data });
    }
    Ok(out)
}

/// Every variable's values at the output points, by name, resolved through
/// `dataInfo` (aliases, negated aliases, time-invariant values repeated).
pub fn trajectories(file: &MatFile) -> Result<Vec<(String, Vec<f64>)>, String> {
    let get = |n: &str| file.get(n).ok_or(format!("no matrix `{n}`"));
    let (names, info, data_1, data_2) = (
        get("name")?,
        get("dataInfo")?,
        get("data_1")?,
        get("data_2")?,
    );
    let points = data_2.cols;
    let mut out = Vec::with_capacity(names.cols);
    for k in 0..names.cols {
        let matrix = info.number(0, k) as i32;
        let row = info.number(1, k) as i32;
        let sign = if row < 0 { -1.0 } else { 1.0 };
        let r = row.unsigned_abs() as usize - 1;
        let values: Vec<f64> = match matrix {
            0 | 2 => (0..points).map(|p| sign * data_2.number(r, p)).collect(),
            1 => vec![sign * data_1.number(r, 0); points],
            m => return Err(format!("dataInfo names matrix data_{m}")),
        };
        out.push((names.text_column(k), values));
    }
    Ok(out)
}
