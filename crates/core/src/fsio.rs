//! Writing files so that a reader never sees half of one: every file the program writes goes to a
//! temporary beside its target, is flushed to the disk, and is renamed into place.
//!
//! A rename within one directory is atomic on POSIX file systems (`rename(2)`): a reader sees
//! either the old file or the new one, never a mixture, and a full disk or a killed process leaves
//! the old file as it was. The temporary lives in the target's own directory because a rename
//! cannot cross file systems. Its name is short and independent of the target's, so any target
//! name the file system accepts has a temporary it accepts too.
//!
//! The temporaries alive at any moment are listed, so that [`remove_temporaries`] can delete them
//! when the process is interrupted (the binary calls it on `SIGINT`, `SIGTERM` and `SIGHUP`).
//!
//! Reading is guarded too: [`open_regular`] opens without waiting (a named pipe with no writer
//! would block forever) and refuses anything but a regular file before a byte is read.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes the temporaries of one process (figures are written from one thread, but a
/// library caller may write from several).
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The temporaries created and not yet renamed or removed.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The longest file name (one path component) POSIX file systems accept, in bytes (`NAME_MAX`).
pub const NAME_MAX: usize = 255;

/// A fresh temporary path beside `target`: hidden, and named by the process and a counter so that
/// two concurrent writers never share one (at most 37 bytes, far under [`NAME_MAX`]).
fn temporary_beside(target: &Path) -> PathBuf {
    let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
    target.with_file_name(format!(".hw3.{}.{unique}.tmp", std::process::id()))
}

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A panic while the list was held leaves it consistent (each change is one push or retain).
    LIVE.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Deletes every temporary this process is still writing, and returns how many it deleted. Called
/// when the process is interrupted, so that no hidden half-written file stays beside a target; a
/// writer that then finishes finds its temporary gone and fails, leaving its target untouched.
pub fn remove_temporaries() -> usize {
    remove_all(&mut live())
}

fn remove_all(list: &mut Vec<PathBuf>) -> usize {
    let removed = list.iter().filter(|p| std::fs::remove_file(p).is_ok()).count();
    list.clear();
    removed
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
    live().push(temporary.clone());
    let result = (|| {
        let mut file = std::fs::OpenOptions::new().write(true).create_new(true).open(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&temporary, path)
    })();
    live().retain(|p| *p != temporary);
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

/// What a path that is not a regular file is, in words, for a refusal.
#[must_use]
pub fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a folder"
    } else if meta.is_file() {
        "a regular file"
    } else {
        "not a regular file"
    }
}

/// Why a file was not opened for reading ([`open_regular`]).
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// The operating system refused to open it, or to describe it.
    #[error("{}", io_reason(.0))]
    Io(#[from] std::io::Error),
    /// It is a folder, a named pipe, a device or a socket: [`kind_of`] says which.
    #[error("it is {0}, not a regular file")]
    NotAFile(&'static str),
}

/// Opens `path` for reading if it is a regular file, without waiting: a named pipe (which would
/// block until a writer comes), a device or a folder is refused before anything is read. Symbolic
/// links are followed.
///
/// # Errors
/// [`OpenError::Io`] when it cannot be opened, [`OpenError::NotAFile`] when it is not a regular file.
///
/// # Examples
/// ```
/// use hw3_core::fsio::{OpenError, open_regular};
/// let error = open_regular(std::path::Path::new("/")).unwrap_err();
/// assert_eq!(error.to_string(), "it is a folder, not a regular file");
/// # #[cfg(unix)]
/// assert!(matches!(open_regular(std::path::Path::new("/dev/null")), Err(OpenError::NotAFile("a device"))));
/// ```
pub fn open_regular(path: &Path) -> Result<(std::fs::File, std::fs::Metadata), OpenError> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        // The flag only matters for the open of a pipe or a device; reads of a regular file
        // ignore it.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path)?;
    let meta = file.metadata()?;
    if meta.is_file() { Ok((file, meta)) } else { Err(OpenError::NotAFile(kind_of(&meta))) }
}

/// Why a path cannot be the output file of a command ([`check_output_file`]).
#[derive(Debug, thiserror::Error)]
pub enum OutputFileError {
    /// The file name is longer than the file system accepts.
    #[error("its name has {0} bytes, more than the {NAME_MAX} a file system accepts")]
    NameTooLong(usize),
    /// The path names no file (it ends in `/`, `.` or `..`).
    #[error("it names a folder, not a file")]
    NoFileName,
    /// It exists and is not a regular file: replacing it would destroy a folder, a device or a pipe.
    #[error("it is {0}; only a regular file is replaced")]
    NotAFile(&'static str),
    /// It is a symbolic link: the rename of [`write_atomic`] would replace the link, not the
    /// file it points to (`/dev/stdout` is one, to the terminal or pipe of the moment).
    #[error("it is a symbolic link; name the file itself")]
    Link,
    /// Its folder cannot receive the file.
    #[error(transparent)]
    Folder(#[from] DirError),
}

/// Checks, before any work, that `path` can be written by [`write_atomic`]: a file name of at most
/// [`NAME_MAX`] bytes, nothing there or a regular file (not a symbolic link), in a folder that
/// accepts new files.
///
/// # Errors
/// The first [`OutputFileError`] that applies.
///
/// # Examples
/// ```
/// use hw3_core::fsio::check_output_file;
/// let dir = std::env::temp_dir();
/// assert!(check_output_file(&dir.join("report.txt")).is_ok());
/// assert!(check_output_file(&dir.join("a".repeat(300))).is_err());
/// assert_eq!(check_output_file(&dir).unwrap_err().to_string(), "it is a folder; only a regular file is replaced");
/// ```
pub fn check_output_file(path: &Path) -> Result<(), OutputFileError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => return Err(OutputFileError::Link),
        Ok(meta) if !meta.is_file() => return Err(OutputFileError::NotAFile(kind_of(&meta))),
        _ => {}
    }
    let name = path.file_name().ok_or(OutputFileError::NoFileName)?;
    if name.len() > NAME_MAX {
        return Err(OutputFileError::NameTooLong(name.len()));
    }
    check_writable_dir(parent_dir(path))?;
    Ok(())
}

/// Whether `a` and `b` are the same file (same device and inode), however they are spelled; false
/// when either cannot be described.
#[must_use]
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
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
    fn interrupted_writes_leave_no_temporary() {
        let dir = scratch("interrupted");
        let temporary = temporary_beside(&dir.join("x".repeat(NAME_MAX)));
        assert!(temporary.file_name().unwrap().len() < 40, "{temporary:?}");
        std::fs::write(&temporary, b"half").unwrap();
        // The process-wide list is shared with the other tests' writes: a list of our own.
        let mut list = vec![temporary.clone(), dir.join("never-created")];
        assert_eq!(remove_all(&mut list), 1);
        assert!(!temporary.exists() && list.is_empty());
        let target = dir.join("after.bin");
        write_atomic(&target, b"whole").unwrap();
        assert!(!live().iter().any(|p| p.parent() == target.parent()), "a finished write is off the list");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn outputs_that_would_destroy_or_cannot_exist_are_refused() {
        let dir = scratch("outputs");
        let file = dir.join("in.toml");
        std::fs::write(&file, b"x").unwrap();
        assert!(check_output_file(&file).is_ok());
        assert!(same_file(&file, &dir.join(".").join("in.toml")));
        assert!(!same_file(&file, &dir.join("other")));
        assert!(matches!(check_output_file(&dir), Err(OutputFileError::NotAFile("a folder"))));
        let long = dir.join("a".repeat(NAME_MAX + 1));
        assert!(matches!(check_output_file(&long), Err(OutputFileError::NameTooLong(256))));
        assert!(check_output_file(&dir.join("a".repeat(NAME_MAX))).is_ok());
        #[cfg(unix)]
        {
            let pipe = dir.join("pipe");
            let c = std::ffi::CString::new(pipe.as_os_str().as_encoded_bytes()).unwrap();
            // SAFETY: a valid NUL-terminated path; mkfifo only creates a file.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
            assert!(matches!(check_output_file(&pipe), Err(OutputFileError::NotAFile("a named pipe"))));
            // Opening the pipe for reading returns at once instead of waiting for a writer.
            assert!(matches!(open_regular(&pipe), Err(OpenError::NotAFile("a named pipe"))));
            assert!(matches!(check_output_file(Path::new("/dev/null")), Err(OutputFileError::NotAFile("a device"))));
            let link = dir.join("link");
            std::os::unix::fs::symlink(&file, &link).unwrap();
            assert!(matches!(check_output_file(&link), Err(OutputFileError::Link)));
        }
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
