//! Sets of files (`write_files`, issue 18 item 8), with faults injected: a set that fails while
//! it is staged changes nothing, and one that fails while it is moved into place has no
//! completion marker, so a consumer never reads a partial set as whole.

use polbrdf_io::write::SET_MARKER;
use polbrdf_io::write_files;
use std::path::Path;

fn files(names: &[&str]) -> Vec<(String, Vec<u8>)> {
    names
        .iter()
        .map(|n| (n.to_string(), format!("new {n}").into_bytes()))
        .collect()
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Every file of `dir` with its bytes, sorted by name.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    listing(dir)
        .into_iter()
        .map(|n| {
            let b = std::fs::read(dir.join(&n)).unwrap();
            (n, b)
        })
        .collect()
}

#[test]
fn a_new_set_appears_whole_with_its_marker() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    write_files(&dir, &files(&["a.csv", "b.png"])).unwrap();
    assert_eq!(listing(&dir), ["_COMPLETE", "a.csv", "b.png"]);
    assert_eq!(
        std::fs::read_to_string(dir.join(SET_MARKER)).unwrap(),
        "a.csv\nb.png\n"
    );
    assert_eq!(listing(tmp.path()), ["out"], "no staging directory left");
}

#[test]
fn a_fault_while_staging_a_new_set_leaves_nothing() {
    // The second file cannot be staged (its name is refused after the first was written).
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let e = write_files(&dir, &files(&["a.csv", "sub/b.png", "c.csv"])).unwrap_err();
    assert!(e.to_string().contains("b.png"), "{e}");
    assert!(!dir.exists(), "a failed new set must not appear");
    assert!(listing(tmp.path()).is_empty(), "{:?}", listing(tmp.path()));
}

#[test]
fn a_fault_while_staging_over_an_old_set_keeps_the_old_set() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    write_files(&dir, &files(&["a.csv", "b.png"])).unwrap();
    let before = contents(&dir);
    assert!(write_files(
        &dir,
        &[("a.csv".into(), b"x".to_vec()), ("".into(), vec![])]
    )
    .is_err());
    let after = contents(&dir);
    assert_eq!(after, before, "the old set, marker included, is untouched");
    assert_eq!(listing(tmp.path()), ["out"], "no staging directory left");
}

#[test]
fn a_fault_while_moving_into_place_leaves_no_marker() {
    // `b.png` of the new set cannot replace what is there (a non-empty directory), after
    // `a.csv` was moved: the directory then holds a mix, and its marker must be gone.
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    write_files(&dir, &files(&["a.csv"])).unwrap();
    std::fs::create_dir(dir.join("b.png")).unwrap();
    std::fs::write(dir.join("b.png").join("keep"), b"x").unwrap();
    assert!(dir.join(SET_MARKER).exists());
    let e = write_files(&dir, &files(&["a.csv", "b.png"])).unwrap_err();
    assert!(e.to_string().contains("b.png"), "{e}");
    assert!(
        !dir.join(SET_MARKER).exists(),
        "a partly replaced set must not carry a completion marker"
    );
    assert_eq!(listing(tmp.path()), ["out"], "no staging directory left");
}
