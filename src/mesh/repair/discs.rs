//! Vertices whose triangles form one closed disc around them: there the shell split has nothing
//! to pair by angle and nothing to split.

/// For each of the `vertex_count` vertices, whether its triangles form exactly one closed fan
/// in which every edge at the vertex is used once each way.
///
/// The link of a vertex `v` is, per triangle at `v`, the edge from the corner after `v` to the
/// corner before it. When those edges start at distinct vertices and, followed end to start,
/// close into one cycle through all of them, every edge `v→x` is used once and `x→v` once (no
/// other triangle holds both), and each corner's previous edge is twinned with the next
/// corner's: one fan. A vertex where two solids touch (two cycles), an open one (a chain) or
/// one on an edge of more than two triangles (a repeated start) is not a disc. A vertex no
/// triangle uses is not one either.
///
/// Costs one counting pass over the corners and a walk around each vertex's few link edges: far
/// less than pairing every half-edge through a sort by edge and a union–find of the corners.
pub(super) fn one_disc(triangles: &[[u32; 3]], vertex_count: usize) -> Vec<bool> {
    // A counting sort of the corners by vertex: `end[v]` counts up to the end of v's run, and
    // filling backwards leaves it at the run's start.
    let mut end = vec![0u32; vertex_count + 1];
    for &v in triangles.iter().flatten() {
        end[v as usize] += 1;
    }
    let mut sum = 0;
    for e in &mut end[..vertex_count] {
        sum += *e;
        *e = sum;
    }
    end[vertex_count] = sum;
    let mut links = vec![(0u32, 0u32); triangles.len() * 3];
    let mut repeats = false;
    for &[a, b, c] in triangles {
        repeats |= a == b || b == c || a == c;
        for (v, next, prev) in [(a, b, c), (b, c, a), (c, a, b)] {
            let at = &mut end[v as usize];
            *at -= 1;
            links[*at as usize] = (next, prev);
        }
    }
    let mut disc: Vec<bool> = end
        .windows(2)
        .map(|w| one_cycle(&links[w[0] as usize..w[1] as usize]))
        .collect();
    if repeats {
        // A triangle through a vertex twice is no part of a disc (its link would pass through
        // the vertex itself).
        for t in triangles {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                for &v in t {
                    disc[v as usize] = false;
                }
            }
        }
    }
    disc
}

/// Whether the directed edges `link` start at distinct vertices and form one cycle.
///
/// Walks from the first edge, each step to the first edge starting where the last one ended.
/// Where that comes back to the first edge's start after exactly `link.len()` steps, the
/// edges met are all distinct (a repeat would loop without coming back) and so are their starts
/// (the first edge with a start is the only one ever taken from there): every edge, once.
fn one_cycle(link: &[(u32, u32)]) -> bool {
    let Some(&(a, mut at)) = link.first() else {
        return false;
    };
    let mut steps = 1;
    while at != a {
        match link.iter().find(|e| e.0 == at) {
            Some(e) => at = e.1,
            None => return false,
        }
        steps += 1;
        if steps > link.len() {
            return false;
        }
    }
    steps == link.len()
}

#[cfg(test)]
mod tests {
    use super::one_disc;

    /// An octahedron: every vertex one disc of four triangles.
    fn octahedron() -> Vec<[u32; 3]> {
        // 0 +x, 1 −x, 2 +y, 3 −y, 4 +z, 5 −z
        vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ]
    }

    #[test]
    fn a_closed_surface_is_discs_everywhere() {
        assert!(one_disc(&octahedron(), 6).iter().all(|&d| d));
    }

    #[test]
    fn an_open_fan_is_not_a_disc() {
        let mut t = octahedron();
        t.pop();
        let disc = one_disc(&t, 6);
        // The removed triangle's corners 0, 3, 5 are open; 1, 2, 4 stay closed.
        assert_eq!(disc, [false, true, true, false, true, false]);
    }

    #[test]
    fn two_solids_touching_at_a_vertex_are_not_a_disc_there() {
        // Two octahedra sharing vertex 0 (the second's −x corner is the first's +x).
        let mut t = octahedron();
        let map = [6, 0, 7, 8, 9, 10];
        t.extend(octahedron().iter().map(|tri| tri.map(|v| map[v as usize])));
        let disc = one_disc(&t, 11);
        assert!(!disc[0]);
        assert!(disc[1..].iter().all(|&d| d));
    }

    #[test]
    fn an_edge_of_four_triangles_is_not_a_disc_at_its_ends() {
        // Two octahedra sharing the edge 0–2.
        let mut t = octahedron();
        let map = [0, 6, 2, 7, 8, 9];
        t.extend(octahedron().iter().map(|tri| tri.map(|v| map[v as usize])));
        let disc = one_disc(&t, 10);
        assert!(!disc[0] && !disc[2]);
        assert!(disc[3] && disc[6]);
    }

    #[test]
    fn a_triangle_repeating_a_vertex_is_no_disc() {
        let mut t = octahedron();
        t.push([0, 0, 2]);
        let disc = one_disc(&t, 6);
        assert!(!disc[0] && !disc[2]);
    }

    #[test]
    fn an_unused_vertex_is_not_a_disc() {
        assert!(!one_disc(&octahedron(), 7)[6]);
    }
}
