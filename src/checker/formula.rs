//! Formulas as answers: a small recursive-descent parser and evaluator for expressions in a
//! question's symbols, with 3-vectors as values, and equivalence by evaluation at random points
//! (the way PrairieLearn's symbolic input grades).
//!
//! The grammar, loosest binding first:
//!
//! ```text
//! sum     = product { ("+" | "-") product }
//! product = unary { ("*" | "/") unary }
//! unary   = "-" unary | power
//! power   = atom [ "^" unary ]            (scalars only; right-associative)
//! atom    = number | symbol | symbol "_" ("x" | "y" | "z") | call | "(" sum ")"
//! call    = ("dot" | "cross" | "max") "(" sum "," sum ")" | ("norm" | "sqrt" | "abs") "(" sum ")"
//! ```
//!
//! The expression crates on crates.io that were considered (`evalexpr`, `meval`) evaluate
//! scalars only; the homework's formulas need vectors, `dot` and `cross`, and a type check that
//! says "a vector is asked" before any number is drawn, so the parser is written here.

use glam::DVec3;
use std::collections::HashMap;
use std::fmt;

/// Whether a symbol (or a formula) is a number or a 3-vector.
///
/// # Examples
/// ```
/// use hw3::checker::{Formula, Kind};
/// let symbols = [("d", Kind::Vector)];
/// assert_eq!(Formula::parse("d_x", &symbols).unwrap().kind(), Kind::Scalar);
/// assert_eq!(Formula::parse("2*d", &symbols).unwrap().kind(), Kind::Vector);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A number.
    Scalar,
    /// A 3-vector (components `v_x`, `v_y`, `v_z`).
    Vector,
}

impl Kind {
    fn word(self) -> &'static str {
        match self {
            Kind::Scalar => "a number",
            Kind::Vector => "a vector",
        }
    }
}

/// A value a formula takes at one point.
///
/// # Examples
/// ```
/// use hw3::checker::{Formula, Kind, Value};
/// let f = Formula::parse("sqrt(r)", &[("r", Kind::Scalar)]).unwrap();
/// assert_eq!(f.eval(&[("r", Value::Scalar(9.0))].into_iter().collect()), Value::Scalar(3.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A number.
    Scalar(f64),
    /// A 3-vector.
    Vector(DVec3),
}

/// Values of the symbols at one point.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::checker::{Point, Value};
/// let point: Point = [("d", Value::Vector(DVec3::X)), ("r", Value::Scalar(2.0))].into_iter().collect();
/// assert_eq!(point["r"], Value::Scalar(2.0));
/// ```
pub type Point = HashMap<&'static str, Value>;

#[derive(Debug, Clone, PartialEq)]
enum Node {
    Number(f64),
    Symbol(String),
    Component(String, usize),
    Neg(Box<Node>),
    Binary(char, Box<Node>, Box<Node>),
    Call(&'static str, Vec<Node>),
}

/// A parsed, type-checked formula.
///
/// # Examples
/// ```
/// use hw3::checker::{Formula, Kind};
/// assert!(Formula::parse("(p - o)/r", &[("p", Kind::Vector), ("o", Kind::Vector), ("r", Kind::Scalar)]).is_ok());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Formula {
    node: Node,
    kind: Kind,
}

/// Why a formula could not be read: what and where (a character offset).
///
/// # Examples
/// ```
/// use hw3::checker::{Formula, Kind};
/// let error = Formula::parse("2*q", &[("r", Kind::Scalar)]).unwrap_err();
/// assert_eq!(error.at, 2);
/// assert!(error.to_string().contains("unknown symbol `q`"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FormulaError {
    /// Character offset of the problem.
    pub at: usize,
    /// What is wrong.
    pub problem: String,
}

impl fmt::Display for FormulaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at character {})", self.problem, self.at + 1)
    }
}

const FUNCTIONS: [(&str, usize); 6] = [("dot", 2), ("cross", 2), ("norm", 1), ("sqrt", 1), ("abs", 1), ("max", 2)];

struct Parser<'a> {
    chars: Vec<char>,
    at: usize,
    symbols: &'a [(&'static str, Kind)],
}

impl Parser<'_> {
    fn error<T>(&self, problem: impl Into<String>) -> Result<T, FormulaError> {
        Err(FormulaError { at: self.at, problem: problem.into() })
    }

    fn skip_space(&mut self) {
        while self.chars.get(self.at).is_some_and(|c| c.is_whitespace()) {
            self.at += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_space();
        self.chars.get(self.at).copied()
    }

    fn expect(&mut self, c: char) -> Result<(), FormulaError> {
        if self.peek() == Some(c) {
            self.at += 1;
            Ok(())
        } else {
            self.error(format!("expected `{c}`"))
        }
    }

    fn sum(&mut self, depth: usize) -> Result<(Node, Kind), FormulaError> {
        let (mut node, mut kind) = self.product(depth)?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.at += 1;
            let (rhs, rhs_kind) = self.product(depth)?;
            if rhs_kind != kind {
                return self.error(format!("`{op}` between {} and {}", kind.word(), rhs_kind.word()));
            }
            node = Node::Binary(op, Box::new(node), Box::new(rhs));
            kind = rhs_kind;
        }
        Ok((node, kind))
    }

    fn product(&mut self, depth: usize) -> Result<(Node, Kind), FormulaError> {
        let (mut node, mut kind) = self.unary(depth)?;
        while let Some(op @ ('*' | '/')) = self.peek() {
            self.at += 1;
            let (rhs, rhs_kind) = self.unary(depth)?;
            kind = match (op, kind, rhs_kind) {
                (_, Kind::Scalar, Kind::Scalar) => Kind::Scalar,
                ('*', Kind::Scalar, Kind::Vector) | (_, Kind::Vector, Kind::Scalar) => Kind::Vector,
                ('*', ..) => return self.error("a vector times a vector: write dot(a, b) or cross(a, b)"),
                _ => return self.error("division by a vector"),
            };
            node = Node::Binary(op, Box::new(node), Box::new(rhs));
        }
        Ok((node, kind))
    }

    fn unary(&mut self, depth: usize) -> Result<(Node, Kind), FormulaError> {
        if depth > 64 {
            return self.error("nested too deeply");
        }
        if self.peek() == Some('-') {
            self.at += 1;
            let (node, kind) = self.unary(depth + 1)?;
            return Ok((Node::Neg(Box::new(node)), kind));
        }
        let (base, kind) = self.atom(depth)?;
        if self.peek() == Some('^') {
            self.at += 1;
            let (exponent, exponent_kind) = self.unary(depth + 1)?;
            if kind != Kind::Scalar || exponent_kind != Kind::Scalar {
                return self.error("`^` takes numbers only: write dot(v, v) or norm(v)^2 for a vector");
            }
            return Ok((Node::Binary('^', Box::new(base), Box::new(exponent)), Kind::Scalar));
        }
        Ok((base, kind))
    }

    fn atom(&mut self, depth: usize) -> Result<(Node, Kind), FormulaError> {
        match self.peek() {
            Some('(') => {
                self.at += 1;
                let inner = self.sum(depth + 1)?;
                self.expect(')')?;
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => {
                let start = self.at;
                while self.chars.get(self.at).is_some_and(|c| c.is_ascii_digit() || *c == '.') {
                    self.at += 1;
                }
                let text: String = self.chars[start..self.at].iter().collect();
                match text.parse::<f64>() {
                    Ok(x) => Ok((Node::Number(x), Kind::Scalar)),
                    Err(_) => self.error(format!("`{text}` is not a number")),
                }
            }
            Some(c) if c.is_ascii_alphabetic() => {
                let start = self.at;
                while self.chars.get(self.at).is_some_and(char::is_ascii_alphanumeric) {
                    self.at += 1;
                }
                let name: String = self.chars[start..self.at].iter().collect();
                if let Some(&(function, arity)) = FUNCTIONS.iter().find(|(f, _)| *f == name) {
                    return self.call(function, arity, depth);
                }
                let Some(&(_, kind)) = self.symbols.iter().find(|(s, _)| *s == name) else {
                    self.at = start;
                    let known: Vec<&str> = self.symbols.iter().map(|(s, _)| *s).collect();
                    return self.error(format!("unknown symbol `{name}`; this part's symbols: {}", known.join(", ")));
                };
                if self.chars.get(self.at) == Some(&'_') {
                    let axis = match self.chars.get(self.at + 1) {
                        Some('x') => 0,
                        Some('y') => 1,
                        Some('z') => 2,
                        _ => return self.error(format!("after `{name}_` write x, y or z")),
                    };
                    if kind != Kind::Vector {
                        return self.error(format!("`{name}` is a number: it has no components"));
                    }
                    self.at += 2;
                    return Ok((Node::Component(name, axis), Kind::Scalar));
                }
                Ok((Node::Symbol(name), kind))
            }
            Some(c) => self.error(format!("unexpected `{c}`")),
            None => self.error("the formula ends too early"),
        }
    }

    fn call(&mut self, function: &'static str, arity: usize, depth: usize) -> Result<(Node, Kind), FormulaError> {
        self.expect('(')?;
        let mut args = Vec::new();
        let mut kinds = Vec::new();
        for i in 0..arity {
            if i > 0 {
                self.expect(',')?;
            }
            let (node, kind) = self.sum(depth + 1)?;
            args.push(node);
            kinds.push(kind);
        }
        self.expect(')')?;
        let kind = match (function, kinds.as_slice()) {
            ("dot", [Kind::Vector, Kind::Vector]) | ("norm", [Kind::Vector]) => Kind::Scalar,
            ("cross", [Kind::Vector, Kind::Vector]) => Kind::Vector,
            ("sqrt" | "abs", [Kind::Scalar]) | ("max", [Kind::Scalar, Kind::Scalar]) => Kind::Scalar,
            ("dot" | "cross" | "norm", _) => return self.error(format!("{function} takes vectors")),
            ("max", _) => return self.error("max takes two numbers"),
            _ => return self.error(format!("{function} takes a number")),
        };
        Ok((Node::Call(function, args), kind))
    }
}

impl Formula {
    /// Parses `text` in the given symbols (each a number or a vector) and type-checks it.
    ///
    /// Multiplication is written `*` (no implicit products); `^` raises numbers only.
    ///
    /// # Errors
    /// [`FormulaError`] with the character offset: a syntax error, an unknown symbol (the message
    /// lists the part's symbols), or an operation on the wrong kinds (a vector times a vector).
    ///
    /// # Examples
    /// ```
    /// use hw3::checker::{Formula, Kind};
    /// let symbols = [("d", Kind::Vector), ("r", Kind::Scalar)];
    /// assert_eq!(Formula::parse("dot(d, d) - r^2", &symbols).unwrap().kind(), Kind::Scalar);
    /// assert!(Formula::parse("d * d", &symbols).is_err());
    /// ```
    pub fn parse(text: &str, symbols: &[(&'static str, Kind)]) -> Result<Self, FormulaError> {
        let mut parser = Parser { chars: text.chars().collect(), at: 0, symbols };
        if parser.chars.len() > 2000 {
            return parser.error("longer than 2000 characters");
        }
        let (node, kind) = parser.sum(0)?;
        if let Some(c) = parser.peek() {
            return parser.error(format!("unexpected `{c}`"));
        }
        Ok(Self { node, kind })
    }

    /// Whether the formula is a number or a vector.
    ///
    /// # Examples
    /// ```
    /// use hw3::checker::{Formula, Kind};
    /// let f = Formula::parse("cross(a, b)", &[("a", Kind::Vector), ("b", Kind::Vector)]).unwrap();
    /// assert_eq!(f.kind(), Kind::Vector);
    /// ```
    #[must_use]
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// The formula's value at `point` (every symbol it uses must be there, of the kind it was
    /// parsed with; a missing one evaluates to NaN). IEEE arithmetic throughout: `sqrt` of a
    /// negative number is NaN, a division by zero infinite.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::checker::{Formula, Kind, Value};
    /// let f = Formula::parse("-dot(e, d)/dot(d, d)", &[("e", Kind::Vector), ("d", Kind::Vector)]).unwrap();
    /// let point = [("e", Value::Vector(DVec3::new(-5.0, 1.0, 0.0))), ("d", Value::Vector(DVec3::X))];
    /// assert_eq!(f.eval(&point.into_iter().collect()), Value::Scalar(5.0));
    /// ```
    #[must_use]
    pub fn eval(&self, point: &Point) -> Value {
        eval(&self.node, point)
    }
}

fn eval(node: &Node, point: &Point) -> Value {
    use Value::{Scalar, Vector};
    let nan = Scalar(f64::NAN);
    match node {
        Node::Number(x) => Scalar(*x),
        Node::Symbol(name) => point.get(name.as_str()).copied().unwrap_or(nan),
        Node::Component(name, axis) => match point.get(name.as_str()) {
            Some(Vector(v)) => Scalar(v[*axis]),
            _ => nan,
        },
        Node::Neg(inner) => match eval(inner, point) {
            Scalar(x) => Scalar(-x),
            Vector(v) => Vector(-v),
        },
        Node::Binary(op, a, b) => match (op, eval(a, point), eval(b, point)) {
            ('+', Scalar(x), Scalar(y)) => Scalar(x + y),
            ('-', Scalar(x), Scalar(y)) => Scalar(x - y),
            ('*', Scalar(x), Scalar(y)) => Scalar(x * y),
            ('/', Scalar(x), Scalar(y)) => Scalar(x / y),
            ('^', Scalar(x), Scalar(y)) => Scalar(x.powf(y)),
            ('+', Vector(u), Vector(v)) => Vector(u + v),
            ('-', Vector(u), Vector(v)) => Vector(u - v),
            ('*', Scalar(x), Vector(v)) | ('*', Vector(v), Scalar(x)) => Vector(v * x),
            ('/', Vector(v), Scalar(x)) => Vector(v / x),
            _ => nan,
        },
        Node::Call(function, args) => {
            let values: Vec<Value> = args.iter().map(|a| eval(a, point)).collect();
            match (*function, values.as_slice()) {
                ("dot", [Vector(u), Vector(v)]) => Scalar(u.dot(*v)),
                ("cross", [Vector(u), Vector(v)]) => Vector(u.cross(*v)),
                ("norm", [Vector(v)]) => Scalar(v.length()),
                ("sqrt", [Scalar(x)]) => Scalar(x.sqrt()),
                ("abs", [Scalar(x)]) => Scalar(x.abs()),
                // NaN propagates: `f64::max` would drop it and let a broken formula agree.
                ("max", [Scalar(x), Scalar(y)]) => Scalar(if x.is_nan() || y.is_nan() { f64::NAN } else { x.max(*y) }),
                _ => nan,
            }
        }
    }
}

/// Whether two values agree to `1e-6` relative to the larger of their sizes and 1 (vectors by
/// the norm of the difference). Only finite values agree: NaN and an infinity (a division by
/// zero) agree with nothing, so `1/0` cannot pass for a finite key.
#[must_use]
pub(super) fn agree(a: Value, b: Value) -> bool {
    match (a, b) {
        (Value::Scalar(x), Value::Scalar(y)) => {
            x.is_finite() && y.is_finite() && (x - y).abs() <= 1e-6 * x.abs().max(y.abs()).max(1.0)
        }
        (Value::Vector(u), Value::Vector(v)) => {
            u.is_finite() && v.is_finite() && (u - v).length() <= 1e-6 * u.length().max(v.length()).max(1.0)
        }
        _ => false,
    }
}

fn show_value(value: Value) -> String {
    match value {
        Value::Scalar(x) => format!("{x:.4}"),
        Value::Vector(v) => format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z),
    }
}

/// Whether `given` equals `key` at every one of `points`, and the first point where it does not,
/// in words.
#[must_use]
pub(super) fn compare_formulas(
    key: &Formula,
    given: &Formula,
    symbols: &[(&'static str, Kind)],
    points: &[Point],
) -> (bool, String) {
    if key.kind != given.kind {
        return (false, format!("your formula gives {}; {} is asked", given.kind.word(), key.kind.word()));
    }
    let differ = points.iter().filter(|p| !agree(key.eval(p), given.eval(p))).count();
    if differ == 0 {
        return (true, format!("equal to the key at all {} random points", points.len()));
    }
    let witness = points.iter().find(|p| !agree(key.eval(p), given.eval(p))).expect("one point differs");
    let at: Vec<String> = symbols
        .iter()
        .filter_map(|(name, _)| witness.get(name).map(|v| format!("{name} = {}", show_value(*v))))
        .collect();
    (
        false,
        format!(
            "differs from the key at {differ} of {} random points; e.g. at {}: yours {}, the key {}",
            points.len(),
            at.join(", "),
            show_value(given.eval(witness)),
            show_value(key.eval(witness))
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const SYMBOLS: [(&str, Kind); 4] =
        [("e", Kind::Vector), ("d", Kind::Vector), ("r", Kind::Scalar), ("t", Kind::Scalar)];

    fn point() -> Point {
        [
            ("e", Value::Vector(DVec3::new(1.0, 2.0, 3.0))),
            ("d", Value::Vector(DVec3::new(0.0, -1.0, 2.0))),
            ("r", Value::Scalar(2.0)),
            ("t", Value::Scalar(0.5)),
        ]
        .into_iter()
        .collect()
    }

    fn value(text: &str) -> Value {
        Formula::parse(text, &SYMBOLS).unwrap().eval(&point())
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(value("1 + 2 * 3"), Value::Scalar(7.0));
        assert_eq!(value("8 / 4 / 2"), Value::Scalar(1.0));
        assert_eq!(value("2 ^ 3 ^ 2"), Value::Scalar(512.0));
        assert_eq!(value("-r^2"), Value::Scalar(-4.0));
        assert_eq!(value("(1 + 2) * 3"), Value::Scalar(9.0));
    }

    #[test]
    fn vectors_components_and_functions() {
        assert_eq!(value("e + d * t"), Value::Vector(DVec3::new(1.0, 1.5, 4.0)));
        assert_eq!(value("d_y"), Value::Scalar(-1.0));
        assert_eq!(value("dot(e, d)"), Value::Scalar(4.0));
        assert_eq!(value("cross(e, d)"), Value::Vector(DVec3::new(7.0, -2.0, -1.0)));
        assert_eq!(value("norm(d)^2"), Value::Scalar(5.000000000000001));
        assert_eq!(value("sqrt(abs(-16))"), Value::Scalar(4.0));
        assert_eq!(value("e / r"), Value::Vector(DVec3::new(0.5, 1.0, 1.5)));
    }

    #[test]
    fn errors_say_what_and_where() {
        for (text, words) in [
            ("e * d", "dot(a, b) or cross(a, b)"),
            ("e + r", "between a vector and a number"),
            ("q + 1", "unknown symbol `q`; this part's symbols: e, d, r, t"),
            ("dot(e)", "expected `,`"),
            ("r_x", "is a number"),
            ("e^2", "numbers only"),
            ("(r + 1", "expected `)`"),
            ("r +", "ends too early"),
            ("2r", "unexpected `r`"),
            ("1.2.3", "not a number"),
            ("sqrt(e)", "takes a number"),
            ("r $ 2", "unexpected `$`"),
        ] {
            let error = Formula::parse(text, &SYMBOLS).unwrap_err();
            assert!(error.problem.contains(words), "{text}: {error}");
        }
        let deep = format!("{}r{}", "(".repeat(500), ")".repeat(500));
        assert!(Formula::parse(&deep, &SYMBOLS).is_err());
        let minus = format!("{}r", "-".repeat(500));
        assert!(Formula::parse(&minus, &SYMBOLS).is_err());
    }

    #[test]
    fn agreement_is_relative_and_nan_never_agrees() {
        assert!(agree(Value::Scalar(1e6), Value::Scalar(1e6 + 0.5)));
        assert!(!agree(Value::Scalar(1.0), Value::Scalar(1.001)));
        assert!(!agree(Value::Scalar(f64::NAN), Value::Scalar(f64::NAN)));
        assert!(!agree(Value::Scalar(1.0), Value::Vector(DVec3::ONE)));
    }
}
