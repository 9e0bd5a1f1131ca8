//! The weight expressions of a scheme file: a formula in the valence `n`
//! (math doc section 12.1).
//!
//! The text is parsed by the `evalexpr` crate; its operator tree is then
//! translated into [`Expr`], which admits only the grammar of the format:
//! numbers, `+ - * / ^`, parentheses, the variable `n`, the constant `pi`
//! and the functions `cos`, `sin`, `sqrt`. [`Expr`] is evaluated here, never
//! by `evalexpr`: in `f64` ([`Expr::eval_f64`]) and exactly in rationals
//! ([`Expr::eval_exact`]) when the expression has no transcendental part.
//!
//! ```
//! use subdiv_lab::schemes::user::Expr;
//! use subdiv_lab::scalar::{Rational, Scalar};
//! let e = Expr::parse("1 - 7/(4*n)").unwrap();
//! assert_eq!(e.eval_exact(5), Some(Ok(Rational::frac(13, 20))));
//! assert_eq!(e.eval_f64(5), 0.65);
//! let t = Expr::parse("cos(2*pi/n)").unwrap();
//! assert_eq!(t.eval_exact(4), None); // transcendental: f64 only
//! assert!(Expr::parse("m + 1").unwrap_err().contains("unknown variable m"));
//! ```

use crate::scalar::{parse_exact, Rational};
use evalexpr::{DefaultNumericTypes, Node, Operator, Value};
use num_traits::{ToPrimitive, Zero};

/// The longest expression text accepted (characters): far above any weight
/// formula, and low enough that the parser's and the evaluator's recursion
/// stay shallow whatever the nesting.
pub const MAX_EXPRESSION_CHARS: usize = 1000;

/// The largest integer exponent `|k|` of `x^k` evaluated exactly; a larger
/// one (or a non-integer one) makes the expression `f64`-only, so that an
/// exact power never grows beyond a few thousand bits per factor.
pub const MAX_EXACT_EXPONENT: u32 = 64;

/// A weight expression in `n`.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A number, exactly as written (`0.1` is `1/10`).
    Num(Rational, f64),
    /// The valence `n`.
    N,
    /// The constant `pi`.
    Pi,
    /// `-a`.
    Neg(Box<Expr>),
    /// `a + b`.
    Add(Box<Expr>, Box<Expr>),
    /// `a - b`.
    Sub(Box<Expr>, Box<Expr>),
    /// `a * b`.
    Mul(Box<Expr>, Box<Expr>),
    /// `a / b`.
    Div(Box<Expr>, Box<Expr>),
    /// `a ^ b`.
    Pow(Box<Expr>, Box<Expr>),
    /// `cos(a)`, `sin(a)` or `sqrt(a)`.
    Call(Function, Box<Expr>),
}

/// The functions of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    /// Cosine (radians).
    Cos,
    /// Sine (radians).
    Sin,
    /// Square root.
    Sqrt,
}

/// Why an exact evaluation fails.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ExactError {
    /// A division by zero (also `0^k` with `k < 0`).
    DivisionByZero,
}

impl Expr {
    /// Parses `text` (the grammar of the module docs); the error is a short
    /// phrase naming the problem (`unknown variable m`, `unknown function
    /// tan`, `unsupported operator ==`, a syntax error).
    pub fn parse(text: &str) -> Result<Expr, String> {
        if text.chars().count() > MAX_EXPRESSION_CHARS {
            return Err(format!(
                "expression longer than {MAX_EXPRESSION_CHARS} characters"
            ));
        }
        if text.trim().is_empty() {
            return Err("empty expression".to_owned());
        }
        let tree = evalexpr::build_operator_tree::<DefaultNumericTypes>(text)
            .map_err(|e| format!("syntax error: {}", one_line(&e.to_string())))?;
        translate(&tree)
    }

    /// Whether the expression is exact (rational at every valence where it is
    /// defined): no `pi`, no function, integer exponents within
    /// [`MAX_EXACT_EXPONENT`].
    pub fn is_rational(&self) -> bool {
        match self {
            Expr::Num(..) | Expr::N => true,
            Expr::Pi | Expr::Call(..) => false,
            Expr::Neg(a) => a.is_rational(),
            Expr::Add(a, b) | Expr::Sub(a, b) | Expr::Mul(a, b) | Expr::Div(a, b) => {
                a.is_rational() && b.is_rational()
            }
            Expr::Pow(a, b) => a.is_rational() && small_integer(b).is_some(),
        }
    }

    /// The value at valence `n` in `f64` (IEEE arithmetic: a division by
    /// zero or `sqrt` of a negative number gives a non-finite value, which
    /// the validator refuses). `x^k` with an integer constant `k` is
    /// `powi`, other powers `powf`.
    pub fn eval_f64(&self, n: usize) -> f64 {
        match self {
            Expr::Num(_, x) => *x,
            Expr::N => n as f64,
            Expr::Pi => std::f64::consts::PI,
            Expr::Neg(a) => -a.eval_f64(n),
            Expr::Add(a, b) => a.eval_f64(n) + b.eval_f64(n),
            Expr::Sub(a, b) => a.eval_f64(n) - b.eval_f64(n),
            Expr::Mul(a, b) => a.eval_f64(n) * b.eval_f64(n),
            Expr::Div(a, b) => a.eval_f64(n) / b.eval_f64(n),
            Expr::Pow(a, b) => match integer_constant(b) {
                Some(k) if i32::try_from(k).is_ok() => a.eval_f64(n).powi(k as i32),
                _ => a.eval_f64(n).powf(b.eval_f64(n)),
            },
            Expr::Call(f, a) => {
                let x = a.eval_f64(n);
                match f {
                    Function::Cos => x.cos(),
                    Function::Sin => x.sin(),
                    Function::Sqrt => x.sqrt(),
                }
            }
        }
    }

    /// The exact value at valence `n`: `None` when the expression is not
    /// rational ([`Expr::is_rational`]), else the value or the division by
    /// zero met on the way.
    pub fn eval_exact(&self, n: usize) -> Option<Result<Rational, ExactError>> {
        self.is_rational().then(|| self.exact(n))
    }

    fn exact(&self, n: usize) -> Result<Rational, ExactError> {
        Ok(match self {
            Expr::Num(q, _) => q.clone(),
            Expr::N => Rational::from_integer((n as u64).into()),
            Expr::Neg(a) => -a.exact(n)?,
            Expr::Add(a, b) => a.exact(n)? + b.exact(n)?,
            Expr::Sub(a, b) => a.exact(n)? - b.exact(n)?,
            Expr::Mul(a, b) => a.exact(n)? * b.exact(n)?,
            Expr::Div(a, b) => {
                let d = b.exact(n)?;
                if d.is_zero() {
                    return Err(ExactError::DivisionByZero);
                }
                a.exact(n)? / d
            }
            Expr::Pow(a, b) => {
                let base = a.exact(n)?;
                let k = small_integer(b).unwrap_or(0);
                if k < 0 && base.is_zero() {
                    return Err(ExactError::DivisionByZero);
                }
                let p = num_traits::pow(base, k.unsigned_abs() as usize);
                if k < 0 {
                    p.recip()
                } else {
                    p
                }
            }
            // is_rational() excludes these.
            Expr::Pi | Expr::Call(..) => return Err(ExactError::DivisionByZero),
        })
    }
}

/// An integer constant exponent (`2`, `-1`, `(3)`), if `e` is one.
fn integer_constant(e: &Expr) -> Option<i64> {
    match e {
        Expr::Num(q, _) if q.is_integer() => q.to_integer().to_i64(),
        Expr::Neg(a) => integer_constant(a).map(|k| -k),
        _ => None,
    }
}

/// An integer constant exponent with `|k| <=` [`MAX_EXACT_EXPONENT`].
fn small_integer(e: &Expr) -> Option<i64> {
    integer_constant(e).filter(|k| k.unsigned_abs() <= u64::from(MAX_EXACT_EXPONENT))
}

/// The first line of a message (the parser's may span several).
fn one_line(s: &str) -> String {
    s.lines().next().unwrap_or("").trim().to_owned()
}

fn binary(node: &Node<DefaultNumericTypes>) -> Result<(Box<Expr>, Box<Expr>), String> {
    match node.children() {
        [a, b] => Ok((Box::new(translate(a)?), Box::new(translate(b)?))),
        _ => Err(format!("operator {} needs two operands", node.operator())),
    }
}

fn unary(node: &Node<DefaultNumericTypes>) -> Result<Box<Expr>, String> {
    match node.children() {
        [a] => Ok(Box::new(translate(a)?)),
        [] => Err(format!("missing operand of {}", node.operator())),
        _ => Err("more than one value where one is expected (a missing operator?)".to_owned()),
    }
}

fn translate(node: &Node<DefaultNumericTypes>) -> Result<Expr, String> {
    Ok(match node.operator() {
        Operator::RootNode => *unary(node)?,
        Operator::Add => {
            let (a, b) = binary(node)?;
            Expr::Add(a, b)
        }
        Operator::Sub => {
            let (a, b) = binary(node)?;
            Expr::Sub(a, b)
        }
        Operator::Mul => {
            let (a, b) = binary(node)?;
            Expr::Mul(a, b)
        }
        Operator::Div => {
            let (a, b) = binary(node)?;
            Expr::Div(a, b)
        }
        Operator::Exp => {
            let (a, b) = binary(node)?;
            Expr::Pow(a, b)
        }
        Operator::Neg => Expr::Neg(unary(node)?),
        Operator::Const { value } => match value {
            Value::Int(i) => Expr::Num(Rational::from_integer((*i).into()), *i as f64),
            // The shortest decimal text of the parsed f64 is the literal as
            // written (up to an exponent's spelling), so `0.1` is exactly 1/10.
            Value::Float(x) => match parse_exact(&x.to_string()) {
                Some(q) if x.is_finite() => Expr::Num(q, *x),
                _ => return Err(format!("number {x} is not finite")),
            },
            other => return Err(format!("unsupported value {other}")),
        },
        Operator::VariableIdentifierRead { identifier } => match identifier.as_str() {
            "n" => Expr::N,
            "pi" => Expr::Pi,
            other => return Err(format!("unknown variable {other} (known: n, pi)")),
        },
        Operator::FunctionIdentifier { identifier } => {
            let f = match identifier.as_str() {
                "cos" => Function::Cos,
                "sin" => Function::Sin,
                "sqrt" => Function::Sqrt,
                other => return Err(format!("unknown function {other} (known: cos, sin, sqrt)")),
            };
            Expr::Call(f, unary(node)?)
        }
        other => return Err(format!("unsupported operator {other}")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Scalar;

    #[test]
    fn grammar_and_both_evaluations() {
        let e = Expr::parse("3/(2*n^2) + 0.1 - -(1/10)").unwrap();
        assert!(e.is_rational());
        assert_eq!(
            e.eval_exact(5).unwrap().unwrap(),
            Rational::frac(3, 50) + Rational::frac(1, 5)
        );
        assert!((e.eval_f64(5) - 0.26).abs() < 1e-15);
        let t = Expr::parse("sqrt(n) * sin(pi/2) + cos(0)").unwrap();
        assert!(!t.is_rational());
        assert_eq!(t.eval_f64(4), 3.0);
        assert_eq!(
            Expr::parse("2^-1").unwrap().eval_exact(3),
            Some(Ok(Rational::frac(1, 2)))
        );
        assert!(!Expr::parse("2^0.5").unwrap().is_rational());
        assert!(!Expr::parse("2^65").unwrap().is_rational());
    }

    #[test]
    fn division_by_zero_is_seen_in_both_arithmetics() {
        let e = Expr::parse("1/(n-4)").unwrap();
        assert_eq!(e.eval_exact(4), Some(Err(ExactError::DivisionByZero)));
        assert!(!e.eval_f64(4).is_finite());
        assert_eq!(
            Expr::parse("(n-3)^-2").unwrap().eval_exact(3),
            Some(Err(ExactError::DivisionByZero))
        );
    }

    #[test]
    fn everything_outside_the_grammar_is_named() {
        for (text, needle) in [
            ("m + 1", "unknown variable m"),
            ("tan(n)", "unknown function tan"),
            ("n == 3", "unsupported operator"),
            ("n % 2", "unsupported operator"),
            ("\"a\"", "unsupported value"),
            ("true", "unsupported value"),
            ("1 +", "needs two operands"),
            ("1 2", "syntax error"),
            ("(1, 2)", "unsupported operator"),
            ("", "empty expression"),
            ("a = 3", "unsupported operator"),
        ] {
            let e = Expr::parse(text).unwrap_err();
            assert!(e.contains(needle), "{text:?}: {e}");
        }
        let long = "1+".repeat(600) + "1";
        assert!(Expr::parse(&long).unwrap_err().contains("longer than"));
        let deep = "(".repeat(400) + "n" + &")".repeat(400);
        assert_eq!(Expr::parse(&deep).unwrap().eval_f64(7), 7.0);
    }
}
