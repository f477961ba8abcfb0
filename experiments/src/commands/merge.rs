//! `grassbench merge`: joins the outputs of sweep shards into one results folder. Rows are
//! read into their types and written with today's columns, so shards written by an older build
//! (fewer columns) merge too.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use grassbench::runner::{FrameRecord, RunSummary, write_atomic, write_csv};
use grassbench::sweep::{ParamRow, read_rows};
use serde::Serialize;
use serde::de::DeserializeOwned;

use super::out_dir::prepare_out_dir;
use super::sweep::SweepMeta;

/// Arguments of `merge`.
#[derive(Clone, Debug, clap::Args)]
pub struct MergeArgs {
    /// Shard results folders.
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// Merged results folder.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Merge shards measured on different adapters or revisions.
    #[arg(long)]
    pub allow_mixed: bool,
    /// Replace a non-empty output folder.
    #[arg(long)]
    pub force: bool,
}

fn read_meta(dir: &Path) -> anyhow::Result<SweepMeta> {
    let path = dir.join("meta.toml");
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "`{}` is not a sweep results folder (no meta.toml)",
            dir.display()
        )
    })?;
    toml::from_str(&text)
        .with_context(|| format!("`{}` is not a sweep's meta.toml", path.display()))
}

/// A row as `merge` compares it: its CSV text, as written.
fn row_text<T: Serialize>(row: &T) -> anyhow::Result<String> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    w.serialize(row)?;
    let bytes = w.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(String::from_utf8(bytes)?)
}

/// Joins file `name` of every shard into `out`, rows in shard order. The same row twice (a
/// shard run twice) is kept once; with `one_per_run` (runs.csv), two different rows of one run
/// (one run with two results) are refused.
fn merge_rows<T: Serialize + DeserializeOwned>(
    shards: &[PathBuf],
    out: &Path,
    name: &str,
    run_id: fn(&T) -> &str,
    one_per_run: bool,
) -> anyhow::Result<()> {
    let mut rows: Vec<T> = Vec::new();
    let mut seen: HashMap<String, HashSet<String>> = HashMap::new();
    for dir in shards {
        let path = dir.join(name);
        for row in read_rows::<T>(&path).with_context(|| format!("reading {}", path.display()))? {
            let text = row_text(&row)?;
            let texts = seen.entry(run_id(&row).to_owned()).or_default();
            if texts.contains(&text) {
                continue;
            }
            if one_per_run && !texts.is_empty() {
                bail!(
                    "run {} has different results in two shards; refusing to merge",
                    run_id(&row)
                );
            }
            texts.insert(text);
            rows.push(row);
        }
    }
    if rows.is_empty() {
        return Ok(());
    }
    write_csv(&out.join(name), &rows)?;
    Ok(())
}

/// Merges the shards.
pub fn merge(args: &MergeArgs) -> anyhow::Result<()> {
    let metas = args
        .shards
        .iter()
        .map(|d| read_meta(d))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let first = &metas[0];
    for (dir, m) in args.shards.iter().zip(&metas) {
        if m.sweep_key != first.sweep_key {
            bail!(
                "`{}` holds another sweep (or another version of the file) than `{}`: refusing to merge",
                dir.display(),
                args.shards[0].display()
            );
        }
        if !args.allow_mixed {
            if m.provenance.adapter.name != first.provenance.adapter.name {
                bail!(
                    "`{}` was measured on `{}`, `{}` on `{}`: timings are not comparable; pass --allow-mixed to merge anyway",
                    dir.display(),
                    m.provenance.adapter.name,
                    args.shards[0].display(),
                    first.provenance.adapter.name
                );
            }
            if m.provenance.revision != first.provenance.revision {
                bail!(
                    "`{}` was built from revision {}, `{}` from {}; pass --allow-mixed to merge anyway",
                    dir.display(),
                    m.provenance.revision,
                    args.shards[0].display(),
                    first.provenance.revision
                );
            }
        }
    }
    prepare_out_dir(&args.out, args.force)?;
    merge_rows(
        &args.shards,
        &args.out,
        "runs.csv",
        |r: &RunSummary| r.run_id.as_str(),
        true,
    )?;
    merge_rows(
        &args.shards,
        &args.out,
        "frames.csv",
        |r: &FrameRecord| r.run_id.as_str(),
        false,
    )?;
    merge_rows(
        &args.shards,
        &args.out,
        "params.csv",
        |r: &ParamRow| r.run_id.as_str(),
        false,
    )?;
    for dir in &args.shards {
        if let Ok(entries) = std::fs::read_dir(dir.join("images")) {
            for e in entries.flatten() {
                let to = args.out.join("images").join(e.file_name());
                std::fs::create_dir_all(args.out.join("images"))?;
                std::fs::copy(e.path(), &to)?;
            }
        }
    }
    let merged = SweepMeta {
        shard: format!("merged from {} shards", metas.len()),
        ..read_meta(&args.shards[0])?
    };
    write_atomic(&args.out.join("meta.toml"), |f| {
        std::io::Write::write_all(
            f,
            toml::to_string_pretty(&merged)
                .unwrap_or_default()
                .as_bytes(),
        )
    })?;
    eprintln!("merged {} shards into {}", metas.len(), args.out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("grassbench-merge-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    const FIXTURE: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/report/runs.csv"
    );

    #[test]
    fn rows_are_read_by_name_kept_once_and_written_with_todays_columns() {
        let (a, b, out) = (temp("a"), temp("b"), temp("out"));
        // The fixture has old columns (the level-of-detail counts, one mixed `blades` count)
        // and lacks today's split counts; the same run in two shards is kept once.
        std::fs::copy(FIXTURE, a.join("runs.csv")).unwrap();
        std::fs::copy(FIXTURE, b.join("runs.csv")).unwrap();
        let shards = [a.clone(), b.clone()];
        fn id(r: &RunSummary) -> &str {
            &r.run_id
        }
        merge_rows(&shards, &out, "runs.csv", id, true).unwrap();
        let merged: Vec<RunSummary> = read_rows(&out.join("runs.csv")).unwrap();
        let original: Vec<RunSummary> = read_rows(Path::new(FIXTURE)).unwrap();
        assert_eq!(merged, original);
        let header = std::fs::read_to_string(out.join("runs.csv")).unwrap();
        assert!(
            header.contains(",blades_drawn,blades_represented,")
                && !header.contains("blades_geometry")
                && !header.contains("efficiency"),
            "{header}"
        );
        // Nothing to merge: no file.
        merge_rows(
            &shards,
            &out,
            "frames.csv",
            |r: &FrameRecord| r.run_id.as_str(),
            false,
        )
        .unwrap();
        assert!(!out.join("frames.csv").exists());
        // One run with two results is refused.
        let mut changed = original.clone();
        changed[1].gpu_wall_ms_median = changed[1].gpu_wall_ms_median.map(|v| v + 1.0);
        write_csv(&b.join("runs.csv"), &changed).unwrap();
        let e = merge_rows(&shards, &out, "runs.csv", id, true)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bbbbbbbbbbbb-r0") && e.contains("different results"),
            "{e}"
        );
        for d in [a, b, out] {
            std::fs::remove_dir_all(d).unwrap();
        }
    }
}
