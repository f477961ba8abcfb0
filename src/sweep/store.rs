//! A sweep's results folder: rows appended and flushed as each run finishes, so a crash loses
//! at most the run in progress, and a restarted sweep skips every run already recorded.
//!
//! Files: `runs.csv` (one row per run, written last), `frames.csv` (one row per measured
//! frame), `params.csv` (long format: run id, key, value), `meta.toml` (provenance, the sweep
//! file, calibration), `images/<configuration>.png` (the last frame of repetition 0,
//! [`image_path`]). [`read_rows`] reads the CSV files back into their row types. A run counts as finished when its `runs.csv` row is complete; on
//! reopening, a torn last line is cut off and frames and parameters of unfinished runs are
//! dropped, so the files hold exactly the finished runs.

use std::collections::HashSet;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::runner::{FrameRecord, RunSummary, write_atomic};
use crate::{Error, Result};

/// A row of `params.csv`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ParamRow {
    /// Run id.
    pub run_id: String,
    /// Technique or `scene`.
    pub owner: String,
    /// Parameter key.
    pub key: String,
    /// Value as text.
    pub value: String,
}

/// An open results folder.
pub struct SweepStore {
    dir: PathBuf,
    finished: HashSet<String>,
}

impl SweepStore {
    /// Opens (creating) `dir` for the sweep whose `meta.toml` text is `meta`. An existing folder
    /// is resumed when its `meta.toml` records the same sweep file (`sweep_key`), refused
    /// otherwise unless `force`, which empties it.
    pub fn open(dir: &Path, sweep_key: &str, force: bool) -> Result<Self> {
        let meta_path = dir.join("meta.toml");
        if dir.exists()
            && std::fs::read_dir(dir)
                .map(|mut d| d.next().is_some())
                .unwrap_or(false)
        {
            let same = std::fs::read_to_string(&meta_path).is_ok_and(|m| m.contains(sweep_key));
            if !same && !force {
                return Err(Error::InvalidFile {
                    path: dir.to_owned(),
                    message: "this results folder holds another sweep (or a different version of this sweep file); \
                              choose another --out, or pass --force to replace it"
                        .into(),
                });
            }
            if force && !same {
                std::fs::remove_dir_all(dir).map_err(|e| Error::io("cannot clear", dir, e))?;
            }
        }
        std::fs::create_dir_all(dir).map_err(|e| Error::io("cannot create folder", dir, e))?;
        let mut store = Self {
            dir: dir.to_owned(),
            finished: HashSet::new(),
        };
        store.recover()?;
        Ok(store)
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Whether run `id` is already recorded.
    pub fn is_finished(&self, id: &str) -> bool {
        self.finished.contains(id)
    }

    /// Number of finished runs.
    pub fn finished_count(&self) -> usize {
        self.finished.len()
    }

    /// Cuts torn last lines and drops frames and parameters of runs without a `runs.csv` row.
    fn recover(&mut self) -> Result<()> {
        let runs = self.dir.join("runs.csv");
        truncate_torn_line(&runs)?;
        self.finished = read_column(&runs, "run_id")?.into_iter().collect();
        for name in ["frames.csv", "params.csv", "levels.csv"] {
            let path = self.dir.join(name);
            truncate_torn_line(&path)?;
            keep_rows(&path, &self.finished)?;
        }
        Ok(())
    }

    /// Appends a finished run: its frames, levels and parameters first, its `runs.csv` row
    /// last.
    pub fn append(
        &mut self,
        run: &RunSummary,
        frames: &[FrameRecord],
        params: &[ParamRow],
    ) -> Result<()> {
        append_rows(&self.dir.join("frames.csv"), frames)?;
        append_rows(
            &self.dir.join("levels.csv"),
            &crate::runner::LevelRow::of(frames),
        )?;
        append_rows(&self.dir.join("params.csv"), params)?;
        append_rows(&self.dir.join("runs.csv"), std::slice::from_ref(run))?;
        self.finished.insert(run.run_id.clone());
        Ok(())
    }

    /// Writes `meta.toml` atomically.
    pub fn write_meta(&self, text: &str) -> Result<()> {
        write_atomic(&self.dir.join("meta.toml"), |f| {
            f.write_all(text.as_bytes())
        })
    }
}

/// Appends rows to a CSV file (header when the file is new) in one write, then syncs.
pub fn append_rows<T: serde::Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    if rows.is_empty() {
        return Ok(());
    }
    let new = !path.exists()
        || std::fs::metadata(path)
            .map(|m| m.len() == 0)
            .unwrap_or(true);
    let mut w = csv::WriterBuilder::new()
        .has_headers(new)
        .from_writer(Vec::new());
    for row in rows {
        w.serialize(row).map_err(|e| Error::Csv {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
    }
    let bytes = w.into_inner().map_err(|e| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(|e| Error::io("cannot open", path, e))?;
    file.write_all(&bytes)
        .and_then(|()| file.sync_data())
        .map_err(|e| Error::io("cannot append to", path, e))
}

/// The rows of a CSV file, by column name (empty when the file does not exist).
pub fn read_rows<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Vec<T>> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    let csv_err = |e: csv::Error| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    };
    csv::Reader::from_path(path)
        .map_err(csv_err)?
        .deserialize()
        .collect::<std::result::Result<_, _>>()
        .map_err(csv_err)
}

/// Where a results folder keeps the last frame of configuration `config_id`, relative to the
/// folder (with `/`, so it is also the image's Markdown link).
pub fn image_path(config_id: &str) -> String {
    format!("images/{config_id}.png")
}

/// The values of one column of a CSV file (empty when the file does not exist).
pub fn read_column(path: &Path, column: &str) -> Result<Vec<String>> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    let mut reader = csv::Reader::from_path(path).map_err(|e| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    let headers = reader
        .headers()
        .map_err(|e| Error::Csv {
            path: path.to_owned(),
            message: e.to_string(),
        })?
        .clone();
    let Some(k) = headers.iter().position(|h| h == column) else {
        return Err(Error::Csv {
            path: path.to_owned(),
            message: format!("no column `{column}`"),
        });
    };
    reader
        .records()
        .map(|r| {
            r.map(|r| r.get(k).unwrap_or_default().to_owned())
                .map_err(|e| Error::Csv {
                    path: path.to_owned(),
                    message: e.to_string(),
                })
        })
        .collect()
}

/// A crash during an append can leave a last line without its newline: cut it off.
fn truncate_torn_line(path: &Path) -> Result<()> {
    let Ok(bytes) = std::fs::read(path) else {
        return Ok(());
    };
    if bytes.is_empty() || bytes.ends_with(b"\n") {
        return Ok(());
    }
    let keep = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
    write_atomic(path, |f| f.write_all(&bytes[..keep]))
}

/// Rewrites a CSV file keeping the header and the rows whose `run_id` is in `keep`.
fn keep_rows(path: &Path, keep: &HashSet<String>) -> Result<()> {
    if !path.exists() {
        return Ok(());
    }
    let csv_err = |e: csv::Error| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let mut reader = csv::Reader::from_path(path).map_err(csv_err)?;
    let headers = reader.headers().map_err(csv_err)?.clone();
    let Some(k) = headers.iter().position(|h| h == "run_id") else {
        return Ok(());
    };
    let mut kept = Vec::new();
    let mut dropped = false;
    for record in reader.records() {
        let record = record.map_err(csv_err)?;
        if keep.contains(record.get(k).unwrap_or_default()) {
            kept.push(record);
        } else {
            dropped = true;
        }
    }
    if !dropped {
        return Ok(());
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&headers).map_err(csv_err)?;
    for r in &kept {
        w.write_record(r).map_err(csv_err)?;
    }
    let bytes = w.into_inner().map_err(|e| Error::Csv {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    write_atomic(path, |f| f.write_all(&bytes))
}
