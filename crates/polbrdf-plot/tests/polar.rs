//! Polar heat maps: layout, colours where the data say, valid PNG and SVG.

use polbrdf_plot::{
    ColorScale, Colormap, MarkShape, PolarFigure, PolarGrid, PolarMark, PolarPanel,
};

/// A smooth test field: v = θ/90 · (1 + cos φ)/2.
fn field(theta: f64, phi: f64) -> f64 {
    theta / 90.0 * (1.0 + phi.to_radians().cos()) / 2.0
}

fn figure(marks: Vec<PolarMark>) -> PolarFigure {
    let theta: Vec<f64> = (0..90).map(f64::from).collect();
    let phi: Vec<f64> = (0..180).map(|j| 2.0 * f64::from(j)).collect();
    let values = theta
        .iter()
        .flat_map(|&t| phi.iter().map(move |&p| field(t, p)))
        .collect();
    PolarFigure {
        panel_size: (600, 560),
        columns: 1,
        panels: vec![PolarPanel {
            title: "test field".into(),
            grid: PolarGrid::new(theta, phi, values).unwrap(),
            scale: ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "value (1)"),
            marks,
        }],
    }
}

fn decode(png: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(png);
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn close(a: [u8; 3], b: [u8; 3], tol: i32) -> bool {
    (0..3).all(|k| (i32::from(a[k]) - i32::from(b[k])).abs() <= tol)
}

#[test]
fn pixels_show_the_colour_of_the_interpolated_value() {
    let fig = figure(vec![]);
    let (w, h, rgb) = decode(&fig.png().unwrap());
    assert_eq!((w, h), fig.size());
    let disk = fig.disk(0);
    let scale = &fig.panels[0].scale;
    let mut checked = 0;
    for (theta, phi) in [
        (10.0, 20.0),
        (45.0, 100.0),
        (75.0, 200.0),
        (50.0, 340.0),
        (85.0, 5.0),
    ] {
        let (x, y) = disk.position(theta, phi);
        let (px, py) = (x.floor() as usize, y.floor() as usize);
        // The pixel centre's own direction, and the field there.
        let (t, p) = disk.direction(px as f64 + 0.5, py as f64 + 0.5).unwrap();
        let want = scale.color(field(t, p));
        let at = 3 * (py * w as usize + px);
        let got = [rgb[at], rgb[at + 1], rgb[at + 2]];
        assert!(
            close(got, [want.0, want.1, want.2], 3),
            "θ = {theta}, φ = {phi}: pixel {got:?}, colour map {want:?}"
        );
        checked += 1;
    }
    assert_eq!(checked, 5);
    // Outside the disk and the decorations, the background is white.
    assert_eq!(&rgb[0..3], &[255, 255, 255]);
}

#[test]
fn azimuth_runs_counterclockwise_from_the_right() {
    let fig = figure(vec![]);
    let d = fig.disk(0);
    let (x, y) = d.position(90.0, 0.0);
    assert!((x - (d.cx + d.r)).abs() < 1e-9 && (y - d.cy).abs() < 1e-9);
    let (x, y) = d.position(90.0, 90.0);
    assert!(
        (x - d.cx).abs() < 1e-9 && (y - (d.cy - d.r)).abs() < 1e-9,
        "φ = 90° is up"
    );
    let (t, p) = d.direction(d.cx - d.r / 2.0, d.cy).unwrap();
    assert!((t - 45.0).abs() < 1e-9 && (p - 180.0).abs() < 1e-9);
    assert!(d.direction(d.cx + d.r + 1.0, d.cy).is_none());
}

#[test]
fn png_and_svg_are_valid_and_hold_the_map() {
    let marks = vec![
        PolarMark {
            theta_deg: 45.0,
            phi_deg: 0.0,
            shape: MarkShape::Sun,
            label: String::new(),
            legend: "sun".into(),
        },
        PolarMark {
            theta_deg: 45.0,
            phi_deg: 180.0,
            shape: MarkShape::Specular,
            label: String::new(),
            legend: "specular".into(),
        },
        PolarMark {
            theta_deg: 60.0,
            phi_deg: 90.0,
            shape: MarkShape::Best,
            label: "1".into(),
            legend: "best".into(),
        },
    ];
    let fig = figure(marks);
    let png = fig.png().unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let (_, _, rgb) = decode(&png);
    let distinct: std::collections::BTreeSet<[u8; 3]> =
        rgb.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    assert!(distinct.len() > 200, "only {} colours", distinct.len());

    let svg = fig.svg().unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("test field") && svg.contains("value (1)") && svg.contains("30°"));
    // The embedded raster decodes to the same map.
    let start = svg.find("data:image/png;base64,").unwrap() + "data:image/png;base64,".len();
    let end = start + svg[start..].find('"').unwrap();
    let bytes = base64_decode(&svg[start..end]);
    let (w, h, _) = decode(&bytes);
    assert_eq!(w, h);
    assert!(f64::from(w) >= 2.0 * fig.disk(0).r);
    // The raster lies under the vector drawing: it comes first, right after the background.
    assert!(svg.find("<image").unwrap() < svg.find("<text").unwrap());
}

fn base64_decode(s: &str) -> Vec<u8> {
    let val = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: {c}"),
        }
    };
    let mut out = Vec::new();
    for chunk in s.as_bytes().chunks(4) {
        let pad = chunk.iter().filter(|&&c| c == b'=').count();
        let n = chunk
            .iter()
            .map(|&c| if c == b'=' { 0 } else { val(c) })
            .fold(0u32, |a, v| (a << 6) | v);
        let bytes = [(n >> 16) as u8, (n >> 8) as u8, n as u8];
        out.extend_from_slice(&bytes[..3 - pad]);
    }
    out
}

#[test]
fn periodic_values_interpolate_on_the_circle() {
    // AoLP-like field: +89° and −89° are 2° apart, not 178°.
    let theta = vec![0.0, 90.0];
    let phi: Vec<f64> = (0..4).map(|j| 90.0 * f64::from(j)).collect();
    let values = vec![89.0, -89.0, 89.0, -89.0, 89.0, -89.0, 89.0, -89.0];
    let mut scale = ColorScale::linear(Colormap::Cyclic, -90.0, 90.0, "AoLP (°)");
    scale.period = Some(180.0);
    let fig = PolarFigure {
        panel_size: (500, 480),
        columns: 1,
        panels: vec![PolarPanel {
            title: String::new(),
            grid: PolarGrid::new(theta, phi, values).unwrap(),
            scale: scale.clone(),
            marks: vec![],
        }],
    };
    let (w, _, rgb) = decode(&fig.png().unwrap());
    let d = fig.disk(0);
    // Halfway between φ = 0° (+89°) and 90° (−89°): the circular mean is 90°, not 0°.
    let (x, y) = d.position(45.0, 45.0);
    let at = 3 * (y as usize * w as usize + x as usize);
    let want = scale.color(90.0);
    let wrong = scale.color(0.0);
    let got = [rgb[at], rgb[at + 1], rgb[at + 2]];
    assert!(
        close(got, [want.0, want.1, want.2], 12),
        "{got:?} vs {want:?}"
    );
    assert!(!close(got, [wrong.0, wrong.1, wrong.2], 12));
}

#[test]
fn log_scale_and_colour_maps() {
    let s = ColorScale::log10(Colormap::Viridis, 1e-3, 10.0, "BRDF (sr⁻¹)");
    assert!((s.t(1e-3)).abs() < 1e-12 && (s.t(10.0) - 1.0).abs() < 1e-12);
    assert!((s.t(0.1) - 0.5).abs() < 1e-12);
    assert!(s.t(0.0) < 0.0, "zero lies below a log scale");
    // Viridis: dark purple to yellow; diverging: blue, white, red; cyclic closes.
    let v0 = Colormap::Viridis.rgb(0.0);
    let v1 = Colormap::Viridis.rgb(1.0);
    assert!(
        v0.2 > v0.1 && v1.0 > 200 && v1.1 > 200 && v1.2 < 80,
        "{v0:?} {v1:?}"
    );
    let mid = Colormap::Diverging.rgb(0.5);
    assert!(mid.0 > 240 && mid.1 > 240 && mid.2 > 240);
    assert!(Colormap::Diverging.rgb(0.0).2 > Colormap::Diverging.rgb(0.0).0);
    assert!(Colormap::Diverging.rgb(1.0).0 > Colormap::Diverging.rgb(1.0).2);
    assert_eq!(Colormap::Cyclic.rgb(0.0), Colormap::Cyclic.rgb(1.0));
    assert_eq!(
        Colormap::Viridis.rgb(f64::NAN),
        polbrdf_plot::colormap::UNDEFINED
    );
    assert_eq!(polbrdf_plot::nice_ceil(0.37), 0.4);
    assert_eq!(polbrdf_plot::nice_ceil(1.0), 1.0);
}

#[test]
fn a_delta_aolp_wrap_at_plus_minus_90_degrees_is_no_edge() {
    // ΔAoLP of +89.9° and −89.9° are orientations 0.2° apart: the same colour (issue 36).
    let scale = ColorScale {
        period: Some(180.0),
        ..ColorScale::linear(Colormap::CyclicDiverging, -90.0, 90.0, "ΔAoLP (°)")
    };
    let (a, b) = (scale.color(89.9), scale.color(-89.9));
    let d = [(a.0, b.0), (a.1, b.1), (a.2, b.2)]
        .iter()
        .map(|&(x, y)| (i32::from(x) - i32::from(y)).abs())
        .max()
        .unwrap();
    assert!(d <= 2, "{a:?} vs {b:?}");
    // The diverging map the contrast figure used before puts them at the two ends of the bar.
    let old = ColorScale {
        colormap: Colormap::Diverging,
        ..scale.clone()
    };
    let (a, b) = (old.color(89.9), old.color(-89.9));
    assert!(i32::from(a.0) - i32::from(b.0) > 50, "{a:?} vs {b:?}");
    // No difference is white.
    let w = scale.color(0.0);
    assert!(w.0 > 230 && w.1 > 230 && w.2 > 230, "{w:?}");
}
