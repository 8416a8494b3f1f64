//! Colour maps for per-face scalars: a viridis-like sequential map and a diverging
//! blue–white–red map for signed quantities.

/// A map from `t ∈ [0, 1]` to an sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorMap {
    /// Perceptually ordered dark blue → green → yellow (viridis control points); for
    /// non-negative quantities such as magnitude or energy.
    Viridis,
    /// Blue (negative) → white (zero) → red (positive); for signed quantities such as
    /// divergence or curl, used with a range symmetric about 0.
    BlueWhiteRed,
}

const VIRIDIS: [[f64; 3]; 9] = [
    [68.0, 1.0, 84.0],
    [71.0, 44.0, 122.0],
    [59.0, 81.0, 139.0],
    [44.0, 113.0, 142.0],
    [33.0, 144.0, 141.0],
    [39.0, 173.0, 129.0],
    [92.0, 200.0, 99.0],
    [170.0, 220.0, 50.0],
    [253.0, 231.0, 37.0],
];

const BLUE_WHITE_RED: [[f64; 3]; 5] = [
    [33.0, 72.0, 170.0],
    [120.0, 160.0, 220.0],
    [247.0, 247.0, 247.0],
    [230.0, 130.0, 100.0],
    [178.0, 24.0, 43.0],
];

impl ColorMap {
    /// The colour at `t` (clamped to `[0, 1]`; NaN maps to `0`).
    pub fn color(self, t: f64) -> [u8; 3] {
        let table: &[[f64; 3]] = match self {
            ColorMap::Viridis => &VIRIDIS,
            ColorMap::BlueWhiteRed => &BLUE_WHITE_RED,
        };
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let x = t * (table.len() - 1) as f64;
        let i = (x.floor() as usize).min(table.len() - 2);
        let f = x - i as f64;
        let mut out = [0u8; 3];
        for (k, o) in out.iter_mut().enumerate() {
            *o = (table[i][k] * (1.0 - f) + table[i + 1][k] * f).round() as u8;
        }
        out
    }

    /// Whether the map is meant for signed data centred at 0.
    pub fn is_diverging(self) -> bool {
        matches!(self, ColorMap::BlueWhiteRed)
    }
}

/// A colour map together with the value range mapped onto it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColorScale {
    /// The colour map.
    pub map: ColorMap,
    /// Value mapped to `t = 0`.
    pub min: f64,
    /// Value mapped to `t = 1`.
    pub max: f64,
}

impl ColorScale {
    /// The range fitted to `values` (non-finite entries ignored): `[min, max]` for a
    /// sequential map, `[−m, m]` with `m = max |value|` for a diverging map, so that 0 is
    /// white. An empty or constant input gets a unit-width range.
    pub fn fit(map: ColorMap, values: &[f64]) -> Self {
        let finite = values.iter().copied().filter(|x| x.is_finite());
        let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        if lo > hi {
            return if map.is_diverging() {
                ColorScale {
                    map,
                    min: -1.0,
                    max: 1.0,
                }
            } else {
                ColorScale {
                    map,
                    min: 0.0,
                    max: 1.0,
                }
            };
        }
        if map.is_diverging() {
            let m = lo.abs().max(hi.abs());
            let m = if m > 0.0 { m } else { 1.0 };
            ColorScale {
                map,
                min: -m,
                max: m,
            }
        } else if hi > lo {
            ColorScale {
                map,
                min: lo,
                max: hi,
            }
        } else {
            ColorScale {
                map,
                min: lo - 0.5,
                max: lo + 0.5,
            }
        }
    }

    /// The colour of `value`.
    pub fn color(&self, value: f64) -> [u8; 3] {
        let width = self.max - self.min;
        let t = if width > 0.0 {
            (value - self.min) / width
        } else {
            0.5
        };
        self.map.color(t)
    }
}
