//! Items grouped by a small integer key: a counting sort.

/// Items grouped by bucket, each bucket's in the order they were given: bucket `b` holds
/// `items[starts[b] as usize..starts[b + 1] as usize]`.
pub(super) struct Buckets<T> {
    pub starts: Vec<u32>,
    pub items: Vec<T>,
}

/// Groups `entries` (bucket, item), every bucket below `count`, by a counting sort: one pass to
/// count, one to place (sequential but for the writes), no comparisons.
///
/// Three lists of a repair pass are grouped so: half-edges by their smaller vertex
/// ([`super::edges::sort_by_edge`]), boundary edges by their ends (the straight-vertex pass of
/// `regions`) and the T-junction search's points by grid cell ([`super::grid::Grid`]).
pub(super) fn buckets<T: Copy + Default>(
    count: usize,
    entries: impl Iterator<Item = (usize, T)> + Clone,
) -> Buckets<T> {
    // Bucket b's size is counted at b + 2, so that after the prefix sum `starts[b + 1]` is b's
    // start: placing advances it to b's end, which is b + 1's start, and no copy of the starts
    // is needed as cursors.
    let mut starts = vec![0u32; count + 2];
    let mut total = 0usize;
    for (b, _) in entries.clone() {
        starts[b + 2] += 1;
        total += 1;
    }
    for b in 2..count + 2 {
        starts[b] += starts[b - 1];
    }
    let mut items = vec![T::default(); total];
    for (b, item) in entries {
        let at = &mut starts[b + 1];
        items[*at as usize] = item;
        *at += 1;
    }
    starts.pop();
    Buckets { starts, items }
}

#[cfg(test)]
mod tests {
    use super::buckets;

    #[test]
    fn groups_in_order_given() {
        let entries = [(2usize, 'a'), (0, 'b'), (2, 'c'), (3, 'd'), (0, 'e')];
        let b = buckets(5, entries.iter().copied());
        assert_eq!(b.starts, [0, 2, 2, 4, 5, 5]);
        assert_eq!(b.items, ['b', 'e', 'a', 'c', 'd']);
        let empty = buckets::<u32>(3, std::iter::empty());
        assert_eq!(empty.starts, [0, 0, 0, 0]);
        assert!(empty.items.is_empty());
    }
}
