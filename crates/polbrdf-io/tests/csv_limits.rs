//! Issue 18's CSV items: an unterminated quote, CR-only line ends, a very wide header, bounded
//! messages and lines, and measurement values outside their physical range.

use polbrdf_io::{
    parse_band_csv, parse_geometry_csv, parse_measurements_csv, parse_sky_profile_csv,
    parse_sky_table_csv, parse_views_csv, Error,
};
use std::path::Path;

const HEAD: &str = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg";

fn syntax_line(e: Error) -> (usize, String) {
    match e {
        Error::Syntax { line, message, .. } => (line, message),
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

#[test]
fn an_unterminated_quote_is_an_error_at_its_line_in_every_reader() {
    let p = Path::new("q.csv");
    // Row 1 (line 2) opens a quote that is never closed: the csv crate read the rest of the
    // file into that field and returned one row.
    let geo = format!("{HEAD},label\n30,0,30,180,\"abc\n40,0,40,180,x\n50,0,50,180,y\n");
    let (line, message) = syntax_line(parse_geometry_csv(geo.as_bytes(), p).unwrap_err());
    assert_eq!(line, 2);
    assert!(message.contains("quote"), "{message}");
    let meas = format!("{HEAD},brdf\n30,0,30,180,1\n40,0,40,180,\"0.5\n50,0,50,180,0.4\n");
    assert_eq!(
        syntax_line(parse_measurements_csv(meas.as_bytes(), p).unwrap_err()).0,
        3
    );
    let band = "wavelength_um,response\n8,1\n\"9,1\n10,1\n";
    assert_eq!(
        syntax_line(parse_band_csv(band.as_bytes(), p).unwrap_err()).0,
        3
    );
    let profile = "zenith_deg,radiance\n\"0,1\n90,1\n";
    assert_eq!(
        syntax_line(parse_sky_profile_csv(profile.as_bytes(), p).unwrap_err()).0,
        2
    );
    let table = "theta_deg,phi_deg,s0,s1,s2,s3\n0,0,1,0,0,0\n90,0,1,0,0,\"0\n";
    assert_eq!(
        syntax_line(parse_sky_table_csv(table.as_bytes(), p).unwrap_err()).0,
        3
    );
    let views = "theta_r_deg,phi_r_deg\n10,0\n20,\"0\n30,0\n";
    assert_eq!(
        syntax_line(parse_views_csv(views.as_bytes(), p).unwrap_err()).0,
        3
    );
    // A quote in the header, too.
    let header = "\"theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n";
    assert_eq!(
        syntax_line(parse_geometry_csv(header.as_bytes(), p).unwrap_err()).0,
        1
    );
}

#[test]
fn quoted_fields_within_a_line_still_work() {
    let geo = format!("{HEAD},label\n30,0,30,180,\"a,\"\"b\"\"\"\n\n40,0,40,180,plain\n");
    let t = parse_geometry_csv(geo.as_bytes(), Path::new("g.csv")).unwrap();
    assert_eq!(t.rows.len(), 2);
    assert_eq!(t.rows[0][4], "a,\"b\"");
    assert_eq!(t.lines, vec![2, 4]);
}

#[test]
fn cr_only_and_mixed_line_ends_count_lines() {
    // Old Mac line ends: each `\r` ends a line; the bad value is on line 3.
    let geo = format!("{HEAD}\r30,0,30,180\r40,0,x,180\r");
    match parse_geometry_csv(geo.as_bytes(), Path::new("g.csv")).unwrap_err() {
        Error::Field { line, field, .. } => assert_eq!((line, field.as_str()), (3, "theta_r_deg")),
        other => panic!("{other:?}"),
    }
    let geo = format!("{HEAD}\r\n30,0,30,180\r40,0,40,180\n50,0,50,180");
    let t = parse_geometry_csv(geo.as_bytes(), Path::new("g.csv")).unwrap();
    assert_eq!(t.lines, vec![2, 3, 4]);
}

#[test]
fn a_wide_header_is_checked_for_duplicates_by_hashing() {
    // 2·10⁵ distinct columns (1.4 MB would exceed the line bound: use short names), then a
    // duplicate at the end. The old pairwise check took O(n²) comparisons (31 s for 10⁵).
    let n = 120_000;
    let mut names: Vec<String> = (0..n).map(|k| format!("c{k}")).collect();
    names.extend(ANGLES.iter().map(|s| s.to_string()));
    let ok = names.join(",") + "\n";
    let t = parse_geometry_csv(ok.as_bytes(), Path::new("w.csv")).unwrap();
    assert_eq!(t.headers.len(), n + 4);
    names.push("c7".into());
    let bad = names.join(",") + "\n";
    let (line, message) =
        syntax_line(parse_geometry_csv(bad.as_bytes(), Path::new("w.csv")).unwrap_err());
    assert_eq!(line, 1);
    assert!(message.contains("`c7` appears twice"), "{message}");
}

const ANGLES: [&str; 4] = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"];

#[test]
fn messages_about_names_are_bounded() {
    // A header of one 500 kB name, 10⁴ others and one angle column (a table of the kind, with
    // three angle columns missing): the message lists the header, shortened. (A header with no
    // angle column at all is not listed: issue 35.)
    let long = "k".repeat(500_000);
    let mut header = vec![long.clone()];
    header.extend((0..10_000).map(|k| format!("column{k}")));
    header.push("theta_i_deg".into());
    let text = header.join(",") + "\n";
    let e = parse_geometry_csv(text.as_bytes(), Path::new("h.csv")).unwrap_err();
    let m = e.to_string();
    assert!(m.len() < 2048, "{} bytes", m.len());
    assert!(
        m.contains("missing column(s) phi_i_deg") && m.contains("more"),
        "{m}"
    );
    // The same name twice.
    let text = format!("{long},{long}\n");
    let m = parse_geometry_csv(text.as_bytes(), Path::new("h.csv"))
        .unwrap_err()
        .to_string();
    assert!(m.len() < 2048 && m.contains("appears twice"), "{m:.200}");
    // A line longer than the bound is refused without reading it whole.
    let text = format!(
        "{HEAD}\n{}\n",
        "1".repeat(polbrdf_io::csv_io::MAX_LINE_BYTES + 1)
    );
    let (line, m) =
        syntax_line(parse_geometry_csv(text.as_bytes(), Path::new("h.csv")).unwrap_err());
    assert_eq!(line, 2);
    assert!(m.contains("longer than"), "{m}");
}

#[test]
fn measured_values_outside_their_physical_range_are_refused() {
    let p = Path::new("m.csv");
    for (column, value) in [
        ("brdf", "-0.1"),
        ("brdf_s", "-1e-3"),
        ("brdf_p", "-2"),
        ("m00", "-1"),
        ("dolp", "5"),
        ("dolp", "-0.01"),
    ] {
        let text = format!("{HEAD},{column}\n30,0,30,180,0.5\n40,0,40,180,{value}\n");
        match parse_measurements_csv(text.as_bytes(), p).unwrap_err() {
            Error::Field { line, field, .. } => assert_eq!((line, field.as_str()), (3, column)),
            other => panic!("{column} = {value}: {other:?}"),
        }
    }
    // Within 5σ of noise, a value outside the range is data; beyond, it is refused.
    let noisy = format!("{HEAD},dolp,sigma_dolp\n30,0,30,180,-0.03,0.01\n40,0,40,180,1.04,0.01\n");
    parse_measurements_csv(noisy.as_bytes(), p).unwrap();
    let far = format!("{HEAD},dolp,sigma_dolp\n30,0,30,180,0.5,0.01\n40,0,40,180,-0.06,0.01\n");
    match parse_measurements_csv(far.as_bytes(), p).unwrap_err() {
        Error::Field { line, field, .. } => assert_eq!((line, field.as_str()), (3, "dolp")),
        other => panic!("{other:?}"),
    }
    // The edges are data, and the other Mueller entries may be negative.
    let text = format!("{HEAD},brdf,dolp,m01\n30,0,30,180,0,1,-0.3\n40,0,40,180,0.2,0,0.1\n");
    parse_measurements_csv(text.as_bytes(), p).unwrap();
}

#[test]
fn a_material_argument_is_a_file_by_its_form_not_by_what_exists() {
    // (The working directory's part is in the CLI tests: `a_file_named_like_a_preset…`.)
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("paint")).unwrap();
    // A path to a folder is a read error (exit code 4), not the preset.
    let e = polbrdf_io::load_material(dir.path().join("paint").to_str().unwrap()).unwrap_err();
    assert!(!e.is_data_error(), "{e}");
    let m = polbrdf_io::load_material("no-such-preset")
        .unwrap_err()
        .to_string();
    assert!(m.contains("not a preset"), "{m}");
}

#[test]
fn toml_files_dotted_keys_cr_only_lines_and_long_keys() {
    let p = Path::new("m.toml");
    let m = polbrdf_io::parse_material("n = 1.5\nsigma_deg = 10\na.b = 1\n", p)
        .unwrap_err()
        .to_string();
    assert!(m.contains(":3:") && m.contains("dotted keys"), "{m}");
    // Old Mac line ends: the bad value is on line 3.
    match polbrdf_io::parse_material("n = 1.5\rsigma_deg = 10\rrho_d = -1\r", p).unwrap_err() {
        Error::Field { line, field, .. } => assert_eq!((line, field.as_str()), (3, "rho_d")),
        other => panic!("{other}"),
    }
    let scene = "wavelength_um = 10\r[target]\rmaterial = \"paint\"\rtemperature_k = -4\r";
    match polbrdf_io::parse_scene(scene, Path::new("s.toml")).unwrap_err() {
        Error::Field { line, .. } => assert_eq!(line, 4),
        other => panic!("{other}"),
    }
    // A 1 MB key: the message stays short.
    let key = "k".repeat(1 << 20);
    for text in [
        format!("{key} = 1\n"),
        format!("n = 1\n{key} = 1\n{key} = 2\n"),
    ] {
        let m = polbrdf_io::parse_material(&text, p)
            .unwrap_err()
            .to_string();
        assert!(m.len() < 2048, "{} bytes: {:.100}", m.len(), m);
    }
    let m = polbrdf_io::parse_scene(&format!("wavelength_um = 1\n[target]\n{key} = 1\n"), p)
        .unwrap_err()
        .to_string();
    assert!(m.len() < 2048, "{} bytes", m.len());
}

/// Issue 35 item 2: a chunk of a wide table holds at most `CHUNK_CELLS` cells (its memory is
/// bounded by bytes, not by a row count), every row still comes through once and in order, and
/// the chunks of the `.npy` form of the same table are cut alike.
#[test]
fn a_wide_table_is_read_in_chunks_bounded_by_cells() {
    use polbrdf_io::npy::NpyWriter;
    use polbrdf_io::stream::{chunk_rows, Format, GeometryReader, CHUNK_CELLS, CHUNK_ROWS};
    let width = 2000;
    let rows = 1100;
    let mut names: Vec<String> = HEAD.split(',').map(str::to_string).collect();
    names.extend((4..width).map(|i| format!("c{i}")));
    let mut csv = names.join(",") + "\n";
    let mut values = Vec::with_capacity(width * rows);
    for r in 0..rows {
        let row: Vec<f64> = (0..width)
            .map(|i| match i {
                0 | 2 => 30.0,
                1 => (r % 360) as f64,
                3 => 180.0,
                _ => 1.0,
            })
            .collect();
        csv += &row
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join(",");
        csv.push('\n');
        values.extend(row);
    }
    let mut npy = Vec::new();
    let mut w = NpyWriter::new(&mut npy, &names, rows as u64).unwrap();
    w.write_rows(&values).unwrap();
    w.finish().unwrap();
    let want = chunk_rows(CHUNK_ROWS, width);
    assert_eq!(want, CHUNK_CELLS / width);
    assert!(want < rows && want * width <= CHUNK_CELLS);
    for (format, bytes) in [(Format::Csv, csv.into_bytes()), (Format::Npy, npy)] {
        let mut r = GeometryReader::from_reader(
            Box::new(std::io::Cursor::new(bytes)),
            Path::new("wide"),
            format,
        )
        .unwrap();
        let mut sizes = Vec::new();
        let mut phi = Vec::new();
        while let Some(c) = r.next_chunk(CHUNK_ROWS).unwrap() {
            sizes.push(c.len());
            let polbrdf_io::stream::Geometries::Angles(g) = &c.geometries else {
                panic!("angles")
            };
            phi.extend(g.iter().map(|g| g.phi_i().to_degrees().round() as usize));
        }
        assert_eq!(sizes, [want, rows - want], "{format:?}");
        assert_eq!(
            phi,
            (0..rows).map(|r| r % 360).collect::<Vec<_>>(),
            "{format:?}"
        );
    }
}
