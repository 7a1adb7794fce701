//! Output targets: every file polbrdf writes goes through [`Output`].
//!
//! - `-` is standard output.
//! - An existing node that is not a regular file (a character or block device such as
//!   `/dev/null`, a FIFO, a socket, or `/dev/fd/N`, `/dev/stdout` and `/proc/*/fd/*` whatever
//!   they point at) is opened and written directly, never replaced.
//! - A regular file (new or existing) is written atomically: to an unnamed temporary file in
//!   the destination's directory (`O_TMPFILE` on Linux, so nothing is left behind even by
//!   `SIGKILL`), flushed and synced, then given a name and renamed over the destination. On
//!   an error, or when dropped without [`Output::commit`], nothing changes at the destination.
//!   Where `O_TMPFILE` is not available the temporary is named `.polbrdf-<pid>-<random>.tmp`,
//!   removed on error, on drop, and on SIGINT/SIGTERM/SIGHUP (see [`install_signal_cleanup`]);
//!   those a killed run left (its pid no longer running) are removed by the next write into
//!   the same directory.
//! - A symbolic link is followed: its target is written atomically (the link stays a link).
//! - An existing regular file without any write permission bit is refused (not replaced),
//!   and so is one with more than one hard link (replacing it would split the links).
//!   A replaced file keeps its permissions and (where the process may set it) its owner.
//!
//! A set of files ([`write_files`](crate::write_set::write_files), module
//! [`write_set`](crate::write_set)) is written as a whole: every file is first written into a
//! staging directory; a new directory is then renamed into place in one step. Into an
//! existing directory the files are renamed one by one after the completion marker
//! [`SET_MARKER`] is removed, and the marker is written last, so a consumer that checks the
//! marker never reads a partial set as whole.

use crate::error::{Error, Result};
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The completion marker of a set of files written by
/// [`write_files`](crate::write_set::write_files): written last, it lists
/// the set's files, one name a line.
pub const SET_MARKER: &str = "_COMPLETE";

/// Prefix of every temporary name polbrdf creates.
const TMP_PREFIX: &str = ".polbrdf-";

/// Where an output goes, decided from the path before anything is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Target {
    /// Standard output (`-`).
    Stdout,
    /// An existing non-regular node, written directly.
    Direct(PathBuf),
    /// A regular file written atomically at this path (a symlink's resolved target).
    Atomic(PathBuf),
}

pub(crate) fn write_err(path: &Path, source: std::io::Error) -> Error {
    Error::Write {
        path: path.to_path_buf(),
        source,
    }
}

pub(crate) fn refuse(path: &Path, message: String) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message,
    }
}

/// Paths that name an already open file descriptor: written directly whatever they point at
/// (replacing what `/proc/self/fd/1` points at would write past the shell's redirection).
fn is_fd_path(p: &Path) -> bool {
    let s = p.to_string_lossy();
    s.starts_with("/dev/fd/")
        || s.starts_with("/proc/")
        || matches!(s.as_ref(), "/dev/stdout" | "/dev/stderr" | "/dev/stdin")
}

impl Target {
    /// Decides how `path` is written (see the module's rules).
    ///
    /// # Errors
    /// [`Error::File`] for a read-only or hard-linked regular file, or a symlink loop;
    /// [`Error::Write`] when the path cannot be examined.
    pub fn of(path: &Path) -> Result<Target> {
        if path.as_os_str() == "-" {
            return Ok(Target::Stdout);
        }
        // Follow symbolic links by hand (a dangling link names the file to create).
        let mut p = path.to_path_buf();
        for _ in 0..40 {
            if is_fd_path(&p) {
                return Ok(Target::Direct(path.to_path_buf()));
            }
            let meta = match std::fs::symlink_metadata(&p) {
                Ok(m) => m,
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    return Ok(Target::Atomic(p));
                }
                Err(e) => return Err(write_err(path, e)),
            };
            if meta.file_type().is_symlink() {
                let link = std::fs::read_link(&p).map_err(|e| write_err(path, e))?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
                continue;
            }
            if !meta.file_type().is_file() {
                if meta.is_dir() {
                    return Err(refuse(path, "is a directory, not a file".into()));
                }
                return Ok(Target::Direct(path.to_path_buf()));
            }
            if meta.permissions().readonly() {
                return Err(refuse(
                    path,
                    "is read-only: refusing to replace it (make it writable, or choose \
                     another output)"
                        .into(),
                ));
            }
            #[cfg(unix)]
            {
                use std::os::unix::fs::MetadataExt;
                if meta.nlink() > 1 {
                    return Err(refuse(
                        path,
                        format!(
                            "has {} hard links: refusing to replace it, which would split \
                             them (remove the other links, or choose another output)",
                            meta.nlink()
                        ),
                    ));
                }
            }
            return Ok(Target::Atomic(p));
        }
        Err(refuse(path, "too many levels of symbolic links".into()))
    }
}

/// The registry of named temporaries (files and staging directories) to remove on a signal.
static TEMPS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

pub(crate) fn register(p: &Path) {
    if let Ok(mut t) = TEMPS.lock() {
        t.push(p.to_path_buf());
    }
}

pub(crate) fn unregister(p: &Path) {
    if let Ok(mut t) = TEMPS.lock() {
        t.retain(|q| q != p);
    }
}

/// Removes the named temporaries of this process (files or directories).
#[cfg_attr(not(unix), allow(dead_code))] // Called by the signal handler, which is Unix's.
fn remove_registered() {
    let list = match TEMPS.lock() {
        Ok(t) => t.clone(),
        Err(poisoned) => poisoned.into_inner().clone(),
    };
    for p in list {
        if p.is_dir() {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
}

/// Makes SIGINT, SIGTERM and SIGHUP remove this process's named temporaries before it dies of
/// the signal (the exit status stays the signal's). Call it first thing in `main`, before any
/// thread starts: it blocks the signals in the calling thread (threads started later inherit
/// that) and waits for them on a thread of its own.
pub fn install_signal_cleanup() {
    #[cfg(unix)]
    // SAFETY: the sigset is initialised by sigemptyset before use; pthread_sigmask and sigwait
    // get valid pointers; signal/raise are called with valid signal numbers.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&mut set, s);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        let spawned = std::thread::Builder::new()
            .name("polbrdf-signals".into())
            .spawn(move || {
                let mut sig: libc::c_int = 0;
                if libc::sigwait(&set, &mut sig) == 0 {
                    remove_registered();
                    libc::signal(sig, libc::SIG_DFL);
                    libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
                    libc::raise(sig);
                    // Blocked in other threads: raise delivers to this one; if not, exit.
                    libc::_exit(128 + sig);
                }
            });
        if spawned.is_err() {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}

/// Is the process `pid` running?
#[cfg(unix)]
fn alive(pid: i32) -> bool {
    // SAFETY: kill with signal 0 only checks for existence.
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

/// Removes temporaries a killed run left in `dir`: `.polbrdf-<pid>-*.tmp` (files, or staging
/// directories) whose pid is not running; `lut`'s old staging directories
/// `.polbrdf-<name>.partial-<pid>-<n>` whose pid is not running; and (the older naming,
/// `.polbrdf-XXXXXX.tmp`, without a pid) those untouched for an hour.
pub fn clean_stale_temporaries(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(name) = name.to_str() else { continue };
        let Some(rest) = name.strip_prefix(TMP_PREFIX) else {
            continue;
        };
        let Some(stem) = rest.strip_suffix(".tmp") else {
            // The staging directories of `polbrdf lut` before 0.2: `.polbrdf-<name>.partial-<pid>-<n>`.
            #[cfg(unix)]
            if let Some((_, tail)) = rest.rsplit_once(".partial-") {
                let dead = tail.split_once('-').is_some_and(|(pid, n)| {
                    n.parse::<u32>().is_ok()
                        && pid.parse::<i32>().is_ok_and(|pid| {
                            pid > 0 && pid != std::process::id() as i32 && !alive(pid)
                        })
                });
                if dead && e.path().is_dir() {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
            continue;
        };
        let stale = match stem.split_once('-') {
            #[cfg(unix)]
            Some((pid, _)) => pid
                .parse::<i32>()
                .is_ok_and(|pid| pid > 0 && pid != std::process::id() as i32 && !alive(pid)),
            #[cfg(not(unix))]
            Some(_) => false,
            None => {
                stem.len() == 6
                    && stem.chars().all(|c| c.is_ascii_alphanumeric())
                    && e.metadata()
                        .and_then(|m| m.modified())
                        .ok()
                        .and_then(|t| t.elapsed().ok())
                        .is_some_and(|age| age.as_secs() > 3600)
            }
        };
        if stale {
            let p = e.path();
            if p.is_dir() {
                let _ = std::fs::remove_dir_all(&p);
            } else {
                let _ = std::fs::remove_file(&p);
            }
        }
    }
}

/// A fresh temporary name in `dir`: `.polbrdf-<pid>-<random>.tmp`.
pub(crate) fn temp_name(dir: &Path) -> PathBuf {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos() as u64),
    );
    dir.join(format!(
        "{TMP_PREFIX}{}-{:016x}.tmp",
        std::process::id(),
        h.finish()
    ))
}

pub(crate) fn dir_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

#[derive(Debug)]
enum Sink {
    Stdout(BufWriter<std::io::Stdout>),
    Direct(BufWriter<File>),
    Temp {
        file: BufWriter<File>,
        dest: PathBuf,
        /// The temporary's name when it has one (no `O_TMPFILE`).
        named: Option<PathBuf>,
    },
}

/// An output being written: `Write` (buffered) and, for regular files, `Seek`. Dropped
/// without [`commit`](Self::commit), a regular destination is left as it was.
#[derive(Debug)]
pub struct Output {
    sink: Option<Sink>,
    /// The name given by the user (for messages).
    shown: PathBuf,
}

impl Output {
    /// Opens `path` as [`Target::of`] decides (`-` = standard output).
    ///
    /// # Errors
    /// As [`Target::of`]; [`Error::Write`] when the temporary or the node cannot be opened.
    pub fn create(path: &Path) -> Result<Output> {
        let target = Target::of(path)?;
        let sink = match target {
            Target::Stdout => Sink::Stdout(BufWriter::with_capacity(1 << 16, std::io::stdout())),
            Target::Direct(p) => {
                let f = std::fs::OpenOptions::new()
                    .append(true)
                    .open(&p)
                    .map_err(|e| write_err(path, e))?;
                Sink::Direct(BufWriter::with_capacity(1 << 16, f))
            }
            Target::Atomic(dest) => {
                let dir = dir_of(&dest).to_path_buf();
                clean_stale_temporaries(&dir);
                let (file, named) = open_temp(&dir).map_err(|e| write_err(path, e))?;
                if let Ok(meta) = std::fs::metadata(&dest) {
                    file.set_permissions(meta.permissions())
                        .map_err(|e| write_err(path, e))?;
                    #[cfg(unix)]
                    {
                        use std::os::unix::fs::MetadataExt;
                        // Keeps the owner where allowed (root; or the same user): best effort.
                        let _ =
                            std::os::unix::fs::fchown(&file, Some(meta.uid()), Some(meta.gid()));
                    }
                }
                Sink::Temp {
                    file: BufWriter::with_capacity(1 << 16, file),
                    dest,
                    named,
                }
            }
        };
        Ok(Output {
            sink: Some(sink),
            shown: path.to_path_buf(),
        })
    }

    /// Standard output.
    pub fn stdout() -> Output {
        Output {
            sink: Some(Sink::Stdout(BufWriter::with_capacity(
                1 << 16,
                std::io::stdout(),
            ))),
            shown: PathBuf::from("-"),
        }
    }

    /// The name given for this output (`-` for standard output).
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// True when the output can seek (a regular file being written atomically).
    pub fn is_seekable(&self) -> bool {
        matches!(self.sink, Some(Sink::Temp { .. }))
    }

    /// An I/O error of this output as the crate's error.
    pub fn error(&self, e: std::io::Error) -> Error {
        write_err(&self.shown, e)
    }

    /// Finishes the output: flushes it, and for a regular file syncs it and moves it into
    /// place.
    ///
    /// # Errors
    /// [`Error::Write`] naming the output; a regular destination is then left as it was.
    pub fn commit(mut self) -> Result<()> {
        let shown = self.shown.clone();
        let err = |e| write_err(&shown, e);
        match self.sink.take().expect("committed once") {
            Sink::Stdout(mut w) => w.flush().map_err(err),
            Sink::Direct(mut w) => w.flush().map_err(err),
            Sink::Temp { file, dest, named } => {
                let file = file.into_inner().map_err(|e| err(e.into_error()))?;
                file.sync_all().map_err(err)?;
                let result = match &named {
                    Some(tmp) => std::fs::rename(tmp, &dest),
                    None => link_and_rename(&file, &dest),
                };
                if let Some(tmp) = &named {
                    if result.is_err() {
                        let _ = std::fs::remove_file(tmp);
                    }
                    unregister(tmp);
                }
                result.map_err(err)
            }
        }
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if let Some(Sink::Temp {
            named: Some(tmp), ..
        }) = &self.sink
        {
            let _ = std::fs::remove_file(tmp);
            unregister(tmp);
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self.sink.as_mut().expect("not committed") {
            Sink::Stdout(w) => w.write(buf),
            Sink::Direct(w) => w.write(buf),
            Sink::Temp { file, .. } => file.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        match self.sink.as_mut().expect("not committed") {
            Sink::Stdout(w) => w.write_all(buf),
            Sink::Direct(w) => w.write_all(buf),
            Sink::Temp { file, .. } => file.write_all(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self.sink.as_mut().expect("not committed") {
            Sink::Stdout(w) => w.flush(),
            Sink::Direct(w) => w.flush(),
            Sink::Temp { file, .. } => file.flush(),
        }
    }
}

impl Seek for Output {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        match self.sink.as_mut().expect("not committed") {
            Sink::Temp { file, .. } => file.seek(pos),
            _ => Err(std::io::Error::new(
                std::io::ErrorKind::Unsupported,
                "this output cannot seek",
            )),
        }
    }
}

/// An unnamed temporary file in `dir` (`O_TMPFILE`), or a named one where the file system
/// has no `O_TMPFILE` (registered for removal on signals). New files get 0666 less the umask.
fn open_temp(dir: &Path) -> std::io::Result<(File, Option<PathBuf>)> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::OpenOptionsExt;
        match std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .mode(0o666)
            .custom_flags(libc::O_TMPFILE)
            .open(dir)
        {
            Ok(f) => return Ok((f, None)),
            Err(e)
                if matches!(
                    e.raw_os_error(),
                    Some(libc::EOPNOTSUPP | libc::EISDIR | libc::ENOENT | libc::EINVAL)
                ) && dir.is_dir() => {}
            Err(e) => return Err(e),
        }
    }
    let mut opts = std::fs::OpenOptions::new();
    opts.read(true).write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.mode(0o666);
    }
    let name = temp_name(dir);
    register(&name);
    match opts.open(&name) {
        Ok(f) => Ok((f, Some(name))),
        Err(e) => {
            unregister(&name);
            Err(e)
        }
    }
}

/// Gives an unnamed temporary a name in `dest`'s directory (`linkat` through `/proc/self/fd`)
/// and renames it over `dest`.
#[cfg(target_os = "linux")]
fn link_and_rename(file: &File, dest: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    use std::os::unix::io::AsRawFd;
    let tmp = temp_name(dir_of(dest));
    let src = CString::new(format!("/proc/self/fd/{}", file.as_raw_fd()))?;
    let dst = CString::new(tmp.as_os_str().as_bytes())?;
    register(&tmp);
    // SAFETY: both paths are valid NUL-terminated strings.
    let r = unsafe {
        libc::linkat(
            libc::AT_FDCWD,
            src.as_ptr(),
            libc::AT_FDCWD,
            dst.as_ptr(),
            libc::AT_SYMLINK_FOLLOW,
        )
    };
    if r != 0 {
        unregister(&tmp);
        return Err(std::io::Error::last_os_error());
    }
    let renamed = std::fs::rename(&tmp, dest);
    if renamed.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    unregister(&tmp);
    renamed
}

#[cfg(not(target_os = "linux"))]
fn link_and_rename(_file: &File, _dest: &Path) -> std::io::Result<()> {
    unreachable!("O_TMPFILE is used on Linux only")
}

/// Writes `bytes` to `path` as an [`Output`] (atomically for a regular file; directly for a
/// device, FIFO or `/dev/fd/N`; `-` = standard output). On error nothing changes at a regular
/// `path`.
///
/// # Errors
/// As [`Output::create`] and [`Output::commit`].
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut out = Output::create(path)?;
    out.write_all(bytes).map_err(|e| out.error(e))?;
    out.commit()
}

/// What names a file for [`check_distinct`]: device and inode of an existing regular file, or
/// the resolved path of one to be created.
#[derive(Debug, PartialEq, Eq)]
enum FileId {
    #[cfg_attr(not(unix), allow(dead_code))] // Unix's device and inode numbers.
    Inode(u64, u64),
    New(PathBuf),
}

fn file_id(path: &Path) -> Option<FileId> {
    if path.as_os_str() == "-" {
        return None;
    }
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => {
            #[cfg(unix)]
            {
                use std::os::unix::fs::MetadataExt;
                Some(FileId::Inode(m.dev(), m.ino()))
            }
            #[cfg(not(unix))]
            {
                std::fs::canonicalize(path).ok().map(FileId::New)
            }
        }
        // Devices, FIFOs, directories: not a file that could be destroyed by replacing.
        Ok(_) => None,
        Err(_) => {
            let target = match Target::of(path) {
                Ok(Target::Atomic(p)) => p,
                _ => path.to_path_buf(),
            };
            let dir = std::fs::canonicalize(dir_of(&target)).ok()?;
            Some(FileId::New(dir.join(target.file_name()?)))
        }
    }
}

/// Refuses outputs that are the same file as an input or as another output (compared by
/// device and inode, so links and other spellings of a name are caught; an output to be
/// created by its resolved path). `-`, devices and FIFOs are not compared.
///
/// # Errors
/// [`Error::File`] naming the output and what it coincides with.
pub fn check_distinct(inputs: &[&Path], outputs: &[&Path]) -> Result<()> {
    let ins: Vec<(&Path, FileId)> = inputs
        .iter()
        .filter_map(|p| match file_id(p) {
            Some(id @ FileId::Inode(..)) => Some((*p, id)),
            _ => None,
        })
        .collect();
    let mut outs: Vec<(&Path, FileId)> = Vec::new();
    for out in outputs {
        let Some(id) = file_id(out) else { continue };
        if let Some((inp, _)) = ins.iter().find(|(_, i)| *i == id) {
            return Err(refuse(
                out,
                format!(
                    "is the same file as the input {}: refusing to overwrite an input",
                    inp.display()
                ),
            ));
        }
        if let Some((other, _)) = outs.iter().find(|(_, i)| *i == id) {
            return Err(refuse(
                out,
                format!("is the same file as the output {}", other.display()),
            ));
        }
        outs.push((out, id));
    }
    Ok(())
}
