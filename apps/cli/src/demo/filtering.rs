//! Demo step 4: papers/'s Figures 7 and 8 on the demo's mesh: a designed field plus noise,
//! filtered in the spectral basis, and its coefficient spectrum.

use super::page::Section;
use super::Context;
use anyhow::Result;
use tvf_papers::brandt2017::figures::figures7_8;

/// Figures 7 and 8, one section each.
pub fn run(cx: &Context) -> Result<Vec<Section>> {
    Ok(figures7_8(&cx.experiment(), cx.plot_size())?
        .iter()
        .map(Section::from_finding)
        .collect())
}
