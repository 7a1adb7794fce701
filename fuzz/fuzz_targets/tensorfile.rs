//! Mitsuba TensorFile (`.pbsdf`) tables as `fit --data x.pbsdf` reads them (issue 35).
//!
//! Any bytes give an error naming the file, or fields whose data lie inside the file, after the
//! header, without overlapping. A header with a field `M` is then written to a temporary file
//! that is extended (sparse, up to 1 TiB) to the size the header claims, so that a few hundred
//! bytes can claim a grid of 65 536 nodes an axis, and read as the CLI's band fit reads it: the
//! fit's plan from the axes (`polbrdf_tasks::pbsdf::plan`, automatic stride, no extra start),
//! then the kept cells of the first and last band one by one (`band_data`, `read_cell`), then
//! the fit's data check and every residual against the paint preset through the engine. Under a
//! counting global allocator, the bytes held at once stay under a fixed budget (the axes at
//! their node bound, the kept cells' measurements at the plan's cell bound) plus 64 × the
//! input's length: a header claiming a huge grid allocates none of it.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf_fit::Measurement;
use polbrdf_fuzz::{measure_peak, paint, Counting};
use polbrdf_io::pbsdf::MAX_NODES;
use polbrdf_tasks::pbsdf::{band_data, plan, AUTO_CELLS};
use std::io::Write;
use std::path::Path;

#[global_allocator]
static ALLOC: Counting = Counting;

/// Largest (sparse) file the target makes from a header's claim.
const SPARSE_MAX: u64 = 1 << 40;

/// The fixed budget: three axes at `MAX_NODES` nodes (f32 read, f64 kept), the wavelengths,
/// and one band's measurements at the plan's bound (16 a cell, × 4 for a vector's growth and
/// its copy while it grows), plus 1 MiB for the header, paths and buffers.
fn budget() -> usize {
    let axes = 3 * MAX_NODES as usize * 12 + MAX_NODES as usize * 2;
    let cells = 4 * AUTO_CELLS * 16 * std::mem::size_of::<Measurement>();
    axes + cells + (1 << 20)
}

/// The header's fields lie inside a file of `size` bytes, after the header, without overlap.
fn check_spans(fields: &[polbrdf_io::tensorfile::Field], header_end: u64, size: u64) -> u64 {
    let mut spans: Vec<(u64, u64)> = fields
        .iter()
        .map(|f| (f.offset, f.offset + f.len() * f.dtype.size()))
        .filter(|s| s.1 > s.0)
        .collect();
    spans.sort();
    for s in &spans {
        assert!(s.0 >= header_end && s.1 <= size);
    }
    assert!(spans.windows(2).all(|w| w[0].1 <= w[1].0));
    spans.last().map_or(0, |s| s.1)
}

/// Reads the table at `path` as the CLI's band fit does; asserts what must hold.
fn fit_path(path: &Path) {
    let mut t = match polbrdf_io::PbsdfTable::open(path) {
        Ok(t) => t,
        Err(e) => {
            assert!(
                e.to_string().starts_with(&path.display().to_string()),
                "{e}"
            );
            return;
        }
    };
    for ax in [&t.phi_d, &t.theta_d, &t.theta_h] {
        assert!(ax.windows(2).all(|w| w[0] < w[1]));
    }
    let stride = plan(&t, None, 0).expect("the automatic stride fits the work bound");
    let last = t.wavelengths_nm.len() - 1;
    for band in [0, last].into_iter().take(if last == 0 { 1 } else { 2 }) {
        let (data, counts) = match band_data(&mut t, band, stride, false, None) {
            Ok(d) => d,
            Err(e) => {
                assert!(!e.to_string().is_empty());
                continue;
            }
        };
        assert!(counts.cells <= AUTO_CELLS && data.len() == 16 * counts.used);
        assert_eq!(
            counts.cells,
            counts.below_horizon + counts.missing + counts.used
        );
        if polbrdf_fit::check_measurements(&data).is_err() {
            continue;
        }
        for m in &data {
            let f = paint().pbrdf(&m.geometry);
            assert!(f.m00() >= 0.0, "{m:?}");
            let r = m.observable.of_pbrdf(&f) - m.value;
            assert!(r.is_finite(), "{m:?}: residual {r}");
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let name = Path::new("fuzz.pbsdf");
    match polbrdf_io::tensorfile::parse_header(data, data.len() as u64, name) {
        Ok((fields, header_end)) => {
            assert!(header_end as usize <= data.len());
            check_spans(&fields, header_end, data.len() as u64);
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.pbsdf")),
    }
    // The same header in a file as large as it claims (sparse: what is not in the input is 0).
    let Ok((fields, header_end)) = polbrdf_io::tensorfile::parse_header(data, SPARSE_MAX, name)
    else {
        return;
    };
    if !fields.iter().any(|f| f.name == "M") {
        return;
    }
    let _ = paint();
    let size = check_spans(&fields, header_end, SPARSE_MAX).max(data.len() as u64);
    let ((), peak) = measure_peak(|| {
        let mut tmp = tempfile::NamedTempFile::new().unwrap();
        tmp.write_all(data).unwrap();
        tmp.as_file().set_len(size).unwrap();
        fit_path(tmp.path());
    });
    assert!(
        peak <= budget() + 64 * data.len(),
        "{peak} bytes held at once for {} bytes of input (a file of {size} bytes)",
        data.len()
    );
});
