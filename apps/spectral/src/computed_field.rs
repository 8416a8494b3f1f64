//! [`check_computed_field`]: a field computed from the user's inputs (filtered, decoded,
//! designed) is checked before it is written, so that overflowing arithmetic (gains or
//! coefficients too large for `f64`) is an error that says why, never a file of NaNs reported
//! as a success. The field writers refuse such a field too ([`crate::FieldIoError`]); this
//! check names the cause.

use thiserror::Error;

/// A computed field with NaN or infinite entries.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error(
    "{what} is not finite: {bad} of its {len} entries are NaN or infinite ({cause}); nothing \
     was written"
)]
pub struct NonFiniteField {
    /// What the field is, e.g. "the filtered field".
    pub what: String,
    /// How many entries are NaN or infinite.
    pub bad: usize,
    /// How many entries the field has.
    pub len: usize,
    /// Which inputs made it so.
    pub cause: String,
}

/// Refuses `field` (called `what` in the message, e.g. "the filtered field") if an entry is NaN
/// or infinite; `cause` says which inputs made it so.
pub fn check_computed_field(field: &[f64], what: &str, cause: &str) -> Result<(), NonFiniteField> {
    let bad = field.iter().filter(|x| !x.is_finite()).count();
    if bad > 0 {
        return Err(NonFiniteField {
            what: what.to_string(),
            bad,
            len: field.len(),
            cause: cause.to_string(),
        });
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
        assert_eq!(
            error,
            "the field is not finite: 2 of its 3 entries are NaN or infinite (why); nothing was \
             written"
        );
    }
}
