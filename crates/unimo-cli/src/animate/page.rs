//! The self-contained HTML page: the scene as JSON (bodies, frames), three.js
//! (vendored from npm, `assets/three`) and the viewer script, all inlined.

use super::spec::{Body, Rotation, Series};
use super::table::ResultTable;
use std::fmt::Write;

/// three.js r170, the minified ES module build (MIT, `assets/three/LICENSE`).
const THREE: &str = include_str!("../../assets/three/three.module.min.js");
const THREE_VERSION: &str = include_str!("../../assets/three/VERSION");
const VIEWER: &str = include_str!("viewer.js");
const TEMPLATE: &str = include_str!("page.html");

/// The frames to draw: indices of rows of `table`, clock values non-decreasing.
pub struct Frames {
    pub rows: Vec<usize>,
    pub times: Vec<f64>,
}

/// Picks at most `max` rows: every row when there are few (of rows with the same clock
/// value the last, the right limit at an event), else the last row at or before each
/// of `max` evenly spaced times. Err: the clock goes backwards or is not finite.
pub fn frames(table: &ResultTable, clock: usize, max: usize) -> Result<Frames, String> {
    let t: Vec<f64> = table.rows.iter().map(|r| r[clock]).collect();
    if let Some(k) = t.iter().position(|x| !x.is_finite()) {
        return Err(format!("row {} of the clock is not finite", k + 1));
    }
    if let Some(k) = t.windows(2).position(|w| w[1] < w[0]) {
        return Err(format!(
            "the clock goes backwards at row {} ({} after {})",
            k + 2,
            t[k + 1],
            t[k]
        ));
    }
    let mut rows: Vec<usize> = (0..t.len())
        .filter(|&k| k + 1 == t.len() || t[k + 1] > t[k])
        .collect();
    let max = max.max(2);
    if rows.len() > max {
        let (t0, t1) = (t[0], t[t.len() - 1]);
        rows = (0..max)
            .map(|i| {
                let at = t0 + (t1 - t0) * i as f64 / (max - 1) as f64;
                // the last row whose clock is <= at
                t.partition_point(|&x| x <= at).saturating_sub(1)
            })
            .collect();
        rows.dedup();
    }
    let times = rows.iter().map(|&k| t[k]).collect();
    Ok(Frames { rows, times })
}

/// What the page shows besides the bodies.
pub struct PageOptions<'a> {
    pub title: &'a str,
    pub clock: &'a str,
    /// The world axis drawn up (0 x, 1 y, 2 z).
    pub up: usize,
}

/// The page's HTML.
pub fn html(bodies: &[Body], table: &ResultTable, frames: &Frames, o: &PageOptions<'_>) -> String {
    let mut data = String::with_capacity(64 + frames.rows.len() * bodies.len() * 100);
    data.push_str("{\"title\":");
    json_string(&mut data, o.title);
    data.push_str(",\"clock\":");
    json_string(&mut data, o.clock);
    let _ = write!(data, ",\"up\":{},\"times\":", o.up);
    exact_numbers(&mut data, &frames.times);
    data.push_str(",\"bodies\":[");
    for (k, b) in bodies.iter().enumerate() {
        if k > 0 {
            data.push(',');
        }
        body_json(&mut data, b, table, frames);
    }
    data.push_str("]}");
    let three = module_as_object(THREE);
    TEMPLATE
        .replace("{{TITLE}}", &html_text(o.title))
        .replace("{{THREE_VERSION}}", THREE_VERSION.trim())
        .replace("{{DATA}}", &data)
        .replace("{{THREE}}", &three)
        .replace("{{VIEWER}}", VIEWER)
}

fn body_json(out: &mut String, b: &Body, table: &ResultTable, frames: &Frames) {
    out.push_str("{\"name\":");
    json_string(out, &b.name);
    out.push_str(",\"class\":");
    json_string(out, &b.class);
    let _ = write!(out, ",\"shape\":\"{}\",\"size\":", b.shape.name());
    numbers(out, b.size.iter().copied());
    out.push_str(",\"normal\":");
    numbers(out, b.normal.iter().copied());
    if let Some(c) = &b.color {
        out.push_str(",\"color\":");
        json_string(out, c);
    }
    let rotation: &[Series] = match &b.rotation {
        Rotation::Identity => &[],
        Rotation::Matrix(s) | Rotation::Quaternion(s) => s,
    };
    // A body whose columns keep their first value (a fixed obstacle) gets one frame.
    let varies = |s: &Series| match *s {
        Series::Column(c) => {
            let first = table.rows[frames.rows[0]][c];
            frames.rows.iter().any(|&r| table.rows[r][c] != first)
        }
        Series::Constant(_) => false,
    };
    let moving = b.position.iter().chain(rotation).any(varies);
    let rows: &[usize] = if moving {
        &frames.rows
    } else {
        &frames.rows[..1]
    };
    let value = |s: &Series, row: usize| match *s {
        Series::Column(c) => table.rows[row][c],
        Series::Constant(x) => x,
    };
    out.push_str(",\"p\":");
    numbers(
        out,
        rows.iter()
            .flat_map(|&r| b.position.iter().map(move |s| value(s, r))),
    );
    out.push_str(",\"q\":");
    let quaternions = rows.iter().flat_map(|&r| {
        let q = match &b.rotation {
            Rotation::Identity => [1.0, 0.0, 0.0, 0.0],
            Rotation::Matrix(m) => {
                let m: Vec<f64> = m.iter().map(|s| value(s, r)).collect();
                matrix_to_quaternion(&m)
            }
            Rotation::Quaternion(q) => normalized([
                value(&q[0], r),
                value(&q[1], r),
                value(&q[2], r),
                value(&q[3], r),
            ]),
        };
        // three.js order: x, y, z, w
        [q[1], q[2], q[3], q[0]]
    });
    numbers(out, quaternions);
    out.push('}');
}

/// The unit quaternion (w, x, y, z) of a rotation matrix (row-major), by the largest
/// of the four squared components (stable for every rotation).
pub fn matrix_to_quaternion(m: &[f64]) -> [f64; 4] {
    let at = |i: usize, j: usize| m[3 * i + j];
    let trace = at(0, 0) + at(1, 1) + at(2, 2);
    let q = if trace > at(0, 0).max(at(1, 1)).max(at(2, 2)) {
        let s = (1.0 + trace).sqrt() * 2.0;
        [
            s / 4.0,
            (at(2, 1) - at(1, 2)) / s,
            (at(0, 2) - at(2, 0)) / s,
            (at(1, 0) - at(0, 1)) / s,
        ]
    } else if at(0, 0) >= at(1, 1) && at(0, 0) >= at(2, 2) {
        let s = (1.0 + at(0, 0) - at(1, 1) - at(2, 2)).max(0.0).sqrt() * 2.0;
        [
            (at(2, 1) - at(1, 2)) / s,
            s / 4.0,
            (at(0, 1) + at(1, 0)) / s,
            (at(0, 2) + at(2, 0)) / s,
        ]
    } else if at(1, 1) >= at(2, 2) {
        let s = (1.0 - at(0, 0) + at(1, 1) - at(2, 2)).max(0.0).sqrt() * 2.0;
        [
            (at(0, 2) - at(2, 0)) / s,
            (at(0, 1) + at(1, 0)) / s,
            s / 4.0,
            (at(1, 2) + at(2, 1)) / s,
        ]
    } else {
        let s = (1.0 - at(0, 0) - at(1, 1) + at(2, 2)).max(0.0).sqrt() * 2.0;
        [
            (at(1, 0) - at(0, 1)) / s,
            (at(0, 2) + at(2, 0)) / s,
            (at(1, 2) + at(2, 1)) / s,
            s / 4.0,
        ]
    };
    normalized(q)
}

fn normalized(q: [f64; 4]) -> [f64; 4] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 && n.is_finite() {
        q.map(|x| x / n)
    } else {
        [1.0, 0.0, 0.0, 0.0]
    }
}

/// A JSON array of numbers written exactly (shortest text that reads back the same).
fn exact_numbers(out: &mut String, xs: &[f64]) {
    out.push('[');
    for (k, x) in xs.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        let _ = write!(out, "{}", x + 0.0);
    }
    out.push(']');
}

/// A JSON array of numbers (single precision: 7 significant digits; a non-finite value
/// is `null`).
fn numbers(out: &mut String, xs: impl Iterator<Item = f64>) {
    out.push('[');
    for (k, x) in xs.enumerate() {
        if k > 0 {
            out.push(',');
        }
        if x.is_finite() {
            let _ = write!(out, "{}", (x + 0.0) as f32);
        } else {
            out.push_str("null");
        }
    }
    out.push(']');
}

/// A JSON string safe inside a `<script>` element (`<` escaped).
fn json_string(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '<' => out.push_str("\\u003c"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn html_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The ES module wrapped in a function that returns its exports: its final
/// `export{a as B,...};` becomes `return{B:a,...};`, and the page gets
/// `const THREE=(function(){...})();` inline, with the viewer after it.
fn module_as_object(module: &str) -> String {
    let Some(start) = module.rfind("export{") else {
        return format!("{module}\nconst THREE=null;");
    };
    let Some(len) = module[start..].find('}') else {
        return format!("{module}\nconst THREE=null;");
    };
    let list = &module[start + "export{".len()..start + len];
    let entries: Vec<String> = list
        .split(',')
        .map(|item| match item.split_once(" as ") {
            Some((local, exported)) => format!("{}:{}", exported.trim(), local.trim()),
            None => item.trim().to_owned(),
        })
        .collect();
    let rest = module[start + len + 1..].trim_start_matches(';');
    // In a function of its own, so that its top-level names stay out of the viewer's.
    format!(
        "const THREE=(function(){{{}return{{{}}};{}}})();",
        &module[..start],
        entries.join(","),
        rest
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_vendored_module_becomes_an_object() {
        let three = module_as_object(THREE);
        assert!(!three.contains("export{"));
        assert!(three.contains("WebGLRenderer:"));
        assert!(three.starts_with("const THREE=(function(){"));
        assert!(!three.contains("</script"));
        assert_eq!(
            module_as_object("const a=1;export{a as A,b};"),
            "const THREE=(function(){const a=1;return{A:a,b};})();"
        );
    }

    #[test]
    fn quaternions_of_rotations() {
        let close = |a: [f64; 4], b: [f64; 4]| {
            let same = a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12);
            let opposite = a.iter().zip(&b).all(|(x, y)| (x + y).abs() < 1e-12);
            assert!(same || opposite, "{a:?} vs {b:?}");
        };
        close(
            matrix_to_quaternion(&[1., 0., 0., 0., 1., 0., 0., 0., 1.]),
            [1., 0., 0., 0.],
        );
        // 90 degrees about z: x -> y
        let h = 0.5f64.sqrt();
        close(
            matrix_to_quaternion(&[0., -1., 0., 1., 0., 0., 0., 0., 1.]),
            [h, 0., 0., h],
        );
        // 180 degrees about x
        close(
            matrix_to_quaternion(&[1., 0., 0., 0., -1., 0., 0., 0., -1.]),
            [0., 1., 0., 0.],
        );
        // 180 degrees about y and about z
        close(
            matrix_to_quaternion(&[-1., 0., 0., 0., 1., 0., 0., 0., -1.]),
            [0., 0., 1., 0.],
        );
        close(
            matrix_to_quaternion(&[-1., 0., 0., 0., -1., 0., 0., 0., 1.]),
            [0., 0., 0., 1.],
        );
    }

    #[test]
    fn frames_keep_right_limits_and_thin_evenly() {
        let rows = [0.0, 0.5, 0.5, 1.0, 2.0].iter().map(|&t| vec![t]).collect();
        let table = ResultTable::new(vec!["time".into()], rows);
        let f = frames(&table, 0, 100).unwrap();
        assert_eq!(f.rows, [0, 2, 3, 4]);
        let f = frames(&table, 0, 3).unwrap();
        assert_eq!(f.times, [0.0, 1.0, 2.0]);
        let back = ResultTable::new(vec!["t".into()], vec![vec![1.0], vec![0.0]]);
        assert!(frames(&back, 0, 10).is_err());
    }
}
