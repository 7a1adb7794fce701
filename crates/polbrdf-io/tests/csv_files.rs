//! Geometry CSV reading and atomic writes.

use polbrdf_io::{read_geometry_csv, write_atomic, Error};

fn with_file(text: &[u8]) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("g.csv");
    std::fs::write(&p, text).unwrap();
    (dir, p)
}

#[test]
fn columns_in_any_order_with_pass_through() {
    let (_d, p) =
        with_file(b"phi_r_deg,x,theta_r_deg,phi_i_deg,theta_i_deg\n180,keep me,30,0,20\n");
    let t = read_geometry_csv(&p).unwrap();
    assert_eq!(t.rows[0][1], "keep me");
    let g = t.geometries[0];
    assert!((g.theta_i() - 20f64.to_radians()).abs() < 1e-15);
    assert!((g.theta_r() - 30f64.to_radians()).abs() < 1e-15);
    assert!((g.phi_r() - 180f64.to_radians()).abs() < 1e-15);
    assert_eq!(t.lines, vec![2]);
}

#[test]
fn errors_name_line_and_column() {
    let (_d, p) = with_file(b"theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n1,2,3,4\n\n1,2,3,inf\n");
    match read_geometry_csv(&p).unwrap_err() {
        Error::Field { line, field, .. } => assert_eq!((line, field.as_str()), (4, "phi_r_deg")),
        other => panic!("{other}"),
    }
    let (_d, p) = with_file(b"theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n1,2,3,4\n190,0,0,0\n");
    let e = read_geometry_csv(&p).unwrap_err().to_string();
    assert!(
        e.contains(":3:") && e.contains("theta_i_deg") && e.contains("190"),
        "{e}"
    );
    let (_d, p) =
        with_file(b"theta_i_deg,phi_i_deg,theta_r_deg,theta_r_deg,phi_r_deg\n1,2,3,3,4\n");
    assert!(read_geometry_csv(&p)
        .unwrap_err()
        .to_string()
        .contains("twice"));
    let (_d, p) = with_file(b"theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n\x00\xff\xfe,1,2,3\n");
    assert!(matches!(
        read_geometry_csv(&p).unwrap_err(),
        Error::Syntax { line: 2, .. }
    ));
}

#[test]
fn atomic_write_replaces_whole_files_only() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("out.csv");
    write_atomic(&p, b"first").unwrap();
    write_atomic(&p, b"second").unwrap();
    assert_eq!(std::fs::read(&p).unwrap(), b"second");
    let bad = dir.path().join("no-such-dir").join("out.csv");
    assert!(matches!(write_atomic(&bad, b"x"), Err(Error::Write { .. })));
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 1, "no temporary files left: {names:?}");
}
