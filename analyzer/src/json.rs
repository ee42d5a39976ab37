//! Strict JSON for the documents users hand us (params, presets libraries, share links): a
//! leading byte-order mark is accepted (editors on Windows write one), a key that appears twice
//! in one object is an error (serde_json keeps the last silently, so
//! `"format": "proctex/9", "format": "proctex/1"` would pass as the second), and parser messages
//! are bounded ([`crate::limits::bounded_message`]) so that a huge bad value is not repeated.

use std::collections::HashSet;
use std::fmt;

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};

use crate::limits::{bounded_message, quote};

/// A JSON value in which no object has a key twice.
struct Unique(Value);

impl<'de> Deserialize<'de> for Unique {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(UniqueVisitor).map(Unique)
    }
}

struct UniqueVisitor;

impl<'de> Visitor<'de> for UniqueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
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
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Value, E> {
        serde_json::Number::from_f64(v)
            .map(Value::Number)
            .ok_or_else(|| E::custom("a number that is not finite"))
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_string()))
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
        let mut out = Vec::new();
        while let Some(Unique(v)) = seq.next_element()? {
            out.push(v);
        }
        Ok(Value::Array(out))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut out = Map::new();
        let mut seen = HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                return Err(de::Error::custom(format_args!(
                    "the key \"{}\" appears twice in one object",
                    quote(&key)
                )));
            }
            let Unique(v) = map.next_value()?;
            out.insert(key, v);
        }
        Ok(Value::Object(out))
    }
}

/// Parses `text` strictly (see the module docs). The error is a bounded message with the line
/// and column.
pub fn parse(text: &str) -> Result<Value, String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    serde_json::from_str::<Unique>(text)
        .map(|u| u.0)
        .map_err(|e| bounded_message(&e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicate_keys_are_refused_at_any_depth() {
        let e = parse(r#"{"format":"proctex/9","format":"proctex/1"}"#).unwrap_err();
        assert!(e.contains("\"format\" appears twice"), "{e}");
        let e = parse(r#"{"a":[{"b":1,"c":{"d":1,"d":2}}]}"#).unwrap_err();
        assert!(e.contains("\"d\" appears twice"), "{e}");
        assert!(parse(r#"{"a":{"d":1},"b":{"d":2}}"#).is_ok());
    }

    #[test]
    fn a_byte_order_mark_is_accepted_and_values_survive() {
        let v = parse("\u{feff}{\"x\": [1, -2, 0.5, true, null, \"s\"]}").unwrap();
        assert_eq!(v, serde_json::json!({"x": [1, -2, 0.5, true, null, "s"]}));
    }

    #[test]
    fn errors_do_not_repeat_huge_values() {
        let huge = format!("{{\"seed\": \"{}\", \"seed\": 1}}", "9".repeat(1_000_000));
        assert!(parse(&huge).unwrap_err().len() < 300);
        assert!(
            parse(&format!("[\"{}", "x".repeat(1_000_000)))
                .unwrap_err()
                .len()
                < 300
        );
    }
}
