//! `ellipsoid-reference`: runs one of paper A's examples with the event-driven reference
//! and prints a summary; `--events FILE` writes every event as `t,kind`.
//!
//! Usage: `ellipsoid-reference [--scene fly-slide-roll|slide-roll-switch|markeev]
//! [--rtol 1e-12] [--t-stop T] [--events FILE] [--clearance-tolerance X]
//! [--perturb INDEX:EPS]`
//!
//! `--perturb 1:1e-12` also runs the scene from the initial state with component INDEX
//! (0..13: r, v, q, body omega) moved by EPS, with the same settings, and prints how far
//! the two event sequences move apart (the divergence a claim of chaos must measure).

use std::io::Write;
use std::process::ExitCode;

use unimo_reference::events::{simulate, EventKind, RunOptions};
use unimo_reference::scenes::by_name;
use unimo_reference::Phase;

struct Args {
    scene: String,
    rtol: f64,
    t_stop: Option<f64>,
    events: Option<String>,
    clearance_tolerance: Option<f64>,
    perturb: Option<(usize, f64)>,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        scene: "fly-slide-roll".into(),
        rtol: 1e-12,
        t_stop: None,
        events: None,
        clearance_tolerance: None,
        perturb: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        let number = |s: String| s.parse::<f64>().map_err(|e| format!("{s}: {e}"));
        match flag.as_str() {
            "--scene" => args.scene = value()?,
            "--rtol" => args.rtol = number(value()?)?,
            "--t-stop" => args.t_stop = Some(number(value()?)?),
            "--events" => args.events = Some(value()?),
            "--clearance-tolerance" => args.clearance_tolerance = Some(number(value()?)?),
            "--perturb" => {
                let text = value()?;
                let (index, eps) = text.split_once(':').ok_or("--perturb INDEX:EPS")?;
                let index = index
                    .parse::<usize>()
                    .map_err(|e| format!("{index}: {e}"))?;
                if index >= 13 {
                    return Err(format!("--perturb index {index} is not below 13"));
                }
                args.perturb = Some((index, number(eps.to_owned())?));
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(args)
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let mut example = by_name(&args.scene).ok_or(format!("unknown scene {}", args.scene))?;
    if let Some(c) = args.clearance_tolerance {
        example.scene.clearance_tolerance = c;
    }
    let options = RunOptions {
        rtol: args.rtol,
        atol: args.rtol / 100.0,
        t_stop: args.t_stop.unwrap_or(example.t_stop),
        max_events: 1_000_000,
    };
    let started = std::time::Instant::now();
    let run =
        simulate(&example.scene, &example.initial_state, &options).map_err(|e| e.to_string())?;
    let elapsed = started.elapsed().as_secs_f64();
    if let Some(path) = &args.events {
        let mut out = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
        let mut text = String::from("t,kind\n");
        for e in &run.events {
            text += &format!("{:.17e},{}\n", e.t, e.kind.name());
        }
        out.write_all(text.as_bytes())
            .map_err(|e| format!("{path}: {e}"))?;
    }
    let count = |k: EventKind| run.count(|x| x == k);
    println!(
        "scene: {} rtol {:e} t_stop {}",
        example.name, args.rtol, options.t_stop
    );
    println!("events: {}", run.events.len());
    println!("impacts: {}", count(EventKind::Impact));
    println!(
        "landings: {} (sliding {}, rolling {})",
        run.count(|k| matches!(k, EventKind::Landing(_))),
        count(EventKind::Landing(Phase::Sliding)),
        count(EventKind::Landing(Phase::Rolling))
    );
    println!("lift-offs: {}", count(EventKind::LiftOff));
    println!("slide-to-roll: {}", count(EventKind::SlideToRoll));
    println!("roll-to-slide: {}", count(EventKind::RollToSlide));
    match run.first_rolling() {
        Some(t) => println!("first rolling: {t:.12}"),
        None => println!("first rolling: none"),
    }
    println!(
        "final time: {:.12}, final state: {:?}",
        run.final_time, run.final_phase
    );
    println!("energy: {:.14e}", run.energy);
    println!("centre height: {:.14e}", run.final_state[1]);
    println!("max |gap| at contact events: {:.2e}", run.max_contact_gap);
    println!(
        "steps: {}, rhs evals: {}, wall: {elapsed:.3} s",
        run.steps, run.rhs_evals
    );
    if let Some((index, eps)) = args.perturb {
        let mut x0 = example.initial_state;
        x0[index] += eps;
        let other = simulate(&example.scene, &x0, &options).map_err(|e| e.to_string())?;
        divergence(&run, &other, index, eps);
    }
    Ok(())
}

/// Prints how two runs' event sequences part: the first event of another kind, and the
/// largest time difference per block of 200 events before it.
fn divergence(base: &unimo_reference::Run, other: &unimo_reference::Run, index: usize, eps: f64) {
    println!(
        "perturbed x0[{index}] by {eps:e}: {} events",
        other.events.len()
    );
    let part = base
        .events
        .iter()
        .zip(&other.events)
        .position(|(a, b)| a.kind != b.kind);
    let agree = part.unwrap_or(base.events.len().min(other.events.len()));
    println!("same kinds through event {agree}");
    for start in (0..agree).step_by(200) {
        let end = (start + 200).min(agree);
        let worst = (start..end)
            .map(|k| (base.events[k].t - other.events[k].t).abs())
            .fold(0.0f64, f64::max);
        println!(
            "  events {start}..{end} (t {:.2}..{:.2}): largest |dt| {worst:.2e}",
            base.events[start].t,
            base.events[end - 1].t
        );
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
