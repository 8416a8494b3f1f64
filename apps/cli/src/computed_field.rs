//! [`check_computed_field`]: a field a command computed is checked before it is written, so that
//! overflowing arithmetic (gains or coefficients too large for `f64`) is an error that says why,
//! never a file of NaNs reported as a success. The field writers refuse such a field too
//! ([`tvf_spectral::FieldIoError::Unwritable`]); this check names the cause.

use anyhow::{bail, Result};

/// Refuses `field` (called `what` in the message, e.g. "the filtered field") if an entry is NaN
/// or infinite; `cause` says which inputs made it so.
pub fn check_computed_field(field: &[f64], what: &str, cause: &str) -> Result<()> {
    let bad = field.iter().filter(|x| !x.is_finite()).count();
    if bad > 0 {
        bail!(
            "{what} is not finite: {bad} of its {} entries are NaN or infinite ({cause}); \
             nothing was written",
            field.len()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_field_is_refused_with_its_count_and_cause() {
        assert!(check_computed_field(&[1.0, -2.0], "the field", "cause").is_ok());
        let error = check_computed_field(&[1.0, f64::NAN, f64::INFINITY], "the field", "why")
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("2 of its 3 entries") && error.contains("why"),
            "{error}"
        );
    }
}
