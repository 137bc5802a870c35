//! [`Located`]: a value with the byte range of the text it came from, when the
//! text is a TOML file, or no range when it came from elsewhere (a Python dict).
//!
//! The `toml` crate hands out spans through a serde convention: a struct named
//! `$__serde_spanned_private_Spanned` whose map has three private keys (this is
//! what `toml::Spanned` does). `Located` asks for that struct; a deserializer
//! that knows the convention answers with the span keys, any other one simply
//! gives the value's own map, which is then read as `T` with no span. So one
//! type serves both paths, and errors found while building still say
//! `file:line:col`. (The names are `serde_spanned`'s; `toml` is pinned to 0.9
//! and the error tests check that positions arrive.)

use std::fmt;
use std::marker::PhantomData;
use std::ops::Range;

use serde::de::{self, DeserializeSeed, IntoDeserializer, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

const NAME: &str = "$__serde_spanned_private_Spanned";
const START: &str = "$__serde_spanned_private_start";
const END: &str = "$__serde_spanned_private_end";
const VALUE: &str = "$__serde_spanned_private_value";
const FIELDS: &[&str] = &[START, END, VALUE];

/// A value and, when known, the byte range of its source text.
#[derive(Clone, Debug, PartialEq)]
pub struct Located<T> {
    /// Byte range in the source text (`None` when the data did not come from text).
    pub span: Option<Range<usize>>,
    /// The value.
    pub value: T,
}

impl<T> Located<T> {
    /// A value with no source position.
    pub fn new(value: T) -> Located<T> {
        Located { span: None, value }
    }
}

impl<T> std::ops::Deref for Located<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Located<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_struct(NAME, FIELDS, LocatedVisitor(PhantomData))
    }
}

struct LocatedVisitor<T>(PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for LocatedVisitor<T> {
    type Value = Located<T>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a table")
    }

    fn visit_map<M: MapAccess<'de>>(self, mut map: M) -> Result<Located<T>, M::Error> {
        let first: Option<String> = map.next_key()?;
        match first.as_deref() {
            Some(START) => {
                let start: usize = map.next_value()?;
                let (mut end, mut value) = (None, None);
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        END => end = Some(map.next_value::<usize>()?),
                        VALUE => value = Some(map.next_value::<T>()?),
                        other => return Err(de::Error::unknown_field(other, FIELDS)),
                    }
                }
                let value = value.ok_or_else(|| de::Error::missing_field(VALUE))?;
                Ok(Located { span: Some(start..end.unwrap_or(start)), value })
            }
            _ => {
                let rest = Replay { first, map };
                Ok(Located::new(T::deserialize(de::value::MapAccessDeserializer::new(rest))?))
            }
        }
    }
}

/// A map whose first key was already read: yields it again, then the rest.
struct Replay<M> {
    first: Option<String>,
    map: M,
}

impl<'de, M: MapAccess<'de>> MapAccess<'de> for Replay<M> {
    type Error = M::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, M::Error> {
        match self.first.take() {
            Some(key) => seed.deserialize(key.into_deserializer()).map(Some),
            None => self.map.next_key_seed(seed),
        }
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, M::Error> {
        self.map.next_value_seed(seed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Point {
        x: f64,
        y: f64,
    }

    #[derive(Debug, Deserialize)]
    struct Doc {
        p: Located<Point>,
    }

    #[test]
    fn toml_gives_the_span() {
        let text = "# c\np = { x = 1, y = 2 }\n";
        let doc: Doc = toml::from_str(text).unwrap();
        assert_eq!(doc.p.value, Point { x: 1.0, y: 2.0 });
        let span = doc.p.span.clone().unwrap();
        assert_eq!(&text[span], "{ x = 1, y = 2 }");
    }

    #[test]
    fn other_deserializers_give_the_value_alone() {
        use std::collections::BTreeMap;
        let mut map = BTreeMap::new();
        map.insert("x".to_string(), 3.0);
        map.insert("y".to_string(), 4.0);
        let de: de::value::MapDeserializer<_, de::value::Error> = map.into_deserializer();
        let p = Located::<Point>::deserialize(de).unwrap();
        assert_eq!(p, Located::new(Point { x: 3.0, y: 4.0 }));
        map_error_names_the_key();
    }

    fn map_error_names_the_key() {
        use std::collections::BTreeMap;
        let mut map = BTreeMap::new();
        map.insert("z".to_string(), 3.0);
        let de: de::value::MapDeserializer<_, de::value::Error> = map.into_deserializer();
        let err = Located::<Point>::deserialize(de).unwrap_err().to_string();
        assert!(err.contains("unknown field `z`"), "{err}");
    }
}
