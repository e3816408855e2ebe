//! Evaluating an expression against the program's parameters: LinuxCNC's and Fanuc's
//! arithmetic, comparisons, logic and functions (degrees), with Fanuc's vacant values.

use super::expr::{BinOp, Expr, Func, ParamRef, COMPARE_TOLERANCE};

/// Where expressions read parameters.
pub(crate) trait Parameters {
    /// The value of numbered parameter `n` (`None`: vacant).
    fn numbered(&self, n: u32) -> Result<Option<f64>, String>;
    /// The value of named parameter `name` (`None`: not defined).
    fn named(&self, name: &str) -> Option<f64>;
}

/// Largest parameter number (Fanuc's system variables reach #19999; LinuxCNC's #5602).
pub(crate) const MAX_PARAMETER_NUMBER: f64 = 99_999.0;

/// The number a parameter index names.
pub(crate) fn parameter_number(index: f64) -> Result<u32, String> {
    let rounded = index.round();
    if !((index - rounded).abs() <= COMPARE_TOLERANCE && (0.0..=MAX_PARAMETER_NUMBER).contains(&rounded)) {
        return Err(format!("#{index} is not a parameter: the number must be a whole number from 0 to 99999"));
    }
    Ok(rounded as u32)
}

/// A numbered reference's number, evaluated.
pub(crate) fn index_of(index: &Expr, params: &dyn Parameters) -> Result<u32, String> {
    parameter_number(evaluate(index, params)?.unwrap_or(0.0))
}

/// Evaluates `e`: `Ok(None)` is a vacant value (an unset Fanuc variable).
pub(crate) fn evaluate(e: &Expr, params: &dyn Parameters) -> Result<Option<f64>, String> {
    let value = |e: &Expr| evaluate(e, params).map(|v| v.unwrap_or(0.0));
    let result = match e {
        Expr::Number(v) => *v,
        Expr::Param(ParamRef::Index(index)) => return params.numbered(index_of(index, params)?),
        Expr::Param(ParamRef::Name(name)) => match params.named(name) {
            Some(v) => v,
            None => return Err(format!("#<{}> is not defined", name.to_ascii_lowercase())),
        },
        Expr::Neg(inner) => -value(inner)?,
        Expr::Func(func, inner) => function(*func, value(inner)?)?,
        Expr::Atan2(y, x) => value(y)?.atan2(value(x)?).to_degrees(),
        Expr::Exists(name) => f64::from(u8::from(params.named(name).is_some())),
        Expr::Binary(op, a, b) => {
            let (va, vb) = (evaluate(a, params)?, evaluate(b, params)?);
            return binary(*op, va, vb).map(Some);
        }
    };
    if !result.is_finite() {
        return Err("the expression's value is out of range".to_string());
    }
    Ok(Some(result))
}

fn truth(v: bool) -> f64 {
    f64::from(u8::from(v))
}

/// A binary operation; vacant operands count as 0, except that `EQ` and `NE` tell a
/// vacant value from 0 (Fanuc).
fn binary(op: BinOp, a: Option<f64>, b: Option<f64>) -> Result<f64, String> {
    if matches!(op, BinOp::Eq | BinOp::Ne) && (a.is_none() || b.is_none()) {
        let same = a.is_none() && b.is_none();
        return Ok(truth(if op == BinOp::Eq { same } else { !same }));
    }
    let (x, y) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
    let equal = (x - y).abs() <= COMPARE_TOLERANCE;
    let v = match op {
        BinOp::Pow => {
            if x < 0.0 && y.fract().abs() > 0.0 {
                return Err(format!("{x} ** {y}: a negative number has no fractional power"));
            }
            x.powf(y)
        }
        BinOp::Mul => x * y,
        BinOp::Div | BinOp::Mod if y.abs() < f64::MIN_POSITIVE => {
            return Err("division by zero".to_string());
        }
        BinOp::Div => x / y,
        BinOp::Mod => {
            let r = x % y;
            if r < 0.0 {
                r + y.abs()
            } else {
                r
            }
        }
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Eq => truth(equal),
        BinOp::Ne => truth(!equal),
        BinOp::Gt => truth(x > y && !equal),
        BinOp::Ge => truth(x > y || equal),
        BinOp::Lt => truth(x < y && !equal),
        BinOp::Le => truth(x < y || equal),
        BinOp::And => truth(x != 0.0 && y != 0.0),
        BinOp::Or => truth(x != 0.0 || y != 0.0),
        BinOp::Xor => truth((x != 0.0) != (y != 0.0)),
    };
    if !v.is_finite() {
        return Err("the expression's value is out of range".to_string());
    }
    Ok(v)
}

fn function(func: Func, x: f64) -> Result<f64, String> {
    Ok(match func {
        Func::Abs => x.abs(),
        Func::Acos | Func::Asin if !(-1.0..=1.0).contains(&x) => {
            return Err(format!("{x} is outside the domain of ACOS and ASIN (-1 to 1)"));
        }
        Func::Acos => x.acos().to_degrees(),
        Func::Asin => x.asin().to_degrees(),
        Func::Atan => x.atan().to_degrees(),
        Func::Cos => x.to_radians().cos(),
        Func::Exp => x.exp(),
        Func::Fix => x.floor(),
        Func::Fup => x.ceil(),
        Func::Ln if x <= 0.0 => return Err(format!("LN[{x}]: the logarithm needs a positive number")),
        Func::Ln => x.ln(),
        Func::Round => x.round(),
        Func::Sin => x.to_radians().sin(),
        Func::Sqrt if x < 0.0 => return Err(format!("SQRT[{x}]: the square root needs a number ≥ 0")),
        Func::Sqrt => x.sqrt(),
        Func::Tan => x.to_radians().tan(),
    })
}
