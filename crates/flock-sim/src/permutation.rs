//! Arrays of per-agent state permuted in place when a simulation re-sorts its agents by cell:
//! cycle by cycle, one flag per agent, so that no array is held twice.

/// One move of a permutation applied cycle by cycle.
enum Move {
    /// Keep the entry at this index aside: its cycle starts here.
    Save(usize),
    /// Move the entry at `from` to `to`.
    Shift { to: usize, from: usize },
    /// Put the entry kept aside at this index: its cycle ends here.
    Restore(usize),
}

/// The moves that give index s what index `from(s)` held, for every s < `len` (`from` a
/// permutation of `0..len`), each cycle from its smallest index.
fn in_cycles(len: usize, from: impl Fn(usize) -> usize, mut apply: impl FnMut(Move)) {
    let mut done = vec![false; len];
    for start in 0..len {
        if done[start] {
            continue;
        }
        apply(Move::Save(start));
        let mut s = start;
        loop {
            done[s] = true;
            let next = from(s);
            if next == start {
                apply(Move::Restore(s));
                break;
            }
            apply(Move::Shift { to: s, from: next });
            s = next;
        }
    }
}

/// `x` with what entry `from(s)` held at index s, for every s (`from` a permutation of
/// `0..x.len()`; nothing is done to an empty `x`).
pub(crate) fn permute_in_place<T: Default>(x: &mut [T], from: impl Fn(usize) -> usize) {
    let mut first = T::default();
    in_cycles(x.len(), from, |m| match m {
        Move::Save(s) => first = core::mem::take(&mut x[s]),
        Move::Shift { to, from } => x[to] = core::mem::take(&mut x[from]),
        Move::Restore(s) => x[s] = core::mem::take(&mut first),
    });
}

/// [`permute_in_place`] of the rows of `width` numbers of `x` (nothing for `width` 0).
pub(crate) fn permute_rows_in_place(x: &mut [f64], width: usize, from: impl Fn(usize) -> usize) {
    if width == 0 {
        return;
    }
    let mut first = vec![0.0; width];
    in_cycles(x.len() / width, from, |m| match m {
        Move::Save(s) => first.copy_from_slice(&x[s * width..(s + 1) * width]),
        Move::Shift { to, from } => x.copy_within(from * width..(from + 1) * width, to * width),
        Move::Restore(s) => x[s * width..(s + 1) * width].copy_from_slice(&first),
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Against a copy gathered through the permutation: every entry, every row width,
        /// permutations of 0–200 entries with cycles of every length.
        #[test]
        fn in_place_is_the_gathered_copy(
            order in (0..200usize).prop_flat_map(|n| Just((0..n).collect::<Vec<_>>()).prop_shuffle()),
            width in 0..4usize,
        ) {
            let n = order.len();
            let from = |s: usize| order[s];
            let values: Vec<u64> = (0..n as u64).map(|k| k * 7 + 1).collect();
            let mut moved = values.clone();
            permute_in_place(&mut moved, from);
            let gathered: Vec<u64> = (0..n).map(|s| values[from(s)]).collect();
            prop_assert_eq!(moved, gathered);
            let rows: Vec<f64> = (0..n * width).map(|k| k as f64).collect();
            let mut moved = rows.clone();
            permute_rows_in_place(&mut moved, width, from);
            let gathered: Vec<f64> = (0..n)
                .flat_map(|s| rows[from(s) * width..(from(s) + 1) * width].to_vec())
                .collect();
            prop_assert_eq!(moved, gathered);
        }
    }
}
