//! Issue 18: a file or folder in the working directory named like a preset never shadows it.

use std::process::Command;

#[test]
fn a_file_named_like_a_preset_does_not_shadow_it() {
    let dir = tempfile::tempdir().unwrap();
    let geo = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n";
    std::fs::write(dir.path().join("g.csv"), geo).unwrap();
    let run = |material: &str| {
        Command::new(env!("CARGO_BIN_EXE_polbrdf"))
            .current_dir(dir.path())
            .args(["eval", "--material", material, "--input", "g.csv"])
            .output()
            .unwrap()
    };
    let before = run("paint");
    assert!(before.status.success());
    // After `map --out paint`: a folder `paint` (was: "Is a directory").
    std::fs::create_dir(dir.path().join("paint")).unwrap();
    let with_folder = run("paint");
    assert!(
        with_folder.status.success(),
        "{}",
        String::from_utf8_lossy(&with_folder.stderr)
    );
    assert_eq!(with_folder.stdout, before.stdout);
    // A material file named like no preset: read with a path, refused as a name.
    std::fs::write(dir.path().join("mine"), "n = 1.5\nsigma_deg = 10\n").unwrap();
    let bare = run("mine");
    assert_eq!(bare.status.code(), Some(3));
    let msg = String::from_utf8_lossy(&bare.stderr);
    assert!(
        msg.contains("not a preset") && msg.contains("./mine"),
        "{msg}"
    );
    assert!(run("./mine").status.success());
}
