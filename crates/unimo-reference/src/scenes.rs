//! The data of paper A's three examples (spec A.9, `models/FlySlideRoll.mo`,
//! `SlideRollSwitch.mo`, `MarkeevEllipsoid.mo`) and their initial states.

use crate::dynamics::Scene;
use crate::geometry::{Ellipsoid, STATE_LEN};

/// One example: its scene, initial state and physical stop time.
#[derive(Debug, Clone, PartialEq)]
pub struct Example {
    pub name: &'static str,
    pub scene: Scene,
    pub initial_state: [f64; STATE_LEN],
    pub t_stop: f64,
}

fn state(r: [f64; 3], v: [f64; 3], omega: [f64; 3]) -> [f64; STATE_LEN] {
    [
        r[0], r[1], r[2], v[0], v[1], v[2], 1.0, 0.0, 0.0, 0.0, omega[0], omega[1], omega[2],
    ]
}

/// Example 1, FlySlideRoll (ClearanceTolerance 1e-12 as the spec says).
pub fn fly_slide_roll() -> Example {
    Example {
        name: "FlySlideRoll",
        scene: Scene {
            body: Ellipsoid {
                semi_axes: [1.0, 0.8, 1.2],
                mass: 1.0,
            },
            gravity: 1.0,
            restitution: 0.6,
            friction: 0.08,
            delta: 1e-3,
            clearance_tolerance: 1e-12,
        },
        initial_state: state([0.0, 5.0, 0.0], [0.05, 0.0, 0.0], [0.0, -10.0, 2.0]),
        t_stop: 150.0,
    }
}

/// The scene of examples 2 and 3 (spec A.9: a, b, c = 1.2, 1, 1.3; g = 9.81; k = 0.5;
/// delta = 1e-4; ClearanceTolerance = 1e-8), which differ in `friction`.
fn scene_of_examples_2_and_3(friction: f64) -> Scene {
    Scene {
        body: Ellipsoid {
            semi_axes: [1.2, 1.0, 1.3],
            mass: 1.0,
        },
        gravity: 9.81,
        restitution: 0.5,
        friction,
        delta: 1e-4,
        clearance_tolerance: 1e-8,
    }
}

/// Example 2, SlideRollSwitch (starts resting on the plane).
pub fn slide_roll_switch() -> Example {
    Example {
        name: "SlideRollSwitch",
        scene: scene_of_examples_2_and_3(0.1),
        initial_state: state([0.0, 1.0, 0.0], [0.05, 0.0, 0.0], [0.0, -2.0, 2.0]),
        t_stop: 20.0,
    }
}

/// Example 3, Markeev's rising ellipsoid (starts resting on the plane).
pub fn markeev() -> Example {
    Example {
        name: "MarkeevEllipsoid",
        scene: scene_of_examples_2_and_3(0.01),
        initial_state: state([0.0, 1.0, 0.0], [0.05, 0.0, 0.0], [0.0, -10.0, 2.0]),
        t_stop: 160.0,
    }
}

/// The example of a name (case-insensitive, `fly-slide-roll` style accepted).
pub fn by_name(name: &str) -> Option<Example> {
    let key: String = name
        .chars()
        .filter(|c| c.is_alphanumeric())
        .collect::<String>()
        .to_lowercase();
    match key.as_str() {
        "flysliderroll" | "flyslideroll" | "1" => Some(fly_slide_roll()),
        "sliderollswitch" | "2" => Some(slide_roll_switch()),
        "markeev" | "markeevellipsoid" | "3" => Some(markeev()),
        _ => None,
    }
}
