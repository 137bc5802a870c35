//! The plain data a kind reads: located values, entries and tables.

use std::ops::Range;

/// Where a value or key came from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Loc {
    /// Nowhere known (made in code).
    #[default]
    Unknown,
    /// A byte range of the source text.
    Span(Range<usize>),
    /// A key path such as `objects[2].radius` (a Python dict).
    Path(String),
}

/// A plain value: what TOML and Python dicts have in common.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `true` or `false`.
    Bool(bool),
    /// A whole number.
    Integer(i64),
    /// A floating-point number.
    Number(f64),
    /// A string.
    String(String),
    /// An array of located values.
    Array(Vec<Item>),
    /// A table.
    Table(Table),
}

/// A value and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// The value.
    pub value: Value,
    /// Where it came from.
    pub loc: Loc,
}

/// One key of a table.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The key.
    pub key: String,
    /// Where the key is written.
    pub key_loc: Loc,
    /// Its value.
    pub item: Item,
}

/// A table: keys in the order they were written, and the table's own place.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The entries, in source order.
    pub entries: Vec<Entry>,
    /// Where the table starts.
    pub loc: Loc,
}

impl Table {
    /// The entry for `key`.
    pub fn get(&self, key: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.key == key)
    }

    /// Removes and returns the entry for `key`.
    pub fn remove(&mut self, key: &str) -> Option<Entry> {
        let i = self.entries.iter().position(|e| e.key == key)?;
        Some(self.entries.remove(i))
    }
}

impl Value {
    /// What the value is, for messages: `a number`, `a string "x"`, `an array of 2`.
    pub fn describe(&self) -> String {
        match self {
            Value::Bool(b) => format!("a boolean {b}"),
            Value::Integer(i) => format!("a number {i}"),
            Value::Number(x) => format!("a number {x}"),
            Value::String(s) => format!("a string {s:?}"),
            Value::Array(a) => format!("an array of {}", a.len()),
            Value::Table(_) => "a table".to_string(),
        }
    }
}
