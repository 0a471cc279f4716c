//! CSV result files: a header of the selected names, then one line per row (time, then
//! the selected columns, numbers as [`crate::numfmt::push_exp`] writes them). Written
//! after the run from a [`SimResult`], or while it runs on a second thread
//! ([`CsvStream`]): the simulation hands each row to the writer as it is recorded, so
//! formatting the numbers (a 9,600-row, 443-column result spends 0.4 s in it) overlaps
//! the integration instead of following it.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Sender};
use std::thread::JoinHandle;
use unimo_runtime::sim::{RowSink, SimResult};

/// Writes the header line: `time`, then the names of `cols` (quoted when needed).
fn write_header(out: &mut dyn Write, names: &[String], cols: &[usize]) -> std::io::Result<()> {
    write!(out, "time")?;
    for &c in cols {
        let n = &names[c];
        if n.contains(',') || n.contains('"') {
            write!(out, ",\"{}\"", n.replace('"', "\"\""))?;
        } else {
            write!(out, ",{n}")?;
        }
    }
    writeln!(out)
}

/// Appends one line to `line`: the time, then `values` (-0 written as 0).
fn push_line(line: &mut Vec<u8>, t: f64, values: impl Iterator<Item = f64>) {
    crate::numfmt::push_exp(line, t);
    for v in values {
        line.push(b',');
        crate::numfmt::push_exp(line, v + 0.0);
    }
    line.push(b'\n');
}

/// Writes the whole result: the header, then the columns `cols` of every row.
pub fn write_csv(out: &mut dyn Write, r: &SimResult, cols: &[usize]) -> std::io::Result<()> {
    write_header(out, &r.names, cols)?;
    let mut line = Vec::with_capacity(24 * (cols.len() + 1));
    for (t, row) in r.times.iter().zip(&r.rows) {
        line.clear();
        push_line(&mut line, *t, cols.iter().map(|&c| row[c]));
        out.write_all(&line)?;
    }
    Ok(())
}

/// Rows handed over in batches (one channel message per batch, not per row).
const BATCH_ROWS: usize = 64;

/// A batch of rows: time and the selected values of each.
type RowBatch = Vec<(f64, Vec<f64>)>;

/// A CSV file (or stdout) written on its own thread from rows sent while the run goes
/// on. The rows sent must be the result's rows, in order ([`Self::sink`]); then
/// [`Self::finish`] waits for the writer and returns its outcome.
pub struct CsvStream {
    sender: Option<Sender<RowBatch>>,
    writer: JoinHandle<std::io::Result<()>>,
}

impl CsvStream {
    /// Starts the writer: it creates `output` (stdout when `None`) and writes the header
    /// of `names` selected by `cols` at once, then every batch of rows it receives.
    pub fn start(output: Option<&Path>, names: Vec<String>, cols: Vec<usize>) -> CsvStream {
        let (sender, receiver) = channel::<RowBatch>();
        let output: Option<PathBuf> = output.map(Path::to_path_buf);
        let writer = std::thread::spawn(move || -> std::io::Result<()> {
            let mut out: Box<dyn Write> = match &output {
                Some(path) => Box::new(std::io::BufWriter::new(std::fs::File::create(path)?)),
                None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
            };
            write_header(&mut out, &names, &cols)?;
            let mut line = Vec::with_capacity(24 * (cols.len() + 1));
            for batch in receiver {
                line.clear();
                for (t, values) in batch {
                    push_line(&mut line, t, values.into_iter());
                }
                out.write_all(&line)?;
            }
            out.flush()
        });
        CsvStream {
            sender: Some(sender),
            writer,
        }
    }

    /// The receiver of the simulation's rows: keeps the columns `cols` of each and sends
    /// them to the writer in batches (the last, partial batch when the sink is dropped).
    pub fn sink<'a>(&self, cols: &'a [usize]) -> RowSink<'a> {
        let Some(sender) = self.sender.clone() else {
            return Box::new(|_, _| {});
        };
        let mut batch = Batch {
            sender,
            rows: Vec::with_capacity(BATCH_ROWS),
        };
        Box::new(move |t, row| {
            batch.rows.push((t, cols.iter().map(|&c| row[c]).collect()));
            if batch.rows.len() >= BATCH_ROWS {
                batch.send();
            }
        })
    }

    /// Waits until every row sent is written (the sinks must have been dropped).
    pub fn finish(mut self) -> std::io::Result<()> {
        self.sender = None;
        match self.writer.join() {
            Ok(written) => written,
            Err(_) => Err(std::io::Error::other("the CSV writer thread panicked")),
        }
    }
}

/// Rows waiting to be sent; the rest go when it is dropped.
struct Batch {
    sender: Sender<RowBatch>,
    rows: RowBatch,
}

impl Batch {
    fn send(&mut self) {
        let rows = std::mem::replace(&mut self.rows, Vec::with_capacity(BATCH_ROWS));
        // A writer that stopped (an I/O error) reports it from `finish`.
        let _ = self.sender.send(rows);
    }
}

impl Drop for Batch {
    fn drop(&mut self) {
        if !self.rows.is_empty() {
            self.send();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streamed_file_equals_the_written_one() {
        let names = vec!["x".to_string(), "a,b".to_string(), "y".to_string()];
        let cols = vec![0, 1, 2];
        let mut result = SimResult {
            names: names.clone(),
            ..SimResult::default()
        };
        let dir = std::env::temp_dir().join(format!("unimo-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("streamed.csv");
        let stream = CsvStream::start(Some(&path), names, cols.clone());
        {
            let mut sink = stream.sink(&cols);
            for k in 0..(3 * BATCH_ROWS + 5) {
                let t = k as f64 * 0.1;
                let row = vec![t.sin(), -0.0, 1e-300 * k as f64];
                sink(t, &row);
                result.times.push(t);
                result.rows.push(row);
            }
        }
        stream.finish().unwrap();
        let streamed = std::fs::read(&path).unwrap();
        let mut written = Vec::new();
        write_csv(&mut written, &result, &cols).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(streamed, written);
        assert!(String::from_utf8(written)
            .unwrap()
            .starts_with("time,x,\"a,b\",y\n0e0,0e0,0e0,0e0\n"));
    }
}
