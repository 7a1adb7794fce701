//! Images: each data pixel a block of its colour, row 0 at the top, NaN grey, cyclic scales
//! wrapped, valid PNG and SVG.

use polbrdf_plot::colormap::UNDEFINED;
use polbrdf_plot::{ColorScale, Colormap, HeatmapFigure, HeatmapPanel};

fn decode(png: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(png);
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// A 4 × 3 image: value = column + 4·row, one NaN.
fn figure(scale: ColorScale) -> HeatmapFigure {
    let mut values: Vec<f64> = (0..12).map(f64::from).collect();
    values[5] = f64::NAN;
    let mut panel = HeatmapPanel::new("test image", 4, 3, values, scale).unwrap();
    panel.outline = Some([1, 1, 3, 2]);
    HeatmapFigure {
        panel_size: (520, 400),
        columns: 1,
        panels: vec![panel],
    }
}

#[test]
fn each_data_pixel_is_a_block_of_its_colour() {
    let scale = ColorScale::linear(Colormap::Viridis, 0.0, 11.0, "value (1)");
    let fig = figure(scale.clone());
    let (w, h, rgb) = decode(&fig.png().unwrap());
    assert_eq!((w, h), fig.size());
    let at = fig.placement(0);
    assert!(at.scale > 50.0, "small images are enlarged: {at:?}");
    let pixel = |x: f64, y: f64| {
        let i = 3 * (y as usize * w as usize + x as usize);
        [rgb[i], rgb[i + 1], rgb[i + 2]]
    };
    for row in 0..3 {
        for col in 0..4 {
            // The centre of the data pixel, a quarter pixel off so the outline never covers it.
            let (x, y) = (
                at.x0 + at.scale * (col as f64 + 0.3),
                at.y0 + at.scale * (row as f64 + 0.3),
            );
            let v = (col + 4 * row) as f64;
            let want = if row == 1 && col == 1 {
                UNDEFINED
            } else {
                scale.color(v)
            };
            assert_eq!(pixel(x, y), [want.0, want.1, want.2], "({row}, {col})");
        }
    }
}

#[test]
fn cyclic_scale_wraps_and_svg_embeds_the_raster() {
    // AoLP-like: period 180 over (−90, 90]; −90 and 90 are the same colour.
    let mut scale = ColorScale::linear(Colormap::Cyclic, -90.0, 90.0, "AoLP (°)");
    scale.period = Some(180.0);
    assert_eq!(scale.color(-90.0), scale.color(90.0));
    let fig = figure(scale);
    let svg = fig.svg().unwrap();
    assert!(svg.contains("<image") && svg.contains("data:image/png;base64,"));
    assert!(svg.contains("test image") && svg.contains("AoLP (°)"));
    assert!(HeatmapPanel::new(
        "bad",
        2,
        2,
        vec![0.0; 3],
        ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "x")
    )
    .is_err());
}
