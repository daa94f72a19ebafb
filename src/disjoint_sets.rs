//! Union–find over `0..n` with path halving: iterative, so no input can overflow the stack.

/// Disjoint sets of the integers `0..n`.
pub(crate) struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    /// `n` singleton sets.
    pub fn new(n: usize) -> Self {
        DisjointSets {
            parent: (0..n).collect(),
        }
    }

    /// The root of `x`'s set.
    pub fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    /// Joins the sets of `items` ([`DisjointSets::union`] of the first with each other one,
    /// with the first's root found once).
    pub fn union_all<const N: usize>(&mut self, items: [usize; N]) {
        let Some(&first) = items.first() else {
            return;
        };
        let mut root = self.find(first);
        for &x in &items[1..] {
            // Already a child of the root (most calls, on a mesh's triangles): nothing to do,
            // and nothing `find` would have changed.
            if self.parent[x] == root {
                continue;
            }
            let other = self.find(x);
            root = self.link(root, other);
        }
    }

    /// Joins the set of `x` to the set whose root is `root` (what [`DisjointSets::union`] of a
    /// member of that set and `x` does, with the root already known); returns the joined set's
    /// root.
    pub fn join(&mut self, root: usize, x: usize) -> usize {
        debug_assert_eq!(self.parent[root], root);
        // Already a child of the root: nothing to do, and nothing `find` would have changed.
        if self.parent[x] == root {
            return root;
        }
        let other = self.find(x);
        self.link(root, other)
    }

    /// Joins the sets of `a` and `b`; the smaller root wins, so a set's root is its first member.
    pub fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        self.link(ra, rb);
    }

    /// Joins the sets of roots `ra` and `rb` under the smaller; returns it.
    fn link(&mut self, ra: usize, rb: usize) -> usize {
        let (root, child) = if ra < rb { (ra, rb) } else { (rb, ra) };
        self.parent[child] = root;
        root
    }
}
