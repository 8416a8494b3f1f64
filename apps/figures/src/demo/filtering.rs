//! Demo step 4: papers/'s Figures 7 and 8 on the demo's mesh: a designed field plus noise,
//! filtered in the spectral basis, and its coefficient spectrum.

use super::page::Section;
use super::Context;
use crate::eigenfields_and_filtering::figures7_8;
use crate::error::FigureError;

/// Figures 7 and 8 in one section.
pub fn run(cx: &Context) -> Result<Section, FigureError> {
    let mut figures = figures7_8(&cx.experiment(), cx.plot_size())?
        .iter()
        .map(Section::from_finding)
        .collect::<Vec<_>>()
        .into_iter();
    let mut section = figures
        .next()
        .ok_or_else(|| FigureError::Invalid("Figure 7 is missing".to_string()))?;
    for more in figures {
        section.text = format!("{} {}: {}", section.text, more.title, more.text);
        section.figures.extend(more.figures);
        section.numbers.extend(more.numbers);
    }
    Ok(section)
}
