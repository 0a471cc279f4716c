//! Parameter folding (issue: leave out what a scene does not need): parameters known at
//! compile time become constants, what they switch off disappears (terms multiplied by
//! zero, branches that cannot be taken, relations that cannot change), and the results
//! stay those of the unfolded model to round-off.

mod common;

use unimo_cli::LoadedModel;
use unimo_dae::FoldOptions;
use unimo_runtime::sim::{simulate, SimResult};
use unimo_solve::Method;

fn load(file: &str, model: &str, fold: &FoldOptions) -> LoadedModel {
    let mut files = vec![common::root().join(file)];
    if file.ends_with("ThreeBalls.mo") {
        files.push(common::root().join("models/ThreeBallsOnTable.mo"));
    }
    unimo_cli::load_model_with(&files, Some(model), fold)
        .unwrap_or_else(|e| panic!("{file} {model}:\n{e}"))
}

fn tunable_all() -> FoldOptions {
    FoldOptions {
        tunable_all: true,
        ..FoldOptions::default()
    }
}

fn run(m: &LoadedModel, stop: f64) -> SimResult {
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, stop, stop / 200.0);
    let r = simulate(&m.compiled, &o);
    assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
    r
}

/// (plan operations, zero crossings, folded parameters)
/// Models `smooth` and `rough` of `file` folded: `smooth` has fewer operations and fewer
/// root functions. Returns it with its operation count.
fn cheaper_than(file: &str, smooth: &str, rough: &str) -> (LoadedModel, usize) {
    let smooth = load(file, smooth, &FoldOptions::default());
    let rough = load(file, rough, &FoldOptions::default());
    let (ops_s, roots_s, _) = cost(&smooth);
    let (ops_r, roots_r, _) = cost(&rough);
    assert!(ops_s < ops_r, "{ops_s} >= {ops_r}");
    assert!(roots_s < roots_r, "{roots_s} >= {roots_r}");
    (smooth, ops_s)
}

/// The names of the parameters folded into constants.
fn folded(m: &LoadedModel) -> Vec<&str> {
    (m.dae.folded_parameters.iter())
        .map(|&s| m.dae.scalar(s).name.as_str())
        .collect()
}

fn cost(m: &LoadedModel) -> (usize, usize, usize) {
    (
        m.compiled.plan_ops(),
        m.compiled.roots.len(),
        m.dae.folded_parameters.len(),
    )
}

/// The largest difference of the states of `m` between two results at the output
/// times both have (an event adds rows at its instant: the last row of each time is
/// compared), relative to each state's largest magnitude (at least 1), and the state.
fn largest_difference(m: &LoadedModel, a: &SimResult, b: &SimResult) -> (f64, String) {
    let last_rows = |r: &SimResult| -> std::collections::BTreeMap<u64, Vec<f64>> {
        r.times
            .iter()
            .zip(&r.rows)
            .map(|(t, row)| (t.to_bits(), row.clone()))
            .collect()
    };
    let (ra, rb) = (last_rows(a), last_rows(b));
    let times: Vec<u64> = ra.keys().filter(|t| rb.contains_key(t)).copied().collect();
    assert!(times.len() > 100, "{} common output times", times.len());
    let mut worst = (0.0, String::new());
    for &s in &m.analysis.plan.states {
        let name = &m.dae.scalar(s).name;
        let col = |r: &SimResult| r.names.iter().position(|n| n == name).unwrap();
        let (ja, jb) = (col(a), col(b));
        let scale = times.iter().map(|t| rb[t][jb].abs()).fold(1.0, f64::max);
        let d = times
            .iter()
            .map(|t| (ra[t][ja] - rb[t][jb]).abs() / scale)
            .fold(0.0, f64::max);
        if d > worst.0 {
            worst = (d, name.clone());
        }
    }
    worst
}

#[test]
fn known_parameters_remove_terms_branches_and_relations() {
    let file = "tests/fold/Folding.mo";
    let folded = load(file, "Folding.Switches", &FoldOptions::default());
    let kept = load(file, "Folding.Switches", &tunable_all());
    let (ops_f, roots_f, n_f) = cost(&folded);
    let (ops_k, roots_k, n_k) = cost(&kept);
    assert_eq!(n_f, 5, "every parameter folded");
    assert_eq!(n_k, 0);
    // mu = 0: `mu > 0 and abs(v) > 1e-3` is false for good, so no zero crossing is left;
    // kept tunable, abs(v) > 1e-3 is watched.
    assert_eq!(roots_f, 0);
    assert_eq!(roots_k, 1);
    assert!(ops_f < ops_k, "{ops_f} >= {ops_k}");
    // Both follow x'' = -x (x = cos t): the kept model stops at an event where
    // abs(v) crosses 1e-3 (mu > 0 is false, so nothing changes there) and restarts
    // its integrator, so the two differ at the tolerance, not at round-off.
    let (rf, rk) = (run(&folded, 5.0), run(&kept, 5.0));
    assert_eq!((rf.stats.events, rk.stats.events), (0, 1));
    for r in [&rf, &rk] {
        let x = r.names.iter().position(|n| n == "x").unwrap();
        let err = r
            .times
            .iter()
            .zip(&r.rows)
            .map(|(t, row)| (row[x] - t.cos()).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-6, "{err:e}");
    }
}

#[test]
fn tunable_parameters_and_their_followers_stay_parameters() {
    let file = "tests/fold/Folding.mo";
    let fold = FoldOptions {
        tunable: vec!["mu".into()],
        ..FoldOptions::default()
    };
    let m = load(file, "Folding.Switches", &fold);
    assert_eq!(folded(&m), ["useSpring", "limit", "c", "g"]);
    assert_eq!(m.compiled.roots.len(), 1, "mu tunable: abs(v) > 1e-3 stays");
    // fixed = false parameters and those bound to them are computed at initialization.
    let m = load(file, "Folding.Initial", &FoldOptions::default());
    assert_eq!(folded(&m), ["k"]);
    let r = run(&m, 1.0);
    let x = r.names.iter().position(|n| n == "x").unwrap();
    let last = r.rows.last().unwrap();
    // a = k + 1 = 4, b = 8: x = exp(-8 t)
    assert!((last[x] - (-8.0f64).exp()).abs() < 1e-6, "{}", last[x]);
}

#[test]
fn a_frictionless_ellipsoid_costs_less_than_one_with_friction() {
    let file = "tests/paper_a/Extremes.mo";
    let (smooth, ops_s) = cheaper_than(file, "Extremes.Frictionless", "Extremes.Base");
    // The same results as the unfolded model: 3 units of the regularising time hold the
    // first flight, bounces and impacts.
    let kept = load(file, "Extremes.Frictionless", &tunable_all());
    assert!(cost(&kept).0 > ops_s);
    let (d, col) = largest_difference(&smooth, &run(&smooth, 3.0), &run(&kept, 3.0));
    assert!(d <= 1e-12, "{col}: {d:e}");
}

#[test]
fn frictionless_balls_cost_less_than_balls_with_friction() {
    let file = "tests/fold/ThreeBalls.mo";
    let (smooth, _) = cheaper_than(file, "ThreeBalls.Frictionless", "ThreeBalls.WithFriction");
    // To the first impacts of ball 1 on the table (t = 0.1 and 0.27 of the regularising
    // time). Later the two differ at the tolerance: the relative normal acceleration of
    // balls 2 and 3, at rest apart on the table, is round-off (|relan| ~ 1e-39), and its
    // sign makes `Launching` (relan < 0) and the events it watches differ.
    let kept = load(file, "ThreeBalls.Frictionless", &tunable_all());
    let (d, col) = largest_difference(&smooth, &run(&smooth, 0.26), &run(&kept, 0.26));
    assert!(d <= 1e-12, "{col}: {d:e}");
}

#[test]
fn the_cost_report_shows_what_friction_costs_and_where() {
    let file = "tests/paper_a/Extremes.mo";
    let smooth = load(file, "Extremes.Frictionless", &FoldOptions::default());
    let rough = load(file, "Extremes.Base", &FoldOptions::default());
    let of = |m: &LoadedModel, name: &str| {
        m.compiled
            .cost_by_component(1)
            .into_iter()
            .find(|c| c.component == name)
            .unwrap_or_else(|| panic!("no component {name}"))
    };
    for m in [&smooth, &rough] {
        let rows = m.compiled.cost_by_component(1);
        let ops: f64 = rows.iter().map(|c| c.ops).sum();
        assert_eq!(ops, m.compiled.plan_ops() as f64);
        let roots: usize = rows.iter().map(|c| c.zero_crossings).sum();
        assert_eq!(roots, m.compiled.roots.len());
        assert_eq!(of(m, "FlySlideRollBody").zero_crossings, 0);
    }
    // The friction's cost is the contact's: its relations and its force terms.
    let (s, r) = (
        of(&smooth, "ConstraintSurfaces"),
        of(&rough, "ConstraintSurfaces"),
    );
    assert_eq!(r.zero_crossings - s.zero_crossings, 2);
    assert!(s.ops < r.ops, "{} >= {}", s.ops, r.ops);
}

/// The cost report's time is measured: every plan step of a run is timed
/// (`Simulator::profile`), and the components' seconds are those times shared out, so
/// they sum to the profile's total, and every component with plan operations got time.
#[test]
fn the_cost_report_shares_out_measured_step_times() {
    let m = load(
        "tests/paper_a/Extremes.mo",
        "Extremes.Base",
        &FoldOptions::default(),
    );
    let sink = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, 0.5, 0.01);
    let r = unimo_runtime::sim::Simulator::new(&m.compiled)
        .profile(sink.clone())
        .run(&o);
    assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
    let steps: Vec<f64> = sink
        .lock()
        .unwrap()
        .iter()
        .map(std::time::Duration::as_secs_f64)
        .collect();
    assert_eq!(steps.len(), m.compiled.steps.len());
    assert!(steps.iter().all(|&s| s > 0.0), "{steps:?}");
    let rows = m.compiled.cost_by_component_timed(1, &steps);
    let (shared, measured): (f64, f64) = (rows.iter().map(|c| c.seconds).sum(), steps.iter().sum());
    assert!(
        (shared - measured).abs() <= 1e-9 * measured,
        "{shared} vs {measured}"
    );
    for c in &rows {
        assert_eq!(c.ops > 0.0, c.seconds > 0.0, "{c:?}");
    }
}
