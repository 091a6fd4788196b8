//! Writing output files atomically: to a temporary file in the same directory, then
//! renamed over the target, so a failed run never leaves a half-written file where a
//! good one was.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::IoError;

/// Writes `bytes` to `path` through a temporary sibling file and a rename.
///
/// # Errors
/// [`IoError::Io`] when the directory cannot be created or the file written or renamed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let mut file = AtomicFile::create(path)?;
    file.write(bytes)?;
    file.commit()
}

/// An output file written as a stream: to a temporary sibling file, renamed over `path`
/// by [`AtomicFile::commit`]; dropped without a commit (an error on the way), the
/// temporary is removed, so a failed run never leaves a half-written file.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    file: Option<std::io::BufWriter<std::fs::File>>,
}

impl AtomicFile {
    /// Starts writing `path` (its directory created if missing).
    ///
    /// # Errors
    /// [`IoError::Io`] when the directory or the temporary cannot be created.
    pub fn create(path: &Path) -> Result<Self, IoError> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&dir).map_err(|e| IoError::io(&dir, e))?;
        let name = path
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
        let file = std::fs::File::create(&tmp).map_err(|e| IoError::io(path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            file: Some(std::io::BufWriter::new(file)),
        })
    }

    /// Appends `bytes`.
    ///
    /// # Errors
    /// [`IoError::Io`] naming the target file.
    pub fn write(&mut self, bytes: &[u8]) -> Result<(), IoError> {
        let path = &self.path;
        match self.file.as_mut() {
            Some(f) => f.write_all(bytes).map_err(|e| IoError::io(path, e)),
            None => Err(IoError::io(
                path,
                std::io::Error::other("already committed"),
            )),
        }
    }

    /// Flushes, syncs and renames the temporary over the target.
    ///
    /// # Errors
    /// [`IoError::Io`] naming the target file (the temporary is then removed).
    pub fn commit(mut self) -> Result<(), IoError> {
        let result = match self.file.take() {
            Some(f) => f
                .into_inner()
                .map_err(std::io::IntoInnerError::into_error)
                .and_then(|f| f.sync_all())
                .and_then(|()| std::fs::rename(&self.tmp, &self.path)),
            None => Ok(()),
        };
        result.map_err(|e| IoError::io(&self.path, e))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Not committed, or the commit failed: best effort, leave no temporary behind
        // (after a successful rename there is nothing to remove).
        let _ = std::fs::remove_file(&self.tmp);
    }
}

/// Formats rows of numbers as CSV with a header line (`{}` formatting: shortest
/// representation that round-trips).
pub fn csv_text(header: &[String], rows: &[Vec<f64>]) -> String {
    let mut s = header.join(",");
    s.push('\n');
    for r in rows {
        let line: Vec<String> = r.iter().map(|v| format!("{v}")).collect();
        s.push_str(&line.join(","));
        s.push('\n');
    }
    s
}
