//! The editor behind `bspcsg edit`: a scene compiled to a WebGL2 fragment shader ([`glsl`]),
//! and the requests the editor's page makes, answered without a network stack ([`api`]) so
//! the command line's server only moves bytes.

pub mod glsl;

pub mod api;
