//! Typed readers of JSON values: each checks one value and names its JSON path when it fails.

use glam::{DVec2, DVec3};
use serde_json::{Map, Value};

use super::MAX_SCENE_MAGNITUDE;
use crate::error::{Error, Result};

pub(super) fn fault(path: &str, message: impl Into<String>) -> Error {
    Error::Scene {
        file: None,
        json_path: path.to_string(),
        message: message.into(),
    }
}

pub(super) fn key_path(path: &str, key: &str) -> String {
    if !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        format!("{path}.{key}")
    } else {
        format!("{path}[{}]", Value::String(key.to_string()))
    }
}

pub(super) fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

pub(super) fn object<'a>(v: &'a Value, path: &str, what: &str) -> Result<&'a Map<String, Value>> {
    v.as_object().ok_or_else(|| {
        fault(
            path,
            format!("expected {what} (an object), found {}", type_name(v)),
        )
    })
}

/// Refuses fields outside `allowed`, naming the first stray one and the expected set.
pub(super) fn only(
    map: &Map<String, Value>,
    path: &str,
    allowed: &[&str],
    context: &str,
) -> Result<()> {
    for k in map.keys() {
        if !allowed.contains(&k.as_str()) {
            let hint = match k.as_str() {
                "pos" | "rot" | "scale" => {
                    " (transforms belong on the node, beside `kind`/`op`, not inside `data`)"
                }
                _ => "",
            };
            return Err(fault(
                &key_path(path, k),
                format!(
                    "unknown field `{k}` in {context}{hint}; expected one of: {}",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

pub(super) fn number(v: &Value, path: &str) -> Result<f64> {
    let x = v
        .as_f64()
        .ok_or_else(|| fault(path, format!("expected a number, found {}", type_name(v))))?;
    if !x.is_finite() || x.abs() > MAX_SCENE_MAGNITUDE {
        return Err(fault(
            path,
            format!("{x} is outside the supported range ±{MAX_SCENE_MAGNITUDE:e}"),
        ));
    }
    Ok(x)
}

pub(super) fn positive(v: &Value, path: &str) -> Result<f64> {
    let x = number(v, path)?;
    if x <= 0.0 {
        return Err(fault(path, format!("must be > 0, found {x}")));
    }
    Ok(x)
}

pub(super) fn non_negative(v: &Value, path: &str) -> Result<f64> {
    let x = number(v, path)?;
    if x < 0.0 {
        return Err(fault(path, format!("must be ≥ 0, found {x}")));
    }
    Ok(x)
}

pub(super) fn count(v: &Value, path: &str, min: u64) -> Result<u32> {
    match v.as_u64() {
        Some(n) if n >= min && n <= u32::MAX as u64 => Ok(n as u32),
        _ => Err(fault(
            path,
            format!("expected a whole number ≥ {min}, found {v}"),
        )),
    }
}

pub(super) fn string<'a>(v: &'a Value, path: &str) -> Result<&'a str> {
    v.as_str()
        .ok_or_else(|| fault(path, format!("expected a string, found {}", type_name(v))))
}

pub(super) fn array<'a>(v: &'a Value, path: &str, len: Option<usize>) -> Result<&'a [Value]> {
    let a = v
        .as_array()
        .ok_or_else(|| fault(path, format!("expected an array, found {}", type_name(v))))?;
    if let Some(n) = len
        && a.len() != n
    {
        return Err(fault(
            path,
            format!("expected {n} numbers, found {}", a.len()),
        ));
    }
    Ok(a)
}

pub(super) fn vec3(v: &Value, path: &str) -> Result<DVec3> {
    let a = array(v, path, Some(3))?;
    Ok(DVec3::new(
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
        number(&a[2], &format!("{path}[2]"))?,
    ))
}

pub(super) fn positive_vec3(v: &Value, path: &str) -> Result<DVec3> {
    let a = array(v, path, Some(3))?;
    Ok(DVec3::new(
        positive(&a[0], &format!("{path}[0]"))?,
        positive(&a[1], &format!("{path}[1]"))?,
        positive(&a[2], &format!("{path}[2]"))?,
    ))
}

pub(super) fn vec2(v: &Value, path: &str) -> Result<DVec2> {
    let a = array(v, path, Some(2))?;
    Ok(DVec2::new(
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
    ))
}

pub(super) fn required<'a>(
    map: &'a Map<String, Value>,
    path: &str,
    key: &str,
    why: &str,
) -> Result<&'a Value> {
    map.get(key)
        .ok_or_else(|| fault(&key_path(path, key), format!("missing `{key}` ({why})")))
}
