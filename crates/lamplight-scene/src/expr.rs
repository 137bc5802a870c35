//! Expressions in `x`, `y`, `z` for implicit surfaces, compiled once to a small
//! stack program.
//!
//! Grammar (usual precedence, `^` binds tighter than unary minus and is right
//! associative, so `-x^2 = -(x^2)`):
//!
//! ```text
//! expr  = term (("+" | "-") term)*
//! term  = unary (("*" | "/") unary)*
//! unary = "-" unary | power
//! power = atom ("^" unary)?
//! atom  = number | x | y | z | pi | e | name "(" expr ("," expr)* ")" | "(" expr ")"
//! ```
//!
//! Functions: `sin cos tan sqrt abs exp ln min max pow`. Written by hand rather
//! than taken from an expression crate because the input is untrusted (fuzzed):
//! nesting is limited (no stack overflow on `((((...`), the program's stack depth
//! is known at compile time so evaluation per ray allocates nothing, and errors
//! name the column.

/// Deepest nesting of parentheses and operators.
const MAX_NESTING: usize = 48;
/// Longest expression, in bytes.
pub const MAX_LEN: usize = 4096;
/// Deepest evaluation stack.
const STACK: usize = 64;

#[derive(Clone, Copy, Debug)]
enum Op {
    Const(f64),
    Var(usize),
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Min,
    Max,
    Fn1(fn(f64) -> f64),
}

/// A compiled expression `f(x, y, z)`.
#[derive(Clone, Debug)]
pub struct Expr {
    ops: Vec<Op>,
}

/// A compile error: byte column (from 0) in the expression and what was expected.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    /// Byte offset in the expression.
    pub offset: usize,
    /// What was wrong.
    pub message: String,
}

impl Expr {
    /// Compiles `text`.
    pub fn compile(text: &str) -> Result<Expr, ExprError> {
        if text.len() > MAX_LEN {
            return Err(ExprError { offset: 0, message: format!("expression longer than {MAX_LEN} bytes") });
        }
        let mut p = Parser { s: text.as_bytes(), i: 0, ops: Vec::new(), depth: 0 };
        p.expr()?;
        p.skip_ws();
        if p.i < p.s.len() {
            return Err(p.err("expected an operator or the end of the expression"));
        }
        let mut depth = 0usize;
        for op in &p.ops {
            depth = match op {
                Op::Const(_) | Op::Var(_) => depth + 1,
                Op::Neg | Op::Fn1(_) => depth,
                _ => depth - 1,
            };
            if depth > STACK {
                return Err(ExprError { offset: 0, message: "expression needs too deep a stack".into() });
            }
        }
        Ok(Expr { ops: p.ops })
    }

    /// `f(x, y, z)`.
    pub fn eval(&self, x: f64, y: f64, z: f64) -> f64 {
        let vars = [x, y, z];
        let mut stack = [0.0f64; STACK];
        let mut n = 0;
        for op in &self.ops {
            match *op {
                Op::Const(c) => {
                    stack[n] = c;
                    n += 1;
                }
                Op::Var(i) => {
                    stack[n] = vars[i];
                    n += 1;
                }
                Op::Neg => stack[n - 1] = -stack[n - 1],
                Op::Fn1(f) => stack[n - 1] = f(stack[n - 1]),
                binary => {
                    let (a, b) = (stack[n - 2], stack[n - 1]);
                    n -= 1;
                    stack[n - 1] = match binary {
                        Op::Add => a + b,
                        Op::Sub => a - b,
                        Op::Mul => a * b,
                        Op::Div => a / b,
                        Op::Pow => pow(a, b),
                        Op::Min => a.min(b),
                        _ => a.max(b),
                    };
                }
            }
        }
        stack[0]
    }
}

/// `a^b`, with small integer exponents as exact products (so `x^2` of a negative `x` is positive and fast).
fn pow(a: f64, b: f64) -> f64 {
    if b == 2.0 {
        a * a
    } else if b.fract() == 0.0 && b.abs() <= 64.0 {
        a.powi(b as i32)
    } else {
        a.powf(b)
    }
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    ops: Vec<Op>,
    depth: usize,
}

impl Parser<'_> {
    fn err(&self, message: &str) -> ExprError {
        ExprError { offset: self.i, message: message.to_string() }
    }

    fn skip_ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.s.get(self.i).copied()
    }

    fn enter(&mut self) -> Result<(), ExprError> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            return Err(self.err("expression nested too deeply"));
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<(), ExprError> {
        self.enter()?;
        self.term()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            self.term()?;
            self.ops.push(if c == b'+' { Op::Add } else { Op::Sub });
        }
        self.depth -= 1;
        Ok(())
    }

    fn term(&mut self) -> Result<(), ExprError> {
        self.unary()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            self.unary()?;
            self.ops.push(if c == b'*' { Op::Mul } else { Op::Div });
        }
        Ok(())
    }

    fn unary(&mut self) -> Result<(), ExprError> {
        self.enter()?;
        if self.peek() == Some(b'-') {
            self.i += 1;
            self.unary()?;
            self.ops.push(Op::Neg);
        } else {
            self.atom()?;
            if self.peek() == Some(b'^') {
                self.i += 1;
                self.unary()?;
                self.ops.push(Op::Pow);
            }
        }
        self.depth -= 1;
        Ok(())
    }

    fn atom(&mut self) -> Result<(), ExprError> {
        match self.peek() {
            Some(b'(') => {
                self.i += 1;
                self.expr()?;
                self.expect(b')')
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() => self.name(),
            _ => Err(self.err("expected a number, x, y, z, a function or '('")),
        }
    }

    fn expect(&mut self, c: u8) -> Result<(), ExprError> {
        if self.peek() == Some(c) {
            self.i += 1;
            Ok(())
        } else {
            Err(self.err(&format!("expected '{}'", c as char)))
        }
    }

    fn number(&mut self) -> Result<(), ExprError> {
        let start = self.i;
        while self.i < self.s.len() && (self.s[self.i].is_ascii_digit() || self.s[self.i] == b'.') {
            self.i += 1;
        }
        if self.i < self.s.len() && matches!(self.s[self.i], b'e' | b'E') {
            let mark = self.i;
            self.i += 1;
            if self.i < self.s.len() && matches!(self.s[self.i], b'+' | b'-') {
                self.i += 1;
            }
            let digits = self.i;
            while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                self.i += 1;
            }
            if self.i == digits {
                self.i = mark; // `2e` is 2 times the constant e? no: leave it to the name rule below
            }
        }
        let text = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => {
                self.ops.push(Op::Const(v));
                Ok(())
            }
            _ => Err(ExprError { offset: start, message: format!("'{text}' is not a finite number") }),
        }
    }

    fn name(&mut self) -> Result<(), ExprError> {
        let start = self.i;
        while self.i < self.s.len() && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_') {
            self.i += 1;
        }
        let name = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
        let op = match name {
            "x" => Op::Var(0),
            "y" => Op::Var(1),
            "z" => Op::Var(2),
            "pi" => Op::Const(std::f64::consts::PI),
            "e" => Op::Const(std::f64::consts::E),
            _ => return self.call(name, start),
        };
        self.ops.push(op);
        Ok(())
    }

    fn call(&mut self, name: &str, start: usize) -> Result<(), ExprError> {
        let (arity, op) = match name {
            "sin" => (1, Op::Fn1(f64::sin)),
            "cos" => (1, Op::Fn1(f64::cos)),
            "tan" => (1, Op::Fn1(f64::tan)),
            "sqrt" => (1, Op::Fn1(f64::sqrt)),
            "abs" => (1, Op::Fn1(f64::abs)),
            "exp" => (1, Op::Fn1(f64::exp)),
            "ln" => (1, Op::Fn1(f64::ln)),
            "min" => (2, Op::Min),
            "max" => (2, Op::Max),
            "pow" => (2, Op::Pow),
            _ => {
                return Err(ExprError {
                    offset: start,
                    message: {
                        let names = ["x", "y", "z", "pi", "e", "sin", "cos", "tan", "sqrt", "abs", "exp", "ln", "min", "max", "pow"];
                        let hint =
                            lamplight_core::params::suggestion(name, names).map(|s| format!("did you mean '{s}'? ")).unwrap_or_default();
                        format!("unknown name '{name}' ({hint}variables: x, y, z; constants: pi, e; functions: sin, cos, tan, sqrt, abs, exp, ln, min, max, pow)")
                    },
                })
            }
        };
        self.expect(b'(')?;
        for k in 0..arity {
            if k > 0 {
                self.expect(b',')?;
            }
            self.expr()?;
        }
        self.expect(b')')?;
        self.ops.push(op);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(s: &str, x: f64, y: f64, z: f64) -> f64 {
        Expr::compile(s).unwrap().eval(x, y, z)
    }

    #[test]
    fn precedence_and_functions() {
        assert_eq!(eval("1 + 2 * 3", 0.0, 0.0, 0.0), 7.0);
        assert_eq!(eval("-x^2", 3.0, 0.0, 0.0), -9.0);
        assert_eq!(eval("2^3^2", 0.0, 0.0, 0.0), 512.0, "right associative");
        assert_eq!(eval("(x - y) / z", 7.0, 1.0, 2.0), 3.0);
        assert_eq!(eval("max(x, min(y, z)) + sqrt(16) + abs(-1)", 1.0, 5.0, 3.0), 8.0);
        assert_eq!(eval("1.5e2 + 2E-1", 0.0, 0.0, 0.0), 150.2);
        let torus = "(x*x+y*y+z*z+R*R-r*r)^2 - 4*R*R*(x*x+y*y)".replace('R', "1").replace('r', "0.25");
        assert_eq!(eval(&torus, 1.25, 0.0, 0.0), 0.0, "a point on the tube");
        assert!((eval("sin(pi/2) + ln(e)", 0.0, 0.0, 0.0) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn a_misspelt_function_names_the_nearest() {
        let err = Expr::compile("sqr(x)").unwrap_err();
        assert!(err.message.starts_with("unknown name 'sqr' (did you mean 'sqrt'? variables: x, y, z;"), "{}", err.message);
    }

    #[test]
    fn errors_name_the_offset() {
        let err = |s: &str| Expr::compile(s).unwrap_err();
        assert_eq!(err("x +").offset, 3);
        assert_eq!(err("x + w").message.split(' ').take(3).collect::<Vec<_>>(), ["unknown", "name", "'w'"]);
        assert_eq!(err("(x").message, "expected ')'");
        assert_eq!(err("x y").message, "expected an operator or the end of the expression");
        assert_eq!(err("min(x)").message, "expected ','");
        assert_eq!(err(&"(".repeat(1000)).message, "expression nested too deeply");
        assert_eq!(err(&"-".repeat(1000)).message, "expression nested too deeply");
        assert_eq!(err("1e999").message, "'1e999' is not a finite number");
    }
}
