//! `unimo plot`: line plots (SVG) of columns of a result CSV, against time or another
//! column (phase plots such as a contact point's x against z).

use crate::error::CliError;
use crate::EXIT_OK;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug, Clone)]
pub struct PlotArgs {
    /// A CSV written by `unimo simulate` (header `time,<names>`).
    #[arg(value_name = "CSV")]
    pub csv: PathBuf,
    /// Columns to plot, comma separated (each one line). Default: every column.
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    pub vars: Vec<String>,
    /// The column on the horizontal axis.
    #[arg(long, value_name = "NAME", default_value = "time")]
    pub x: String,
    /// Where to write the SVG.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "SVG",
        default_value = "plot.svg"
    )]
    pub output: PathBuf,
    /// Title of the figure [default: the CSV's file name].
    #[arg(long)]
    pub title: Option<String>,
    /// Label of the vertical axis [default: the column name when there is one].
    #[arg(long, value_name = "TEXT")]
    pub ylabel: Option<String>,
    /// Logarithmic vertical axis (values <= 0 are left out).
    #[arg(long)]
    pub log_y: bool,
    /// Only rows whose `--range-of` column is in this range, e.g. `--range 20,60`.
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "FROM,TO",
        allow_negative_numbers = true
    )]
    pub range: Vec<f64>,
    /// The column that `--range` selects on [default: the `--x` column].
    #[arg(long, value_name = "NAME")]
    pub range_of: Option<String>,
    /// Points per line at most: longer series are thinned keeping each bucket's first,
    /// smallest, largest and last point, so peaks and jumps stay visible.
    #[arg(long, value_name = "N", default_value_t = 4000)]
    pub max_points: usize,
    /// Size in pixels.
    #[arg(long, value_delimiter = ',', value_name = "W,H", default_values_t = [900, 560])]
    pub size: Vec<u32>,
}

/// A result table: column names and rows.
pub struct Table {
    pub names: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

/// Reads a CSV as written by `simulate` (numbers only after the header).
pub fn read_csv(path: &Path) -> Result<Table, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header = lines
        .next()
        .ok_or_else(|| format!("{}: the file is empty", path.display()))?;
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_owned()).collect();
    let mut rows = Vec::new();
    for (k, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let row: Result<Vec<f64>, _> = line.split(',').map(|s| s.trim().parse::<f64>()).collect();
        let row = row.map_err(|e| format!("{}:{}: {e}", path.display(), k + 2))?;
        if row.len() != names.len() {
            return Err(format!(
                "{}:{}: {} values for {} columns",
                path.display(),
                k + 2,
                row.len(),
                names.len()
            ));
        }
        rows.push(row);
    }
    Ok(Table { names, rows })
}

fn column(t: &Table, name: &str) -> Result<usize, CliError> {
    t.names.iter().position(|n| n == name).ok_or_else(|| {
        let near = t
            .names
            .iter()
            .filter(|n| n.ends_with(name) || name.ends_with(n.as_str()))
            .take(5)
            .cloned()
            .collect();
        CliError::NoColumn {
            name: name.to_owned(),
            near,
        }
    })
}

/// Thins a series to at most `max` points: per bucket of consecutive points the first,
/// the smallest, the largest and the last y (in their original order).
pub fn thin(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 8 {
        return points.to_vec();
    }
    let buckets = max / 4;
    let per = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(max);
    for chunk in points.chunks(per) {
        let (mut lo, mut hi) = (0, 0);
        for (k, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = k;
            }
            if p.1 > chunk[hi].1 {
                hi = k;
            }
        }
        let mut keep = [0, lo, hi, chunk.len() - 1];
        keep.sort_unstable();
        let mut last = usize::MAX;
        for k in keep {
            if k != last {
                out.push(chunk[k]);
                last = k;
            }
        }
    }
    out
}

pub fn plot(a: &PlotArgs) -> i32 {
    match run(a) {
        Ok(n) => {
            eprintln!("wrote {} ({n} lines)", a.output.display());
            EXIT_OK
        }
        Err(e) => e.report(),
    }
}

fn run(a: &PlotArgs) -> Result<usize, CliError> {
    if !a.range.is_empty() && a.range.len() != 2 {
        return Err(CliError::PlotRange {});
    }
    if a.size.len() != 2 || a.size.contains(&0) {
        return Err(CliError::PlotSize {});
    }
    let t = read_csv(&a.csv).map_err(|why| CliError::ResultTable { why })?;
    if t.rows.is_empty() {
        return Err(CliError::NoRowsToPlot {
            path: a.csv.clone(),
        });
    }
    let xc = column(&t, &a.x)?;
    let ycols: Vec<usize> = if a.vars.is_empty() {
        (0..t.names.len()).filter(|&c| c != xc).collect()
    } else {
        a.vars
            .iter()
            .map(|v| column(&t, v))
            .collect::<Result<_, _>>()?
    };
    if ycols.is_empty() {
        return Err(CliError::NothingToPlot {});
    }
    let rc = match &a.range_of {
        Some(n) => column(&t, n)?,
        None => xc,
    };
    let in_range = |x: f64| a.range.len() != 2 || (x >= a.range[0] && x <= a.range[1]);
    let series: Vec<(String, Vec<(f64, f64)>)> = ycols
        .iter()
        .map(|&c| {
            let pts: Vec<(f64, f64)> = t
                .rows
                .iter()
                .filter(|r| in_range(r[rc]))
                .map(|r| (r[xc], r[c]))
                .filter(|&(x, y)| x.is_finite() && y.is_finite() && (!a.log_y || y > 0.0))
                .collect();
            (t.names[c].clone(), thin(&pts, a.max_points))
        })
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (_, pts) in &series {
        for &(x, y) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if !x0.is_finite() || !y0.is_finite() {
        return Err(CliError::NoFinitePoints {});
    }
    let pad = |lo: f64, hi: f64| {
        let d = (hi - lo).abs().max(1e-12 * lo.abs().max(1.0));
        (lo - 0.03 * d, hi + 0.03 * d)
    };
    let (x0, x1) = pad(x0, x1);
    let title = a.title.clone().unwrap_or_else(|| {
        a.csv
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    let ylabel = a.ylabel.clone().unwrap_or_else(|| {
        if series.len() == 1 {
            series[0].0.clone()
        } else {
            String::new()
        }
    });
    let size = (
        a.size.first().copied().unwrap_or(900),
        a.size.get(1).copied().unwrap_or(560),
    );
    draw(
        &a.output,
        size,
        &title,
        &a.x,
        &ylabel,
        (x0, x1),
        (y0, y1),
        a.log_y,
        &series,
    )
    .map_err(|e| CliError::CannotWrite {
        what: a.output.display().to_string(),
        reason: e.to_string(),
    })?;
    Ok(series.len())
}

#[allow(clippy::too_many_arguments)]
fn draw(
    path: &Path,
    size: (u32, u32),
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xr: (f64, f64),
    yr: (f64, f64),
    log_y: bool,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let mut builder = ChartBuilder::on(&root);
    builder
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70);
    macro_rules! finish {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(xlabel)
                .y_desc(ylabel)
                .draw()?;
            for (k, (label, pts)) in series.iter().enumerate() {
                let color = Palette99::pick(k).to_rgba();
                chart
                    .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?
                    .label(label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                    });
            }
            if series.len() > 1 {
                chart
                    .configure_series_labels()
                    .border_style(BLACK)
                    .background_style(WHITE.mix(0.9))
                    .draw()?;
            }
        }};
    }
    if log_y {
        let (lo, hi) = (yr.0 * 0.8, yr.1 * 1.25);
        finish!(builder.build_cartesian_2d(xr.0..xr.1, (lo..hi).log_scale())?);
    } else {
        let d = (yr.1 - yr.0).abs().max(1e-12 * yr.0.abs().max(1.0));
        finish!(builder.build_cartesian_2d(xr.0..xr.1, (yr.0 - 0.05 * d)..(yr.1 + 0.05 * d))?);
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::thin;

    #[test]
    fn thinning_keeps_extremes_and_ends() {
        let pts: Vec<(f64, f64)> = (0..10_000)
            .map(|k| (k as f64, if k == 5_003 { 9.0 } else { (k % 7) as f64 }))
            .collect();
        let t = thin(&pts, 400);
        assert!(t.len() <= 400, "{}", t.len());
        assert_eq!(t.first(), pts.first());
        assert_eq!(t.last(), pts.last());
        assert!(t.contains(&(5_003.0, 9.0)));
        assert!(t.windows(2).all(|w| w[0].0 < w[1].0));
    }
}
