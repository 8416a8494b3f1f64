//! The check every solved field passes before it is reported or written: finite entries and
//! finite constraint residuals, with the worst residual found NaN-aware.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use crate::spline::{residual, ConstraintResidual};

/// The residual with the largest relative value, counting a NaN or infinite one as the worst
/// (unlike a fold with `f64::max`, which skips NaN). `None` for no residuals.
pub fn worst_residual(residuals: &[ConstraintResidual]) -> Option<&ConstraintResidual> {
    residuals
        .iter()
        .max_by(|a, b| rank(a.relative).total_cmp(&rank(b.relative)))
}

/// `value`, with NaN and infinities ranked above every finite value.
fn rank(value: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        f64::INFINITY
    }
}

/// The residuals of `constraints` for the solved `field`, or an error when the field or a
/// residual is NaN or infinite. The error names the constraint whose residual is not finite
/// or, for a non-finite field, the constraint with the largest prescribed values (the usual
/// cause: values or `omega` so large that `f64` arithmetic overflows).
pub fn checked_residuals(
    field: &[f64],
    constraints: &[CompiledConstraint],
    omega: f64,
) -> Result<Vec<ConstraintResidual>, DesignError> {
    let residuals: Vec<ConstraintResidual> =
        constraints.iter().map(|c| residual(c, field)).collect();
    let bad_entries = field.iter().filter(|x| !x.is_finite()).count();
    let largest = constraints
        .iter()
        .max_by(|a, b| largest_value(a).total_cmp(&largest_value(b)));
    let cause = match largest {
        Some(c) => format!(
            "constraint '{}' has values up to {:e} and omega is {omega:e}: values or omega this \
             large overflow f64 arithmetic (scale them down)",
            c.id,
            largest_value(c)
        ),
        None => format!("omega is {omega:e}"),
    };
    if bad_entries > 0 {
        return Err(DesignError::NotFinite {
            id: largest.map_or_else(String::new, |c| c.id.clone()),
            problem: format!(
                "the solved field has {bad_entries} NaN or infinite entries (of {})",
                field.len()
            ),
            cause,
        });
    }
    if let Some(r) = residuals
        .iter()
        .find(|r| !(r.absolute.is_finite() && r.relative.is_finite()))
    {
        return Err(DesignError::NotFinite {
            id: r.id.clone(),
            problem: format!(
                "its residual is not finite (absolute {:e}, relative {:e})",
                r.absolute, r.relative
            ),
            cause,
        });
    }
    Ok(residuals)
}

/// The largest `|value|` of a constraint (infinite if a value is not finite).
fn largest_value(constraint: &CompiledConstraint) -> f64 {
    constraint.values.iter().fold(0.0, |m: f64, v| {
        if v.is_finite() {
            m.max(v.abs())
        } else {
            f64::INFINITY
        }
    })
}
