//! Colours in scene documents: linear RGB(A) arrays, sRGB hex strings, material objects.

use serde_json::Value;

use super::json::{fault, key_path, number, only, required, type_name};
use crate::error::Result;

/// A colour: `[r, g, b]` or `[r, g, b, a]` in linear 0..1, `"#rrggbb"` / `"#rrggbbaa"` in sRGB,
/// or `{"base_color": …}`.
pub(super) fn colour(v: &Value, path: &str) -> Result<[f64; 4]> {
    match v {
        // A material object holds a plain colour, not another material.
        Value::Object(m) => {
            only(m, path, &["base_color", "name"], "a material")?;
            plain_colour(
                required(m, path, "base_color", "the material's colour")?,
                &key_path(path, "base_color"),
            )
        }
        _ => plain_colour(v, path),
    }
}

/// A colour as `[r, g, b(, a)]` or `"#rrggbb(aa)"`.
pub(super) fn plain_colour(v: &Value, path: &str) -> Result<[f64; 4]> {
    match v {
        Value::Array(a) => {
            if !(a.len() == 3 || a.len() == 4) {
                return Err(fault(
                    path,
                    format!("a colour has 3 or 4 components, found {}", a.len()),
                ));
            }
            let mut c = [1.0; 4];
            for (i, x) in a.iter().enumerate() {
                let p = format!("{path}[{i}]");
                let x = number(x, &p)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(fault(
                        &p,
                        format!("colour components lie in 0..1, found {x}"),
                    ));
                }
                c[i] = x;
            }
            Ok(c)
        }
        Value::String(s) => {
            let hex = s.strip_prefix('#').unwrap_or(s);
            if !(hex.len() == 6 || hex.len() == 8) || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
                return Err(fault(
                    path,
                    format!("expected \"#rrggbb\" or \"#rrggbbaa\", found {s:?}"),
                ));
            }
            let mut c = [1.0; 4];
            for (i, slot) in c.iter_mut().enumerate().take(hex.len() / 2) {
                let byte = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16)
                    .map_err(|_| fault(path, "bad hex digit"))?;
                let x = byte as f64 / 255.0;
                // sRGB → linear for the colour channels; alpha is linear already.
                *slot = if i == 3 {
                    x
                } else if x <= 0.04045 {
                    x / 12.92
                } else {
                    ((x + 0.055) / 1.055).powf(2.4)
                };
            }
            Ok(c)
        }
        _ => Err(fault(
            path,
            format!(
                "expected a colour ([r, g, b(, a)], \"#rrggbb\" or {{\"base_color\": …}}), found {}",
                type_name(v)
            ),
        )),
    }
}
