//! The header dict of a `.npy` file, parsed strictly: a Python literal
//! `{'descr': '<f4', 'fortran_order': False, 'shape': (N, 3), }` with exactly
//! these three keys in any order, single- or double-quoted strings, and an
//! optional trailing comma; the rest of the header is spaces and one newline.

/// The three fields of a header.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Header {
    /// Element type, e.g. `<f4`.
    pub descr: String,
    /// Column-major data.
    pub fortran_order: bool,
    /// Dimensions, each as written (any `u64`; sizes are checked by the caller).
    pub shape: Vec<u64>,
}

/// A value in the dict.
enum Value {
    Str(String),
    Bool(bool),
    Tuple(Vec<u64>),
}

struct Parser<'a> {
    text: &'a str,
    at: usize,
}

impl Parser<'_> {
    fn skip_space(&mut self) {
        let rest = &self.text[self.at..];
        self.at += rest.len() - rest.trim_start_matches([' ', '\t']).len();
    }

    /// Consumes `token` after optional spaces.
    fn eat(&mut self, token: &str) -> bool {
        self.skip_space();
        let found = self.text[self.at..].starts_with(token);
        if found {
            self.at += token.len();
        }
        found
    }

    fn expect(&mut self, token: &str) -> Result<(), String> {
        if self.eat(token) {
            Ok(())
        } else {
            Err(format!("expected '{token}' at byte {}", self.at))
        }
    }

    fn string(&mut self) -> Result<String, String> {
        self.skip_space();
        let quote = match self.text[self.at..].chars().next() {
            Some(q @ ('\'' | '"')) => q,
            _ => return Err(format!("expected a quoted string at byte {}", self.at)),
        };
        let body = &self.text[self.at + 1..];
        let end = body.find(quote).ok_or_else(|| format!("unterminated string at byte {}", self.at))?;
        if body[..end].contains('\\') {
            return Err(format!("escape sequences are not supported (string at byte {})", self.at));
        }
        self.at += end + 2;
        Ok(body[..end].to_string())
    }

    fn integer(&mut self) -> Result<u64, String> {
        self.skip_space();
        let rest = &self.text[self.at..];
        let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        if digits == 0 {
            return Err(format!("expected a non-negative integer at byte {}", self.at));
        }
        let value = rest[..digits].parse::<u64>().map_err(|_| format!("dimension {} does not fit in 64 bits", &rest[..digits]))?;
        self.at += digits;
        Ok(value)
    }

    fn value(&mut self) -> Result<Value, String> {
        if self.eat("True") {
            return Ok(Value::Bool(true));
        }
        if self.eat("False") {
            return Ok(Value::Bool(false));
        }
        if self.eat("(") {
            let mut dims = Vec::new();
            loop {
                if self.eat(")") {
                    return Ok(Value::Tuple(dims));
                }
                dims.push(self.integer()?);
                if !self.eat(",") {
                    self.expect(")")?;
                    // `(3)` is an integer in Python, not a tuple.
                    if dims.len() == 1 {
                        return Err("a one-element shape needs a trailing comma, as in (3,)".into());
                    }
                    return Ok(Value::Tuple(dims));
                }
            }
        }
        Ok(Value::Str(self.string()?))
    }
}

/// Parses the header text (everything between the length field and the data).
pub fn parse(text: &str) -> Result<Header, String> {
    let mut p = Parser { text, at: 0 };
    p.expect("{")?;
    let (mut descr, mut fortran_order, mut shape) = (None, None, None);
    loop {
        if p.eat("}") {
            break;
        }
        let key = p.string()?;
        if !["descr", "fortran_order", "shape"].contains(&key.as_str()) {
            return Err(format!("unexpected key '{key}'"));
        }
        p.expect(":")?;
        let value = p.value()?;
        let slot_taken = match (key.as_str(), value) {
            ("descr", Value::Str(s)) => descr.replace(s).is_some(),
            ("fortran_order", Value::Bool(b)) => fortran_order.replace(b).is_some(),
            ("shape", Value::Tuple(t)) => shape.replace(t).is_some(),
            _ => return Err(format!("'{key}' has the wrong type")),
        };
        if slot_taken {
            return Err(format!("'{key}' appears twice"));
        }
        if !p.eat(",") {
            p.expect("}")?;
            break;
        }
    }
    let rest = &text[p.at..];
    if !rest.trim_end_matches(['\n']).trim_matches(' ').is_empty() || !rest.ends_with('\n') {
        return Err("the dict must be followed by spaces and a newline only".into());
    }
    match (descr, fortran_order, shape) {
        (Some(descr), Some(fortran_order), Some(shape)) => Ok(Header { descr, fortran_order, shape }),
        _ => Err("'descr', 'fortran_order' and 'shape' are all required".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numpy_headers_parse() {
        let h = parse("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }          \n").unwrap();
        assert_eq!(h, Header { descr: "<f4".into(), fortran_order: false, shape: vec![2, 3] });
        let h = parse("{\"shape\": (7,), \"fortran_order\": True, \"descr\": \"<i8\"}\n").unwrap();
        assert_eq!(h, Header { descr: "<i8".into(), fortran_order: true, shape: vec![7] });
        assert_eq!(parse("{'descr': '<f8', 'fortran_order': False, 'shape': (), }\n").unwrap().shape, Vec::<u64>::new());
        assert_eq!(parse("{'descr':'<f8','fortran_order':False,'shape':(18446744073709551615,3)}\n").unwrap().shape[0], u64::MAX);
    }

    #[test]
    fn malformed_headers_say_what_was_expected() {
        let cases = [
            ("'descr': '<f4'}\n", "expected '{' at byte 0"),
            ("{'descr': '<f4', 'fortran_order': False}\n", "'descr', 'fortran_order' and 'shape' are all required"),
            ("{'descr': '<f4', 'fortran_order': False, 'shape': (-1, 3)}\n", "expected a non-negative integer at byte 51"),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (18446744073709551616, 3)}\n",
                "dimension 18446744073709551616 does not fit in 64 bits",
            ),
            ("{'descr': '<f4', 'fortran_order': False, 'shape': (3)}\n", "a one-element shape needs a trailing comma, as in (3,)"),
            ("{'descr': '<f4', 'fortran_order': 0, 'shape': (3,)}\n", "expected a quoted string at byte 34"),
            ("{'descr': '<f4', 'fortran_order': 'no', 'shape': (3,)}\n", "'fortran_order' has the wrong type"),
            ("{'descr': '<f4', 'descr': '<f4', 'shape': (3,)}\n", "'descr' appears twice"),
            ("{'descr': '<f4', 'fortran_order': False, 'shape': (3,), 'x': 1}\n", "unexpected key 'x'"),
            ("{'descr': '<f4', 'fortran_order': False, 'shape': (3,)} junk\n", "the dict must be followed by spaces and a newline only"),
            ("{'descr': '<f4', 'fortran_order': False, 'shape': (3,)}", "the dict must be followed by spaces and a newline only"),
            ("{'descr': '<f4\n", "unterminated string at byte 10"),
        ];
        for (text, want) in cases {
            assert_eq!(parse(text).unwrap_err(), want, "{text:?}");
        }
    }
}
