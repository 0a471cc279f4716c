//! CSV result files: a header of the selected names, then one line per row (time, then
//! the selected columns, numbers as [`crate::numfmt::push_exp`] writes them). Written
//! after the run from a [`SimResult`], or while it runs on a second thread
//! ([`CsvStream`]): the simulation hands each row to the writer as it is recorded, so
//! formatting the numbers (a 9,600-row, 443-column result spends 0.4 s in it) overlaps
//! the integration instead of following it.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver, Sender};
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

/// Rows handed over in batches of about this many values (one channel message per
/// batch, not per row; at least one row a batch).
const BATCH_VALUES: usize = 1 << 16;

/// The batches in circulation, at most (256 MiB of values): the simulation does not
/// wait for a writer that falls behind (formatting the numbers may take longer than
/// computing them) until that many are queued, and the written ones are reused (a
/// large model's rows are not allocated and faulted in anew when the writer keeps up).
const BATCHES: usize = 512;

/// A batch of rows: the times, and the selected values of each row one after the other.
#[derive(Default)]
struct RowBatch {
    times: Vec<f64>,
    values: Vec<f64>,
}

impl RowBatch {
    fn with_capacity(rows: usize, width: usize) -> RowBatch {
        RowBatch {
            times: Vec::with_capacity(rows),
            values: Vec::with_capacity(rows * width),
        }
    }
}

/// A CSV file (or stdout) written on its own thread from rows sent while the run goes
/// on. The rows sent must be the result's rows, in order ([`Self::sink`]); then
/// [`Self::finish`] waits for the writer and returns its outcome.
pub struct CsvStream {
    sender: Option<Sender<RowBatch>>,
    /// Written batches coming back, to be filled again.
    spent: Option<Receiver<RowBatch>>,
    writer: JoinHandle<std::io::Result<()>>,
}

impl CsvStream {
    /// Starts the writer: it creates `output` (stdout when `None`) and writes the header
    /// of `names` selected by `cols` at once, then every batch of rows it receives, one
    /// line at a time (the line buffer holds one row, whatever the batch's size).
    pub fn start(output: Option<&Path>, names: Vec<String>, cols: Vec<usize>) -> CsvStream {
        let (sender, receiver) = channel::<RowBatch>();
        let (give_back, spent) = channel::<RowBatch>();
        let output: Option<PathBuf> = output.map(Path::to_path_buf);
        let writer = std::thread::spawn(move || -> std::io::Result<()> {
            let mut out: Box<dyn Write> = match &output {
                Some(path) => Box::new(std::io::BufWriter::new(std::fs::File::create(path)?)),
                None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
            };
            write_header(&mut out, &names, &cols)?;
            let mut line = Vec::with_capacity(24 * (cols.len() + 1));
            for batch in receiver {
                let width = cols.len();
                for (k, &t) in batch.times.iter().enumerate() {
                    line.clear();
                    let row = &batch.values[k * width..(k + 1) * width];
                    push_line(&mut line, t, row.iter().copied());
                    out.write_all(&line)?;
                }
                // The simulation may have finished: then the batch is dropped here.
                let _ = give_back.send(batch);
            }
            out.flush()
        });
        CsvStream {
            sender: Some(sender),
            spent: Some(spent),
            writer,
        }
    }

    /// The receiver of the simulation's rows: keeps the columns `cols` of each and sends
    /// them to the writer in batches (the last, partial batch when the sink is dropped).
    /// Only the first sink reuses the written batches.
    pub fn sink<'a>(&mut self, cols: &'a [usize]) -> RowSink<'a> {
        self.sink_with(cols, BATCHES)
    }

    /// [`Self::sink`] with at most `batches` batches in circulation.
    fn sink_with<'a>(&mut self, cols: &'a [usize], batches: usize) -> RowSink<'a> {
        let Some(sender) = self.sender.clone() else {
            return Box::new(|_, _| {});
        };
        let width = cols.len();
        let rows = (BATCH_VALUES / width.max(1)).max(1);
        let mut batch = Batch {
            sender,
            spent: self.spent.take(),
            new_ones: batches.max(1) - 1,
            rows: RowBatch::with_capacity(rows, width),
            capacity: (rows, width),
        };
        Box::new(move |t, row| {
            batch.rows.times.push(t);
            batch.rows.values.extend(cols.iter().map(|&c| row[c]));
            if batch.rows.times.len() >= rows {
                batch.send();
            }
        })
    }

    /// Waits until every row sent is written (the sinks must have been dropped).
    pub fn finish(mut self) -> std::io::Result<()> {
        self.sender = None;
        self.spent = None;
        match self.writer.join() {
            Ok(written) => written,
            Err(_) => Err(std::io::Error::other("the CSV writer thread panicked")),
        }
    }
}

/// Rows waiting to be sent; the rest go when it is dropped.
struct Batch {
    sender: Sender<RowBatch>,
    /// The written batches (none for a second sink: it allocates each batch).
    spent: Option<Receiver<RowBatch>>,
    /// How many more batches may be allocated before waiting for a written one.
    new_ones: usize,
    rows: RowBatch,
    /// Rows a batch and values a row.
    capacity: (usize, usize),
}

impl Batch {
    fn send(&mut self) {
        let mut next = match &self.spent {
            Some(spent) if self.new_ones == 0 => spent.recv().ok(),
            Some(spent) => spent.try_recv().ok(),
            None => None,
        }
        .unwrap_or_else(|| {
            // A writer that stopped (an I/O error) sends nothing back: no waiting then.
            self.new_ones = self.new_ones.saturating_sub(1);
            RowBatch::with_capacity(self.capacity.0, self.capacity.1)
        });
        next.times.clear();
        next.values.clear();
        let rows = std::mem::replace(&mut self.rows, next);
        // A writer that stopped reports its error from `finish`.
        let _ = self.sender.send(rows);
    }
}

impl Drop for Batch {
    fn drop(&mut self) {
        if !self.rows.times.is_empty() {
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
        let mut stream = CsvStream::start(Some(&path), names, cols.clone());
        {
            // Two batches in circulation and five to write: the sink waits for written
            // ones and reuses them.
            let mut sink = stream.sink_with(&cols, 2);
            for k in 0..(5 * (BATCH_VALUES / cols.len()) + 5) {
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
