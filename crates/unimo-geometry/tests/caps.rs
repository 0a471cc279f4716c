//! Two parallel flat caps (coaxial discs): parry's manifold turns the caps' square
//! approximations with the contact's azimuth, which is noise when the caps are
//! parallel. The normal and the depths must not depend on the last digits of a
//! position.

use unimo_geometry::{contacts, ContactQuery, Placement, Scratch, Shape, ShapeKind};

#[test]
fn parallel_caps_give_the_axis_and_the_exact_depth_whatever_the_last_digits() {
    // Discs 4 mm thick with their axes (body y) on world z, overlapping by 7.39e-6 m.
    let rz = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
    let disc = Shape::new(ShapeKind::Cylinder {
        half_height: 0.002,
        radius: 0.02,
    })
    .unwrap();
    let mut scratch = Scratch::default();
    let mut worst = (0.0f64, 0.0f64);
    for k in 0..200 {
        let za = 0.003991874306 + k as f64 * 1e-12;
        let zb = 0.007984484018 + (k as f64 * 0.37).sin() * 1e-12;
        let (pa, pb) = (
            Placement {
                r: [0.0, 0.0, za],
                rot: rz,
            },
            Placement {
                r: [0.0, 0.0, zb],
                rot: rz,
            },
        );
        let mut out = Vec::new();
        let query = ContactQuery {
            a: &disc,
            pa: &pa,
            b: &disc,
            pb: &pb,
            prediction: 1e-3,
        };
        contacts(query, &mut scratch, &mut out).unwrap();
        assert!(
            out.len() >= 3,
            "a face contact has at least 3 points: {out:?}"
        );
        let exact = (zb - za) - 0.004;
        for c in &out {
            let tilt = c.normal[0].hypot(c.normal[1]);
            worst = (worst.0.max(tilt), worst.1.max((c.dist - exact).abs()));
        }
    }
    assert!(worst.0 < 1e-12, "normal off the axis by {:e}", worst.0);
    assert!(worst.1 < 1e-15, "depth off by {:e} m", worst.1);
}
