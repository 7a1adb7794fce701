//! The CLI is an adapter over the task layer: the files `polbrdf contrast` writes hold exactly
//! what `polbrdf_tasks::contrast` returns for the same request (the README's three contrast
//! examples on a coarser grid), so any other adapter (Python) calling the task gets the same
//! bits.

use crate::common::{polbrdf, stderr};
use polbrdf_tasks::contrast::{contrast, ContrastRequest, RankRequest, SourceRequest};
use polbrdf_tasks::hemisphere::LightRequest;
use polbrdf_tasks::spectrum::SpectralRequest;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn same_files(args: &[&str], request: &ContrastRequest) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut all = vec![
        "contrast",
        "--grid-deg",
        "5,10",
        "--out",
        out.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    let o = polbrdf(&all);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    let study = contrast(request).unwrap();
    let mut csv = polbrdf_io::CsvTable::new(study.columns());
    for row in study.rows() {
        csv.row(&row);
    }
    let written = std::fs::read(out.join("contrast.csv")).unwrap();
    assert!(
        written == csv.into_bytes(),
        "{args:?}: contrast.csv differs"
    );
    let mut best = serde_json::to_string_pretty(&study.best_json()).unwrap();
    best.push('\n');
    let written = std::fs::read_to_string(out.join("best.json")).unwrap();
    assert_eq!(written, best, "{args:?}: best.json differs");
}

#[test]
fn contrast_files_are_the_task_results() {
    let scene = |file: &str| ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Scene(example(file).into()),
        grid_deg: (5.0, 10.0),
        rank: RankRequest::default(),
    };
    let (olive, soil) = (example("olive-paint.toml"), example("dry-soil.toml"));
    same_files(
        &[
            "--target",
            &olive,
            "--background",
            &soil,
            "--sun-zenith-deg",
            "50",
        ],
        &ContrastRequest {
            target: Some(olive.clone()),
            background: Some(soil.clone()),
            source: SourceRequest::Collimated {
                light: LightRequest::sun(50.0, 0.0),
                spectral: SpectralRequest::default(),
            },
            grid_deg: (5.0, 10.0),
            rank: RankRequest::default(),
        },
    );
    for file in ["daylight-scene.toml", "lwir-scene.toml"] {
        same_files(&["--scene", &example(file)], &scene(file));
    }
}
