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
    for w in sorted.starts.windows(2) {
        let run = &mut sorted.items[w[0] as usize..w[1] as usize];
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
    sorted
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
}
