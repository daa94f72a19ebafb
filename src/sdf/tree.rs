//! The evaluable tree: an arena of nodes with local transforms, as the scene parser builds it.
//! Everything that walks it uses an explicit stack, so a deep document cannot overflow ours.

use glam::{DAffine3, DVec3};

use super::shapes::Shape;
use crate::geom::euler_degrees;
use crate::solid::BoolOp;

/// Index of a node in [`Tree::nodes`].
pub(crate) type NodeId = u32;

/// How a smooth operation blends.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum SmoothKind {
    /// The spec's log-sum-exp: `smooth_union = −ln(e^(−k·a) + e^(−k·b)) / k`. `k` is a
    /// sharpness in 1/length: the blend deepens a crease by at most `ln 2 / k`.
    #[default]
    Exponential,
    /// Seed 000's quadratic polynomial smooth minimum. `k` is a blend width in length units:
    /// the two shapes blend where their distances differ by less than `k`, deepening a crease
    /// by at most `k / 4`.
    Polynomial,
}

/// A node's placement in its parent's frame: `p_parent = pos + R · (scale ⊙ p_local)`, where
/// `R` rotates first about X, then Y, then Z (fixed axes, degrees), as `Solid::rotate_euler`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Transform {
    pub pos: DVec3,
    pub rot: DVec3,
    pub scale: DVec3,
}

impl Default for Transform {
    fn default() -> Self {
        Transform {
            pos: DVec3::ZERO,
            rot: DVec3::ZERO,
            scale: DVec3::ONE,
        }
    }
}

impl Transform {
    pub(crate) fn is_identity(&self) -> bool {
        *self == Transform::default()
    }

    /// Local → parent.
    pub(crate) fn affine(&self) -> DAffine3 {
        DAffine3::from_scale_rotation_translation(self.scale, euler_degrees(self.rot), self.pos)
    }

    /// The smallest and largest stretch of the map: the scale factors' magnitudes (the
    /// rotation is orthonormal).
    pub(crate) fn stretch(&self) -> (f64, f64) {
        let s = self.scale.abs();
        (s.min_element(), s.max_element())
    }
}

#[derive(Clone, Debug)]
pub(crate) enum NodeKind {
    Leaf {
        shape: Shape,
        /// Index into the scene's material list (= mesh source id).
        material: u32,
    },
    Op {
        op: BoolOp,
        /// `(kind, k)` for the smooth variants, `k` in the node's local units.
        smooth: Option<(SmoothKind, f64)>,
        children: Vec<NodeId>,
    },
}

#[derive(Clone, Debug)]
pub(crate) struct Node {
    pub transform: Transform,
    pub kind: NodeKind,
}

/// The arena. A scene's root is the last node the parser adds.
#[derive(Clone, Debug, Default)]
pub(crate) struct Tree {
    pub nodes: Vec<Node>,
}

impl Tree {
    pub(crate) fn push(&mut self, node: Node) -> NodeId {
        self.nodes.push(node);
        (self.nodes.len() - 1) as NodeId
    }

    pub(crate) fn node(&self, id: NodeId) -> &Node {
        &self.nodes[id as usize]
    }
}

/// Where a node sits in the world: the composite map and its stretch bounds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    /// Local → world.
    pub to_world: DAffine3,
    /// Product of the smallest stretches on the path: world distances are at least this many
    /// times local ones, so `σ · d_local` never overestimates.
    pub sigma: f64,
    /// Product of the largest stretches on the path.
    pub sigma_max: f64,
}

impl Frame {
    pub(crate) const WORLD: Frame = Frame {
        to_world: DAffine3::IDENTITY,
        sigma: 1.0,
        sigma_max: 1.0,
    };

    pub(crate) fn child(&self, t: &Transform) -> Frame {
        if t.is_identity() {
            return *self;
        }
        let (lo, hi) = t.stretch();
        Frame {
            to_world: self.to_world * t.affine(),
            sigma: self.sigma * lo,
            sigma_max: self.sigma_max * hi,
        }
    }

    /// How far a local distance can stretch relative to the bound `σ · d` (≥ 1).
    pub(crate) fn condition(&self) -> f64 {
        self.sigma_max / self.sigma
    }
}
