//! Half-edges grouped by undirected edge, by a counting sort on vertex indices.

use super::buckets::{Buckets, buckets};

/// The undirected edge `a`–`b` as one key: the smaller index in the high half.
#[inline]
pub(super) fn undirected(a: u32, b: u32) -> u64 {
    ((a.min(b) as u64) << 32) | a.max(b) as u64
}

/// A ring edge's partner (see [`run_partners`]) where its edge has other uses than one ring's
/// each way, or one alone: three rings along it, or two the same way.
pub(super) const CROWDED: u32 = u32::MAX;

/// A ring edge's partner where no other ring edge runs along it, either way.
pub(super) const ONLY_USE: u32 = u32::MAX - 1;

/// A ring edge's partner not yet known: its edge is to be sorted (again).
pub(super) const UNKNOWN: u32 = u32::MAX - 2;

/// Sets the partner of each use of one edge, `run` (a run of equal keys from [`sort_by_edge`],
/// payloads `i << 1 | reversed`; the use's half-edge is `half(i)`, its ring `ring(i)`): the
/// ring across where exactly one ring uses the edge each way, [`ONLY_USE`] where it is the
/// edge's only use, [`CROWDED`] otherwise.
#[inline]
pub(super) fn run_partners(
    run: &[(u64, u32)],
    half: impl Fn(u32) -> usize,
    ring: impl Fn(u32) -> u32,
    partner: &mut [u32],
) {
    match *run {
        [(_, x), (_, y)] if (x ^ y) & 1 == 1 => {
            partner[half(x >> 1)] = ring(y >> 1);
            partner[half(y >> 1)] = ring(x >> 1);
        }
        [(_, x)] => partner[half(x >> 1)] = ONLY_USE,
        _ => {
            for &(_, h) in run {
                partner[half(h >> 1)] = CROWDED;
            }
        }
    }
}

/// Runs of at most this many entries (a vertex's edges, usually about six) are sorted by
/// insertion.
const INSERTION_RUN: usize = 16;

/// `keyed` (pairs of [`undirected`] edge and a payload that grows with the position in the
/// list) sorted by key, then payload: the order `sort_unstable` gives, so each edge's uses come
/// together in the order they were listed. Grouped by the smaller vertex: vertex `v`'s edges
/// are `items[starts[v]..starts[v + 1]]`.
///
/// Every key's smaller vertex is below `vertex_count`: a counting sort on it (one pass to
/// count, one to place, sequential but for the writes) and then a sort of each vertex's few
/// edges by the other end. A boolean's soup has 10⁶ half-edges: a comparison sort of them was
/// a quarter of `to_mesh`, done three times.
pub(super) fn sort_by_edge(keyed: &[(u64, u32)], vertex_count: usize) -> Buckets<(u64, u32)> {
    // Listed in payload order, placed in that order: each vertex's run keeps it.
    let mut sorted = buckets(
        vertex_count,
        keyed.iter().map(|&entry| ((entry.0 >> 32) as usize, entry)),
    );
    let halves = rayon::current_num_threads() > 1;
    sort_runs(&sorted.starts, &mut sorted.items, halves);
    sorted
}

/// From this many half-edges on, with more than one thread, the runs are sorted in two halves
/// at a vertex's boundary, one per thread (each run is sorted alone, so the result is the same).
const HALVES_FROM: usize = 1 << 14;

/// Sorts each run `items[starts[v] - starts[0]..starts[v + 1] - starts[0]]`.
fn sort_runs(starts: &[u32], items: &mut [(u64, u32)], halves: bool) {
    if halves && items.len() >= HALVES_FROM {
        let base = starts[0];
        // The first vertex whose run starts at or past the middle.
        let mid = starts.partition_point(|&s| ((s - base) as usize) < items.len() / 2);
        if mid > 0 && mid < starts.len() - 1 {
            let (left, right) = items.split_at_mut((starts[mid] - base) as usize);
            rayon::join(
                || sort_runs(&starts[..=mid], left, false),
                || sort_runs(&starts[mid..], right, false),
            );
            return;
        }
    }
    let base = starts[0];
    for w in starts.windows(2) {
        let run = &mut items[(w[0] - base) as usize..(w[1] - base) as usize];
        if run.len() > INSERTION_RUN {
            run.sort_unstable();
        } else {
            // A vertex's few edges: an insertion sort, without the general sort's setup.
            for i in 1..run.len() {
                let mut j = i;
                while j > 0 && run[j] < run[j - 1] {
                    run.swap(j, j - 1);
                    j -= 1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_order_as_a_comparison_sort() {
        // A small soup of edges with repeats in both directions, payloads in list order.
        let ends = [
            (3, 1),
            (1, 3),
            (0, 2),
            (2, 0),
            (4, 0),
            (0, 4),
            (1, 3),
            (2, 4),
            (0, 1),
        ];
        let keyed: Vec<(u64, u32)> = ends
            .iter()
            .enumerate()
            .map(|(i, &(a, b))| (undirected(a, b), (i as u32) << 1 | u32::from(a > b)))
            .collect();
        let mut expected = keyed.clone();
        expected.sort_unstable();
        assert_eq!(sort_by_edge(&keyed, 5).items, expected);
    }

    /// The runs sorted in two halves (one per thread) are the runs sorted in one pass: a soup
    /// large enough to split, with long runs (sorted by the general sort) and short ones.
    #[test]
    fn runs_sorted_in_halves_are_sorted_as_one() {
        let mut next = crate::hash::test_support::lcg(5);
        let n = 3 * HALVES_FROM;
        let keyed: Vec<(u64, u32)> = (0..n)
            .map(|i| {
                let a = (next() >> 40) as u32 % 2000;
                let b = if i % 7 == 0 {
                    3
                } else {
                    (next() >> 40) as u32 % 5000
                };
                (undirected(a, b), (i as u32) << 1 | u32::from(a > b))
            })
            .collect();
        let mut expected = keyed.clone();
        expected.sort_unstable();
        let mut sorted = buckets(5000, keyed.iter().map(|&e| ((e.0 >> 32) as usize, e)));
        sort_runs(&sorted.starts, &mut sorted.items, true);
        assert_eq!(sorted.items, expected);
        let mut serial = buckets(5000, keyed.iter().map(|&e| ((e.0 >> 32) as usize, e)));
        sort_runs(&serial.starts, &mut serial.items, false);
        assert_eq!(serial.items, expected);
    }
}
