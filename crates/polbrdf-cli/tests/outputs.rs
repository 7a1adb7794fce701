//! Output guarantees (issue 18): `-`, devices, FIFOs and links; same-file refusal; no
//! temporaries left; streaming `eval` with `.npy` in and out; closed standard output.

use crate::common::{polbrdf, stderr, write};
use polbrdf_io::npy::{npy_bytes, parse_npy};
use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};

const GEO: &str = "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,tag\n30,0,30,180,1\n45,0,20,90,2\n";

fn eval_to(input: &str, output: &str) -> std::process::Output {
    polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        input,
        "--output",
        output,
    ])
}

fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".polbrdf-"))
        .collect()
}

#[test]
fn dash_is_standard_output_not_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    let o = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .current_dir(dir.path())
        .args([
            "eval",
            "--material",
            "paint",
            "--input",
            &geo,
            "--output",
            "-",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert_eq!(text.lines().count(), 3);
    assert!(text.starts_with("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,tag,brdf,"));
    assert!(!dir.path().join("-").exists());
}

#[cfg(unix)]
#[test]
fn devices_and_links_to_them_are_written_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    // A link to the null device (what `mknod fakedev/null c 1 3` makes, without root).
    let link = dir.path().join("null");
    std::os::unix::fs::symlink("/dev/null", &link).unwrap();
    for out in [link.to_str().unwrap(), "/dev/null"] {
        let o = eval_to(&geo, out);
        assert!(o.status.success(), "{out}: {}", stderr(&o));
    }
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    // A device node proper, where we may make one (root).
    let node = dir.path().join("fakenull");
    let made = Command::new("mknod")
        .arg(&node)
        .args(["c", "1", "3"])
        .status()
        .is_ok_and(|s| s.success());
    if made {
        let o = eval_to(&geo, node.to_str().unwrap());
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(std::fs::metadata(&node)
            .unwrap()
            .file_type()
            .is_char_device());
    } else {
        eprintln!("skipped the mknod case: cannot create a device node here (not root)");
    }
    assert!(temporaries(dir.path()).is_empty());
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_an_io_error_naming_it() {
    if !Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    let o = eval_to(&geo, "/dev/full");
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("/dev/full: cannot write"),
        "{}",
        stderr(&o)
    );
}

#[cfg(unix)]
#[test]
fn a_fifo_is_written_to_its_reader() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    let fifo = dir.path().join("pipe");
    if !Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        eprintln!("skipped: mkfifo unavailable");
        return;
    }
    let reader_path = fifo.clone();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        std::fs::File::open(&reader_path)
            .unwrap()
            .read_to_string(&mut s)
            .unwrap();
        s
    });
    let o = eval_to(&geo, fifo.to_str().unwrap());
    assert!(o.status.success(), "{}", stderr(&o));
    let got = reader.join().unwrap();
    assert_eq!(got.lines().count(), 3, "{got}");
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert!(temporaries(dir.path()).is_empty());
}

#[cfg(unix)]
#[test]
fn a_symlinked_output_writes_its_target_and_stays_a_link() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    std::fs::create_dir(dir.path().join("real")).unwrap();
    let target = dir.path().join("real/out.csv");
    std::fs::write(&target, "old").unwrap();
    let link = dir.path().join("out.csv");
    std::os::unix::fs::symlink("real/out.csv", &link).unwrap();
    let o = eval_to(&geo, link.to_str().unwrap());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap().lines().count(), 3);
    // A dangling link creates its target.
    let dangling = dir.path().join("new.csv");
    std::os::unix::fs::symlink("real/created.csv", &dangling).unwrap();
    let o = eval_to(&geo, dangling.to_str().unwrap());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("real/created.csv").is_file());
}

#[cfg(unix)]
#[test]
fn read_only_and_hard_linked_outputs_are_refused_untouched() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    let ro = dir.path().join("ro.csv");
    std::fs::write(&ro, "keep").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    let o = eval_to(&geo, ro.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("read-only"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "keep");
    let a = dir.path().join("a.csv");
    let b = dir.path().join("b.csv");
    std::fs::write(&a, "keep").unwrap();
    std::fs::hard_link(&a, &b).unwrap();
    let o = eval_to(&geo, a.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("2 hard links"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&b).unwrap(), "keep");
}

#[test]
fn an_output_that_is_an_input_or_another_output_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    // The same file under another spelling.
    let other = format!("{}/./g.csv", dir.path().display());
    let o = eval_to(&geo, &other);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("same file as the input"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&geo).unwrap(), GEO);

    let meas = write(
        dir.path(),
        "m.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n20,0,20,180,1.0\n30,0,30,180,0.5\n40,0,40,180,0.4\n",
    );
    let fit = |extra: &[&str]| {
        let mut args = vec![
            "fit",
            "--material",
            "paint",
            "--data",
            &meas,
            "--free",
            "rho_d",
        ];
        args.extend_from_slice(extra);
        polbrdf(&args)
    };
    let o = fit(&["--output", &meas]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let o = fit(&["--plot", &meas]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&meas)
        .unwrap()
        .starts_with("theta_i_deg"));
    let x = dir.path().join("x.out");
    let x = x.to_str().unwrap();
    let o = fit(&["--output", x, "--material-out", x]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("same file as the output"),
        "{}",
        stderr(&o)
    );
    assert!(!Path::new(x).exists());

    let mat = write(dir.path(), "mat.toml", "n = 1.5\nk = 0\nsigma_deg = 10\n");
    let o = polbrdf(&["albedo", "--material", &mat, "--output", &mat]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&mat)
        .unwrap()
        .starts_with("n = 1.5"));
}

#[test]
fn npy_in_and_out_agree_with_csv() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    let d = dir.path().to_str().unwrap();
    let (csv_out, npy_out) = (format!("{d}/o.csv"), format!("{d}/o.npy"));
    assert!(eval_to(&geo, &csv_out).status.success());
    let o = eval_to(&geo, &npy_out);
    assert!(o.status.success(), "{}", stderr(&o));
    let t = parse_npy(&std::fs::read(&npy_out).unwrap(), Path::new(&npy_out)).unwrap();
    let text = std::fs::read_to_string(&csv_out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(t.columns, header);
    let values: Vec<f64> = lines
        .flat_map(|l| l.split(',').map(|f| f.parse::<f64>().unwrap()))
        .collect();
    assert_eq!(
        t.data, values,
        "the CSV's shortest round-trip text is the .npy's value"
    );
    // The .npy as input: the same table again (passthrough columns as numbers).
    let input = format!("{d}/in.npy");
    let cols = [
        "theta_i_deg",
        "phi_i_deg",
        "theta_r_deg",
        "phi_r_deg",
        "tag",
    ];
    let rows = [30.0, 0.0, 30.0, 180.0, 1.0, 45.0, 0.0, 20.0, 90.0, 2.0];
    std::fs::write(&input, npy_bytes(&cols, &rows).unwrap()).unwrap();
    let again = format!("{d}/again.npy");
    let o = eval_to(&input, &again);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(&again).unwrap(),
        std::fs::read(&npy_out).unwrap()
    );
    // To a pipe (unseekable), the count is patched in a spool and copied.
    let o = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args([
            "eval",
            "--material",
            "paint",
            "--input",
            &geo,
            "--output",
            "/dev/stdout",
        ])
        .stdout(Stdio::piped())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    // `/dev/stdout` has no .npy extension: CSV.
    assert_eq!(String::from_utf8(o.stdout).unwrap(), text);
}

#[test]
fn npy_output_of_a_text_column_and_bad_npy_input_name_the_place() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(
        dir.path(),
        "g.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,name\n30,0,30,180,one\n",
    );
    let out = dir.path().join("o.npy");
    let o = eval_to(&geo, out.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3));
    assert!(
        stderr(&o).contains("g.csv:2: field `name`"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    let bad = dir.path().join("bad.npy");
    std::fs::write(
        &bad,
        npy_bytes(
            &["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"],
            &[30.0, 0.0, f64::NAN, 0.0],
        )
        .unwrap(),
    )
    .unwrap();
    let o = eval_to(bad.to_str().unwrap(), out.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3));
    assert!(
        stderr(&o).contains("bad.npy:1: field `theta_r_deg`"),
        "{}",
        stderr(&o)
    );
    std::fs::write(&bad, b"\x93NUMPY\x01\x00\x10\x00{'descr': '<f8'").unwrap();
    let o = eval_to(bad.to_str().unwrap(), out.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3));
    assert!(stderr(&o).contains("bad.npy: "), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn an_error_mid_stream_leaves_no_output_and_names_the_line() {
    let dir = tempfile::tempdir().unwrap();
    // More than one chunk (65 536 rows), the bad row in the second.
    let mut text = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    for k in 0..70_000 {
        text += if k == 69_000 {
            "30,0,x,180\n"
        } else {
            "30,0,30,180\n"
        };
    }
    let geo = write(dir.path(), "g.csv", &text);
    let out = dir.path().join("out.csv");
    let o = eval_to(&geo, out.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3));
    assert!(
        stderr(&o).contains("g.csv:69002: field `theta_r_deg`"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    assert!(temporaries(dir.path()).is_empty());
}

#[cfg(unix)]
#[test]
fn stale_temporaries_of_a_killed_run_are_cleaned() {
    let dir = tempfile::tempdir().unwrap();
    let geo = write(dir.path(), "g.csv", GEO);
    // A pid above any pid_max: that run is gone.
    let stale = dir.path().join(".polbrdf-2000000000-0123456789abcdef.tmp");
    std::fs::write(&stale, "left by SIGKILL").unwrap();
    let o = eval_to(&geo, dir.path().join("out.csv").to_str().unwrap());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stale.exists());
}

#[cfg(unix)]
#[test]
fn sigterm_leaves_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    for _ in 0..400_000 {
        text += "30,0,30,180\n";
    }
    let geo = write(dir.path(), "g.csv", &text);
    let out = dir.path().join("out.csv");
    let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args(["eval", "--material", "paint", "--input", &geo, "--output"])
        .arg(&out)
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(150));
    // SAFETY: signalling our own child.
    unsafe { libc_kill(child.id() as i32, 15) };
    let status = child.wait().unwrap();
    if status.success() {
        eprintln!("the run ended before the signal: nothing to check");
    } else {
        assert!(!out.exists());
    }
    assert!(temporaries(dir.path()).is_empty());
}

/// Issue 35: a signal during `export` leaves no temporary (the tempfile crate's
/// `.polbrdf-XXXXXX.tmp` of 7–377 MB stayed), nor the destination.
#[cfg(unix)]
#[test]
fn sigterm_during_export_leaves_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.pbsdf");
    let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args([
            "export",
            "--material",
            "paint",
            "--grid",
            "181,91,91",
            "--output",
        ])
        .arg(&out)
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(300));
    // SAFETY: signalling our own child.
    unsafe { libc_kill(child.id() as i32, 15) };
    let status = child.wait().unwrap();
    if status.success() {
        eprintln!("the run ended before the signal: nothing to check");
    } else {
        assert!(!out.exists());
    }
    assert!(
        temporaries(dir.path()).is_empty(),
        "{:?}",
        temporaries(dir.path())
    );
}

#[cfg(unix)]
unsafe fn libc_kill(pid: i32, sig: i32) {
    extern "C" {
        fn kill(pid: i32, sig: i32) -> i32;
    }
    // SAFETY: kill has no memory-safety preconditions.
    unsafe {
        kill(pid, sig);
    }
}

#[cfg(unix)]
#[test]
fn a_closed_standard_output_is_one_quiet_policy() {
    let dir = tempfile::tempdir().unwrap();
    let mut big = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n");
    for _ in 0..20_000 {
        big += "30,0,30,180\n";
    }
    let big = write(dir.path(), "big.csv", &big);
    let cases: Vec<Vec<&str>> = vec![
        vec!["eval", "--material", "paint", "--input", &big],
        vec!["materials"],
        vec!["albedo", "--material", "paint"],
        vec!["check", "--material", "paint", "--grid-deg", "30"],
    ];
    for args in cases {
        // Standard output a pipe whose reader is gone.
        let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        let msg = stderr(&o);
        assert!(!msg.contains("internal error"), "{args:?}: {msg}");
        assert!(!msg.contains("panicked"), "{args:?}: {msg}");
        assert!(
            matches!(o.status.code(), Some(0 | 141)),
            "{args:?}: {:?} {msg}",
            o.status
        );
    }
}

#[test]
fn fit_writes_its_files_before_a_closed_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let meas = write(
        dir.path(),
        "m.csv",
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf\n20,0,20,180,1.0\n30,0,30,180,0.5\n40,0,40,180,0.4\n50,0,50,180,0.5\n",
    );
    let mat = dir.path().join("fitted.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args([
            "fit",
            "--material",
            "paint",
            "--data",
            &meas,
            "--free",
            "rho_d",
            "--material-out",
        ])
        .arg(&mat)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let msg = stderr(&o);
    assert!(!msg.contains("internal error"), "{msg}");
    assert!(mat.is_file(), "the material file was not written: {msg}");
    assert_ne!(o.status.code(), Some(0), "a cut-off output must not exit 0");
    // A closed standard error: no abort, the files are there.
    let json = dir.path().join("fit.json");
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "'{}' fit --material paint --data '{meas}' --free rho_d --output '{}' 2>&-",
            env!("CARGO_BIN_EXE_polbrdf"),
            json.display()
        ))
        .output()
        .unwrap();
    assert!(json.is_file());
    assert_ne!(o.status.code(), Some(134), "aborted");
}

/// Issue 35: `export` writes through the output layer like every other command: `-` is
/// standard output, a FIFO is written to its reader, a symlink stays a link, a read-only or
/// hard-linked file is refused untouched, and the material file is never its output.
#[cfg(unix)]
#[test]
fn export_writes_through_the_output_layer() {
    use std::os::unix::fs::{FileTypeExt, PermissionsExt};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let export = |out: &str| {
        Command::new(env!("CARGO_BIN_EXE_polbrdf"))
            .current_dir(d)
            .args([
                "export",
                "--material",
                "paint",
                "--grid",
                "3,3,3",
                "--output",
                out,
            ])
            .output()
            .unwrap()
    };
    // `-`: the table on standard output, no file named `-`.
    let o = export("-");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.starts_with(b"tensor_file\0"));
    assert!(!d.join("-").exists());
    // A symlink: its target written, the link kept.
    std::fs::write(d.join("real.pbsdf"), "old").unwrap();
    std::os::unix::fs::symlink("real.pbsdf", d.join("link.pbsdf")).unwrap();
    let o = export("link.pbsdf");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(d.join("link.pbsdf"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(d.join("real.pbsdf"))
        .unwrap()
        .starts_with(b"tensor_file\0"));
    // Read-only, hard-linked: refused, untouched.
    let ro = d.join("ro.pbsdf");
    std::fs::write(&ro, "keep").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    let o = export("ro.pbsdf");
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("read-only"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "keep");
    std::fs::write(d.join("a.pbsdf"), "keep").unwrap();
    std::fs::hard_link(d.join("a.pbsdf"), d.join("b.pbsdf")).unwrap();
    let o = export("a.pbsdf");
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("2 hard links"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(d.join("b.pbsdf")).unwrap(), "keep");
    // A device: written, not replaced.
    let o = export("/dev/null");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    // A FIFO: its reader gets the table.
    let fifo = d.join("pipe");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let path = fifo.clone();
        let reader = std::thread::spawn(move || {
            let mut b = Vec::new();
            std::fs::File::open(&path)
                .unwrap()
                .read_to_end(&mut b)
                .unwrap();
            b
        });
        let o = export("pipe");
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(reader.join().unwrap().starts_with(b"tensor_file\0"));
        assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    }
    assert!(temporaries(d).is_empty(), "{:?}", temporaries(d));
}

/// The path checks before a command read the files a scene names, but never standard input:
/// `--scene -` is read once, by the command.
#[test]
fn a_scene_on_standard_input_is_read_by_the_command_only() {
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let mut child = Command::new(env!("CARGO_BIN_EXE_polbrdf"))
        .args([
            "radiance",
            "--material",
            "paint",
            "--scene",
            "-",
            "--theta-deg",
            "30",
            "--output",
        ])
        .arg(&out)
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"wavelength_um = 10\n[surface]\ntemperature_k = 300\n")
        .unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&out).unwrap().lines().count(), 2);
}

/// Issue 33: every command's `--out DIR` treats an existing directory the same way — its own
/// files replaced as a set (the marker `_COMPLETE`, listing them, last) and every other file
/// left alone — and refuses a `DIR` that is a regular file, leaving it as it was.
#[test]
fn every_out_dir_keeps_other_files_and_replaces_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let lut = write(
        d,
        "lut.toml",
        "materials = [\"paint\"]\nwavelength_um = [0.6]\ntheta_i_deg = [0, 30]\n\
         theta_r_deg = [0]\ndphi_deg = [180]\n",
    );
    let ex = |name: &str| format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let lines: Vec<Vec<String>> = [
        vec![
            "map",
            "--material",
            "paint",
            "--sun-zenith-deg",
            "30",
            "--grid-deg",
            "30",
        ],
        vec![
            "contrast",
            "--target",
            "paint",
            "--background",
            "glass",
            "--sun-zenith-deg",
            "30",
            "--grid-deg",
            "30",
        ],
        vec!["spectrum", "--material", "paint", "--points", "2"],
        vec!["lut", "--config", &lut],
        vec![
            "detect",
            "--scene",
            &ex("detect-daylight-scene.toml"),
            "--sensor",
            &ex("sensors/sony-imx250mzr-dofp.toml"),
            "--theta-deg",
            "0",
            "--no-search",
        ],
    ]
    .iter()
    .map(|l| l.iter().map(|a| a.to_string()).collect())
    .collect();
    for line in lines {
        let out = d.join(format!("{}-out", line[0]));
        std::fs::create_dir(&out).unwrap();
        std::fs::write(out.join("notes.txt"), "keep").unwrap();
        let mut args: Vec<&str> = line.iter().map(String::as_str).collect();
        args.extend(["--out", out.to_str().unwrap()]);
        for run in 0..2 {
            let o = polbrdf(&args);
            assert!(o.status.success(), "{args:?} (run {run}): {}", stderr(&o));
        }
        assert_eq!(
            std::fs::read_to_string(out.join("notes.txt")).unwrap(),
            "keep",
            "{args:?}"
        );
        let listed = std::fs::read_to_string(out.join("_COMPLETE")).unwrap();
        assert!(!listed.contains("notes.txt"), "{args:?}: {listed}");
        assert!(listed.lines().count() >= 2, "{args:?}: {listed}");
        for name in listed.lines() {
            assert!(out.join(name).is_file(), "{args:?}: {name}");
        }
        assert!(
            temporaries(&out).is_empty() && temporaries(d).is_empty(),
            "{args:?}"
        );
        // A regular file where the directory goes: refused, untouched.
        let file = d.join(format!("{}-file", line[0]));
        std::fs::write(&file, "keep").unwrap();
        args.pop();
        args.push(file.to_str().unwrap());
        let o = polbrdf(&args);
        assert_eq!(o.status.code(), Some(4), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("not a directory"), "{}", stderr(&o));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
    }
}
