//! Writing files so that a reader never sees half of one: every file the program writes goes to a
//! temporary beside its target, is flushed to the disk, and is renamed into place.
//!
//! A rename within one directory is atomic on POSIX file systems (`rename(2)`): a reader sees
//! either the old file or the new one, never a mixture, and a full disk or a killed process leaves
//! the old file as it was. The temporary lives in the target's own directory because a rename
//! cannot cross file systems.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes the temporaries of one process (figures are written from one thread, but a
/// library caller may write from several).
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A fresh temporary path beside `target`: hidden, and named by the process and a counter so that
/// two concurrent writers never share one.
fn temporary_beside(target: &Path) -> PathBuf {
    let name = target.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
    target.with_file_name(format!(".{name}.{}.{unique}.tmp", std::process::id()))
}

/// The directory a file path lives in (`.` for a bare file name).
#[must_use]
pub fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// Writes `bytes` to `path` atomically: to a temporary in the same directory, `fsync`ed, then
/// renamed over `path`. An existing `path` is replaced only once the new content is complete.
///
/// # Errors
/// The I/O error of the step that failed (create, write, sync or rename); the temporary is then
/// removed, and `path` is untouched.
///
/// # Examples
/// ```
/// let path = std::env::temp_dir().join(format!("hw3-fsio-doc-{}.txt", std::process::id()));
/// hw3_core::fsio::write_atomic(&path, b"first").unwrap();
/// hw3_core::fsio::write_atomic(&path, b"second").unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"second");
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let temporary = temporary_beside(path);
    let result = (|| {
        let mut file = std::fs::OpenOptions::new().write(true).create_new(true).open(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&temporary, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    } else {
        // The rename itself is durable only once the directory is synced; a failure here loses
        // nothing that is not already visible, so it is not reported.
        if let Ok(dir) = std::fs::File::open(parent_dir(path)) {
            let _ = dir.sync_all();
        }
    }
    result
}

/// Why a folder cannot receive the files a command will write ([`check_writable_dir`]).
///
/// # Examples
/// ```
/// use hw3_core::fsio::{DirError, check_writable_dir};
/// let error = check_writable_dir(std::path::Path::new("/no/such/dir")).unwrap_err();
/// assert!(matches!(&error, DirError::Unreadable { source, .. } if source.kind() == std::io::ErrorKind::NotFound));
/// assert_eq!(error.to_string(), "/no/such/dir: No such file or directory");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum DirError {
    /// The folder's metadata cannot be read (it does not exist, or a parent cannot be searched).
    #[error("{}: {}", .dir.display(), io_reason(.source))]
    Unreadable {
        /// The folder.
        dir: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The path exists but is not a directory.
    #[error("{} is not a directory", .dir.display())]
    NotADirectory {
        /// The path.
        dir: PathBuf,
    },
    /// The folder refuses a new file (permissions, a read-only file system, a full disk).
    #[error("cannot write in {}: {}", .dir.display(), io_reason(.source))]
    NotWritable {
        /// The folder.
        dir: PathBuf,
        /// The operating system's error on creating a file in it.
        source: std::io::Error,
    },
}

/// Checks, before any work, that a file can later be written into `dir`: it exists, is a
/// directory, and accepts a new file (a temporary is created and removed).
///
/// # Errors
/// [`DirError::Unreadable`] when `dir` cannot be read, [`DirError::NotADirectory`] when it is not
/// a directory, [`DirError::NotWritable`] when a file cannot be created in it.
///
/// # Examples
/// ```
/// assert!(hw3_core::fsio::check_writable_dir(&std::env::temp_dir()).is_ok());
/// assert!(hw3_core::fsio::check_writable_dir(std::path::Path::new("/no/such/dir")).is_err());
/// ```
pub fn check_writable_dir(dir: &Path) -> Result<(), DirError> {
    match std::fs::metadata(dir) {
        Err(source) => return Err(DirError::Unreadable { dir: dir.to_path_buf(), source }),
        Ok(meta) if !meta.is_dir() => return Err(DirError::NotADirectory { dir: dir.to_path_buf() }),
        Ok(_) => {}
    }
    let probe = temporary_beside(&dir.join("probe"));
    match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(file) => {
            drop(file);
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(source) => Err(DirError::NotWritable { dir: dir.to_path_buf(), source }),
    }
}

/// An I/O error's description without the `(os error N)` suffix, for a one-line message.
///
/// # Examples
/// ```
/// let error = std::fs::read("/no/such/file").unwrap_err();
/// assert_eq!(hw3_core::fsio::io_reason(&error), "No such file or directory");
/// ```
#[must_use]
pub fn io_reason(error: &std::io::Error) -> String {
    let text = error.to_string();
    text.split(" (os error").next().unwrap_or(&text).to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("hw3-fsio-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = scratch("failed");
        let target = dir.join("out.bin");
        write_atomic(&target, b"old").unwrap();
        // A directory where the target's temporary would go makes the rename fail: the target is a
        // non-empty directory, which rename(2) refuses to replace with a file.
        let blocked = dir.join("blocked");
        std::fs::create_dir_all(blocked.join("inside")).unwrap();
        assert!(write_atomic(&blocked, b"new").is_err());
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn writable_dir_refuses_a_file_and_a_missing_folder() {
        let dir = scratch("writable");
        let file = dir.join("a_file");
        std::fs::write(&file, b"x").unwrap();
        assert!(check_writable_dir(&dir).is_ok());
        let not_a_dir = check_writable_dir(&file).unwrap_err();
        assert!(matches!(&not_a_dir, DirError::NotADirectory { dir } if *dir == file), "{not_a_dir:?}");
        assert_eq!(not_a_dir.to_string(), format!("{} is not a directory", file.display()));
        assert!(matches!(check_writable_dir(&dir.join("missing")), Err(DirError::Unreadable { .. })));
        assert_eq!(parent_dir(Path::new("x.png")), Path::new("."));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
