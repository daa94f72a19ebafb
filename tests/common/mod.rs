//! Test-local mesh checks (the crate's own `Mesh::report` lands on another branch).

#![allow(dead_code)]

use std::collections::HashMap;

use bspcsg::Mesh;

/// Counts of a mesh's topology.
#[derive(Debug, Clone, PartialEq)]
pub struct Topology {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    /// Undirected edges used by one triangle only.
    pub boundary_edges: usize,
    /// Undirected edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Directed edges used twice (neighbours wound the same way).
    pub misoriented_edges: usize,
    /// Triangles with a repeated vertex index.
    pub degenerate: usize,
    /// Connected components (by shared edges).
    pub components: usize,
}

impl Topology {
    pub fn of(mesh: &Mesh) -> Topology {
        let mut undirected: HashMap<(u32, u32), u32> = HashMap::new();
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        let mut degenerate = 0;
        let mut used = vec![false; mesh.positions.len()];
        for t in &mesh.triangles {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                degenerate += 1;
            }
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                used[a as usize] = true;
                *undirected.entry((a.min(b), a.max(b))).or_default() += 1;
                *directed.entry((a, b)).or_default() += 1;
            }
        }
        // Components over triangles joined by shared vertices' edges: union-find on vertices.
        let mut parent: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        fn find(p: &mut [u32], mut x: u32) -> u32 {
            while p[x as usize] != x {
                p[x as usize] = p[p[x as usize] as usize];
                x = p[x as usize];
            }
            x
        }
        for &(a, b) in undirected.keys() {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                parent[ra as usize] = rb;
            }
        }
        let vertices = used.iter().filter(|&&u| u).count();
        let components = (0..mesh.positions.len() as u32)
            .filter(|&v| used[v as usize] && find(&mut parent, v) == v)
            .count();
        Topology {
            vertices,
            edges: undirected.len(),
            faces: mesh.triangles.len(),
            boundary_edges: undirected.values().filter(|&&c| c == 1).count(),
            non_manifold_edges: undirected.values().filter(|&&c| c > 2).count(),
            misoriented_edges: directed.values().filter(|&&c| c > 1).count(),
            degenerate,
            components,
        }
    }

    pub fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }

    /// Total genus, assuming a closed orientable surface: χ = 2·components − 2·genus.
    pub fn genus(&self) -> i64 {
        (2 * self.components as i64 - self.euler()) / 2
    }

    pub fn is_closed_manifold(&self) -> bool {
        self.boundary_edges == 0
            && self.non_manifold_edges == 0
            && self.misoriented_edges == 0
            && self.degenerate == 0
    }

    /// Also checks that every vertex's triangles form a single fan (no pinched vertices).
    pub fn assert_closed_manifold(&self, what: &str) {
        assert!(self.is_closed_manifold(), "{what}: {self:?}");
    }
}

/// True when every vertex's link is one cycle: no two surface sheets pinch at a vertex.
pub fn vertices_are_manifold(mesh: &Mesh) -> bool {
    let mut around: HashMap<u32, Vec<(u32, u32)>> = HashMap::new();
    for t in &mesh.triangles {
        for i in 0..3 {
            around
                .entry(t[i])
                .or_default()
                .push((t[(i + 1) % 3], t[(i + 2) % 3]));
        }
    }
    around.values().all(|link| {
        // Follow the link edges a → b from one start; a single cycle covers them all.
        let next: HashMap<u32, u32> = link.iter().copied().collect();
        if next.len() != link.len() {
            return false;
        }
        let start = link[0].0;
        let mut x = start;
        let mut steps = 0;
        loop {
            let Some(&y) = next.get(&x) else { return false };
            x = y;
            steps += 1;
            if x == start || steps > link.len() {
                break;
            }
        }
        x == start && steps == link.len()
    })
}
