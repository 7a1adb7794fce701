//! `polbrdf_tasks::pbsdf`: the export's bounds, and a fit's plan from the header alone.

use polbrdf_tasks::pbsdf::{plan, ExportRequest, MAX_EXPORT_BYTES, MAX_FIT_WORK};
use polbrdf_tasks::TaskError;

fn field(e: TaskError) -> String {
    match e {
        TaskError::Invalid { field, .. } => field,
        e => panic!("{e}"),
    }
}

#[test]
fn the_export_is_bounded_by_its_size_before_anything_is_computed() {
    let bands = vec![450, 500, 550, 600, 650];
    let ok = ExportRequest {
        bands_nm: bands.clone(),
        grid: [361, 91, 91],
    };
    assert_eq!(ok.matrix_bytes(), 361 * 91 * 91 * 5 * 64);
    ok.validate().unwrap();
    // 2 × 4096 × 4096 cells × 5 bands: 10.7 GB, each axis within its range.
    let big = ExportRequest {
        bands_nm: bands.clone(),
        grid: [2, 4096, 4096],
    };
    assert!(big.matrix_bytes() > MAX_EXPORT_BYTES);
    assert_eq!(field(big.validate().unwrap_err()), "grid");
    let four = ExportRequest {
        bands_nm: vec![450, 500, 550, 600],
        grid: [3, 3, 3],
    };
    assert_eq!(field(four.validate().unwrap_err()), "bands_nm");
    // Refused before the material is even built: an export of a refused request writes nothing.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.pbsdf");
    let spec = polbrdf::preset("paint").unwrap();
    assert!(polbrdf_tasks::pbsdf::export(&spec, &big, &out).is_err());
    assert!(!out.exists());
}

#[test]
fn the_fit_plan_bounds_starts_times_cells() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.pbsdf");
    let req = ExportRequest {
        bands_nm: vec![450, 500, 550, 600, 650],
        grid: [21, 20, 20],
    };
    polbrdf_tasks::pbsdf::export(&polbrdf::preset("paint").unwrap(), &req, &path).unwrap();
    let table = polbrdf_io::PbsdfTable::open(&path).unwrap();
    // 8400 cells: stride 1 automatically (≤ 20 000), 476 starts at most.
    assert_eq!(plan(&table, None, 2).unwrap(), 1);
    let most = MAX_FIT_WORK / 8400 - 1;
    assert_eq!(plan(&table, Some(1), most).unwrap(), 1);
    assert_eq!(
        field(plan(&table, Some(1), most + 1).unwrap_err()),
        "starts"
    );
    // A larger stride makes room for more starts: 11 × 10 × 10 cells.
    assert_eq!(plan(&table, Some(2), most + 1).unwrap(), 2);
    assert_eq!(field(plan(&table, Some(0), 2).unwrap_err()), "subsample");
    assert_eq!(field(plan(&table, None, 10_001).unwrap_err()), "starts");
}
