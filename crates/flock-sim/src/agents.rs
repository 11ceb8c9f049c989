//! Loops over the agents, each agent's work on its own slots, in parallel with the `parallel`
//! feature (the results the same for any split).

/// `f(i, &mut a[i], &mut b[i], &mut c[i])` for every agent i (the three slices of one length;
/// `&mut vec![(); n]` for one unused, which allocates nothing), in parallel with the `parallel`
/// feature, and the sum of what `f` returns (a count: the same for any split).
pub(crate) fn for_each_agent<A: Send, B: Send, C: Send>(
    a: &mut [A],
    b: &mut [B],
    c: &mut [C],
    f: impl Fn(usize, &mut A, &mut B, &mut C) -> usize + Sync + Send,
) -> usize {
    debug_assert!(a.len() == b.len() && b.len() == c.len());
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        a.par_iter_mut()
            .zip(b.par_iter_mut())
            .zip(c.par_iter_mut())
            .enumerate()
            .with_min_len(1024)
            .map(|(i, ((a, b), c))| f(i, a, b, c))
            .sum()
    }
    #[cfg(not(feature = "parallel"))]
    a.iter_mut()
        .zip(b.iter_mut())
        .zip(c.iter_mut())
        .enumerate()
        .map(|(i, ((a, b), c))| f(i, a, b, c))
        .sum()
}

/// `f(i, &mut items[i], scratch)` for every item, in parallel with the `parallel` feature; in
/// index order. Each worker's `scratch` is made by `init` and passed from item to item (its
/// buffers keep their capacity): `f`'s result must not depend on what it held before.
pub(crate) fn map_agents_mut<S: Send, W, T: Send>(
    items: &mut [S],
    init: impl Fn() -> W + Sync + Send,
    f: impl Fn(usize, &mut S, &mut W) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .map_init(init, |w, (i, s)| f(i, s, w))
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut w = init();
        items
            .iter_mut()
            .enumerate()
            .map(|(i, s)| f(i, s, &mut w))
            .collect()
    }
}
