//! What the fuzz targets share: the counting allocator of the allocation targets, the text
//! filter of the targets whose files name other files, the paint preset the evaluating targets
//! use, and the three formats `eval` reads.
use polbrdf::Material;
use polbrdf_io::stream::Format;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

/// The system allocator, counting the bytes held now and the peak since the last
/// [`measure_peak`]. A target that measures installs it:
/// `#[global_allocator] static ALLOC: Counting = Counting;`.
pub struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; only counters are added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = NOW.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

/// Runs `f` and returns its result and the most bytes held at once while it ran, beyond what
/// was held before it (counted only when [`Counting`] is the global allocator).
pub fn measure_peak<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = NOW.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let out = f();
    (out, PEAK.load(Ordering::Relaxed) - base)
}

/// The input as the text of a file that names files to read (a scene, a sensor, a lookup-table
/// configuration), or `None`: not UTF-8, or naming a device or pseudo-file that never ends
/// (/dev/zero) or blocks (a FIFO), also when spelled with TOML escapes.
pub fn file_text(data: &[u8]) -> Option<&str> {
    let text = std::str::from_utf8(data).ok()?;
    let unsafe_name = ["/dev", "/proc", "/sys", "\\u", "\\U"]
        .iter()
        .any(|s| text.contains(s));
    (!unsafe_name).then_some(text)
}

/// The paint preset, built once (at its own wavelength, or at 0.55 µm if it has none).
pub fn paint() -> &'static Material {
    static PAINT: OnceLock<Material> = OnceLock::new();
    PAINT.get_or_init(|| {
        let spec = polbrdf::preset("paint").unwrap();
        spec.build().or_else(|_| spec.build_at(0.55)).unwrap()
    })
}

/// The formats `eval` streams its input from, each with the file name its errors must start
/// with.
pub const EVAL_FORMATS: [(&str, Format); 3] = [
    ("fuzz.csv", Format::Csv),
    ("fuzz.npy", Format::Npy),
    ("fuzz.arrows", Format::ArrowStream),
];
