//! Numbers formatted for reading in reports and on pages: durations, ratios, thousands.

/// A duration in the unit that suits it: `850 µs`, `12.3 ms`, `4.56 s`, `123 s`.
pub fn seconds(value: f64) -> String {
    if !value.is_finite() {
        "–".to_string()
    } else if value < 1e-3 {
        format!("{:.0} µs", value * 1e6)
    } else if value < 0.1 {
        format!("{:.2} ms", value * 1e3)
    } else if value < 1.0 {
        format!("{:.0} ms", value * 1e3)
    } else if value < 100.0 {
        format!("{value:.2} s")
    } else {
        format!("{value:.0} s")
    }
}

/// `paper / ours` as `×1.23`, or `–` when either is missing.
pub fn ratio(paper: Option<f64>, ours: Option<f64>) -> String {
    match (paper, ours) {
        (Some(p), Some(o)) if o > 0.0 && p.is_finite() => {
            let r = p / o;
            if r >= 100.0 {
                format!("×{r:.0}")
            } else if r >= 10.0 {
                format!("×{r:.1}")
            } else {
                format!("×{r:.2}")
            }
        }
        _ => "–".to_string(),
    }
}

/// An integer with thousands separators: `69,666`.
pub fn thousands(value: usize) -> String {
    let digits = value.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_formatted_for_reading() {
        assert_eq!(seconds(0.0005), "500 µs");
        assert_eq!(seconds(0.0123), "12.30 ms");
        assert_eq!(seconds(4.561), "4.56 s");
        assert_eq!(seconds(1246.0), "1246 s");
        assert_eq!(ratio(Some(23.0), Some(11.5)), "×2.00");
        assert_eq!(ratio(None, Some(1.0)), "–");
        assert_eq!(thousands(69666), "69,666");
        assert_eq!(thousands(331904), "331,904");
        assert_eq!(thousands(12), "12");
    }
}
