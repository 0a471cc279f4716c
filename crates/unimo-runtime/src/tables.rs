//! The Modelica Standard Library's tables (`ModelicaStandardTables`: `CombiTable1D*`
//! and `CombiTimeTable`), written again in Rust: interpolation by linear or constant
//! segments, the four extrapolations, time tables with a start time, a shift, jumps at
//! repeated time points and the time events at their points. Objects are built once,
//! after the parameters, from the constructor's arguments (`unimo_dae::external`).
//!
//! Not provided yet (a coded error at initialization, never a silent fallback): the
//! smooth interpolations (Akima, Fritsch-Butland, Steffen, modified Akima) and tables
//! read from files.

use unimo_dae::external::{ExtFn, ObjectKind};

/// `Modelica.Blocks.Types.Smoothness` (ordinals 1..6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Smoothness {
    LinearSegments,
    ConstantSegments,
}

/// `Modelica.Blocks.Types.Extrapolation` (ordinals 1..4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extrapolation {
    HoldLastPoint,
    LastTwoPoints,
    Periodic,
    NoExtrapolation,
}

/// `Modelica.Blocks.Types.TimeEvents` (ordinals 1..3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeEvents {
    Always,
    AtDiscontinuities,
    NoTimeEvents,
}

/// "No further event" (`Modelica.Constants.inf`, as the MSL spells it).
pub const NO_EVENT: f64 = 1e60;

/// A table of functions of one abscissa (the first column).
#[derive(Clone, Debug)]
pub struct Table {
    rows: usize,
    cols: usize,
    /// Row by row.
    data: Vec<f64>,
    /// 0-based table columns of the outputs.
    columns: Vec<usize>,
    smoothness: Smoothness,
    extrapolation: Extrapolation,
}

/// A table object: a 1-D table, or a time table with its start and shift.
#[derive(Clone, Debug)]
pub enum TableObject {
    Table1D(Table),
    Time {
        table: Table,
        start: f64,
        shift: f64,
        events: TimeEvents,
    },
}

/// The constructor's arguments, evaluated.
pub struct TableArgs<'a> {
    pub kind: ObjectKind,
    pub data: &'a [f64],
    pub rows: usize,
    pub cols: usize,
    pub columns: &'a [f64],
    pub smoothness: f64,
    pub extrapolation: f64,
    pub start_time: f64,
    pub shift_time: f64,
    pub time_events: f64,
}

impl TableObject {
    /// Builds a table, checking what the C library checks: sizes, the column indices,
    /// an abscissa that never decreases (strictly increasing for 1-D tables).
    pub fn new(a: &TableArgs<'_>) -> Result<TableObject, String> {
        let smoothness = match a.smoothness as i64 {
            1 => Smoothness::LinearSegments,
            3 => Smoothness::ConstantSegments,
            2 | 4..=6 => {
                return Err(format!(
                    "table smoothness {} is not supported yet (LinearSegments and ConstantSegments are)",
                    smoothness_name(a.smoothness as i64)
                ))
            }
            k => return Err(format!("table smoothness {k} is not a Smoothness")),
        };
        let extrapolation = match a.extrapolation as i64 {
            1 => Extrapolation::HoldLastPoint,
            2 => Extrapolation::LastTwoPoints,
            3 => Extrapolation::Periodic,
            4 => Extrapolation::NoExtrapolation,
            k => return Err(format!("table extrapolation {k} is not an Extrapolation")),
        };
        if a.rows == 0 || a.cols < 2 || a.data.len() != a.rows * a.cols {
            return Err(format!(
                "a table needs an abscissa and at least one value column (got {} x {})",
                a.rows, a.cols
            ));
        }
        let mut columns = Vec::with_capacity(a.columns.len());
        for &c in a.columns {
            let c = c as usize;
            if c < 2 || c > a.cols {
                return Err(format!(
                    "table column {c} does not exist (columns 2..{} hold values)",
                    a.cols
                ));
            }
            columns.push(c - 1);
        }
        let strict = a.kind == ObjectKind::Table1D;
        for i in 1..a.rows {
            let (x0, x1) = (a.data[(i - 1) * a.cols], a.data[i * a.cols]);
            if x1 < x0 || (strict && x1 == x0) || !x1.is_finite() {
                return Err(format!(
                    "the table's first column must be {} (row {} after row {i})",
                    if strict {
                        "strictly increasing"
                    } else {
                        "increasing"
                    },
                    i + 1
                ));
            }
        }
        let table = Table {
            rows: a.rows,
            cols: a.cols,
            data: a.data.to_vec(),
            columns,
            smoothness,
            extrapolation,
        };
        Ok(match a.kind {
            ObjectKind::Table1D => TableObject::Table1D(table),
            ObjectKind::TimeTable => TableObject::Time {
                table,
                start: a.start_time,
                shift: a.shift_time,
                events: match a.time_events as i64 {
                    2 => TimeEvents::AtDiscontinuities,
                    3 => TimeEvents::NoTimeEvents,
                    _ => TimeEvents::Always,
                },
            },
        })
    }

    /// `f(object, a, b)` for the functions of this kind of object (NaN for a function
    /// of another kind, or a column out of range).
    pub fn eval(&self, f: ExtFn, a: f64, b: f64) -> f64 {
        match (self, f) {
            (TableObject::Table1D(t), ExtFn::Table1D) => t.value(a, b, false),
            (TableObject::Table1D(t), ExtFn::Table1DSlope) => t.value(a, b, true),
            (TableObject::Table1D(t), ExtFn::Table1DMin) => t.x(0),
            (TableObject::Table1D(t), ExtFn::Table1DMax) => t.x(t.rows - 1),
            (
                TableObject::Time {
                    table,
                    start,
                    shift,
                    ..
                },
                ExtFn::TimeTable | ExtFn::TimeTableSlope,
            ) => {
                // Before the start time the table gives 0 (the block's output is its
                // offset); after it, time is shifted.
                if b < *start {
                    0.0
                } else {
                    table.value(a, b - shift, f == ExtFn::TimeTableSlope)
                }
            }
            (TableObject::Time { table, shift, .. }, ExtFn::TimeTableMin) => table.x(0) + shift,
            (TableObject::Time { table, shift, .. }, ExtFn::TimeTableMax) => {
                table.x(table.rows - 1) + shift
            }
            (TableObject::Time { .. }, ExtFn::TimeTableNextEvent) => self.next_event(a),
            _ => f64::NAN,
        }
    }

    /// The first time after `t` at which the time table's output has a kink or a jump
    /// (every point with `Always`, only repeated points and the ends with
    /// `AtDiscontinuities`); [`NO_EVENT`] when there is none.
    fn next_event(&self, t: f64) -> f64 {
        let TableObject::Time {
            table,
            start,
            shift,
            events,
        } = self
        else {
            return NO_EVENT;
        };
        if t < *start {
            return *start;
        }
        if *events == TimeEvents::NoTimeEvents {
            return NO_EVENT;
        }
        let constant = table.smoothness == Smoothness::ConstantSegments;
        let n = table.rows;
        let is_event = |i: usize| {
            *events == TimeEvents::Always
                || constant
                || i == 0
                || i == n - 1
                || (i + 1 < n && table.x(i + 1) == table.x(i))
                || (i > 0 && table.x(i - 1) == table.x(i))
        };
        let (x0, xn) = (table.x(0), table.x(n - 1));
        let local = t - shift;
        let (period, base) = if table.extrapolation == Extrapolation::Periodic && xn > x0 {
            let p = xn - x0;
            let k = ((local - x0) / p).floor();
            (p, x0 + k * p)
        } else {
            (0.0, 0.0)
        };
        let offset = if period > 0.0 { base - x0 } else { 0.0 };
        for round in 0..2 {
            let extra = offset + round as f64 * period;
            for i in 0..n {
                let at = table.x(i) + extra;
                if at > local && is_event(i) {
                    return at + shift;
                }
            }
            if period == 0.0 {
                break;
            }
        }
        NO_EVENT
    }
}

fn smoothness_name(k: i64) -> &'static str {
    match k {
        2 => "ContinuousDerivative",
        4 => "MonotoneContinuousDerivative1",
        5 => "MonotoneContinuousDerivative2",
        6 => "ModifiedContinuousDerivative",
        _ => "?",
    }
}

impl Table {
    fn x(&self, i: usize) -> f64 {
        self.data[i * self.cols]
    }

    fn y(&self, i: usize, col: usize) -> f64 {
        self.data[i * self.cols + col]
    }

    /// Output `icol` (1-based, into the selected columns) at `u`, or its slope.
    fn value(&self, icol: f64, u: f64, slope: bool) -> f64 {
        let k = icol as usize;
        if k == 0 || k > self.columns.len() || !u.is_finite() {
            return f64::NAN;
        }
        let col = self.columns[k - 1];
        let n = self.rows;
        if n == 1 {
            return if slope { 0.0 } else { self.y(0, col) };
        }
        let (x0, xn) = (self.x(0), self.x(n - 1));
        let mut u = u;
        if u < x0 || u > xn {
            match self.extrapolation {
                Extrapolation::Periodic => {
                    let p = xn - x0;
                    u = x0 + (u - x0).rem_euclid(p);
                }
                Extrapolation::NoExtrapolation => return f64::NAN,
                Extrapolation::HoldLastPoint => {
                    let i = if u < x0 { 0 } else { n - 1 };
                    return if slope { 0.0 } else { self.y(i, col) };
                }
                Extrapolation::LastTwoPoints => {}
            }
        }
        // The segment [x_i, x_i+1] holding u: the last row with x <= u (right-continuous
        // at a repeated point), clamped to the first and last segments.
        let above = (0..n)
            .collect::<Vec<_>>()
            .partition_point(|&i| self.x(i) <= u);
        let i = above.saturating_sub(1).min(n - 2);
        let (xa, xb) = (self.x(i), self.x(i + 1));
        let (ya, yb) = (self.y(i, col), self.y(i + 1, col));
        match self.smoothness {
            Smoothness::ConstantSegments => {
                if slope {
                    0.0
                } else if u >= xb {
                    yb
                } else {
                    ya
                }
            }
            Smoothness::LinearSegments => {
                if xb == xa {
                    return if slope { 0.0 } else { yb };
                }
                let m = (yb - ya) / (xb - xa);
                if slope {
                    m
                } else {
                    ya + m * (u - xa)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1-D table of two columns (abscissa, values) reading column 2, linear segments,
    /// holding its last point: what a test changes is written over it.
    fn args(data: &[f64]) -> TableArgs<'_> {
        TableArgs {
            kind: ObjectKind::Table1D,
            data,
            rows: data.len() / 2,
            cols: 2,
            columns: &[2.0],
            smoothness: 1.0,
            extrapolation: 1.0,
            start_time: 0.0,
            shift_time: 0.0,
            time_events: 1.0,
        }
    }

    /// A table of `kind` with the MSL's `smoothness` and `extrapolation` codes.
    fn table(kind: ObjectKind, data: &[f64], smoothness: f64, extrapolation: f64) -> TableObject {
        TableObject::new(&TableArgs {
            kind,
            smoothness,
            extrapolation,
            ..args(data)
        })
        .unwrap()
    }

    fn table_1d(data: &[f64], smooth: f64, extra: f64) -> TableObject {
        table(ObjectKind::Table1D, data, smooth, extra)
    }

    fn time_table(data: &[f64], smooth: f64, extra: f64) -> TableObject {
        table(ObjectKind::TimeTable, data, smooth, extra)
    }

    #[test]
    fn linear_segments_interpolate_and_extrapolate() {
        let t = table_1d(&[0.0, 0.0, 1.0, 2.0, 3.0, 2.0], 1.0, 2.0);
        assert_eq!(t.eval(ExtFn::Table1D, 1.0, 0.5), 1.0);
        assert_eq!(t.eval(ExtFn::Table1D, 1.0, 2.0), 2.0);
        assert_eq!(t.eval(ExtFn::Table1DSlope, 1.0, 0.5), 2.0);
        // LastTwoPoints: the last segment continued (slope 0), the first one backwards.
        assert_eq!(t.eval(ExtFn::Table1D, 1.0, 4.0), 2.0);
        assert_eq!(t.eval(ExtFn::Table1D, 1.0, -1.0), -2.0);
        assert_eq!(t.eval(ExtFn::Table1DMin, 0.0, 0.0), 0.0);
        assert_eq!(t.eval(ExtFn::Table1DMax, 0.0, 0.0), 3.0);
        let hold = table_1d(&[0.0, 0.0, 1.0, 2.0], 1.0, 1.0);
        assert_eq!(hold.eval(ExtFn::Table1D, 1.0, 5.0), 2.0);
        assert_eq!(hold.eval(ExtFn::Table1DSlope, 1.0, 5.0), 0.0);
        let periodic = table_1d(&[0.0, 0.0, 1.0, 2.0], 1.0, 3.0);
        assert!((periodic.eval(ExtFn::Table1D, 1.0, 2.25) - 0.5).abs() < 1e-15);
        let none = table_1d(&[0.0, 0.0, 1.0, 2.0], 1.0, 4.0);
        assert!(none.eval(ExtFn::Table1D, 1.0, 1.5).is_nan());
    }

    #[test]
    fn time_tables_jump_at_repeated_points_and_report_their_events() {
        // 0 until t = 1, then a jump to 1, constant to t = 2.
        let t = time_table(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 2.0, 1.0], 1.0, 1.0);
        assert_eq!(t.eval(ExtFn::TimeTable, 1.0, 0.999), 0.0);
        assert_eq!(t.eval(ExtFn::TimeTable, 1.0, 1.0), 1.0);
        assert_eq!(t.eval(ExtFn::TimeTableNextEvent, 0.5, 0.0), 1.0);
        assert_eq!(t.eval(ExtFn::TimeTableNextEvent, 1.0, 0.0), 2.0);
        assert_eq!(t.eval(ExtFn::TimeTableNextEvent, 2.0, 0.0), NO_EVENT);
        let steps = time_table(&[0.0, 1.0, 1.0, 2.0, 2.0, 3.0], 3.0, 1.0);
        assert_eq!(steps.eval(ExtFn::TimeTable, 1.0, 1.5), 2.0);
        assert_eq!(steps.eval(ExtFn::TimeTableSlope, 1.0, 1.5), 0.0);
    }

    #[test]
    fn bad_tables_are_errors() {
        // An abscissa that decreases; a column that is not there; Akima splines.
        let decreasing = args(&[1.0, 0.0, 0.0, 1.0]);
        assert!(TableObject::new(&decreasing).is_err());
        let column_3 = TableArgs {
            columns: &[3.0],
            ..args(&[0.0, 0.0, 1.0, 1.0])
        };
        assert!(TableObject::new(&column_3).is_err());
        let akima = TableObject::new(&TableArgs {
            smoothness: 2.0,
            ..args(&[0.0, 0.0, 1.0, 1.0])
        });
        assert!(akima.unwrap_err().contains("ContinuousDerivative"));
    }
}
