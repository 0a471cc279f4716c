//! Broadphase: candidate pairs from bounding boxes. Sweep and prune along x costs
//! O(n log n + k) (and O(n + k) when the order barely changes between calls, thanks to
//! insertion sort); the all-pairs variant is O(n²) and kept for comparison and for
//! scenes of two bodies, where a broadphase has nothing to save.

use crate::query::Aabb;

/// Produces candidate pairs `(i, j)`, `i < j`, whose boxes overlap.
pub trait Broadphase {
    fn pairs(&mut self, boxes: &[Aabb], out: &mut Vec<(u32, u32)>);
    /// Box-overlap tests done so far (for reports).
    fn tests(&self) -> u64;
}

/// Every pair tested.
#[derive(Default, Debug)]
pub struct AllPairs {
    tests: u64,
}

impl Broadphase for AllPairs {
    fn pairs(&mut self, boxes: &[Aabb], out: &mut Vec<(u32, u32)>) {
        out.clear();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                self.tests += 1;
                if boxes[i].overlaps(&boxes[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
    }

    fn tests(&self) -> u64 {
        self.tests
    }
}

/// Sweep and prune on the x axis; the order from the previous call is kept and
/// repaired by insertion sort.
#[derive(Default, Debug)]
pub struct SweepAndPrune {
    order: Vec<u32>,
    active: Vec<u32>,
    tests: u64,
}

impl Broadphase for SweepAndPrune {
    fn pairs(&mut self, boxes: &[Aabb], out: &mut Vec<(u32, u32)>) {
        out.clear();
        if self.order.len() != boxes.len() {
            self.order = (0..boxes.len() as u32).collect();
        }
        // Insertion sort by min x: linear when nearly sorted.
        for i in 1..self.order.len() {
            let mut j = i;
            while j > 0
                && boxes[self.order[j - 1] as usize].min[0] > boxes[self.order[j] as usize].min[0]
            {
                self.order.swap(j - 1, j);
                j -= 1;
            }
        }
        self.active.clear();
        for &i in &self.order {
            let bi = &boxes[i as usize];
            self.active
                .retain(|&a| boxes[a as usize].max[0] >= bi.min[0]);
            for &a in &self.active {
                self.tests += 1;
                if bi.overlaps(&boxes[a as usize]) {
                    out.push((a.min(i), a.max(i)));
                }
            }
            self.active.push(i);
        }
    }

    fn tests(&self) -> u64 {
        self.tests
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn boxes(v: &[(f64, f64, f64, f64)]) -> Vec<Aabb> {
        v.iter()
            .map(|&(x, y, z, h)| Aabb {
                min: [x - h, y - h, z - h],
                max: [x + h, y + h, z + h],
            })
            .collect()
    }

    proptest! {
        #[test]
        fn sweep_and_prune_finds_exactly_the_overlapping_pairs(
            v in prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64, -1.0..1.0f64, 0.01..2.0f64), 0..60),
            shift in -1.0..1.0f64,
        ) {
            let mut b = boxes(&v);
            let mut sap = SweepAndPrune::default();
            for round in 0..2 {
                let (mut p, mut q) = (Vec::new(), Vec::new());
                sap.pairs(&b, &mut p);
                AllPairs::default().pairs(&b, &mut q);
                p.sort_unstable();
                q.sort_unstable();
                prop_assert_eq!(p, q, "round {}", round);
                // Move every box a little: the second call repairs the order.
                for (k, x) in b.iter_mut().enumerate() {
                    let d = shift * ((k % 7) as f64 - 3.0);
                    x.min[0] += d;
                    x.max[0] += d;
                }
            }
        }
    }

    #[test]
    fn sweep_and_prune_tests_few_pairs_on_a_spread_row() {
        let v: Vec<_> = (0..1000).map(|k| (k as f64, 0.0, 0.0, 0.4)).collect();
        let b = boxes(&v);
        let mut sap = SweepAndPrune::default();
        let mut out = Vec::new();
        sap.pairs(&b, &mut out);
        assert!(out.is_empty());
        assert!(sap.tests() < 1000, "{} tests", sap.tests());
    }
}
