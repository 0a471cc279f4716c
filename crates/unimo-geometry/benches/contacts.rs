//! The narrowphase of sphere scenes: the closed forms of sphere–sphere and
//! sphere–plane contacts and sweeps against parry's general queries for the same pairs
//! (`contacts` vs `contacts_general`, `time_of_impact` vs `time_of_impact_general`).

use unimo_geometry::query::{contacts_general, time_of_impact_general};
use unimo_geometry::{
    contacts, time_of_impact, ContactQuery, Moving, Placement, Scratch, Shape, ShapeKind,
};

fn main() {
    divan::main();
}

/// A ball of radius 0.0286 (a billiard ball) against another ball or the table.
fn pair(plane: bool) -> (Shape, Placement, Shape, Placement) {
    let ball = Shape::new(ShapeKind::Sphere { radius: 0.0286 }).unwrap();
    if plane {
        let table = Shape::new(ShapeKind::HalfSpace).unwrap();
        (
            ball,
            Placement::at([0.1, 0.2, 0.0285]),
            table,
            Placement::IDENTITY,
        )
    } else {
        let other = Shape::new(ShapeKind::Sphere { radius: 0.0286 }).unwrap();
        (
            ball,
            Placement::at([0.0, 0.0, 0.0]),
            other,
            Placement::at([0.0571, 0.001, 0.0]),
        )
    }
}

/// `contacts` or `contacts_general`.
type ContactsFn = fn(
    ContactQuery<'_>,
    &mut Scratch,
    &mut Vec<unimo_geometry::ContactPoint>,
) -> Result<usize, unimo_geometry::Unsupported>;

/// `time_of_impact` or `time_of_impact_general`.
type SweepQuery = fn(Moving<'_>, Moving<'_>, f64) -> Option<f64>;

fn contact(b: divan::Bencher, case: &str, query: ContactsFn) {
    let (sa, pa, sb, pb) = pair(case == "sphere-plane");
    let (mut scratch, mut out) = (Scratch::default(), Vec::new());
    b.bench_local(|| {
        out.clear();
        let pair = ContactQuery {
            a: &sa,
            pa: divan::black_box(&pa),
            b: &sb,
            pb: &pb,
            prediction: 1e-3,
        };
        query(pair, &mut scratch, &mut out)
    });
}

fn sweep(b: divan::Bencher, case: &str, query: SweepQuery) {
    let (sa, pa, sb, pb) = pair(case == "sphere-plane");
    let v = [0.0, 0.0, -1.0];
    b.bench_local(|| {
        let mover = Moving {
            shape: &sa,
            placement: divan::black_box(&pa),
            velocity: v,
        };
        let target = Moving {
            shape: &sb,
            placement: &pb,
            velocity: [0.0; 3],
        };
        query(mover, target, 1.0)
    });
}

#[divan::bench(args = ["sphere-sphere", "sphere-plane"])]
fn contact_closed_form(b: divan::Bencher, case: &str) {
    contact(b, case, contacts);
}

#[divan::bench(args = ["sphere-sphere", "sphere-plane"])]
fn contact_general(b: divan::Bencher, case: &str) {
    contact(b, case, contacts_general);
}

#[divan::bench(args = ["sphere-sphere", "sphere-plane"])]
fn sweep_closed_form(b: divan::Bencher, case: &str) {
    sweep(b, case, time_of_impact);
}

#[divan::bench(args = ["sphere-sphere", "sphere-plane"])]
fn sweep_general(b: divan::Bencher, case: &str) {
    sweep(b, case, time_of_impact_general);
}
