//! [`Bvh`]: a bounding-volume hierarchy over axis-aligned boxes, written once for `V: Vector`.
//!
//! A binary tree built top-down by median splits of the box centres along the widest axis, with up
//! to [`LEAF_SIZE`] boxes per leaf; nodes in depth-first order (a node's left child follows it).
//! Queries visit only the subtrees whose box can matter, so their cost grows with the boxes near
//! the query point, not with all of them.

use flock_math::Vector;

/// The largest number of boxes in a leaf.
const LEAF_SIZE: usize = 4;

/// A bounding-volume hierarchy over boxes `(min, max)` tagged with indices.
#[derive(Clone, Debug)]
pub(crate) struct Bvh<V> {
    nodes: Vec<Node<V>>,
    /// The boxes `(index, min, max)`, in leaf order: each leaf covers a contiguous range.
    boxes: Vec<(usize, V, V)>,
}

#[derive(Clone, Copy, Debug)]
struct Node<V> {
    min: V,
    max: V,
    /// Leaf: the first of its boxes in `indices`. Inner node: the index of its right child (the
    /// left child is the next node).
    first_or_right: usize,
    /// Leaf: the number of its boxes (`> 0`). Inner node: `0`.
    count: usize,
}

/// A box during the build.
#[derive(Clone, Copy)]
struct Entry<V> {
    index: usize,
    min: V,
    max: V,
    centre: V,
}

impl<V: Vector> Bvh<V> {
    /// The hierarchy of the boxes `(index, min, max)`.
    pub(crate) fn new(boxes: impl IntoIterator<Item = (usize, V, V)>) -> Self {
        let mut entries: Vec<Entry<V>> = boxes
            .into_iter()
            .map(|(index, min, max)| Entry {
                index,
                min,
                max,
                centre: (min + max) * 0.5,
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * entries.len().div_ceil(LEAF_SIZE));
        if !entries.is_empty() {
            build(&mut entries, 0, &mut nodes);
        }
        Self {
            nodes,
            boxes: entries
                .iter()
                .map(|entry| (entry.index, entry.min, entry.max))
                .collect(),
        }
    }

    /// Calls `visit(index)` for every box at distance `< range` from `q` or containing `q`
    /// (boundary included), in an order fixed by the hierarchy.
    pub(crate) fn visit_near(&self, q: V, range: f64, visit: &mut impl FnMut(usize)) {
        if !self.nodes.is_empty() {
            let range_squared = if range > 0.0 { range * range } else { 0.0 };
            self.near(0, q, range_squared, visit);
        }
    }

    fn near(&self, id: usize, q: V, range_squared: f64, visit: &mut impl FnMut(usize)) {
        let node = &self.nodes[id];
        let near = |min: V, max: V| {
            let distance_squared = distance_squared(q, min, max);
            distance_squared < range_squared || distance_squared == 0.0
        };
        if !near(node.min, node.max) {
            return;
        }
        if node.count > 0 {
            let first = node.first_or_right;
            for &(index, min, max) in &self.boxes[first..first + node.count] {
                if near(min, max) {
                    visit(index);
                }
            }
        } else {
            self.near(id + 1, q, range_squared, visit);
            self.near(node.first_or_right, q, range_squared, visit);
        }
    }

    /// Lowers `best` to the least `distance(index)` over the boxes, where `distance(index)` is a
    /// signed distance from `q` to a set inside box `index`: at least the distance from `q` to the
    /// box when `q` is outside it. Branch and bound, nearest subtree first: skips the boxes that do
    /// not contain `q` and are no nearer than `best`.
    pub(crate) fn nearest(&self, q: V, best: &mut f64, distance: &mut impl FnMut(usize) -> f64) {
        if let Some(root) = self.nodes.first() {
            let bound = distance_squared(q, root.min, root.max).sqrt();
            self.nearest_in(0, bound, q, best, distance);
        }
    }

    fn nearest_in(
        &self,
        id: usize,
        bound: f64,
        q: V,
        best: &mut f64,
        distance: &mut impl FnMut(usize) -> f64,
    ) {
        if bound > 0.0 && bound >= *best {
            return;
        }
        let node = &self.nodes[id];
        if node.count > 0 {
            let first = node.first_or_right;
            for &(index, min, max) in &self.boxes[first..first + node.count] {
                let bound = distance_squared(q, min, max).sqrt();
                if bound == 0.0 || bound < *best {
                    *best = best.min(distance(index));
                }
            }
            return;
        }
        let (left, right) = (id + 1, node.first_or_right);
        let bound_of = |child: usize| {
            let child = &self.nodes[child];
            distance_squared(q, child.min, child.max).sqrt()
        };
        let (left_bound, right_bound) = (bound_of(left), bound_of(right));
        if right_bound < left_bound {
            self.nearest_in(right, right_bound, q, best, distance);
            self.nearest_in(left, left_bound, q, best, distance);
        } else {
            self.nearest_in(left, left_bound, q, best, distance);
            self.nearest_in(right, right_bound, q, best, distance);
        }
    }
}

/// Builds the subtree of `entries` (whose first is at `offset` in the final order) and returns the
/// index of its root.
fn build<V: Vector>(entries: &mut [Entry<V>], offset: usize, nodes: &mut Vec<Node<V>>) -> usize {
    let (mut min, mut max) = (entries[0].min, entries[0].max);
    let (mut centre_min, mut centre_max) = (entries[0].centre, entries[0].centre);
    for entry in &entries[1..] {
        min = min.min(entry.min);
        max = max.max(entry.max);
        centre_min = centre_min.min(entry.centre);
        centre_max = centre_max.max(entry.centre);
    }
    let id = nodes.len();
    nodes.push(Node {
        min,
        max,
        first_or_right: offset,
        count: entries.len(),
    });
    if entries.len() <= LEAF_SIZE {
        return id;
    }
    let spread = centre_max - centre_min;
    let axis = (0..V::DIM)
        .max_by(|&i, &j| spread.coord(i).total_cmp(&spread.coord(j)))
        .unwrap_or(0);
    let middle = entries.len() / 2;
    entries.select_nth_unstable_by(middle, |a, b| {
        a.centre
            .coord(axis)
            .total_cmp(&b.centre.coord(axis))
            .then(a.index.cmp(&b.index))
    });
    let (left, right) = entries.split_at_mut(middle);
    build(left, offset, nodes);
    let right = build(right, offset + middle, nodes);
    nodes[id].first_or_right = right;
    nodes[id].count = 0;
    id
}

/// The squared distance from `q` to the box `[min, max]` (0 inside).
#[inline]
fn distance_squared<V: Vector>(q: V, min: V, max: V) -> f64 {
    (min - q).max(q - max).max(V::ZERO).length_squared()
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::*;

    /// Boxes of a 10 × 10 grid of unit squares with gaps.
    fn grid() -> Vec<(usize, DVec2, DVec2)> {
        (0..100)
            .map(|k| {
                let corner = DVec2::new((k % 10) as f64 * 2.0, (k / 10) as f64 * 2.0);
                (k, corner, corner + DVec2::ONE)
            })
            .collect()
    }

    #[test]
    fn visit_near_matches_brute_force() {
        let boxes = grid();
        let bvh = Bvh::new(boxes.iter().copied());
        for (q, range) in [
            (DVec2::new(3.5, 3.5), 1.0),
            (DVec2::new(0.5, 0.5), 0.0),
            (DVec2::new(-5.0, 9.0), 5.5),
            (DVec2::new(10.0, 10.0), f64::INFINITY),
            (DVec2::new(2.0, 2.0), -1.0),
        ] {
            let mut found = Vec::new();
            bvh.visit_near(q, range, &mut |k| found.push(k));
            found.sort_unstable();
            let range_squared = if range > 0.0 { range * range } else { 0.0 };
            let expected: Vec<usize> = boxes
                .iter()
                .filter(|&&(_, min, max)| {
                    let d = distance_squared(q, min, max);
                    d < range_squared || d == 0.0
                })
                .map(|&(k, ..)| k)
                .collect();
            assert_eq!(found, expected, "q = {q}, range = {range}");
        }
    }

    #[test]
    fn nearest_matches_brute_force() {
        let boxes = grid();
        let bvh = Bvh::new(boxes.iter().copied());
        for q in [
            DVec2::new(3.7, -2.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(30.0, 7.7),
        ] {
            let mut visited = 0;
            let mut best = f64::INFINITY;
            bvh.nearest(q, &mut best, &mut |k| {
                visited += 1;
                let (_, min, max) = boxes[k];
                distance_squared(q, min, max).sqrt()
            });
            let expected = boxes
                .iter()
                .map(|&(_, min, max)| distance_squared(q, min, max).sqrt())
                .fold(f64::INFINITY, f64::min);
            assert_eq!(best, expected, "q = {q}");
            assert!(visited < 30, "{visited} boxes visited for q = {q}");
        }
    }

    #[test]
    fn empty() {
        let bvh = Bvh::<DVec2>::new([]);
        bvh.visit_near(DVec2::ZERO, f64::INFINITY, &mut |_| panic!("no box"));
        let mut best = f64::INFINITY;
        bvh.nearest(DVec2::ZERO, &mut best, &mut |_| panic!("no box"));
        assert_eq!(best, f64::INFINITY);
    }
}
