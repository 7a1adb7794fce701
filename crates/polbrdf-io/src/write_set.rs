//! Sets of files written as a whole into a directory (docs/io.md, Output targets): every
//! file is first written into a staging directory next to the destination; a new directory is
//! then renamed into place in one step. Into an existing directory the set's files are renamed
//! one by one after the completion marker [`SET_MARKER`] is removed, and the marker, which lists
//! the set's files, is written last: a consumer that checks the marker never reads a partial set
//! as whole, and no other file of the directory is touched. [`write_files`] holds its files in
//! memory; [`StagingDir`] is filled by the caller, for outputs too large for that.

use crate::error::Result;
use crate::write::{
    clean_stale_temporaries, dir_of, refuse, register, temp_name, unregister, write_err, SET_MARKER,
};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Creates `dir` (and its parents) and writes the files `(name, bytes)` into it as a set (see
/// the module's rules: staged, then moved into place, the marker [`SET_MARKER`] last); returns
/// the paths in order.
///
/// # Errors
/// [`crate::Error::Write`] naming the directory or the file; then no file of the set was changed
/// unless the error came while moving the staged files (the marker is then missing).
pub fn write_files(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    let (parent, fresh) = stage_parent(dir)?;
    clean_stale_temporaries(&parent);
    let stage = temp_name(&parent);
    register(&stage);
    let names: Vec<String> = files.iter().map(|(name, _)| name.clone()).collect();
    let result = stage_set(&stage, dir, files).and_then(|()| place(&stage, dir, &names, fresh));
    let _ = std::fs::remove_dir_all(&stage);
    unregister(&stage);
    result.map(|()| files.iter().map(|(name, _)| dir.join(name)).collect())
}

/// Where the staging directory of a set for `dir` goes, and whether `dir` is new: beside a new
/// `dir` (its parents created), inside an existing one (so that the renames stay within it).
///
/// # Errors
/// [`crate::Error::Write`] naming `dir` when its parents cannot be created; [`crate::Error::File`] when
/// `dir` exists and is not a directory.
fn stage_parent(dir: &Path) -> Result<(PathBuf, bool)> {
    if std::fs::symlink_metadata(dir).is_err() {
        let parent = dir_of(dir).to_path_buf();
        std::fs::create_dir_all(&parent).map_err(|e| write_err(dir, e))?;
        Ok((parent, true))
    } else if dir.is_dir() {
        Ok((dir.to_path_buf(), false))
    } else {
        Err(refuse(dir, "exists and is not a directory".into()))
    }
}

/// Moves the staged set (its files `names` and the marker) into `dir`: a new `dir` is the
/// staging directory renamed; into an existing one the marker is removed first, the files are
/// renamed one by one and the marker last.
fn place(stage: &Path, dir: &Path, names: &[String], fresh: bool) -> Result<()> {
    if fresh {
        return std::fs::rename(stage, dir).map_err(|e| write_err(dir, e));
    }
    match std::fs::remove_file(dir.join(SET_MARKER)) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(write_err(dir, e)),
        _ => {}
    }
    for name in names.iter().map(String::as_str).chain([SET_MARKER]) {
        std::fs::rename(stage.join(name), dir.join(name))
            .map_err(|e| write_err(&dir.join(name), e))?;
    }
    Ok(())
}

/// Writes every file and the marker into the staging directory, synced.
fn stage_set(stage: &Path, dir: &Path, files: &[(String, Vec<u8>)]) -> Result<()> {
    std::fs::create_dir(stage).map_err(|e| write_err(dir, e))?;
    let mut listing = String::new();
    for (name, bytes) in files {
        if name.contains('/') || name == SET_MARKER || name.is_empty() {
            return Err(refuse(&dir.join(name), "is not a plain file name".into()));
        }
        let path = stage.join(name);
        let shown = dir.join(name);
        let mut f = File::create(&path).map_err(|e| write_err(&shown, e))?;
        f.write_all(bytes)
            .and_then(|()| f.sync_all())
            .map_err(|e| write_err(&shown, e))?;
        listing.push_str(name);
        listing.push('\n');
    }
    let marker = stage.join(SET_MARKER);
    std::fs::write(&marker, listing).map_err(|e| write_err(&dir.join(SET_MARKER), e))?;
    Ok(())
}

/// A set of files staged next to its destination directory (or inside it, when it exists) as
/// `.polbrdf-<pid>-<random>.tmp` (registered for removal on SIGINT/SIGTERM/SIGHUP; a later run
/// removes it if this process was killed), filled by the caller, then moved into place by
/// [`StagingDir::commit`] by the rules of [`write_files`]: an existing directory keeps every
/// file that is not of the set. Dropped without commit, it is removed. For outputs too large to
/// hold in memory ([`write_files`] holds its files' bytes).
#[derive(Debug)]
pub struct StagingDir {
    path: Option<PathBuf>,
    dest: PathBuf,
    fresh: bool,
}

impl StagingDir {
    /// Stages a set for the directory `dest` (created with its parents if missing).
    ///
    /// # Errors
    /// [`crate::Error::Write`] naming `dest`; [`crate::Error::File`] when `dest` exists and is not a
    /// directory.
    pub fn create(dest: &Path) -> Result<StagingDir> {
        let (parent, fresh) = stage_parent(dest)?;
        clean_stale_temporaries(&parent);
        let path = temp_name(&parent);
        register(&path);
        if let Err(e) = std::fs::create_dir(&path) {
            unregister(&path);
            return Err(write_err(dest, e));
        }
        Ok(StagingDir {
            path: Some(path),
            dest: dest.to_path_buf(),
            fresh,
        })
    }

    /// Where to write the files (plain files, no subdirectory).
    pub fn path(&self) -> &Path {
        self.path.as_deref().expect("not committed")
    }

    /// Writes the marker (the staged files' names, sorted) and moves the set into place.
    ///
    /// # Errors
    /// [`crate::Error::Write`] naming the destination; the staged directory is then removed.
    pub fn commit(mut self) -> Result<()> {
        let path = self.path.take().expect("committed once");
        let r = self.place(&path);
        let _ = std::fs::remove_dir_all(&path);
        unregister(&path);
        r
    }

    fn place(&self, path: &Path) -> Result<()> {
        let mut names = Vec::new();
        for entry in std::fs::read_dir(path).map_err(|e| write_err(&self.dest, e))? {
            let entry = entry.map_err(|e| write_err(&self.dest, e))?;
            names.push(entry.file_name().to_string_lossy().into_owned());
        }
        names.sort();
        let listing: String = names.iter().map(|n| format!("{n}\n")).collect();
        std::fs::write(path.join(SET_MARKER), listing)
            .map_err(|e| write_err(&self.dest.join(SET_MARKER), e))?;
        place(path, &self.dest, &names, self.fresh)
    }
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if let Some(p) = self.path.take() {
            let _ = std::fs::remove_dir_all(&p);
            unregister(&p);
        }
    }
}
