//! The collision world end to end (paper B's scenes without its limits): no tunnelling
//! at any tolerance, momentum with impulse and penalty impacts, a line contact at rest,
//! exact contact onset, and the refusal of placements the world cannot read.

mod common;

use unimo_runtime::sim::{simulate, SimOptions, SimResult};
use unimo_solve::Method;

use common::load;

fn run(m: &unimo_cli::LoadedModel, method: Method, rtol: f64, stop: f64) -> SimResult {
    let o = SimOptions {
        every_step: true,
        output_rtol: 0.0,
        ..common::sim_options(method, rtol, 0.0, stop, stop / 100.0)
    };
    let r = simulate(&m.compiled, &o);
    assert!(
        r.error.is_none(),
        "{:?}",
        r.error.as_ref().map(|e| e.message())
    );
    r
}

fn col(r: &SimResult, name: &str) -> usize {
    r.names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no {name} in {:?}", r.names))
        + 1
}

fn series(r: &SimResult, name: &str) -> Vec<f64> {
    let k = col(r, name) - 1;
    r.rows.iter().map(|row| row[k]).collect()
}

#[test]
fn a_fast_ball_never_passes_through_a_thin_plate() {
    // 5 cm ball, 100 m/s, 1 cm plate (top at z = 0.005): explicit and implicit
    // methods, tolerances 1e-3 to 1e-9.
    let m = load("tests/collision/Tunnel.mo", None);
    for method in [Method::Dopri5, Method::Radau5, Method::Bdf] {
        for k in 3..=9 {
            let rtol = 10f64.powi(-k);
            let r = run(&m, method, rtol, 0.05);
            let z = series(&r, "ball.r[3]");
            let v = series(&r, "ball.v[3]");
            let zmin = z.iter().cloned().fold(f64::INFINITY, f64::min);
            assert!(
                zmin > 0.005 + 0.01,
                "{method:?} rtol {rtol}: the ball's centre reached z = {zmin}"
            );
            let (zl, vl) = (*z.last().unwrap(), *v.last().unwrap());
            assert!(
                zl > 3.0 && (80.0..100.0).contains(&vl),
                "{method:?} rtol {rtol}: ends at z = {zl}, v = {vl}"
            );
        }
    }
}

#[test]
fn without_the_sweep_the_ball_ghosts_through() {
    // The same scene with the sweep test off: a step from above to below the plate
    // sees no overlap at either end (paper B's "ghosting"), so the test above can fail.
    let m = load("tests/collision/TunnelNoSweep.mo", None);
    let r = run(&m, Method::Dopri5, 1e-3, 0.05);
    let z = series(&r, "ball.r[3]");
    assert!(*z.last().unwrap() < -3.0, "{:?}", z.last());
}

fn momentum_and_energy(r: &SimResult) -> (Vec<[f64; 2]>, Vec<f64>) {
    let (px, py, e) = (series(r, "Px"), series(r, "Py"), series(r, "E"));
    (px.iter().zip(&py).map(|(&x, &y)| [x, y]).collect(), e)
}

#[test]
fn impulse_impacts_conserve_momentum_and_energy_to_round_off() {
    let m = load("models/BilliardsBreakImpulses.mo", None);
    let r = run(&m, Method::Dopri5, 1e-6, 1.0);
    let (p, e) = momentum_and_energy(&r);
    let p0 = (p[0][0].hypot(p[0][1]), e[0]);
    let dp = p
        .iter()
        .map(|q| (q[0] - p[0][0]).hypot(q[1] - p[0][1]) / p0.0)
        .fold(0.0, f64::max);
    let de = e
        .iter()
        .map(|x| (x - p0.1).abs() / p0.1)
        .fold(0.0, f64::max);
    assert!(dp < 1e-13, "momentum error {dp:e}");
    assert!(de < 1e-13, "energy error {de:e} (elastic impulses)");
    // The break happened: the last ball of the rack moves.
    let v = series(&r, "b15.v[1]");
    assert!(*v.last().unwrap() > 0.1, "{:?}", v.last());
}

#[test]
fn penalty_impacts_keep_momentum_and_never_gain_energy() {
    // At rtol 1e-7: at 1e-6 the state interpolated at the first located onset carries
    // an error of 1.7e-5 of the energy (the step's later stages felt the contact force),
    // which shows up as a rise; from 1e-7 on there is none (docs/results/paper-b.md).
    let m = load("models/BilliardsBreakPenalty.mo", None);
    let r = run(&m, Method::Dopri5, 1e-7, 1.0);
    let (p, e) = momentum_and_energy(&r);
    let dp = p
        .iter()
        .map(|q| (q[0] - p[0][0]).hypot(q[1] - p[0][1]) / p[0][0].hypot(p[0][1]))
        .fold(0.0, f64::max);
    // Equal and opposite contact forces: a Runge-Kutta method keeps linear
    // invariants, so momentum drifts only by round-off.
    assert!(dp < 1e-12, "momentum drift {dp:e}");
    // Kinetic energy leaves into the contact springs and comes back: compare it only
    // where no pair is in contact (the separation gap is then its idle value 1).
    let sep = series(&r, "world.gaps[2]");
    let free: Vec<f64> = e
        .iter()
        .zip(&sep)
        .filter(|(_, &g)| g == 1.0)
        .map(|(&x, _)| x)
        .collect();
    assert!(free.len() > 10, "{} contact-free rows", free.len());
    let gain = free
        .windows(2)
        .map(|w| (w[1] - w[0]) / e[0])
        .fold(f64::MIN, f64::max);
    assert!(
        gain < 1e-12,
        "kinetic energy rose by {gain:e} of the initial between contacts"
    );
    assert!(
        *e.last().unwrap() < 0.9 * e[0],
        "restitution 0.95 dissipates"
    );
    let v = series(&r, "b15.v[1]");
    assert!(*v.last().unwrap() > 0.05, "{:?}", v.last());
}

#[test]
fn contact_onset_is_a_located_event() {
    // Dropped from 1 m with radius 0.1: touches at sqrt(2 * 0.9 / 9.81).
    let m = load("models/CollisionBouncingBall.mo", None);
    let r = run(&m, Method::Bdf, 1e-8, 3.0);
    let t_touch = (2.0 * 0.9 / 9.81f64).sqrt();
    let first = r
        .times
        .windows(2)
        .find(|w| w[0] == w[1])
        .map(|w| w[0])
        .expect("an event");
    assert!(
        ((first - t_touch) / t_touch).abs() < 1e-9,
        "onset at {first}, expected {t_touch}"
    );
    let changes = series(&r, "world.contactChanges");
    insta::assert_snapshot!(format!(
        "contact changes: {}\nbounce apexes (z at v = 0 crossings, rounded):\n{}",
        changes.last().unwrap(),
        apexes(&r)
    ));
}

fn apexes(r: &SimResult) -> String {
    let (z, v) = (series(r, "ball.r[3]"), series(r, "ball.v[3]"));
    let mut out = String::new();
    for k in 1..v.len() {
        if v[k - 1] > 0.0 && v[k] <= 0.0 {
            out += &format!("  t = {:.3}: z = {:.4}\n", r.times[k], z[k]);
        }
    }
    out
}

#[test]
fn a_cylinder_lying_on_a_box_stays_at_rest() {
    let m = load("models/CylinderOnBox.mo", None);
    let r = run(&m, Method::Auto, 1e-6, 10.0);
    for k in 1..=3 {
        let w = series(&r, &format!("cylinder.w[{k}]"));
        let wmax = w.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(
            wmax < 1e-8,
            "w[{k}] reached {wmax:e} rad/s: the cylinder rocks"
        );
        let x = series(&r, &format!("cylinder.r[{k}]"));
        let drift = x.iter().fold(0.0f64, |a, y| a.max((y - x[0]).abs()));
        assert!(drift < 1e-8, "r[{k}] drifted by {drift:e} m");
    }
}

#[test]
fn a_placement_computed_by_the_model_is_refused() {
    let m = load("tests/collision/ComputedPlacement.mo", None);
    let o = SimOptions {
        start: 0.0,
        stop: 1.0,
        rtol: 1e-6,
        atol: 1e-6,
        method: Method::Auto,
        interval: 0.1,
        every_step: false,
        output_rtol: 0.0,
    };
    let r = simulate(&m.compiled, &o);
    let e = r.error.expect("refused");
    assert_eq!(e.code(), "E4001");
    assert!(e.message().contains("height"), "{}", e.message());
}

/// A direct `collisionBody` call with a damping-law code that does not exist is a
/// compile error naming the argument, not a silent fallback to another law.
#[test]
fn an_unknown_damping_law_code_is_refused() {
    let e = match unimo_cli::load_model(
        &[common::root().join("tests/collision/UnknownLaw.mo")],
        None,
    ) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert!(e.contains("E3019"), "{e}");
    assert!(e.contains("7 is not a damping law code"), "{e}");
}

/// The library's `CollisionBody` and the compiler agree on `collisionBody`'s arguments:
/// the call passes the parameters of `COLLISION_BODY_PARAMS` in order, each declared
/// with that many scalars; the enumerations list the shape and law codes in order; and
/// a compiled ball's named position, velocity and angular velocity are its states.
#[test]
fn the_library_and_the_runtime_agree_on_collision_arguments() {
    use unimo_dae::collision_args::{LawCode, ShapeCode, COLLISION_BODY_PARAMS};
    let text =
        std::fs::read_to_string(common::root().join("stdlib/Unimo/Collision/package.mo")).unwrap();
    let body =
        &text[text.find("model CollisionBody").unwrap()..text.find("end CollisionBody;").unwrap()];
    let call = &body[body.find("collisionBody(").unwrap() + "collisionBody(".len()..];
    let call = &call[..call.find(");").unwrap()];
    let names: Vec<String> = call
        .split(',')
        .map(|a| {
            let a = a.trim();
            a.strip_prefix("Integer(")
                .and_then(|x| x.strip_suffix(')'))
                .unwrap_or(a)
                .to_string()
        })
        .collect();
    let expected: Vec<&str> = COLLISION_BODY_PARAMS.iter().map(|p| p.0).collect();
    assert_eq!(names, expected);
    // Each argument's declared size: `Real dims[3]`, `Real R[3, 3]`, scalars.
    for (name, size) in COLLISION_BODY_PARAMS {
        let decl = body
            .lines()
            .find(|l| {
                let l = l.trim();
                !l.starts_with("cat(")
                    && (l.contains(&format!(" {name} ")) || l.contains(&format!(" {name}[")))
                    && !l.contains("collisionBody")
            })
            .unwrap_or_else(|| panic!("no declaration of {name}"));
        let declared = match decl.split_once(&format!(" {name}[")) {
            Some((_, dims)) => dims[..dims.find(']').unwrap()]
                .split(',')
                .map(|d| d.trim().parse::<usize>().unwrap())
                .product(),
            None => 1,
        };
        assert_eq!(declared, size, "{name}: {decl}");
    }
    // Enumeration literals in code order.
    let literals = |ty: &str| -> Vec<String> {
        let e = &text[text.find(&format!("type {ty} = enumeration(")).unwrap()..];
        let e = &e[..e.find(");").unwrap()];
        e.lines()
            .skip(1)
            .map(|l| l.trim().split(' ').next().unwrap().to_string())
            .collect()
    };
    let shapes: Vec<String> = ShapeCode::ALL.iter().map(|c| format!("{c:?}")).collect();
    assert_eq!(literals("ShapeType"), shapes);
    let laws: Vec<String> = LawCode::ALL.iter().map(|c| format!("{c:?}")).collect();
    assert_eq!(literals("DampingLaw"), laws);
    for (k, c) in ShapeCode::ALL.iter().enumerate() {
        assert_eq!(*c as usize, k + 1);
    }
    // The compiled ball reads its states through the named arguments.
    let m = load("models/CollisionBouncingBall.mo", None);
    let args = m.dae.collision[0].args;
    let name = |e| {
        m.dae
            .arena
            .vars(e)
            .iter()
            .map(|&s| m.dae.name(s))
            .collect::<Vec<_>>()
    };
    assert_eq!(name(args.position[2]), ["ball.r[3]"]);
    assert_eq!(name(args.velocity[0]), ["ball.v[1]"]);
    assert_eq!(name(args.angular_velocity[1]), ["ball.w[2]"]);
}

#[test]
fn a_disc_resting_face_on_carries_its_weight_with_one_spring() {
    // parry's manifold for two parallel caps has 4 or 8 points, and its normal can come
    // out 8° off the axis, depending on the last digits of the position. The pair's
    // law acts once (K δ = m g, whatever the number of points), along the axis.
    let m = load("tests/collision/DiscOnDisc.mo", None);
    let expected = 0.5 * 9.81 / 1e7;
    for method in [Method::Bdf, Method::Radau5] {
        for rtol in [1e-4, 1e-6, 1e-8] {
            let r = run(&m, method, rtol, 0.2);
            let depth = *series(&r, "depth").last().unwrap();
            assert!(
                ((depth - expected) / expected).abs() < 1e-3,
                "{method:?} rtol {rtol}: depth {depth:e}, K delta = m g gives {expected:e}"
            );
            for x in ["disc.r[1]", "disc.r[2]"] {
                let side = series(&r, x).iter().fold(0.0f64, |a, v| a.max(v.abs()));
                assert!(
                    side < 1e-12,
                    "{method:?} rtol {rtol}: |{x}| reached {side:e}"
                );
            }
            // A crawl (steps of 1e-10 s, as on the spring before) would take millions.
            assert!(
                r.stats.solver.steps < 10_000,
                "{method:?} rtol {rtol}: {} steps for a disc coming to rest",
                r.stats.solver.steps
            );
        }
    }
}
