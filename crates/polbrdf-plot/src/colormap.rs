//! Colour maps for heat maps: a sequential one (viridis), a diverging one (ColorBrewer RdBu,
//! blue for negative, white at the centre, red for positive), a cyclic one (a hue circle of
//! constant OKLab lightness and chroma, for angles) and a cyclic diverging one (for differences
//! of angles: white at 0, blue and red either side, the same dark grey at both ends).

use plotters::style::RGBColor;

/// Colour of values that are not defined (NaN).
pub const UNDEFINED: RGBColor = RGBColor(190, 190, 190);

/// A colour map from `[0, 1]` to sRGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Colormap {
    /// Matplotlib's viridis (perceptually uniform, sequential, readable in greyscale and by
    /// colour-blind viewers), as the degree-6 polynomial fit of Matt Zucker.
    Viridis,
    /// ColorBrewer's 11-class RdBu, reversed: 0 → dark blue, ½ → near white, 1 → dark red.
    /// For signed quantities with symmetric limits.
    Diverging,
    /// A closed hue circle at constant OKLab lightness (0.72) and chroma (0.11): 0 and 1 give the
    /// same colour. For angles (e.g. AoLP).
    Cyclic,
    /// Cyclic and diverging, for signed differences of angles (e.g. ΔAoLP in (−90°, 90°]):
    /// near white at ½ (no difference), blue below, red above, and the same dark grey at 0 and 1
    /// (±90°, the same orientation), so a wrap shows no edge. In OKLab with `x = 2π(t − ½)`:
    /// lightness `0.6 + 0.35·cos x`, chroma `0.15·|sin x|`, hue 30° (red) for `x > 0`, 255°
    /// (blue) for `x < 0`; the hue changes only where the chroma is 0, so the map is continuous.
    CyclicDiverging,
}

/// Viridis, polynomial fit (matplotlib's viridis is CC0; fit by Matt Zucker).
const VIRIDIS: [[f64; 3]; 7] = [
    [
        0.277_727_327_223_417_7,
        0.005_407_344_544_966_578,
        0.334_099_805_335_306_1,
    ],
    [
        0.105_093_043_108_577_4,
        1.404_613_529_898_575,
        1.384_590_162_594_685,
    ],
    [
        -0.330_861_828_725_556_3,
        0.214_847_559_468_213,
        0.095_095_163_028_236_59,
    ],
    [
        -4.634_230_498_983_486,
        -5.799_100_973_351_585,
        -19.332_440_956_279_87,
    ],
    [
        6.228_269_936_347_081,
        14.179_933_366_805_09,
        56.690_552_600_681_05,
    ],
    [
        4.776_384_997_670_288,
        -13.745_145_377_746_01,
        -65.353_032_633_372_34,
    ],
    [
        -5.435_455_855_934_631,
        4.645_852_612_178_535,
        26.312_435_249_583_2,
    ],
];

/// ColorBrewer RdBu (11 classes; Apache-2.0, Cynthia Brewer), from blue to red.
const RDBU_R: [[u8; 3]; 11] = [
    [0x05, 0x30, 0x61],
    [0x21, 0x66, 0xac],
    [0x43, 0x93, 0xc3],
    [0x92, 0xc5, 0xde],
    [0xd1, 0xe5, 0xf0],
    [0xf7, 0xf7, 0xf7],
    [0xfd, 0xdb, 0xc7],
    [0xf4, 0xa5, 0x82],
    [0xd6, 0x60, 0x4d],
    [0xb2, 0x18, 0x2b],
    [0x67, 0x00, 0x1f],
];

fn to_u8(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Linear-light value to the sRGB transfer curve.
fn srgb_encode(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// OKLab (Björn Ottosson, 2020) to 8-bit sRGB, clipped to the gamut.
fn oklab(l: f64, a: f64, b: f64) -> RGBColor {
    let l_ = l + 0.396_337_777_4 * a + 0.215_803_757_3 * b;
    let m_ = l - 0.105_561_345_8 * a - 0.063_854_172_8 * b;
    let s_ = l - 0.089_484_177_5 * a - 1.291_485_548_0 * b;
    let (l3, m3, s3) = (l_ * l_ * l_, m_ * m_ * m_, s_ * s_ * s_);
    let r = 4.076_741_662_1 * l3 - 3.307_711_591_3 * m3 + 0.230_969_929_2 * s3;
    let g = -1.268_438_004_6 * l3 + 2.609_757_401_1 * m3 - 0.341_319_396_5 * s3;
    let bl = -0.004_196_086_3 * l3 - 0.703_418_614_7 * m3 + 1.707_614_701_0 * s3;
    RGBColor(
        to_u8(srgb_encode(r)),
        to_u8(srgb_encode(g)),
        to_u8(srgb_encode(bl)),
    )
}

impl Colormap {
    /// The colour at `t` (clamped to `[0, 1]`; wrapped for [`Colormap::Cyclic`]);
    /// [`UNDEFINED`] grey for NaN.
    pub fn rgb(self, t: f64) -> RGBColor {
        if t.is_nan() {
            return UNDEFINED;
        }
        match self {
            Colormap::Viridis => {
                let t = t.clamp(0.0, 1.0);
                let mut c = [0.0; 3];
                for (k, v) in c.iter_mut().enumerate() {
                    *v = VIRIDIS.iter().rev().fold(0.0, |acc, row| acc * t + row[k]);
                }
                RGBColor(to_u8(c[0]), to_u8(c[1]), to_u8(c[2]))
            }
            Colormap::Diverging => {
                let x = t.clamp(0.0, 1.0) * (RDBU_R.len() - 1) as f64;
                let i = (x.floor() as usize).min(RDBU_R.len() - 2);
                let f = x - i as f64;
                let (a, b) = (RDBU_R[i], RDBU_R[i + 1]);
                let mix = |k: usize| {
                    (f64::from(a[k]) + f * (f64::from(b[k]) - f64::from(a[k]))).round() as u8
                };
                RGBColor(mix(0), mix(1), mix(2))
            }
            Colormap::Cyclic => {
                let h = std::f64::consts::TAU * t.rem_euclid(1.0);
                oklab(0.72, 0.11 * h.cos(), 0.11 * h.sin())
            }
            Colormap::CyclicDiverging => {
                let x = std::f64::consts::TAU * (t.rem_euclid(1.0) - 0.5);
                let chroma = 0.15 * x.sin().abs();
                let hue = if x > 0.0 { 30f64 } else { 255f64 }.to_radians();
                oklab(0.6 + 0.35 * x.cos(), chroma * hue.cos(), chroma * hue.sin())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance(a: RGBColor, b: RGBColor) -> i32 {
        [(a.0, b.0), (a.1, b.1), (a.2, b.2)]
            .iter()
            .map(|&(x, y)| (i32::from(x) - i32::from(y)).abs())
            .max()
            .unwrap_or(0)
    }

    #[test]
    fn the_cyclic_maps_close_and_the_diverging_one_does_not() {
        for map in [Colormap::Cyclic, Colormap::CyclicDiverging] {
            assert!(distance(map.rgb(0.0005), map.rgb(0.9995)) <= 2, "{map:?}");
            // Continuous everywhere: neighbours 1/1000 apart differ by a few levels at most.
            for i in 0..1000 {
                let t = f64::from(i) / 1000.0;
                assert!(
                    distance(map.rgb(t), map.rgb(t + 0.001)) <= 4,
                    "{map:?} at {t}"
                );
            }
        }
        assert!(distance(Colormap::Diverging.rgb(0.0), Colormap::Diverging.rgb(1.0)) > 60);
    }

    #[test]
    fn the_cyclic_diverging_map_is_light_at_zero_and_blue_below_red_above() {
        let m = Colormap::CyclicDiverging;
        let white = m.rgb(0.5);
        assert!(white.0 > 230 && white.1 > 230 && white.2 > 230, "{white:?}");
        let (blue, red) = (m.rgb(0.25), m.rgb(0.75));
        assert!(blue.2 > blue.0 + 40, "{blue:?}");
        assert!(red.0 > red.2 + 40, "{red:?}");
        let dark = m.rgb(0.0);
        assert!(dark.0 < 90 && dark.1 < 90 && dark.2 < 90, "{dark:?}");
    }
}
