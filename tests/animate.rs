//! `unimo animate` and `simulate --animate`: the page's scene comes from the model's
//! `__unimo_visual` annotations (every shape of the collision library, paper A's
//! ellipsoid and plane, a user's own classes), bad input gets coded errors, and the page
//! runs in headless Chromium: no console error, and the pixels and positions drawn at
//! two times differ where a body moved. Without Chromium the browser tests print a note
//! and pass, except under CI (`CI` set), where they fail unless `.ci/run` could not
//! install it (it then says why in `UNIMO_CHROMIUM_UNAVAILABLE`, and the note prints it).

mod common;

use common::root;
use std::path::{Path, PathBuf};
use std::process::Command;

fn unimo(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(args)
        .current_dir(root())
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("animate");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Simulates `model` to `csv` (extra arguments after), asserting success.
fn simulate(model: &str, csv: &Path, extra: &[&str]) {
    let mut args = vec!["simulate", model, "-o", s(csv)];
    args.extend_from_slice(extra);
    let o = unimo(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Writes the page of `csv`, asserting success; its text.
fn animate(csv: &Path, model: &str, page: &Path, extra: &[&str]) -> String {
    let mut args = vec!["animate", s(csv), "--model", model, "-o", s(page)];
    args.extend_from_slice(extra);
    let o = unimo(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(page).unwrap()
}

/// The scene's JSON data in a page.
fn data(page: &str) -> &str {
    let start = page.find("id=\"unimo-data\">").unwrap() + "id=\"unimo-data\">".len();
    &page[start..start + page[start..].find("</script>").unwrap()]
}

#[test]
fn every_collision_shape_comes_from_the_model() {
    let csv = scratch("tumble.csv");
    simulate("tests/animate/Tumble.mo", &csv, &[]);
    let page = animate(
        &csv,
        "tests/animate/Tumble.mo",
        &scratch("tumble.html"),
        &[],
    );
    let d = data(&page);
    for (name, shape, size) in [
        ("ball.body", "sphere", "[0.1,0,0]"),
        ("box.body", "box", "[0.3,0.15,0.1]"),
        ("egg.body", "ellipsoid", "[0.15,0.1,0.08]"),
        ("floor.body", "plane", "[0,0,0]"),
        ("pillar.body", "cylinder", "[0.05,0.3,0]"),
        ("spike.body", "cone", "[0.08,0.25,0]"),
        ("post.body", "capsule", "[0.05,0.2,0]"),
    ] {
        let entry = format!("\"name\":\"{name}\",\"class\":\"Unimo.Collision.CollisionBody\",\"shape\":\"{shape}\",\"size\":{size}");
        assert!(
            d.contains(&entry),
            "{entry} not in the scene:\n{}",
            &d[..d.len().min(3000)]
        );
    }
    // z is up (the floor's normal); the page is self-contained: no address to fetch
    assert!(d.contains("\"up\":2"));
    assert!(!page.contains("src=\"http") && !page.contains("import "));
    assert!(page.contains("Copyright 2010-2024 Three.js Authors"));
}

#[test]
fn paper_a_draws_the_ellipsoid_and_the_plane_with_its_semi_axes() {
    let csv = scratch("fly.csv");
    let short = ["-p", "tStop=0.3", "-p", "b=0.7"];
    simulate("models/FlySlideRoll.mo", &csv, &short);
    let page = animate(&csv, "models/FlySlideRoll.mo", &scratch("fly.html"), &short);
    let d = data(&page);
    assert!(d.contains("\"name\":\"FlySlideRollBody\",\"class\":\"UnilateralMBS.Bodies.HeavyEllipsoidBody\",\"shape\":\"ellipsoid\",\"size\":[1,0.7,1.2]"), "{}", &d[..d.len().min(2000)]);
    assert!(d.contains("\"name\":\"ConstraintSurfaces\",\"class\":\"UnilateralMBS.Constraints.EllipsoidAndHorizontalPlane\",\"shape\":\"plane\",\"size\":[0,0,0],\"normal\":[0,1,0]"));
    assert!(d.contains("\"up\":1"), "y is up: the plane's normal");
    // The same page from `simulate --animate` (the run's own values, no recompiling).
    let direct = scratch("fly-direct.html");
    simulate(
        "models/FlySlideRoll.mo",
        &scratch("fly2.csv"),
        &[&short[..], &["--animate", s(&direct)]].concat(),
    );
    let direct = std::fs::read_to_string(direct).unwrap();
    assert!(data(&direct).contains("\"shape\":\"ellipsoid\",\"size\":[1,0.7,1.2]"));
}

#[test]
fn bad_input_gets_coded_errors() {
    let csv = scratch("novisual.csv");
    simulate("tests/animate/NoVisual.mo", &csv, &[]);
    let own = scratch("own-errors.csv");
    simulate("tests/animate/OwnBody.mo", &own, &[]);
    let page = scratch("never.html");
    let cases: [(&[&str], &str, i32); 5] = [
        (
            &["animate", s(&csv), "--model", "tests/animate/NoVisual.mo"],
            "E0074",
            2,
        ),
        (
            &[
                "animate",
                "no-such.csv",
                "--model",
                "tests/animate/NoVisual.mo",
            ],
            "E0070",
            2,
        ),
        (
            &["animate", s(&csv), "--model", "tests/animate/BadVisual.mo"],
            "E0072",
            1,
        ),
        (
            &["animate", s(&csv), "--model", "tests/animate/Tumble.mo"],
            "E0073",
            2,
        ),
        (
            &[
                "animate",
                s(&own),
                "--model",
                "tests/animate/OwnBody.mo",
                "--clock",
                "tau",
            ],
            "E0075",
            2,
        ),
    ];
    for (args, code, exit) in cases {
        let mut args = args.to_vec();
        args.extend(["-o", s(&page)]);
        let o = unimo(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(exit), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("error[{code}]")),
            "{args:?}: {stderr}"
        );
    }
    assert!(!page.exists());
}

/// The Chromium binary, or None (with a note) where it cannot be had outside CI.
fn chromium() -> Option<PathBuf> {
    let names = ["chromium", "chromium-browser", "google-chrome"];
    let found = std::env::var_os("UNIMO_CHROMIUM")
        .map(PathBuf::from)
        .into_iter()
        .chain(names.iter().map(PathBuf::from))
        .find(|p| {
            Command::new(p)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        });
    if found.is_none() {
        // .ci/run sets this, with the reason, when it could not install chromium.
        let why = std::env::var("UNIMO_CHROMIUM_UNAVAILABLE").ok();
        assert!(
            std::env::var_os("CI").is_none() || why.is_some(),
            "CI must run the browser tests: install Debian's `chromium` (.ci/run does)"
        );
        eprintln!(
            "note: no chromium found (UNIMO_CHROMIUM, chromium, google-chrome{}): browser tests not run",
            why.map(|w| format!("; {w}")).unwrap_or_default()
        );
    }
    found
}

fn headless(browser: &Path) -> Command {
    let mut c = Command::new(browser);
    c.args([
        "--headless",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--window-size=900,640",
        "--hide-scrollbars",
        "--virtual-time-budget=3000",
        "--enable-logging=stderr",
        "--v=0",
    ]);
    c.env("HOME", scratch("home"));
    c
}

/// What the page exposes after drawing at clock `t`: the state's JSON text.
fn state_at(browser: &Path, page: &Path, t: f64, screenshot: &Path) -> String {
    let url = format!("file://{}#t={t}", s(page));
    let o = headless(browser)
        .arg("--dump-dom")
        .arg(&url)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let console_errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("CONSOLE") && (l.contains("Error") || l.contains("error")))
        .collect();
    assert!(
        console_errors.is_empty(),
        "console errors: {console_errors:#?}"
    );
    let dom = String::from_utf8_lossy(&o.stdout).into_owned();
    let start = dom.find("id=\"unimo-state\"").expect("state element");
    let text = &dom[start..];
    let text = &text[text.find('>').unwrap() + 1..text.find("</pre>").unwrap()];
    assert!(
        text.contains("\"ready\":true"),
        "the page did not draw: {text:.2000}"
    );
    assert!(
        text.contains("\"errors\":[]"),
        "errors on the page: {text:.2000}"
    );
    let shot = headless(browser)
        .arg(format!("--screenshot={}", s(screenshot)))
        .arg(&url)
        .output()
        .unwrap();
    assert!(shot.status.success() && screenshot.exists());
    text.replace("&quot;", "\"")
}

/// The number after `"key":` in `text` following `after`.
fn number(text: &str, after: &str, key: &str) -> f64 {
    let from = text
        .find(after)
        .unwrap_or_else(|| panic!("{after} not in {text:.500}"));
    let rest = &text[from..];
    let k = rest.find(&format!("\"{key}\":")).unwrap() + key.len() + 3;
    let end = rest[k..].find([',', '}', ']']).unwrap();
    rest[k..k + end].trim_start_matches('[').parse().unwrap()
}

/// The position drawn for body `name`.
fn position(text: &str, name: &str) -> [f64; 3] {
    let from = text.find(&format!("\"name\":\"{name}\"")).unwrap();
    let rest = &text[from..];
    let k = rest.find("\"position\":[").unwrap() + "\"position\":[".len();
    let list = &rest[k..k + rest[k..].find(']').unwrap()];
    let v: Vec<f64> = list.split(',').map(|x| x.parse().unwrap()).collect();
    [v[0], v[1], v[2]]
}

#[test]
fn the_page_draws_in_chromium_and_moves_where_bodies_move() {
    let Some(browser) = chromium() else { return };
    let csv = scratch("tumble-browser.csv");
    simulate("tests/animate/Tumble.mo", &csv, &[]);
    let page = scratch("tumble-browser.html");
    animate(&csv, "tests/animate/Tumble.mo", &page, &[]);
    let early = state_at(&browser, &page, 0.0, &scratch("tumble-0.png"));
    let late = state_at(&browser, &page, 0.6, &scratch("tumble-0.6.png"));
    eprintln!("screenshots: {}", s(&scratch("tumble-0.png")));
    assert_eq!(number(&early, "\"pixels\"", "width"), 900.0);
    let drawn = number(&early, "\"pixels\"", "drawn");
    assert!(
        drawn > 10_000.0,
        "the scene covers the view: {drawn} pixels drawn"
    );
    // the ball fell: its centre went down by more than its radius
    let (b0, b1) = (position(&early, "ball.body"), position(&late, "ball.body"));
    assert!(
        (b0[2] - 0.6).abs() < 1e-6 && b1[2] < 0.5,
        "{b0:?} -> {b1:?}"
    );
    // a fixed body stays where it was
    assert_eq!(
        position(&early, "pillar.body"),
        position(&late, "pillar.body")
    );
    let checksum = |t: &str| number(t, "\"pixels\"", "checksum");
    assert_ne!(checksum(&early), checksum(&late), "the picture changed");
    assert!(number(&late, "\"time\"", "time") == 0.6);
}

#[test]
fn a_users_own_classes_are_drawn_in_chromium() {
    let Some(browser) = chromium() else { return };
    let csv = scratch("own.csv");
    simulate("tests/animate/OwnBody.mo", &csv, &[]);
    let page = scratch("own.html");
    let html = animate(&csv, "tests/animate/OwnBody.mo", &page, &[]);
    assert!(data(&html).contains("\"name\":\"spinner\",\"class\":\"OwnBody.Spinner\",\"shape\":\"cone\",\"size\":[0.2,0.5,0],\"normal\":[0,0,1],\"color\":\"#cc3333\""));
    let a = state_at(&browser, &page, 0.0, &scratch("own-0.png"));
    let b = state_at(&browser, &page, 0.75, &scratch("own-0.75.png"));
    // the slider moved along x by 2 * 0.75; the spinner turned by 1.5 rad about z
    let (p0, p1) = (position(&a, "slider"), position(&b, "slider"));
    assert!(
        (p0[0] + 1.0).abs() < 1e-6 && (p1[0] - 0.5).abs() < 1e-6,
        "{p0:?} {p1:?}"
    );
    let qz = number(&b, "\"name\":\"spinner\"", "quaternion");
    assert_eq!(qz, 0.0, "x component of a turn about z");
    assert_ne!(
        number(&a, "\"pixels\"", "checksum"),
        number(&b, "\"pixels\"", "checksum")
    );
}
