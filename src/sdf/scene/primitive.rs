//! Primitive nodes' `data`: box, sphere, cylinder, cone, pyramid, plane, torus.

use serde_json::Map;
use serde_json::Value;

use super::json::{
    fault, key_path, non_negative, number, only, positive, positive_vec3, required, string, vec3,
};
use super::parser::Parser;
use crate::error::Result;
use crate::sdf::shapes::Shape;

impl Parser {
    pub(super) fn primitive(&mut self, d: &Map<String, Value>, path: &str) -> Result<(Shape, u32)> {
        let tp = key_path(path, "primitive_type");
        let ty = string(
            required(
                d,
                path,
                "primitive_type",
                "box, sphere, cylinder, cone, pyramid, plane or torus",
            )?,
            &tp,
        )?;
        let fields: &[&str] = match ty {
            "box" => &["size"],
            "sphere" => &["radius"],
            "cylinder" => &["radius", "height"],
            "cone" => &["radius", "height", "radius_top"],
            "pyramid" => &["base", "height"],
            "plane" => &["normal", "offset"],
            "torus" => &["radius", "tube_radius"],
            other => {
                return Err(fault(
                    &tp,
                    format!(
                        "unknown primitive_type `{other}`; expected box, sphere, cylinder, cone, \
                         pyramid, plane or torus"
                    ),
                ));
            }
        };
        let mut allowed = vec!["primitive_type", "material", "name"];
        allowed.extend_from_slice(fields);
        only(d, path, &allowed, &format!("a {ty} primitive"))?;
        let shape = shape(ty, d, path)?;
        let material = self.optional_material(d, path)?;
        Ok((shape, material))
    }
}

/// The shape of a primitive whose `primitive_type` is `ty` (known) and whose fields were checked.
fn shape(ty: &str, d: &Map<String, Value>, path: &str) -> Result<Shape> {
    let get = |key: &str, why: &str| -> Result<f64> {
        positive(required(d, path, key, why)?, &key_path(path, key))
    };
    Ok(match ty {
        "box" => Shape::Box {
            half: positive_vec3(
                required(d, path, "size", "[x, y, z] edge lengths")?,
                &key_path(path, "size"),
            )? * 0.5,
        },
        "sphere" => Shape::Sphere {
            radius: get("radius", "the sphere's radius")?,
        },
        "cylinder" => Shape::Cylinder {
            radius: get("radius", "the cylinder's radius")?,
            half_height: 0.5 * get("height", "the cylinder's height along Y")?,
        },
        "cone" => Shape::Cone {
            r_bottom: get("radius", "the cone's base radius")?,
            r_top: match d.get("radius_top") {
                Some(v) => non_negative(v, &key_path(path, "radius_top"))?,
                None => 0.0,
            },
            half_height: 0.5 * get("height", "the cone's height along Y")?,
        },
        "pyramid" => Shape::Pyramid {
            base: get("base", "the side of the square base")?,
            height: get("height", "the pyramid's height along Y")?,
        },
        "plane" => {
            let np = key_path(path, "normal");
            let n = vec3(
                required(d, path, "normal", "[x, y, z], pointing out of the solid")?,
                &np,
            )?;
            let normal = n
                .try_normalize()
                .ok_or_else(|| fault(&np, "the normal must not be zero"))?;
            let offset = match d.get("offset") {
                Some(v) => number(v, &key_path(path, "offset"))?,
                None => 0.0,
            };
            Shape::Plane { normal, offset }
        }
        _ => {
            let major = get("radius", "the distance from the axis to the tube's centre")?;
            let minor = get("tube_radius", "the tube's radius")?;
            if minor >= major {
                return Err(fault(
                    &key_path(path, "tube_radius"),
                    format!("must be smaller than radius ({major}), found {minor}"),
                ));
            }
            Shape::Torus { major, minor }
        }
    })
}
