//! JSON parsing that refuses duplicate keys. `serde_json::Value` keeps the last of two equal
//! keys in an object without a word, so `{"radius": 1, "radius": 5}` would silently be a sphere
//! of radius 5 here and of radius 1 in a reader that keeps the first. This builds the same
//! `Value` and fails at the first repeated key, naming its JSON path.

use serde::de::{DeserializeSeed, Deserializer, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};

use super::json::key_path;

/// The marker that starts the message of a duplicate-key error, followed by the path.
const DUPLICATE: &str = "duplicate key at ";

/// Parses `text`; `Err((json_path, message))` for invalid JSON (path `$`) or a repeated key.
pub(super) fn parse(text: &str) -> Result<Value, (String, String)> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value = At("$".into())
        .deserialize(&mut de)
        .and_then(|v| de.end().map(|()| v))
        .map_err(|e| {
            let message = e.to_string();
            match message.strip_prefix(DUPLICATE) {
                Some(rest) => {
                    let path = rest.split(" at line ").next().unwrap_or(rest);
                    (
                        path.to_owned(),
                        format!(
                            "duplicate key (line {}): a key may appear once in an object",
                            e.line()
                        ),
                    )
                }
                None => ("$".to_owned(), format!("not valid JSON: {message}")),
            }
        })?;
    Ok(value)
}

/// A value at a JSON path.
struct At(String);

impl<'de> DeserializeSeed<'de> for At {
    type Value = Value;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for At {
    type Value = Value;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element_seed(At(format!("{}[{}]", self.0, items.len())))? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            let path = key_path(&self.0, &key);
            if out.contains_key(&key) {
                return Err(A::Error::custom(format!("{DUPLICATE}{path}")));
            }
            let value = map.next_value_seed(At(path))?;
            out.insert(key, value);
        }
        Ok(Value::Object(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_keys_are_refused_with_their_path() {
        let (path, message) =
            parse(r#"{"tree": {"data": {"radius": 1, "radius": 5}}}"#).unwrap_err();
        assert_eq!(path, "$.tree.data.radius");
        assert!(message.contains("duplicate key"), "{message}");
        let (path, _) = parse(r#"{"children": [{}, {"a": 1, "a": 1}]}"#).unwrap_err();
        assert_eq!(path, "$.children[1].a");
        let v = parse(r#"{"a": [1, 2.5, "x", null, true], "b": {"a": 1}}"#).unwrap();
        assert_eq!(
            v,
            serde_json::json!({"a": [1, 2.5, "x", null, true], "b": {"a": 1}})
        );
        assert_eq!(parse("{").unwrap_err().0, "$");
    }
}
