//! A small JSON writer for the answers. serde_json would cost about 30 KB of the wasm
//! module (a tenth of it) for what is here a few dozen lines: the answers are built once
//! and written once, and nothing is parsed (requests arrive as numbers).

use std::fmt::Write as _;

/// A JSON value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Null,
    Bool(bool),
    /// Written in Rust's shortest round-trip form; a non-finite number is written `null`.
    Num(f64),
    Str(String),
    Array(Vec<Value>),
    Object(Vec<(&'static str, Value)>),
    /// JSON text written as it is: an answer another crate built (the part's document,
    /// `rotlang_geometry::slice::json`, which the CLI prints too).
    Raw(String),
}

/// Builds a [`Value::Object`]: `obj!({ "key": expr, ... })`. Values are taken by
/// reference through [`ToJson`].
#[macro_export]
macro_rules! obj {
    ({ $($key:literal : $value:expr),* $(,)? }) => {
        $crate::json::Value::Object(vec![$(($key, $crate::json::ToJson::to_json(&$value))),*])
    };
}

/// Conversion to a JSON value, by reference (so fields need not be moved or cloned).
pub trait ToJson {
    fn to_json(&self) -> Value;
}

impl ToJson for Value {
    fn to_json(&self) -> Value {
        self.clone()
    }
}
impl ToJson for bool {
    fn to_json(&self) -> Value {
        Value::Bool(*self)
    }
}
impl ToJson for str {
    fn to_json(&self) -> Value {
        Value::Str(self.to_owned())
    }
}
impl ToJson for String {
    fn to_json(&self) -> Value {
        Value::Str(self.clone())
    }
}
macro_rules! numbers {
    ($($t:ty),*) => {$(
        impl ToJson for $t {
            // Counts and offsets stay far below 2^53: exact as f64.
            #[allow(clippy::cast_precision_loss, clippy::cast_lossless)]
            fn to_json(&self) -> Value {
                Value::Num(*self as f64)
            }
        }
    )*};
}
numbers!(f64, usize, u32, i32, u64);
impl<T: ToJson + ?Sized> ToJson for &T {
    fn to_json(&self) -> Value {
        (**self).to_json()
    }
}
impl<T: ToJson> ToJson for Option<T> {
    fn to_json(&self) -> Value {
        self.as_ref().map_or(Value::Null, ToJson::to_json)
    }
}
impl<T: ToJson> ToJson for [T] {
    fn to_json(&self) -> Value {
        Value::Array(self.iter().map(ToJson::to_json).collect())
    }
}
impl<T: ToJson> ToJson for Vec<T> {
    fn to_json(&self) -> Value {
        self.as_slice().to_json()
    }
}

impl FromIterator<Value> for Value {
    fn from_iter<I: IntoIterator<Item = Value>>(iter: I) -> Value {
        Value::Array(iter.into_iter().collect())
    }
}

impl Value {
    /// The fields of `other` appended to this object's (both must be objects).
    pub fn merged(mut self, other: Value) -> Value {
        if let (Value::Object(a), Value::Object(b)) = (&mut self, other) {
            a.extend(b);
        }
        self
    }

    pub fn write(&self, out: &mut String) {
        match self {
            Value::Null => out.push_str("null"),
            Value::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
            Value::Num(x) if x.is_finite() => {
                // Display of f64 is the shortest round-trip form, without exponent.
                let _ = write!(out, "{x}");
            }
            Value::Num(_) => out.push_str("null"),
            Value::Str(s) => string(s, out),
            Value::Raw(text) => out.push_str(text),
            Value::Array(items) => {
                out.push('[');
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    v.write(out);
                }
                out.push(']');
            }
            Value::Object(fields) => {
                out.push('{');
                for (i, (k, v)) in fields.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    string(k, out);
                    out.push(':');
                    v.write(out);
                }
                out.push('}');
            }
        }
    }
}

fn string(s: &str, out: &mut String) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

#[cfg(test)]
mod tests {

    #[test]
    fn writes_valid_json() {
        let v = obj!({
            "s": "a\"b\\c\n\u{1}°𝕏",
            "n": 0.1 + 0.2,
            "i": 42usize,
            "neg": -3i32,
            "nan": f64::NAN,
            "big": 1e21,
            "none": None::<u32>,
            "list": vec![1u32, 2],
            "t": true,
        });
        let mut out = String::new();
        v.write(&mut out);
        assert_eq!(
            out,
            r#"{"s":"a\"b\\c\n\u0001°𝕏","n":0.30000000000000004,"i":42,"neg":-3,"nan":null,"big":1000000000000000000000,"none":null,"list":[1,2],"t":true}"#
        );
    }
}
