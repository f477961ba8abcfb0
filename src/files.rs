//! Writing result files so that a crash never leaves half a file: everything goes to a
//! temporary file in the same folder first, then is renamed over the target.

use std::io::Write as _;
use std::path::Path;

use crate::{Error, Result};

/// Writes `path` atomically: `write` fills a temporary file next to it, which is then renamed.
/// Parent folders are created.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>,
) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| Error::io("cannot create folder", dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        write(&mut file)?;
        file.flush()?;
        file.sync_all()
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io("cannot write", path, e));
    }
    std::fs::rename(&tmp, path).map_err(|e| Error::io("cannot move into place", path, e))
}

/// Writes rows as CSV (header from the struct's fields), atomically.
pub fn write_csv<T: serde::Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        writer.serialize(row).map_err(|e| Error::Csv {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
    }
    let bytes = writer.into_inner().map_err(|e| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    write_atomic(path, |f| f.write_all(&bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_creates_folders_and_leaves_no_temp_files() {
        let dir = std::env::temp_dir().join(format!("grassbench-atomic-{}", std::process::id()));
        let path = dir.join("a/b/out.txt");
        write_atomic(&path, |f| f.write_all(b"hello")).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello");
        // A failing writer leaves the old file intact.
        let err = write_atomic(&path, |_| Err(std::io::Error::other("boom")));
        assert!(err.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello");
        let leftovers = std::fs::read_dir(dir.join("a/b")).unwrap().count();
        assert_eq!(leftovers, 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
