//! The result table an animation reads: a CSV as `simulate` writes it (header names,
//! quoted when they hold a comma, as `T[1,2]`), or a run's rows in memory.

use crate::api::ApiError;
use crate::error::CliError;
use std::collections::HashMap;
use std::path::Path;

/// Column names (the first is the clock) and rows of numbers.
pub struct ResultTable {
    pub names: Vec<String>,
    pub rows: Vec<Vec<f64>>,
    index: HashMap<String, usize>,
}

impl ResultTable {
    /// A table from names and rows (every row as long as `names`).
    pub fn new(names: Vec<String>, rows: Vec<Vec<f64>>) -> ResultTable {
        let index = names
            .iter()
            .enumerate()
            .map(|(k, n)| (n.clone(), k))
            .collect();
        ResultTable { names, rows, index }
    }

    /// The column named `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.index.get(name).copied()
    }

    /// Reads a CSV result file (`E0070` when it cannot be read or is not a table).
    pub fn read_csv(path: &Path) -> Result<ResultTable, ApiError> {
        let text = std::fs::read_to_string(path).map_err(|e| CliError::ResultTable {
            why: format!("cannot read `{}`: {e}", path.display()),
        })?;
        let table = ResultTable::parse_csv(&text);
        Ok(table.map_err(|m| CliError::ResultTable {
            why: format!("{}: {m}", path.display()),
        })?)
    }

    /// Parses CSV text: a header of names, then rows of numbers.
    pub fn parse_csv(text: &str) -> Result<ResultTable, String> {
        let mut lines = text.lines();
        let header = lines.next().ok_or("the file is empty")?;
        let names = split_header(header)?;
        let mut rows = Vec::new();
        for (k, line) in lines.enumerate() {
            if line.trim().is_empty() {
                continue;
            }
            let row: Result<Vec<f64>, _> =
                line.split(',').map(|s| s.trim().parse::<f64>()).collect();
            let row = row.map_err(|e| format!("line {}: {e}", k + 2))?;
            if row.len() != names.len() {
                return Err(format!(
                    "line {}: {} values for {} columns",
                    k + 2,
                    row.len(),
                    names.len()
                ));
            }
            rows.push(row);
        }
        if rows.is_empty() {
            return Err("the table has no rows".into());
        }
        Ok(ResultTable::new(names, rows))
    }
}

/// The header's names: comma separated, a name in double quotes may hold commas
/// (`""` is a quote).
fn split_header(header: &str) -> Result<Vec<String>, String> {
    let mut names = Vec::new();
    let mut current = String::new();
    let mut chars = header.trim_end_matches('\r').chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                current.push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => names.push(std::mem::take(&mut current).trim().to_owned()),
            _ => current.push(c),
        }
    }
    if quoted {
        return Err("the header has an unclosed quote".into());
    }
    names.push(current.trim().to_owned());
    Ok(names)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_names_keep_their_commas() {
        let t = ResultTable::parse_csv("time,x,\"T[1,2]\",\"a\"\"b\"\n0,1,2,3\n").unwrap();
        assert_eq!(t.names, ["time", "x", "T[1,2]", "a\"b"]);
        assert_eq!(t.column("T[1,2]"), Some(2));
        assert!(ResultTable::parse_csv("time,x\n0,1,2\n").is_err());
        assert!(ResultTable::parse_csv("time,x\n").is_err());
    }
}
