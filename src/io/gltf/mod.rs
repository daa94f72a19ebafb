//! glTF 2.0: `.gltf` (external or embedded buffers) and `.glb`, in and out.
//!
//! The `gltf` crate parses and validates the JSON; the binary container, the buffers and the
//! accessors are read here, with checked arithmetic, because the crate's own readers assume
//! well-formed files (a GLB length below 12 or an accessor count of 0 underflows, an attribute
//! of the wrong type trips a debug assertion).
//!
//! - `container.rs`: the GLB container, split and assembled;
//! - `uri.rs`: buffers from the GLB chunk, `data:` URIs or files beside the document;
//! - `scene.rs`: reading: the document checked, the scenes walked, node transforms applied;
//! - `accessor.rs`: primitives' positions and indices out of the buffers;
//! - `write.rs`: meshes out, one primitive per source id.

mod accessor;
mod container;
mod scene;
mod uri;
mod write;

pub(crate) use scene::read;
pub(crate) use uri::percent_decode;
pub(crate) use write::write;
