//! The editor behind `bspcsg edit`: a scene compiled to a WebGL2 fragment shader ([`glsl`]).

pub mod glsl;
