//! Cutting one operand's edges by the other's knife tree into in, out and on parts.
//!
//! A piece that lies on a knife's line is on the boundary only where the cells on the two sides
//! of the line differ; so it walks the front subtree to learn the label in front, then the back
//! subtree to learn the label behind, and the pair decides: (out, in) is boundary facing the
//! knife's way, (in, out) boundary facing the other way, equal labels are plain in or out.

use glam::DVec2;

use super::knife::{Frag, KnifeTree, Label, Link, Side, side};

/// Where a piece of an edge lies relative to the other operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Class {
    Inside,
    Outside,
    /// On the boundary, the other operand's outward normal the same as the edge's.
    OnSame,
    /// On the boundary, the other operand's outward normal opposite to the edge's.
    OnOpposite,
}

#[derive(Clone, Copy)]
enum Phase {
    /// An ordinary walk.
    Open,
    /// On the line of `node`, walking its front subtree.
    OnFront { node: u32 },
    /// On the line of `node`, walking its back subtree; the front side was `front`.
    OnBack { node: u32, front: Label },
}

/// Cuts `edges` (region on their left) by `tree` and calls `emit` for every piece.
pub(super) fn classify(
    tree: &KnifeTree,
    edges: &[[DVec2; 2]],
    eps: f64,
    mut emit: impl FnMut(Frag, Class),
) {
    let margin = 2.0 * eps;
    let mut stack: Vec<(Frag, Link, Phase)> = edges
        .iter()
        .enumerate()
        .rev()
        .map(|(i, &e)| (Frag::whole(i as u32, e), tree.root, Phase::Open))
        .collect();
    while let Some((f, link, phase)) = stack.pop() {
        let i = match link {
            Link::Leaf(label) => {
                match phase {
                    Phase::Open => emit(f, plain(label)),
                    Phase::OnFront { node } => stack.push((
                        f,
                        tree.nodes[node as usize].back,
                        Phase::OnBack { node, front: label },
                    )),
                    Phase::OnBack { node, front } => {
                        let same =
                            normal(&f, edges).dot(tree.nodes[node as usize].line.normal) > 0.0;
                        let class = match (front, label) {
                            (Label::Outside, Label::Inside) if same => Class::OnSame,
                            (Label::Outside, Label::Inside) => Class::OnOpposite,
                            (Label::Inside, Label::Outside) if same => Class::OnOpposite,
                            (Label::Inside, Label::Outside) => Class::OnSame,
                            (l, _) => plain(l),
                        };
                        emit(f, class);
                    }
                }
                continue;
            }
            Link::Node(i) => i,
        };
        let node = &tree.nodes[i as usize];
        if matches!(phase, Phase::Open) && !f.bbox().overlaps(&node.content, margin) {
            // No edge below comes near: the piece lies in one cell region.
            emit(f, plain(tree.locate(link, 0.5 * (f.a + f.b))));
            continue;
        }
        match side(&node.line, &f, eps) {
            Side::Front => stack.push((f, node.front, phase)),
            Side::Back => stack.push((f, node.back, phase)),
            Side::Spanning(da, db) => {
                let (pf, pb) = f.cut(&node.line, da, db, edges);
                stack.push((pf, node.front, phase));
                stack.push((pb, node.back, phase));
            }
            Side::On => match phase {
                Phase::Open if node.knife => {
                    stack.push((f, node.front, Phase::OnFront { node: i }))
                }
                // A cell line carries no edge: both sides agree.
                Phase::Open => stack.push((f, node.front, phase)),
                // Already on an earlier knife's line: follow the side that faces the same way.
                Phase::OnFront { node: n } | Phase::OnBack { node: n, .. } => {
                    let along = node.line.normal.dot(tree.nodes[n as usize].line.normal) > 0.0;
                    let to_front = along == matches!(phase, Phase::OnFront { .. });
                    let next = if to_front { node.front } else { node.back };
                    stack.push((f, next, phase));
                }
            },
        }
    }
}

fn plain(label: Label) -> Class {
    match label {
        Label::Inside => Class::Inside,
        Label::Outside => Class::Outside,
    }
}

/// The outward normal of the fragment's edge (not normalised).
fn normal(f: &Frag, edges: &[[DVec2; 2]]) -> DVec2 {
    let [a, b] = edges[f.edge as usize];
    let d = b - a;
    DVec2::new(d.y, -d.x)
}
